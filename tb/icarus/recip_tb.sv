// recip_tb: plain Verilog testbench of fxr_recip driven by the golden vectors (docs/vectors.md),
// for any simulator with SystemVerilog-2012 basics (checked with Icarus 11):
//
//   iverilog -g2012 -s recip_tb -I tb/icarus -y rtl -Y .sv build/gen/fxr_config_pkg.sv \
//            rtl/fxr_recip.sv tb/icarus/recip_tb.sv
//   vvp -n a.out +vectors=$PWD/vectors/recip/recip.hex +count=<manifest count> [+seed=N]
//
// Fields (vectors/recip/recip.json): in_neg, in_exp, in_sig | out_neg, out_exp, out_sig, out_dbz,
// out_ovf. Each line is one word, the fields concatenated msb first, each padded to whole hex
// digits; field f is word[offset_f +: width_f] with the manifest's offsets, recomputed here from
// the package widths by the same rule (the last field at bit 0).
`timescale 1ns / 1ps
module recip_tb;
  import fxr_config_pkg::*;

  `include "vec_layout.svh"
  localparam Unit           = "recip";
  localparam int OffOvf      = 0;
  localparam int OffDbz      = OffOvf + pad(1);
  localparam int OffOutSig   = OffDbz + pad(1);
  localparam int OffOutExp   = OffOutSig + pad(RecipOutSigBits);
  localparam int OffOutNeg   = OffOutExp + pad(RecipExpBits);
  localparam int OffInSig    = OffOutNeg + pad(1);
  localparam int OffInExp    = OffInSig + pad(RecipInSigBits);
  localparam int OffInNeg    = OffInExp + pad(RecipExpBits);
  localparam int WordBits    = OffInNeg + pad(1);
  localparam int OutWordBits = OffInSig;

  logic                       out_neg, out_dbz, out_ovf;
  logic [RecipExpBits-1:0]    out_exp;
  logic [RecipOutSigBits-1:0] out_sig;
  logic [OutWordBits-1:0]     got;
  always_comb begin
    got = '0;
    got[OffOutNeg]                    = out_neg;
    got[OffOutExp +: RecipExpBits]    = out_exp;
    got[OffOutSig +: RecipOutSigBits] = out_sig;
    got[OffDbz]                       = out_dbz;
    got[OffOvf]                       = out_ovf;
  end

  `include "vec_stream.svh"

  fxr_recip dut (
    .clk_i      (clk),
    .rst_ni     (rst_n),
    .in_valid_i (in_valid),
    .in_ready_o (in_ready),
    .in_neg_i   (cur[OffInNeg]),
    .in_exp_i   (cur[OffInExp +: RecipExpBits]),
    .in_sig_i   (cur[OffInSig +: RecipInSigBits]),
    .out_valid_o(out_valid),
    .out_ready_i(out_ready),
    .out_neg_o  (out_neg),
    .out_exp_o  (out_exp),
    .out_sig_o  (out_sig),
    .out_dbz_o  (out_dbz),
    .out_ovf_o  (out_ovf)
  );
endmodule

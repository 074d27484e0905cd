// div_tb: plain Verilog testbench of fxr_div driven by the golden vectors (docs/vectors.md),
// for any simulator with SystemVerilog-2012 basics (checked with Icarus 11):
//
//   iverilog -g2012 -s div_tb -I tb/icarus -y rtl -Y .sv build/gen/fxr_config_pkg.sv \
//            rtl/fxr_div.sv tb/icarus/div_tb.sv
//   vvp -n a.out +vectors=$PWD/vectors/div/div.hex +count=<manifest count> [+seed=N]
//
// Fields (vectors/div/div.json): in_num, in_den | out_sig, out_exp_adj, out_dbz. Each line is one
// word, the fields concatenated msb first, each padded to whole hex digits; field f is
// word[offset_f +: width_f] with the manifest's offsets, recomputed here from the package widths
// by the same rule (the last field at bit 0).
`timescale 1ns / 1ps
module div_tb;
  import fxr_config_pkg::*;

  `include "vec_layout.svh"
  localparam Unit           = "div";
  localparam int ExpAdjBits  = 2;
  localparam int OffDbz      = 0;
  localparam int OffExpAdj   = OffDbz + pad(1);
  localparam int OffSig      = OffExpAdj + pad(ExpAdjBits);
  localparam int OffDen      = OffSig + pad(DivQuotBits);
  localparam int OffNum      = OffDen + pad(DivDenBits);
  localparam int WordBits    = OffNum + pad(DivNumBits);
  localparam int OutWordBits = OffDen;

  logic [DivQuotBits-1:0] out_sig;
  logic [ExpAdjBits-1:0]  out_exp_adj;
  logic                   out_dbz;
  logic [OutWordBits-1:0] got;
  always_comb begin
    got = '0;
    got[OffSig +: DivQuotBits]   = out_sig;
    got[OffExpAdj +: ExpAdjBits] = out_exp_adj;
    got[OffDbz]                  = out_dbz;
  end

  `include "vec_stream.svh"

  fxr_div dut (
    .clk_i        (clk),
    .rst_ni       (rst_n),
    .in_valid_i   (in_valid),
    .in_ready_o   (in_ready),
    .in_num_i     (cur[OffNum +: DivNumBits]),
    .in_den_i     (cur[OffDen +: DivDenBits]),
    .out_valid_o  (out_valid),
    .out_ready_i  (out_ready),
    .out_sig_o    (out_sig),
    .out_exp_adj_o(out_exp_adj),
    .out_dbz_o    (out_dbz)
  );
endmodule

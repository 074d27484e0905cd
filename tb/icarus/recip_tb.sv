// recip_tb: plain Verilog testbench of fxr_recip driven by the golden vectors (docs/vectors.md),
// for any simulator with SystemVerilog-2012 basics (checked with Icarus 11):
//
//   build/app/fxraster layout --emit-sv build/gen/fxr_vec_pkg.sv
//   iverilog -g2012 -s recip_tb -I tb/icarus -y rtl -Y .sv build/gen/fxr_config_pkg.sv \
//            build/gen/fxr_vec_pkg.sv rtl/fxr_recip.sv tb/icarus/recip_tb.sv
//   vvp -n a.out +vectors=$PWD/vectors/recip/recip.hex +count=<manifest count> [+seed=N]
//
// The line layout is not written here: fxr_vec_pkg (generated from the model's vector layout)
// gives the packed struct recip_vec_t of a whole line and recip_vec_out_t of its output part
// (the low bits), padding fields included, so the ports connect to struct members by name.
`timescale 1ns / 1ps
module recip_tb;
  import fxr_vec_pkg::*;

  localparam Unit           = "recip";
  localparam int WordBits    = RecipVecWordBits;
  localparam int OutWordBits = RecipVecOutWordBits;

  recip_vec_out_t         out_v;
  logic [OutWordBits-1:0] got;
  assign got = out_v & RecipVecOutMask;  // padding bits 0 (left undriven here)

  `include "vec_stream.svh"

  recip_vec_t in_v;
  assign in_v = cur;

  fxr_recip dut (
    .clk_i      (clk),
    .rst_ni     (rst_n),
    .in_valid_i (in_valid),
    .in_ready_o (in_ready),
    .in_neg_i   (in_v.in_neg),
    .in_exp_i   (in_v.in_exp),
    .in_sig_i   (in_v.in_sig),
    .out_valid_o(out_valid),
    .out_ready_i(out_ready),
    .out_neg_o  (out_v.out_neg),
    .out_exp_o  (out_v.out_exp),
    .out_sig_o  (out_v.out_sig),
    .out_dbz_o  (out_v.out_dbz),
    .out_ovf_o  (out_v.out_ovf)
  );
endmodule

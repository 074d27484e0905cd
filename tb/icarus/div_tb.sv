// div_tb: plain Verilog testbench of fxr_div driven by the golden vectors (docs/vectors.md),
// for any simulator with SystemVerilog-2012 basics (checked with Icarus 11):
//
//   build/app/fxraster layout --emit-sv build/gen/fxr_vec_pkg.sv
//   iverilog -g2012 -s div_tb -I tb/icarus -y rtl -Y .sv build/gen/fxr_config_pkg.sv \
//            build/gen/fxr_vec_pkg.sv rtl/fxr_div.sv tb/icarus/div_tb.sv
//   vvp -n a.out +vectors=$PWD/vectors/div/div.hex +count=<manifest count> [+seed=N]
//
// The line layout is not written here: fxr_vec_pkg (generated from the model's vector layout)
// gives the packed struct div_vec_t of a whole line and div_vec_out_t of its output part (the
// low bits), padding fields included, so the ports connect to struct members by name.
`timescale 1ns / 1ps
module div_tb;
  import fxr_vec_pkg::*;

  localparam Unit           = "div";
  localparam int WordBits    = DivVecWordBits;
  localparam int OutWordBits = DivVecOutWordBits;

  div_vec_out_t           out_v;
  logic [OutWordBits-1:0] got;
  assign got = out_v & DivVecOutMask;  // padding bits 0 (left undriven here)

  `include "vec_stream.svh"

  div_vec_t in_v;
  assign in_v = cur;

  fxr_div dut (
    .clk_i        (clk),
    .rst_ni       (rst_n),
    .in_valid_i   (in_valid),
    .in_ready_o   (in_ready),
    .in_num_i     (in_v.in_num),
    .in_den_i     (in_v.in_den),
    .out_valid_o  (out_valid),
    .out_ready_i  (out_ready),
    .out_sig_o    (out_v.out_sig),
    .out_exp_adj_o(out_v.out_exp_adj),
    .out_dbz_o    (out_v.out_dbz)
  );
endmodule

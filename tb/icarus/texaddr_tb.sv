// texaddr_tb: plain Verilog testbench of fxr_texaddr driven by the golden vectors (docs/vectors.md),
// for any simulator with SystemVerilog-2012 basics (checked with Icarus 11):
//
//   build/app/fxraster layout --emit-sv build/gen/fxr_vec_pkg.sv
//   iverilog -g2012 -s texaddr_tb -I tb/icarus -y rtl -Y .sv build/gen/fxr_config_pkg.sv \
//            build/gen/fxr_vec_pkg.sv rtl/fxr_texaddr_axis.sv rtl/fxr_texaddr.sv tb/icarus/texaddr_tb.sv
//   vvp -n a.out +vectors=$PWD/vectors/texaddr/texaddr.hex +count=<manifest count> [+seed=N]
//
// The line layout is not written here: fxr_vec_pkg (generated from the model's vector layout)
// gives the packed struct texaddr_vec_t of a whole line and texaddr_vec_out_t of its output part
// (the low bits), padding fields included, so the ports connect to struct members by name.
`timescale 1ns / 1ps
module texaddr_tb;
  import fxr_vec_pkg::*;

  localparam Unit           = "texaddr";
  localparam int WordBits    = TexaddrVecWordBits;
  localparam int OutWordBits = TexaddrVecOutWordBits;

  texaddr_vec_out_t         out_v;
  logic [OutWordBits-1:0] got;
  assign got = out_v & TexaddrVecOutMask;  // padding bits 0 (left undriven here)

  `include "vec_stream.svh"

  texaddr_vec_t in_v;
  assign in_v = cur;

  fxr_texaddr dut (
    .clk_i      (clk),
    .rst_ni     (rst_n),
    .in_valid_i (in_valid),
    .in_ready_o (in_ready),
    .filter_i  (in_v.filter),
    .wrap_i    (in_v.wrap),
    .u_neg_i   (in_v.u_neg),
    .u_exp_i   (in_v.u_exp),
    .u_sig_i   (in_v.u_sig),
    .v_neg_i   (in_v.v_neg),
    .v_exp_i   (in_v.v_exp),
    .v_sig_i   (in_v.v_sig),
    .width_i   (in_v.width),
    .height_i  (in_v.height),
    .out_valid_o(out_valid),
    .out_ready_i(out_ready),
    .s_i0_o    (out_v.s_i0),
    .s_i1_o    (out_v.s_i1),
    .s_b0_o    (out_v.s_b0),
    .s_b1_o    (out_v.s_b1),
    .s_w_o     (out_v.s_w),
    .t_i0_o    (out_v.t_i0),
    .t_i1_o    (out_v.t_i1),
    .t_b0_o    (out_v.t_b0),
    .t_b1_o    (out_v.t_b1),
    .t_w_o     (out_v.t_w)
  );
endmodule

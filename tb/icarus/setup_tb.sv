// setup_tb: plain Verilog testbench of fxr_setup_fields driven by the golden vectors (docs/vectors.md),
// for any simulator with SystemVerilog-2012 basics (checked with Icarus 11):
//
//   build/app/fxraster layout --emit-sv build/gen/fxr_vec_pkg.sv
//   iverilog -g2012 -s setup_tb -I tb/icarus -y rtl -Y .sv build/gen/fxr_config_pkg.sv \
//            build/gen/fxr_vec_pkg.sv rtl/fxr_setup_fields.sv tb/icarus/setup_tb.sv
//   vvp -n a.out +vectors=$PWD/vectors/setup/setup.hex +count=<manifest count> [+seed=N]
//
// The line layout is not written here: fxr_vec_pkg (generated from the model's vector layout)
// gives the packed struct setup_vec_t of a whole line and setup_vec_out_t of its output part
// (the low bits), padding fields included, so the ports connect to struct members by name.
`timescale 1ns / 1ps
module setup_tb;
  import fxr_vec_pkg::*;

  localparam Unit           = "setup";
  localparam int WordBits    = SetupVecWordBits;
  localparam int OutWordBits = SetupVecOutWordBits;

  setup_vec_out_t         out_v;
  logic [OutWordBits-1:0] got;
  assign got = out_v & SetupVecOutMask;  // padding bits 0 (left undriven here)

  `include "vec_stream.svh"

  setup_vec_t in_v;
  assign in_v = cur;

  fxr_setup_fields dut (
    .clk_i         (clk),
    .rst_ni        (rst_n),
    .in_valid_i    (in_valid),
    .in_ready_o    (in_ready),
    .prim_i        (in_v.prim),
    .v0_x_i        (in_v.v0_x),
    .v0_y_i        (in_v.v0_y),
    .v0_ax_i       (in_v.v0_ax),
    .v0_ay_i       (in_v.v0_ay),
    .v0_z_i        (in_v.v0_z),
    .v0_rw_neg_i   (in_v.v0_rw_neg),
    .v0_rw_sig_i   (in_v.v0_rw_sig),
    .v0_rw_exp_i   (in_v.v0_rw_exp),
    .v0_vw0_neg_i  (in_v.v0_vw0_neg),
    .v0_vw0_sig_i  (in_v.v0_vw0_sig),
    .v0_vw0_exp_i  (in_v.v0_vw0_exp),
    .v0_vw1_neg_i  (in_v.v0_vw1_neg),
    .v0_vw1_sig_i  (in_v.v0_vw1_sig),
    .v0_vw1_exp_i  (in_v.v0_vw1_exp),
    .v1_x_i        (in_v.v1_x),
    .v1_y_i        (in_v.v1_y),
    .v1_ax_i       (in_v.v1_ax),
    .v1_ay_i       (in_v.v1_ay),
    .v1_z_i        (in_v.v1_z),
    .v1_rw_neg_i   (in_v.v1_rw_neg),
    .v1_rw_sig_i   (in_v.v1_rw_sig),
    .v1_rw_exp_i   (in_v.v1_rw_exp),
    .v1_vw0_neg_i  (in_v.v1_vw0_neg),
    .v1_vw0_sig_i  (in_v.v1_vw0_sig),
    .v1_vw0_exp_i  (in_v.v1_vw0_exp),
    .v1_vw1_neg_i  (in_v.v1_vw1_neg),
    .v1_vw1_sig_i  (in_v.v1_vw1_sig),
    .v1_vw1_exp_i  (in_v.v1_vw1_exp),
    .v2_x_i        (in_v.v2_x),
    .v2_y_i        (in_v.v2_y),
    .v2_ax_i       (in_v.v2_ax),
    .v2_ay_i       (in_v.v2_ay),
    .v2_z_i        (in_v.v2_z),
    .v2_rw_neg_i   (in_v.v2_rw_neg),
    .v2_rw_sig_i   (in_v.v2_rw_sig),
    .v2_rw_exp_i   (in_v.v2_rw_exp),
    .v2_vw0_neg_i  (in_v.v2_vw0_neg),
    .v2_vw0_sig_i  (in_v.v2_vw0_sig),
    .v2_vw0_exp_i  (in_v.v2_vw0_exp),
    .v2_vw1_neg_i  (in_v.v2_vw1_neg),
    .v2_vw1_sig_i  (in_v.v2_vw1_sig),
    .v2_vw1_exp_i  (in_v.v2_vw1_exp),
    .viewport_x_i  (in_v.viewport_x),
    .viewport_y_i  (in_v.viewport_y),
    .viewport_w_i  (in_v.viewport_w),
    .viewport_h_i  (in_v.viewport_h),
    .scissor_x_i   (in_v.scissor_x),
    .scissor_y_i   (in_v.scissor_y),
    .scissor_w_i   (in_v.scissor_w),
    .scissor_h_i   (in_v.scissor_h),
    .cull_i        (in_v.cull),
    .front_ccw_i   (in_v.front_ccw),
    .interp_i      (in_v.interp),
    .out_valid_o   (out_valid),
    .out_ready_i   (out_ready),
    .outcome_o     (out_v.outcome),
    .out_prim_o    (out_v.out_prim),
    .e0_a_o        (out_v.e0_a),
    .e0_b_o        (out_v.e0_b),
    .e0_c_o        (out_v.e0_c),
    .e0_bias_o     (out_v.e0_bias),
    .e1_a_o        (out_v.e1_a),
    .e1_b_o        (out_v.e1_b),
    .e1_c_o        (out_v.e1_c),
    .e1_bias_o     (out_v.e1_bias),
    .e2_a_o        (out_v.e2_a),
    .e2_b_o        (out_v.e2_b),
    .e2_c_o        (out_v.e2_c),
    .e2_bias_o     (out_v.e2_bias),
    .area2_o       (out_v.area2),
    .front_o       (out_v.front),
    .x0_o          (out_v.x0),
    .x1_o          (out_v.x1),
    .y0_o          (out_v.y0),
    .y1_o          (out_v.y1),
    .z_c_o         (out_v.z_c),
    .z_dx_o        (out_v.z_dx),
    .z_dy_o        (out_v.z_dy),
    .z_i0_o        (out_v.z_i0),
    .z_j0_o        (out_v.z_j0),
    .z_den_o       (out_v.z_den),
    .den_c_o       (out_v.den_c),
    .den_dx_o      (out_v.den_dx),
    .den_dy_o      (out_v.den_dy),
    .den_i0_o      (out_v.den_i0),
    .den_j0_o      (out_v.den_j0),
    .den_exp_o     (out_v.den_exp),
    .num0_c_o      (out_v.num0_c),
    .num0_dx_o     (out_v.num0_dx),
    .num0_dy_o     (out_v.num0_dy),
    .num0_i0_o     (out_v.num0_i0),
    .num0_j0_o     (out_v.num0_j0),
    .num0_exp_o    (out_v.num0_exp),
    .num1_c_o      (out_v.num1_c),
    .num1_dx_o     (out_v.num1_dx),
    .num1_dy_o     (out_v.num1_dy),
    .num1_i0_o     (out_v.num1_i0),
    .num1_j0_o     (out_v.num1_j0),
    .num1_exp_o    (out_v.num1_exp)
  );
endmodule

// fxr_setup: stage 5, triangle setup (issue 10), with record ports. One snapped triangle in (the
// model's SetupStage::In, SetupTriangle), its equations out (SetupStage::Out, TriangleEquations),
// both packed structs of the generated package fxr_rec_pkg (docs/rtl.md, "Record ports"); the
// draw state on per-field ports. The datapath is fxr_setup_fields (the setup vector unit's port
// list; edges, culling, candidate rectangle, planes: docs/pipeline.md, stage 5).
// Model: fxr::SetupStage (model/stages/setup.hpp); vectors: the transaction dumps' setup.in /
// setup.out (tb/txn/setup_txn_test.cpp) and vectors/setup/ (tb/setup_test.cpp, the core).
//
// Ports:
//   clk_i, rst_ni                 clock, active-low asynchronous reset
//   in_valid_i / in_ready_o       input handshake
//   in_i                          fxr_rec_pkg::setup_triangle_t (SetupTriangle::visit())
//   viewport_*_i, scissor_*_i,    draw state (DrawState::visit_rects, cull, front_ccw, interp), as
//   cull_i, front_ccw_i, interp_i fxr_setup_fields; stable while triangles are in flight
//   out_valid_o / out_ready_i     output handshake: only drawn triangles (outcome ok) come out,
//                                 as the model's step() emits nothing for the others (1 → 0..1)
//   out_o                         fxr_rec_pkg::triangle_equations_t
//   cull_valid_o, cull_outcome_o  one-clock pulse per triangle not drawn, with the model's
//                                 SetupOutcome code (1 zero area, 2 back face, 3 no samples,
//                                 4 range; precedence range > zero area > back face > no samples,
//                                 fxr_setup_edges); it needs no ready (counters take it)
//
// Latency and II as fxr_setup_fields (9 clocks, II 1). A culled triangle leaves the last
// register without waiting for out_ready_i. Varyings: fxr_rec_pkg::NumVaryings must be the
// core's two (kSetupVecVaryings); another package is refused at elaboration.
module fxr_setup #(
  parameter int WindowIntBits = fxr_config_pkg::RasterWindowIntBits,
  localparam int NV = fxr_rec_pkg::NumVaryings
) (
  input  logic                             clk_i,
  input  logic                             rst_ni,
  input  logic                             in_valid_i,
  output logic                             in_ready_o,
  input  fxr_rec_pkg::setup_triangle_t     in_i,
  input  logic [WindowIntBits-1:0]         viewport_x_i,
  input  logic [WindowIntBits-1:0]         viewport_y_i,
  input  logic [WindowIntBits:0]           viewport_w_i,
  input  logic [WindowIntBits:0]           viewport_h_i,
  input  logic [WindowIntBits-1:0]         scissor_x_i,
  input  logic [WindowIntBits-1:0]         scissor_y_i,
  input  logic [WindowIntBits:0]           scissor_w_i,
  input  logic [WindowIntBits:0]           scissor_h_i,
  input  logic [1:0]                       cull_i,
  input  logic                             front_ccw_i,
  input  logic                             interp_i,
  output logic                             out_valid_o,
  input  logic                             out_ready_i,
  output fxr_rec_pkg::triangle_equations_t out_o,
  output logic                             cull_valid_o,
  output logic [2:0]                       cull_outcome_o
);
  localparam int SetupVaryings = 2;  // fxr_setup_fields' varying ports (kSetupVecVaryings)
  if (NV != SetupVaryings) begin : g_bad_varyings
    $error("fxr_setup: fxr_rec_pkg::NumVaryings must be 2 (the varying ports of fxr_setup_fields)");
  end

  logic       f_valid, f_ready;
  logic [2:0] outcome;
  logic       ok;
  assign ok             = outcome == 3'd0;  // fxr_setup_edges::OutcomeOk
  assign out_valid_o    = f_valid & ok;
  assign f_ready        = out_ready_i | ~ok;
  assign cull_valid_o   = f_valid & ~ok;
  assign cull_outcome_o = outcome;

  fxr_setup_fields #(.WindowIntBits(WindowIntBits)) u_core (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .in_valid_i  (in_valid_i),
    .in_ready_o  (in_ready_o),
    .prim_i      (in_i.prim),
    .v0_x_i      (in_i.v0_x),     .v0_y_i(in_i.v0_y),
    .v0_ax_i     (in_i.v0_ax),    .v0_ay_i(in_i.v0_ay),
    .v0_z_i      (in_i.v0_z),
    .v0_rw_neg_i (in_i.v0_rw_neg), .v0_rw_sig_i(in_i.v0_rw_sig), .v0_rw_exp_i(in_i.v0_rw_exp),
    .v0_vw0_neg_i(in_i.v0_vw0_neg), .v0_vw0_sig_i(in_i.v0_vw0_sig), .v0_vw0_exp_i(in_i.v0_vw0_exp),
    .v0_vw1_neg_i(in_i.v0_vw1_neg), .v0_vw1_sig_i(in_i.v0_vw1_sig), .v0_vw1_exp_i(in_i.v0_vw1_exp),
    .v1_x_i      (in_i.v1_x),     .v1_y_i(in_i.v1_y),
    .v1_ax_i     (in_i.v1_ax),    .v1_ay_i(in_i.v1_ay),
    .v1_z_i      (in_i.v1_z),
    .v1_rw_neg_i (in_i.v1_rw_neg), .v1_rw_sig_i(in_i.v1_rw_sig), .v1_rw_exp_i(in_i.v1_rw_exp),
    .v1_vw0_neg_i(in_i.v1_vw0_neg), .v1_vw0_sig_i(in_i.v1_vw0_sig), .v1_vw0_exp_i(in_i.v1_vw0_exp),
    .v1_vw1_neg_i(in_i.v1_vw1_neg), .v1_vw1_sig_i(in_i.v1_vw1_sig), .v1_vw1_exp_i(in_i.v1_vw1_exp),
    .v2_x_i      (in_i.v2_x),     .v2_y_i(in_i.v2_y),
    .v2_ax_i     (in_i.v2_ax),    .v2_ay_i(in_i.v2_ay),
    .v2_z_i      (in_i.v2_z),
    .v2_rw_neg_i (in_i.v2_rw_neg), .v2_rw_sig_i(in_i.v2_rw_sig), .v2_rw_exp_i(in_i.v2_rw_exp),
    .v2_vw0_neg_i(in_i.v2_vw0_neg), .v2_vw0_sig_i(in_i.v2_vw0_sig), .v2_vw0_exp_i(in_i.v2_vw0_exp),
    .v2_vw1_neg_i(in_i.v2_vw1_neg), .v2_vw1_sig_i(in_i.v2_vw1_sig), .v2_vw1_exp_i(in_i.v2_vw1_exp),
    .viewport_x_i(viewport_x_i),
    .viewport_y_i(viewport_y_i),
    .viewport_w_i(viewport_w_i),
    .viewport_h_i(viewport_h_i),
    .scissor_x_i (scissor_x_i),
    .scissor_y_i (scissor_y_i),
    .scissor_w_i (scissor_w_i),
    .scissor_h_i (scissor_h_i),
    .cull_i      (cull_i),
    .front_ccw_i (front_ccw_i),
    .interp_i    (interp_i),
    .out_valid_o (f_valid),
    .out_ready_i (f_ready),
    .outcome_o   (outcome),
    .out_prim_o  (out_o.prim),
    .e0_a_o      (out_o.e0_a), .e0_b_o(out_o.e0_b), .e0_c_o(out_o.e0_c), .e0_bias_o(out_o.e0_bias),
    .e1_a_o      (out_o.e1_a), .e1_b_o(out_o.e1_b), .e1_c_o(out_o.e1_c), .e1_bias_o(out_o.e1_bias),
    .e2_a_o      (out_o.e2_a), .e2_b_o(out_o.e2_b), .e2_c_o(out_o.e2_c), .e2_bias_o(out_o.e2_bias),
    .area2_o     (out_o.area2),
    .front_o     (out_o.front),
    .x0_o        (out_o.x0), .x1_o(out_o.x1), .y0_o(out_o.y0), .y1_o(out_o.y1),
    .z_c_o       (out_o.z_c), .z_dx_o(out_o.z_dx), .z_dy_o(out_o.z_dy),
    .z_i0_o      (out_o.z_i0), .z_j0_o(out_o.z_j0),
    .z_den_o     (out_o.z_den),
    .den_c_o     (out_o.den_c), .den_dx_o(out_o.den_dx), .den_dy_o(out_o.den_dy),
    .den_i0_o    (out_o.den_i0), .den_j0_o(out_o.den_j0),
    .den_exp_o   (out_o.den_exp),
    .num0_c_o    (out_o.num0_c), .num0_dx_o(out_o.num0_dx), .num0_dy_o(out_o.num0_dy),
    .num0_i0_o   (out_o.num0_i0), .num0_j0_o(out_o.num0_j0),
    .num0_exp_o  (out_o.num0_exp),
    .num1_c_o    (out_o.num1_c), .num1_dx_o(out_o.num1_dx), .num1_dy_o(out_o.num1_dy),
    .num1_i0_o   (out_o.num1_i0), .num1_j0_o(out_o.num1_j0),
    .num1_exp_o  (out_o.num1_exp)
  );
endmodule

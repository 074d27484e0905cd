// fxr_viewport: stage 4 of the raster unit (the model's "viewport" stage, issue 11): the snap of
// every vertex to the subpixel grid and the attribute positions. Model: fxr::ViewportStage
// (model/stages/viewport.hpp: snap_window; model/stages/attr.hpp: attr_window, attr_depth,
// attr_quotient); vectors: the transaction dumps' viewport.in / viewport.out (docs/vectors.md,
// "Transaction vectors"; tb/txn/viewport_txn_test.cpp); docs/rtl.md, "fxr_viewport".
//
// Ports:
//   clk_i, rst_ni                 clock, active-low asynchronous reset
//   in_valid_i / in_ready_o       input handshake (transfer when both are high)
//   in_i                          fxr_rec_pkg::recip_triangle_t (RecipTriangle::visit(): prim, per
//                                 vertex x, y, z, w, wa, the varyings, then 1/w of each vertex)
//   viewport_x_i, viewport_y_i    draw state (register block): the viewport origin (signed
//   viewport_w_i, viewport_h_i    WindowIntBits) and size (WindowIntBits + 1, ≥ 1)
//   interp_i                      InterpMode: 0 perspective, 1 affine (v_k itself instead of v_k/w)
//   out_valid_o / out_ready_i     output handshake
//   out_o                         fxr_rec_pkg::setup_triangle_t (SetupTriangle::visit())
//   rej_range_o                   a triangle is dropped in this clock (a snapped or attribute
//                                 position outside its code: the model's RejectedRange), one pulse
//                                 per triangle, for the unit's counter
//
// Function, per vertex (exact, one rounding each):
//   x, y    snap_window(x_c·r): fxr_viewport_snap, SnapLanes units shared over the slots;
//   ax, ay  attr_window(x_c / w_a), z = attr_depth(z_c / w_a), rw = attr_quotient(1 / w_a),
//   vw_k    attr_quotient(v_k / w_a) (affine: v_k rounded to AttrSigBits, a division by 1):
//           (4 + NumVaryings) correctly rounded quotients per vertex on Lanes pipelined restoring
//           dividers (fxr_viewport_lane); w_a = wa (the attribute w) when set, else w.
// Schedule: a triangle's J = 3·(4 + NumVaryings) quotient jobs are issued Lanes per clock over
// Slots = ceil(J / Lanes) clocks (the initiation interval); the snaps run in the same slots. The
// results come out of the lanes in issue order after QuotBits + 2 clocks and are written into the
// output register field by field; the snaps and prim wait in a small FIFO. Latency Slots +
// QuotBits + 2 clocks. One pipeline enable (out register free or taken) stalls everything.
// Only the attribute-position configuration (raster.attr_subpixel_bits > subpixel_bits, the
// default) is built: on the other path the stage is products only (not yet in RTL).
module fxr_viewport #(
  parameter int Lanes = fxr_rec_pkg::ViewportLanes  // model/stages/viewport.hpp kViewportLanes
) (
  input  logic                                                  clk_i,
  input  logic                                                  rst_ni,
  input  logic                                                  in_valid_i,
  output logic                                                  in_ready_o,
  input  fxr_rec_pkg::recip_triangle_t                          in_i,
  input  logic signed [fxr_config_pkg::RasterWindowIntBits-1:0] viewport_x_i,
  input  logic signed [fxr_config_pkg::RasterWindowIntBits-1:0] viewport_y_i,
  input  logic signed [fxr_config_pkg::RasterWindowIntBits:0]   viewport_w_i,
  input  logic signed [fxr_config_pkg::RasterWindowIntBits:0]   viewport_h_i,
  input  logic                                                  interp_i,
  output logic                                                  out_valid_o,
  input  logic                                                  out_ready_i,
  output fxr_rec_pkg::setup_triangle_t                          out_o,
  output logic                                                  rej_range_o
);
  fxr_viewport_core #(.Lanes(Lanes)) u_core (
    .clk_i, .rst_ni, .in_valid_i, .in_ready_o, .in_i, .viewport_x_i, .viewport_y_i, .viewport_w_i, .viewport_h_i,
    .interp_i, .out_valid_o, .out_ready_i, .out_o, .rej_range_o
  );
endmodule

// fxr_line_rec: stage 6L, line traversal with record ports (issue 15). One segment's equations in,
// its covered pixels inside the draw rectangle out, in the model's order. Model:
// fxr::LineTraverseStage (model/stages/line_setup.hpp, stage name "line"); the walk is
// rtl/fxr_line.sv; vectors: the transaction dumps' line.in / line.out (docs/vectors.md,
// "Transaction vectors"; tb/txn/line_txn_test.cpp); docs/lines.md, "RTL".
//
// Ports:
//   clk_i, rst_ni                 clock, active-low asynchronous reset
//   in_valid_i / in_ready_o       input handshake (transfer when both are high)
//   in_i                          fxr_rec_pkg::line_equations_t (LineEquations::visit(); only prim,
//                                 the snapped endpoints x0, y0, x1, y1 and the rectangle are used)
//   out_valid_o / out_ready_i     output handshake
//   out_o                         fxr_rec_pkg::line_fragment_t: prim, pixel x, y
//
// Function: fxr_line walks the whole snapped segment (its guard-band part included); a pixel
// outside rect_x0 ≤ x ≤ rect_x1, rect_y0 ≤ y ≤ rect_y1 (viewport ∩ scissor) is dropped here,
// without a cycle of its own (fxr_line's output is taken in the clock it appears). The segment's
// prim and rectangle are latched with the input; a new segment is accepted while fxr_line is idle
// and its last pixel has left (or leaves in this clock), so every pixel carries its own segment's
// prim. Timing: fxr_line's (one set-up cycle, then one major-axis step per clock).
module fxr_line_rec #(
  parameter int WindowIntBits = fxr_config_pkg::RasterWindowIntBits
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  input  logic                         in_valid_i,
  output logic                         in_ready_o,
  /* verilator lint_off UNUSEDSIGNAL */
  input  fxr_rec_pkg::line_equations_t in_i,  // the interpolators' fields: not used here
  /* verilator lint_on UNUSEDSIGNAL */
  output logic                         out_valid_o,
  input  logic                         out_ready_i,
  output fxr_rec_pkg::line_fragment_t  out_o
);
  typedef logic signed [WindowIntBits-1:0] pix_t;

  logic line_ready, line_valid, line_take, in_rect;
  pix_t line_x, line_y;
  pix_t rx0_q, rx1_q, ry0_q, ry1_q;
  logic [$bits(in_i.prim)-1:0] prim_q;

  assign in_rect = line_x >= rx0_q && line_x <= rx1_q && line_y >= ry0_q && line_y <= ry1_q;
  assign line_take = in_rect ? out_ready_i : 1'b1;  // outside the rectangle: dropped at once
  assign in_ready_o = line_ready && (!line_valid || line_take);

  fxr_line u_line (
    .clk_i,
    .rst_ni,
    .in_valid_i (in_valid_i && in_ready_o),
    .in_ready_o (line_ready),
    .in_x0_i    ($signed(in_i.x0)),
    .in_y0_i    ($signed(in_i.y0)),
    .in_x1_i    ($signed(in_i.x1)),
    .in_y1_i    ($signed(in_i.y1)),
    .out_valid_o(line_valid),
    .out_ready_i(line_take),
    .out_x_o    (line_x),
    .out_y_o    (line_y)
  );

  always_ff @(posedge clk_i) begin
    if (in_valid_i && in_ready_o) begin
      prim_q <= in_i.prim;
      rx0_q <= $signed(in_i.rect_x0);
      rx1_q <= $signed(in_i.rect_x1);
      ry0_q <= $signed(in_i.rect_y0);
      ry1_q <= $signed(in_i.rect_y1);
    end
  end

  assign out_valid_o = line_valid && in_rect;
  assign out_o.prim = prim_q;
  assign out_o.x = line_x;
  assign out_o.y = line_y;
endmodule

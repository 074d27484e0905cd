// fxr_clip: stage 2 of the raster unit, the clipper, on fxr_rec_pkg's record ports: exact_triangle_t
// in, 0..n clipped_triangle_t out. The datapath and the port descriptions are in
// rtl/fxr_clip_core.sv (flat ports, the same bits); docs/rtl.md, "fxr_clip".
module fxr_clip (
  input  logic                                           clk_i,
  input  logic                                           rst_ni,
  input  logic [fxr_config_pkg::RasterWindowIntBits-1:0] viewport_x_i,
  input  logic [fxr_config_pkg::RasterWindowIntBits-1:0] viewport_y_i,
  input  logic [fxr_config_pkg::RasterWindowIntBits:0]   viewport_w_i,
  input  logic [fxr_config_pkg::RasterWindowIntBits:0]   viewport_h_i,
  input  logic                                           in_valid_i,
  output logic                                           in_ready_o,
  input  fxr_rec_pkg::exact_triangle_t                   in_i,
  output logic                                           out_valid_o,
  input  logic                                           out_ready_i,
  output fxr_rec_pkg::clipped_triangle_t                 out_o,
  output logic                                           out_last_o,
  output logic                                           done_o,
  output logic [fxr_rec_pkg::ClipOutcomeBits-1:0]        done_outcome_o,
  output logic [$clog2(fxr_rec_pkg::ClipMaxPolyVerts * fxr_rec_pkg::ClipNumPlanes + 1)-1:0] done_created_o
);
  logic [fxr_rec_pkg::ExactTriangleBits-1:0] in_flat;
  logic [fxr_rec_pkg::ClippedTriangleBits-1:0] out_flat;
  assign in_flat = in_i;
  assign out_o = out_flat;
  fxr_clip_core u_core (
    .clk_i, .rst_ni, .viewport_x_i, .viewport_y_i, .viewport_w_i, .viewport_h_i,
    .in_valid_i, .in_ready_o, .in_i(in_flat), .out_valid_o, .out_ready_i, .out_o(out_flat), .out_last_o,
    .done_o, .done_outcome_o, .done_created_o);
endmodule

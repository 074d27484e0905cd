// fxr_viewport with 7 divider lanes (tb/txn/viewport_txn_test.cpp): ceil(3·(4 + NumVaryings) / 7) clocks per
// triangle, the last slot partly empty, two snap units. The configuration comes from the fxr_config_pkg it is verilated with.
module fxr_viewport_lanes7 (
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
  fxr_viewport #(.Lanes(7)) u_viewport (
    .clk_i, .rst_ni, .in_valid_i, .in_ready_o, .in_i, .viewport_x_i, .viewport_y_i, .viewport_w_i, .viewport_h_i,
    .interp_i, .out_valid_o, .out_ready_i, .out_o, .rej_range_o
  );
endmodule

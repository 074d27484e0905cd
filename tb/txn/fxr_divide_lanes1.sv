// fxr_divide with one divider lane (tb/txn/divide_txn_test.cpp): NumVaryings clocks per fragment.
// The configuration comes from the fxr_config_pkg it is verilated with.
module fxr_divide_lanes1 (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  input  logic                       in_valid_i,
  output logic                       in_ready_o,
  input  fxr_rec_pkg::plane_sample_t in_i,
  output logic                       out_valid_o,
  input  logic                       out_ready_i,
  output fxr_rec_pkg::fragment_t     out_o
);
  fxr_divide #(
    .Lanes(1)
  ) u_divide (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .in_valid_i (in_valid_i),
    .in_ready_o (in_ready_o),
    .in_i       (in_i),
    .out_valid_o(out_valid_o),
    .out_ready_i(out_ready_i),
    .out_o      (out_o)
  );
endmodule

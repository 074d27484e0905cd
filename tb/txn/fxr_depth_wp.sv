// fxr_depth_wp: rtl/fxr_depth.sv with its separate write channel (WritePort = 1), for
// tb/txn/depth_txn_test.cpp (docs/rtl.md, "fxr_depth"). Same ports as fxr_depth.
module fxr_depth_wp #(
  localparam int PB       = fxr_config_pkg::RasterWindowIntBits,
  localparam int Db       = fxr_config_pkg::RasterDepthFormat == fxr_config_pkg::RasterDepthFormatD24 ? 24 : 16,
  localparam int AddrBits = 2 * PB,
  localparam int NumFuncs = 8,                 // DepthFunc values, as fxr_depth
  localparam int FuncBits = $clog2(NumFuncs)   // kDepthFuncBits
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  input  logic [FuncBits-1:0]        depth_func_i,
  input  logic                       depth_test_i,
  input  logic                       depth_write_i,
  input  logic [PB-1:0]              viewport_x_i,
  input  logic [PB-1:0]              viewport_y_i,
  input  logic [PB:0]                viewport_w_i,
  input  logic                       in_valid_i,
  output logic                       in_ready_o,
  input  fxr_rec_pkg::plane_sample_t in_i,
  output logic                       out_valid_o,
  input  logic                       out_ready_i,
  output fxr_rec_pkg::plane_sample_t out_o,
  output logic                       mem_req_valid_o,
  input  logic                       mem_req_ready_i,
  output logic                       mem_req_write_o,
  output logic [AddrBits-1:0]        mem_req_addr_o,
  output logic [Db-1:0]              mem_req_wdata_o,
  input  logic                       mem_rsp_valid_i,
  input  logic [Db-1:0]              mem_rsp_rdata_i,
  output logic                       mem_wr_valid_o,
  input  logic                       mem_wr_ready_i,
  output logic [AddrBits-1:0]        mem_wr_addr_o,
  output logic [Db-1:0]              mem_wr_data_o
);
  fxr_depth #(.WritePort(1'b1)) u_depth (.*);
endmodule

// fxr_depth: stage 8, the depth test (issue 10). Plane samples in, the samples that pass out (in
// order), against a depth buffer behind a memory port with variable latency. Model:
// fxr::DepthStage (model/stages/depth.hpp); algorithm and figures: docs/rtl.md, "fxr_depth";
// vectors: the transaction dumps' depth.in / depth.out (docs/vectors.md; the dump re-steps depth
// on a freshly cleared buffer), tb/txn/depth_txn_test.cpp with the memory model tb/depth_mem.hpp.
//
// Ports:
//   clk_i, rst_ni                   clock, active-low asynchronous reset
//   depth_func_i                    DepthFunc: 0 never, 1 less, 2 equal, 3 lequal, 4 greater,
//                                   5 notequal, 6 gequal, 7 always (`incoming func stored`)
//   depth_test_i, depth_write_i     the draw state's test enable and write mask (test off: every
//                                   sample passes, no memory access)
//   viewport_x_i, viewport_y_i      buffer origin (signed pixels), as fxr_setup's ports
//   viewport_w_i                    buffer row length (pixels)
//   (the draw state must not change while samples are in flight)
//   in_valid_i / in_ready_o         input handshake
//   in_i                            fxr_rec_pkg::plane_sample_t
//   out_valid_o / out_ready_i       output handshake
//   out_o                           the passing samples, unchanged, in input order
//   mem_req_valid_o / _ready_i      memory request handshake
//   mem_req_write_o                 1 write, 0 read
//   mem_req_addr_o                  pixel index (y − viewport_y)·viewport_w + (x − viewport_x)
//   mem_req_wdata_o                 the depth code to write
//   mem_rsp_valid_i, mem_rsp_rdata_i  read response (always accepted: every read has its slot)
//   mem_wr_valid_o / _ready_i,     the write channel when WritePort = 1 (then the request port
//   mem_wr_addr_o, mem_wr_data_o   carries only reads); unused (valid 0) when WritePort = 0
// The memory performs requests in the order it accepts them and returns read responses in that
// order, after any latency (at least one clock); writes have no response. With the write
// channel, a read accepted after a write was accepted must see it (a read and a write accepted
// in the same clock never share an address: the hazard stall below).
//
// Algorithm. An in-order queue of QueueDepth samples: a sample enters when its read request is
// accepted (test on) and leaves from the head once its stored code has come back: compare,
// then the sample goes to a 2-entry output FIFO when it passes and its write request is issued
// in the same clock (passes, test on and write mask on). Hazard: a sample whose pixel is in the
// queue waits at the input (write mask on) until that entry has left — its write is then
// accepted before the new read, so the read sees it. So the outputs and the final buffer are
// the model's sequential ones whatever the latency.
//
// Timing: one sample per clock while the queue covers the memory's round trip (QueueDepth ≥
// latency + 2) and no hazard; with WritePort = 0 a write and a read share the port (the write
// first), so with the write mask on, each passing sample costs one more port slot; with
// WritePort = 1 reads and writes each have their own channel.
module fxr_depth #(
  parameter int WindowIntBits = fxr_config_pkg::RasterWindowIntBits,
  parameter int DepthFormat   = fxr_config_pkg::RasterDepthFormat,  // raster_depth_format_e
  parameter int QueueDepth    = 8,  // samples in flight (a power of two; kDepthQueueDepth of the model's cost)
  parameter bit WritePort     = 1'b0,  // 1: writes on the mem_wr_* channel (a second memory port)
  // derived (model/unit/io.hpp, model/stages/setup.hpp)
  localparam int Db        = DepthFormat == fxr_config_pkg::RasterDepthFormatD24 ? 24 : 16,
  localparam int PB        = WindowIntBits,                 // pixel index (signed)
  localparam int AddrBits  = 2 * WindowIntBits,             // pixel index of the buffer
  localparam int NumFuncs  = 8,                             // DepthFunc values
  localparam int FuncBits  = $clog2(NumFuncs),              // kDepthFuncBits
  localparam int QB        = $clog2(QueueDepth),
  localparam int PSB       = fxr_rec_pkg::PlaneSampleBits
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic [FuncBits-1:0]           depth_func_i,
  input  logic                          depth_test_i,
  input  logic                          depth_write_i,
  input  logic [PB-1:0]                 viewport_x_i,
  input  logic [PB-1:0]                 viewport_y_i,
  input  logic [PB:0]                   viewport_w_i,
  input  logic                          in_valid_i,
  output logic                          in_ready_o,
  input  fxr_rec_pkg::plane_sample_t    in_i,
  output logic                          out_valid_o,
  input  logic                          out_ready_i,
  output fxr_rec_pkg::plane_sample_t    out_o,
  output logic                          mem_req_valid_o,
  input  logic                          mem_req_ready_i,
  output logic                          mem_req_write_o,
  output logic [AddrBits-1:0]           mem_req_addr_o,
  output logic [Db-1:0]                 mem_req_wdata_o,
  input  logic                          mem_rsp_valid_i,
  input  logic [Db-1:0]                 mem_rsp_rdata_i,
  output logic                          mem_wr_valid_o,
  input  logic                          mem_wr_ready_i,
  output logic [AddrBits-1:0]           mem_wr_addr_o,
  output logic [Db-1:0]                 mem_wr_data_o
);

  if (QueueDepth < 2 || (1 << QB) != QueueDepth) begin : g_param_check
    $error("fxr_depth: QueueDepth must be a power of two >= 2");
  end

  // ---- input: the buffer address ------------------------------------------------------------
  logic signed [PB:0]       in_dx, in_dy;
  /* verilator lint_off UNUSEDSIGNAL */  // the index is below 2^AddrBits for a pixel in the viewport
  logic signed [2*PB+1:0]   in_row;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [AddrBits-1:0]      in_addr;
  always_comb begin
    in_dx   = (PB + 1)'($signed(in_i.x)) - (PB + 1)'($signed(viewport_x_i));
    in_dy   = (PB + 1)'($signed(in_i.y)) - (PB + 1)'($signed(viewport_y_i));
    in_row  = in_dy * $signed(viewport_w_i);
    in_addr = in_row[AddrBits-1:0] + AddrBits'(in_dx);
  end

  // ---- the queue ------------------------------------------------------------------------------
  logic [PSB-1:0]             q_rec_q [QueueDepth];     // (arrays of plain vectors: Yosys 0.23)
  logic [AddrBits-1:0]        q_addr_q [QueueDepth];
  logic [Db-1:0]              q_depth_q [QueueDepth];   // the sample's code (in_i.depth)
  logic [Db-1:0]              q_stored_q [QueueDepth];
  logic [QueueDepth-1:0]      q_valid_q, q_data_q;  // occupied / stored code arrived
  logic [QB-1:0]              head_q, tail_q, rsp_q;
  logic [QB:0]                count_q;

  logic full, hazard;
  always_comb begin
    full   = count_q == (QB + 1)'(QueueDepth);
    hazard = 1'b0;
    for (int e = 0; e < QueueDepth; e++)
      if (q_valid_q[e] && q_addr_q[e] == in_addr) hazard = depth_test_i & depth_write_i;
  end

  // ---- head: compare ------------------------------------------------------------------------
  logic [Db-1:0] h_in, h_st;
  logic          h_ready, h_pass, h_write;
  always_comb begin
    h_in    = q_depth_q[head_q];
    h_st    = q_stored_q[head_q];
    h_ready = q_valid_q[head_q] && (!depth_test_i || q_data_q[head_q]);
    unique case (depth_func_i)
      FuncBits'(0): h_pass = 1'b0;
      FuncBits'(1): h_pass = h_in < h_st;
      FuncBits'(2): h_pass = h_in == h_st;
      FuncBits'(3): h_pass = h_in <= h_st;
      FuncBits'(4): h_pass = h_in > h_st;
      FuncBits'(5): h_pass = h_in != h_st;
      FuncBits'(6): h_pass = h_in >= h_st;
      default: h_pass = 1'b1;
    endcase
    if (!depth_test_i) h_pass = 1'b1;
    h_write = depth_test_i & depth_write_i & h_pass;
  end

  // ---- output FIFO (2 entries) ----------------------------------------------------------------
  logic [PSB-1:0]             of_rec_q [2];
  logic                       of_rd_q, of_wr_q;
  logic [1:0]                 of_count_q;
  logic                       of_room;
  assign of_room = of_count_q != 2'd2;

  // ---- the memory port: the head's write first, then the input's read -----------------------
  // (WritePort: the write on its own channel, the request port for reads only.)
  logic wr_req, rd_req, retire, in_fire, rsp_take, out_fire, port_wr, wr_ready;
  always_comb begin
    wr_req   = h_ready & h_write & of_room;
    port_wr  = wr_req & ~WritePort;                 // the write holds the request port
    wr_ready = WritePort ? mem_wr_ready_i : mem_req_ready_i;
    rd_req   = in_valid_i & depth_test_i & ~full & ~hazard & ~port_wr;
    retire   = h_ready & (~h_pass | of_room) & (~h_write | wr_ready);
    in_ready_o = ~full & ~hazard & (~depth_test_i | (~port_wr & mem_req_ready_i));
    in_fire  = in_valid_i & in_ready_o;
    rsp_take = mem_rsp_valid_i;
    out_fire = out_valid_o & out_ready_i;
  end
  assign mem_req_valid_o = port_wr | rd_req;
  assign mem_req_write_o = port_wr;
  assign mem_req_addr_o  = port_wr ? q_addr_q[head_q] : in_addr;
  assign mem_req_wdata_o = h_in;
  assign mem_wr_valid_o  = wr_req & WritePort;
  assign mem_wr_addr_o   = q_addr_q[head_q];
  assign mem_wr_data_o   = h_in;
  assign out_valid_o     = of_count_q != 2'd0;
  assign out_o           = of_rec_q[of_rd_q];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      q_valid_q  <= '0;
      q_data_q   <= '0;
      head_q     <= '0;
      tail_q     <= '0;
      rsp_q      <= '0;
      count_q    <= '0;
      of_rd_q    <= 1'b0;
      of_wr_q    <= 1'b0;
      of_count_q <= '0;
    end else begin
      if (in_fire) begin
        q_valid_q[tail_q] <= 1'b1;
        q_data_q[tail_q]  <= 1'b0;
        tail_q <= tail_q + QB'(1);
      end
      if (rsp_take) begin
        q_data_q[rsp_q] <= 1'b1;
        rsp_q <= rsp_q + QB'(1);
      end
      if (retire) begin
        q_valid_q[head_q] <= 1'b0;
        head_q <= head_q + QB'(1);
      end
      count_q <= count_q + (QB + 1)'(in_fire) - (QB + 1)'(retire);
      if (retire && h_pass) of_wr_q <= ~of_wr_q;
      if (out_fire) of_rd_q <= ~of_rd_q;
      of_count_q <= of_count_q + 2'(retire && h_pass) - 2'(out_fire);
    end
  end

  always_ff @(posedge clk_i) begin
    if (in_fire) begin
      q_rec_q[tail_q]  <= in_i;
      q_addr_q[tail_q] <= in_addr;
      q_depth_q[tail_q] <= in_i.depth;
    end
    if (rsp_take) q_stored_q[rsp_q] <= mem_rsp_rdata_i;
    if (retire && h_pass) of_rec_q[of_wr_q] <= q_rec_q[head_q];
  end

endmodule

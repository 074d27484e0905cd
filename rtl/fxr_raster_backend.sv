// fxr_raster_backend: the raster unit's back end (issue 10), stages 5–9 as one valid / ready
// chain: fxr_setup → fxr_traverse → fxr_interp → fxr_depth → fxr_divide, snapped triangles in,
// the fragments that pass the depth test out with their varyings, in the model's order (model/unit/chain.hpp, FragmentChain), the
// depth buffer behind a memory port and the model's RasterStats back-end counters as registers.
// docs/rtl.md, "fxr_raster_backend"; co-simulation: tb/backend_test.cpp.
//
// Ports:
//   clk_i, rst_ni                   clock, active-low asynchronous reset
//   in_valid_i / in_ready_o, in_i   fxr_rec_pkg::setup_triangle_t (the model's setup.in)
//   viewport_*_i, scissor_*_i,      the draw state (DrawState, the register block): as fxr_setup
//   cull_i, front_ccw_i, interp_i,  and fxr_depth; stable while triangles are in flight
//   depth_func_i, depth_test_i,
//   depth_write_i
//   out_valid_o / out_ready_i,      fxr_rec_pkg::fragment_t: the fragments that pass (the model's
//   out_o                           divide.out: prim, x, y, depth code, every varying)
//   mem_req_*, mem_rsp_*            fxr_depth's depth-buffer port (request / response, any latency)
//   mem_wr_*                        its write channel (DepthWritePort = 1: writes here, reads on
//                                   mem_req_*; 0: unused, mem_wr_valid_o low)
//   stat_*_o                        counters since reset (StatBits wide, wrapping):
//     tri_in        triangles accepted
//     tri_drawn     triangles set up (SetupOutcome::Ok)
//     tri_zero_area, tri_backface, tri_no_samples, tri_range   culled / rejected at setup, by the
//                   model's outcome, per setup triangle (RasterStats::tris; the model's
//                   dispositions prims_* count per primitive: docs/pipeline.md, "Statistics")
//     spans         spans out of traversal
//     frag_generated  RasterStats::fragments_generated (covered pixels: x1 − x0 + 1 per span)
//     frag_depth_pass RasterStats::fragments_depth_pass (samples out of fxr_depth, into fxr_divide)
//     frag_depth_fail RasterStats::fragments_depth_fail (samples into fxr_depth − passed: exact
//                   once the samples in flight have left the depth unit's queue)
//   perf_*_o                        clocks in which a stage held a result its successor did not
//                                   take (what limits the throughput, docs/rtl.md):
//     setup_stall   a drawn triangle waits for traversal (busy) or the FIFO
//     fifo_full     … of which the equations FIFO was full
//     span_stall    a span waits for fxr_interp (busy with the span before)
//     span_wait     a span waits for its equations (the FIFO head being retired)
//     sample_stall  a sample waits for fxr_depth (memory latency / back-pressure, hazards)
//     pass_stall    a passing sample waits for fxr_divide
//     out_stall     a fragment waits at out_o (out_ready_i low)
//
// The triangle's equations for fxr_interp's ctx_i. fxr_traverse accepts the next triangle while
// the spans of the previous one still travel to fxr_interp, so the equations wait in a FIFO of
// TriFifoDepth entries, written when traversal accepts a triangle. Traversal carries a tag
// instead of the primitive id (its prim field passes through to the spans untouched): the FIFO
// write index. A span meets its equations when its tag is the FIFO head's; the primitive id is
// put back from the FIFO. The head is retired once traversal is past it (a register fin_q: every
// tag below it has all its spans out of traversal) and no span of it is waiting; a span of the
// entry after the head may use that entry directly (the head is retired in the same clock), so
// consecutive one-span triangles go at one span per clock.
module fxr_raster_backend #(
  parameter int WindowIntBits   = fxr_config_pkg::RasterWindowIntBits,
  parameter int DepthFormat     = fxr_config_pkg::RasterDepthFormat,  // raster_depth_format_e
  parameter int TriFifoDepth    = 4,   // triangles between traversal's input and fxr_interp (power of two, ≥ 2)
  parameter int DepthQueueDepth = 8,   // fxr_depth's samples in flight (power of two)
  parameter bit DepthWritePort  = 1'b1,  // fxr_depth's WritePort: writes on mem_wr_* (0: on mem_req_*)
  parameter int StatBits        = 32,  // counter registers (wrap at 2^StatBits)
  parameter int InterpDivSteps  = 4,   // fxr_interp's DivStepsPerClock (quotient bits per clock)
  parameter int DivideLanes     = fxr_rec_pkg::NumVaryings,  // fxr_divide's Lanes (varyings per clock)
  // derived (model/unit/io.hpp, model/stages/setup.hpp)
  localparam int Db       = DepthFormat == fxr_config_pkg::RasterDepthFormatD24 ? 24 : 16,
  localparam int PB       = WindowIntBits,      // pixel index (signed)
  localparam int AddrBits = 2 * WindowIntBits,  // fxr_depth's buffer index
  localparam int FuncBits = $clog2(8),          // kDepthFuncBits: 8 DepthFunc values
  localparam int FB       = $clog2(TriFifoDepth) + 1  // FIFO pointers and tags (one wrap bit)
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic                          in_valid_i,
  output logic                          in_ready_o,
  input  fxr_rec_pkg::setup_triangle_t  in_i,
  input  logic [PB-1:0]                 viewport_x_i,
  input  logic [PB-1:0]                 viewport_y_i,
  input  logic [PB:0]                   viewport_w_i,
  input  logic [PB:0]                   viewport_h_i,
  input  logic [PB-1:0]                 scissor_x_i,
  input  logic [PB-1:0]                 scissor_y_i,
  input  logic [PB:0]                   scissor_w_i,
  input  logic [PB:0]                   scissor_h_i,
  input  logic [1:0]                    cull_i,
  input  logic                          front_ccw_i,
  input  logic                          interp_i,
  input  logic [FuncBits-1:0]           depth_func_i,
  input  logic                          depth_test_i,
  input  logic                          depth_write_i,
  output logic                          out_valid_o,
  input  logic                          out_ready_i,
  output fxr_rec_pkg::fragment_t        out_o,
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
  output logic [Db-1:0]                 mem_wr_data_o,
  output logic [StatBits-1:0]           stat_tri_in_o,
  output logic [StatBits-1:0]           stat_tri_drawn_o,
  output logic [StatBits-1:0]           stat_tri_zero_area_o,
  output logic [StatBits-1:0]           stat_tri_backface_o,
  output logic [StatBits-1:0]           stat_tri_no_samples_o,
  output logic [StatBits-1:0]           stat_tri_range_o,
  output logic [StatBits-1:0]           stat_spans_o,
  output logic [StatBits-1:0]           stat_frag_generated_o,
  output logic [StatBits-1:0]           stat_frag_depth_pass_o,
  output logic [StatBits-1:0]           stat_frag_depth_fail_o,
  output logic [StatBits-1:0]           perf_setup_stall_o,
  output logic [StatBits-1:0]           perf_fifo_full_o,
  output logic [StatBits-1:0]           perf_span_stall_o,
  output logic [StatBits-1:0]           perf_span_wait_o,
  output logic [StatBits-1:0]           perf_sample_stall_o,
  output logic [StatBits-1:0]           perf_pass_stall_o,
  output logic [StatBits-1:0]           perf_out_stall_o
);
  if (TriFifoDepth < 2 || (TriFifoDepth & (TriFifoDepth - 1)) != 0) begin : g_bad_depth
    $error("fxr_raster_backend: TriFifoDepth must be a power of two, at least 2");
  end

  // ---- stage 5: setup ---------------------------------------------------------------------------
  logic                             su_valid, su_ready, su_cull_valid;
  logic [2:0]                       su_cull_outcome;
  fxr_rec_pkg::triangle_equations_t su_out;
  fxr_setup #(.WindowIntBits(WindowIntBits)) u_setup (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .in_valid_i    (in_valid_i),
    .in_ready_o    (in_ready_o),
    .in_i          (in_i),
    .viewport_x_i  (viewport_x_i),
    .viewport_y_i  (viewport_y_i),
    .viewport_w_i  (viewport_w_i),
    .viewport_h_i  (viewport_h_i),
    .scissor_x_i   (scissor_x_i),
    .scissor_y_i   (scissor_y_i),
    .scissor_w_i   (scissor_w_i),
    .scissor_h_i   (scissor_h_i),
    .cull_i        (cull_i),
    .front_ccw_i   (front_ccw_i),
    .interp_i      (interp_i),
    .out_valid_o   (su_valid),
    .out_ready_i   (su_ready),
    .out_o         (su_out),
    .cull_valid_o  (su_cull_valid),
    .cull_outcome_o(su_cull_outcome)
  );

  // ---- the equations FIFO (setup → traversal, kept for interp's ctx_i) ------------------------
  // One flat vector, entry k at [k·EqBits +: EqBits] (Yosys 0.23 reads an unpacked array of
  // packed structs as a single entry, and no packed 2-D arrays).
  localparam int EqBits = fxr_rec_pkg::TriangleEquationsBits;
  logic [TriFifoDepth*EqBits-1:0] eq_q;
  logic [FB-1:0] wr_q, rd_q, fin_q;
  logic          fifo_full, fifo_empty, push, pop;
  assign fifo_full  = (wr_q - rd_q) == FB'(TriFifoDepth);
  assign fifo_empty = wr_q == rd_q;

  logic                             tv_in_valid, tv_in_ready;
  fxr_rec_pkg::triangle_equations_t tv_in;
  // The record is copied only with setup's output valid ('0 otherwise: traversal reads it with
  // in_valid_i only), so that a simulator skips the 2,179-bit copy on idle clocks.
  always_comb begin
    tv_in = '0;
    if (su_valid) begin
      tv_in      = su_out;
      tv_in.prim = 32'(wr_q);  // the tag (the primitive id is kept in the FIFO)
    end
  end
  assign tv_in_valid = su_valid & ~fifo_full;
  assign su_ready    = tv_in_ready & ~fifo_full;
  assign push        = tv_in_valid & tv_in_ready;

  // ---- stage 6: traversal -----------------------------------------------------------------------
  logic               tv_out_valid, tv_out_ready;
  fxr_rec_pkg::span_t tv_out;
  fxr_traverse #(.WindowIntBits(WindowIntBits)) u_traverse (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .in_valid_i (tv_in_valid),
    .in_ready_o (tv_in_ready),
    .in_i       (tv_in),
    .out_valid_o(tv_out_valid),
    .out_ready_i(tv_out_ready),
    .out_o      (tv_out)
  );

  // ---- span ↔ equations ---------------------------------------------------------------------
  logic [FB-1:0] span_tag, rd_next;
  logic          head_fin, hit_head, hit_next, sel_next;
  assign span_tag = tv_out.prim[FB-1:0];
  assign rd_next  = rd_q + FB'(1);
  assign head_fin = fin_q != rd_q;                    // traversal is past the head
  assign hit_head = tv_out_valid & ~fifo_empty & (span_tag == rd_q);
  // The span belongs to the entry after the head (then the head is finished: spans are in order).
  assign hit_next = tv_out_valid & ((wr_q - rd_q) >= FB'(2)) & (span_tag == rd_next);
  assign sel_next = ~hit_head & hit_next;

  logic [FB-2:0]                    rd_sel;  // the FIFO entry of the span
  assign rd_sel = sel_next ? rd_next[FB-2:0] : rd_q[FB-2:0];
  logic                             ip_in_valid, ip_in_ready;
  fxr_rec_pkg::span_t               ip_in;
  fxr_rec_pkg::triangle_equations_t ip_ctx;
  // The entry is selected only in a clock interp reads it (a span offered that it may accept:
  // ip_ctx_en, fxr_interp's ctx_en_o; the record is '0 otherwise), so that a simulator skips the
  // wide select on the other clocks — on a large triangle a span waits at interp's input for most
  // of the clocks (docs/rtl.md, "Co-simulation speed", sessions 8 and 10).
  logic ip_ctx_en;
  always_comb begin
    ip_ctx     = '0;
    if (ip_in_valid && ip_ctx_en) ip_ctx = eq_q[rd_sel * EqBits +: EqBits];
    ip_in      = tv_out;
    ip_in.prim = ip_ctx.prim;
  end
  assign ip_in_valid  = hit_head | hit_next;
  assign tv_out_ready = ip_in_ready & ip_in_valid;
  // Retire the head: traversal is past it and none of its spans waits (or the next entry's span
  // is taken now).
  assign pop = ~fifo_empty & (sel_next | (head_fin & ~hit_head));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wr_q  <= '0;
      rd_q  <= '0;
      fin_q <= '0;
    end else begin
      if (push) wr_q <= wr_q + FB'(1);
      if (pop) rd_q <= rd_q + FB'(1);
      // In a clock with traversal ready for a new triangle, every triangle accepted before has
      // its spans out of the search (the last one, possibly, in traversal's output register).
      if (tv_in_ready) fin_q <= wr_q;
    end
  end
  always_ff @(posedge clk_i) begin
    if (push) eq_q[wr_q[FB-2:0] * EqBits +: EqBits] <= su_out;
  end

  // ---- stage 7: interpolators -------------------------------------------------------------------
  logic                       ip_out_valid, ip_out_ready;
  fxr_rec_pkg::plane_sample_t ip_out;
  /* verilator lint_off UNUSEDSIGNAL */
  logic                       ip_out_last;
  /* verilator lint_on UNUSEDSIGNAL */
  fxr_interp #(.WindowIntBits(WindowIntBits), .DepthFormat(DepthFormat), .DivStepsPerClock(InterpDivSteps)) u_interp (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .in_valid_i (ip_in_valid),
    .in_ready_o (ip_in_ready),
    .in_i       (ip_in),
    .ctx_i      (ip_ctx),
    .out_valid_o(ip_out_valid),
    .out_ready_i(ip_out_ready),
    .out_o      (ip_out),
    .out_last_o (ip_out_last),
    .ctx_en_o   (ip_ctx_en)
  );

  // ---- stage 8: depth -----------------------------------------------------------------------------
  logic                       dp_in_ready, dp_out_valid, dp_out_ready;
  fxr_rec_pkg::plane_sample_t dp_out;
  assign ip_out_ready = dp_in_ready;
  fxr_depth #(.WindowIntBits(WindowIntBits), .DepthFormat(DepthFormat), .QueueDepth(DepthQueueDepth),
             .WritePort(DepthWritePort)) u_depth (
    .clk_i          (clk_i),
    .rst_ni         (rst_ni),
    .depth_func_i   (depth_func_i),
    .depth_test_i   (depth_test_i),
    .depth_write_i  (depth_write_i),
    .viewport_x_i   (viewport_x_i),
    .viewport_y_i   (viewport_y_i),
    .viewport_w_i   (viewport_w_i),
    .in_valid_i     (ip_out_valid),
    .in_ready_o     (dp_in_ready),
    .in_i           (ip_out),
    .out_valid_o    (dp_out_valid),
    .out_ready_i    (dp_out_ready),
    .out_o          (dp_out),
    .mem_req_valid_o(mem_req_valid_o),
    .mem_req_ready_i(mem_req_ready_i),
    .mem_req_write_o(mem_req_write_o),
    .mem_req_addr_o (mem_req_addr_o),
    .mem_req_wdata_o(mem_req_wdata_o),
    .mem_rsp_valid_i(mem_rsp_valid_i),
    .mem_rsp_rdata_i(mem_rsp_rdata_i),
    .mem_wr_valid_o (mem_wr_valid_o),
    .mem_wr_ready_i (mem_wr_ready_i),
    .mem_wr_addr_o  (mem_wr_addr_o),
    .mem_wr_data_o  (mem_wr_data_o)
  );

  // ---- stage 9: divide ---------------------------------------------------------------------------
  fxr_divide #(.WindowIntBits(WindowIntBits), .DepthFormat(DepthFormat), .Lanes(DivideLanes)) u_divide (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .in_valid_i (dp_out_valid),
    .in_ready_o (dp_out_ready),
    .in_i       (dp_out),
    .out_valid_o(out_valid_o),
    .out_ready_i(out_ready_i),
    .out_o      (out_o)
  );

  // ---- counters -------------------------------------------------------------------------------
  logic [StatBits-1:0] n_tri_in_q, n_drawn_q, n_zero_q, n_back_q, n_nosamp_q, n_range_q;
  logic [StatBits-1:0] n_spans_q, n_gen_q, n_tested_q, n_pass_q;
  logic                in_fire, tv_fire, ip_fire, dp_fire, pass_fire;
  assign in_fire  = in_valid_i & in_ready_o;
  assign tv_fire  = tv_out_valid & tv_out_ready;
  assign ip_fire  = ip_out_valid & ip_out_ready;
  assign pass_fire = dp_out_valid & dp_out_ready;
  assign dp_fire  = ip_fire;

  logic signed [PB:0] span_len;
  assign span_len = {tv_out.x1[PB-1], tv_out.x1} - {tv_out.x0[PB-1], tv_out.x0} + (PB+1)'(1);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      n_tri_in_q <= '0; n_drawn_q <= '0; n_zero_q <= '0; n_back_q <= '0; n_nosamp_q <= '0;
      n_range_q <= '0; n_spans_q <= '0; n_gen_q <= '0; n_tested_q <= '0; n_pass_q <= '0;
    end else begin
      if (in_fire) n_tri_in_q <= n_tri_in_q + StatBits'(1);
      if (push) n_drawn_q <= n_drawn_q + StatBits'(1);
      if (su_cull_valid) begin
        unique case (su_cull_outcome)
          3'd1: n_zero_q <= n_zero_q + StatBits'(1);
          3'd2: n_back_q <= n_back_q + StatBits'(1);
          3'd3: n_nosamp_q <= n_nosamp_q + StatBits'(1);
          default: n_range_q <= n_range_q + StatBits'(1);
        endcase
      end
      if (tv_fire) begin
        n_spans_q <= n_spans_q + StatBits'(1);
        n_gen_q   <= n_gen_q + StatBits'(unsigned'(span_len));
      end
      if (dp_fire) n_tested_q <= n_tested_q + StatBits'(1);
      if (pass_fire) n_pass_q <= n_pass_q + StatBits'(1);
    end
  end
  assign stat_tri_in_o          = n_tri_in_q;
  assign stat_tri_drawn_o       = n_drawn_q;
  assign stat_tri_zero_area_o   = n_zero_q;
  assign stat_tri_backface_o    = n_back_q;
  assign stat_tri_no_samples_o  = n_nosamp_q;
  assign stat_tri_range_o       = n_range_q;
  assign stat_spans_o           = n_spans_q;
  assign stat_frag_generated_o  = n_gen_q;
  assign stat_frag_depth_pass_o = n_pass_q;
  assign stat_frag_depth_fail_o = n_tested_q - n_pass_q;

  logic [StatBits-1:0] p_setup_q, p_full_q, p_span_q, p_wait_q, p_sample_q, p_pass_q, p_out_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      p_setup_q <= '0; p_full_q <= '0; p_span_q <= '0; p_wait_q <= '0; p_sample_q <= '0; p_pass_q <= '0;
      p_out_q <= '0;
    end else begin
      if (su_valid && !su_ready) p_setup_q <= p_setup_q + StatBits'(1);
      if (su_valid && fifo_full) p_full_q <= p_full_q + StatBits'(1);
      if (ip_in_valid && !ip_in_ready) p_span_q <= p_span_q + StatBits'(1);
      if (tv_out_valid && !ip_in_valid) p_wait_q <= p_wait_q + StatBits'(1);
      if (ip_out_valid && !ip_out_ready) p_sample_q <= p_sample_q + StatBits'(1);
      if (dp_out_valid && !dp_out_ready) p_pass_q <= p_pass_q + StatBits'(1);
      if (out_valid_o && !out_ready_i) p_out_q <= p_out_q + StatBits'(1);
    end
  end
  assign perf_setup_stall_o  = p_setup_q;
  assign perf_fifo_full_o    = p_full_q;
  assign perf_span_stall_o   = p_span_q;
  assign perf_span_wait_o    = p_wait_q;
  assign perf_sample_stall_o = p_sample_q;
  assign perf_pass_stall_o   = p_pass_q;
  assign perf_out_stall_o    = p_out_q;

endmodule

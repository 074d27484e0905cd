// fxr_raster_unit: the whole raster unit (issue 11), stages 1–9 as one valid / ready chain:
// fxr_input → fxr_clip → fxr_recip_stage → fxr_viewport → fxr_raster_backend (setup, traversal,
// interpolators, depth, divider). Float32 clip-space primitives in, the fragments that pass the
// depth test out with their varyings, in the model's order (model/unit/chain.hpp, UnitChain);
// the depth buffer behind a memory port; the draw state in a register block; counters.
// docs/rtl.md, "fxr_raster_unit"; co-simulation: tb/unit/unit_test.cpp and `fxraster cosim`.
//
// Ports:
//   clk_i, rst_ni                  clock, active-low asynchronous reset
//   reg_we_i, reg_addr_i,          the register block's write port: in a clock with reg_we_i high,
//   reg_wdata_i                    register reg_addr_i takes reg_wdata_i (low bits; signed
//                                  registers two's complement). Write between draws (no primitive
//                                  in flight). Registers (RegAddrBits address, RegDataBits data):
//                                    0 viewport_x   1 viewport_y   2 viewport_w   3 viewport_h
//                                    4 scissor_x    5 scissor_y    6 scissor_w    7 scissor_h
//                                    8 cull (0 none, 1 back, 2 front)   9 front_ccw
//                                   10 depth_func (DepthFunc)  11 depth_test  12 depth_write
//                                   13 interp (0 perspective, 1 affine)
//                                   14 num_varyings (0..NumVaryings: the varyings from this index
//                                      on enter as +0, the model's draw with fewer varyings)
//   in_valid_i / in_ready_o, in_i  fxr_rec_pkg::input_triangle_t (the model's convert.in)
//   out_valid_o / out_ready_i,     fxr_rec_pkg::fragment_t (the model's divide.out)
//   out_o
//   mem_req_*, mem_rsp_*, mem_wr_* the depth buffer (fxr_raster_backend's, fxr_depth's port)
//   stat_*_o                       counters since reset (StatBits wide, wrapping), RasterStats:
//     prims_in, prims_rejected_nan, prims_rejected_inf, prims_varying_nonfinite  (stage 1)
//     prims_trivial_accept, prims_clipped, clip_vertices_created, clip_triangles_out,
//     prims_culled_outside                                                      (stage 2)
//     geom_rejected_range   primitives the clipper rejects for range (RejectedViewport /
//                           RejectedOverflow) + clipped pieces dropped by stage 3 (a reciprocal
//                           error) or 4 (a code out of range): a dropped piece is dropped alone,
//                           the primitive's other pieces go on (RasterStats::tris.geom_rejected_range)
//     tri_*, spans, frag_*  fxr_raster_backend's, per setup triangle (RasterStats::tris; the
//                           model's dispositions prims_* are per primitive: docs/pipeline.md,
//                           "Statistics: primitives, pieces, setup triangles")
//   perf_busy_o, perf_stalled_o,   per stage (index 0 input, 1 clip, 2 recip, 3 viewport, 4 back
//   perf_starved_o                 end), StatBits each at [i*StatBits +: StatBits]: clocks with a
//                                  record leaving the stage (busy), one waiting for the next stage
//                                  (stalled), none ready (starved)
//   perf_*_o                       fxr_raster_backend's stall counters
module fxr_raster_unit #(
  parameter int WindowIntBits  = fxr_config_pkg::RasterWindowIntBits,
  parameter int DepthFormat    = fxr_config_pkg::RasterDepthFormat,
  parameter int StatBits       = 32,
  parameter int ViewportLanes  = fxr_rec_pkg::ViewportLanes,  // fxr_viewport's dividers (docs/rtl.md, "fxr_viewport")
  localparam int Db            = DepthFormat == fxr_config_pkg::RasterDepthFormatD24 ? 24 : 16,
  localparam int PB            = WindowIntBits,
  localparam int AddrBits      = 2 * WindowIntBits,
  localparam int RegAddrBits   = 4,
  localparam int RegDataBits   = WindowIntBits + 1,  // the widest register: a viewport / scissor size
  localparam int NumStages     = 5
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  input  logic                              reg_we_i,
  input  logic [RegAddrBits-1:0]            reg_addr_i,
  input  logic [RegDataBits-1:0]            reg_wdata_i,
  input  logic                              in_valid_i,
  output logic                              in_ready_o,
  input  fxr_rec_pkg::input_triangle_t      in_i,
  output logic                              out_valid_o,
  input  logic                              out_ready_i,
  output fxr_rec_pkg::fragment_t            out_o,
  output logic                              mem_req_valid_o,
  input  logic                              mem_req_ready_i,
  output logic                              mem_req_write_o,
  output logic [AddrBits-1:0]               mem_req_addr_o,
  output logic [Db-1:0]                     mem_req_wdata_o,
  input  logic                              mem_rsp_valid_i,
  input  logic [Db-1:0]                     mem_rsp_rdata_i,
  output logic                              mem_wr_valid_o,
  input  logic                              mem_wr_ready_i,
  output logic [AddrBits-1:0]               mem_wr_addr_o,
  output logic [Db-1:0]                     mem_wr_data_o,
  output logic [StatBits-1:0]               stat_prims_in_o,
  output logic [StatBits-1:0]               stat_prims_rejected_nan_o,
  output logic [StatBits-1:0]               stat_prims_rejected_inf_o,
  output logic [StatBits-1:0]               stat_prims_varying_nonfinite_o,
  output logic [StatBits-1:0]               stat_prims_trivial_accept_o,
  output logic [StatBits-1:0]               stat_prims_clipped_o,
  output logic [StatBits-1:0]               stat_clip_vertices_created_o,
  output logic [StatBits-1:0]               stat_clip_triangles_out_o,
  output logic [StatBits-1:0]               stat_prims_culled_outside_o,
  output logic [StatBits-1:0]               stat_geom_rejected_range_o,
  output logic [StatBits-1:0]               stat_tri_in_o,
  output logic [StatBits-1:0]               stat_tri_drawn_o,
  output logic [StatBits-1:0]               stat_tri_zero_area_o,
  output logic [StatBits-1:0]               stat_tri_backface_o,
  output logic [StatBits-1:0]               stat_tri_no_samples_o,
  output logic [StatBits-1:0]               stat_tri_range_o,
  output logic [StatBits-1:0]               stat_spans_o,
  output logic [StatBits-1:0]               stat_frag_generated_o,
  output logic [StatBits-1:0]               stat_frag_depth_pass_o,
  output logic [StatBits-1:0]               stat_frag_depth_fail_o,
  output logic [NumStages*StatBits-1:0]     perf_busy_o,
  output logic [NumStages*StatBits-1:0]     perf_stalled_o,
  output logic [NumStages*StatBits-1:0]     perf_starved_o,
  output logic [StatBits-1:0]               perf_setup_stall_o,
  output logic [StatBits-1:0]               perf_fifo_full_o,
  output logic [StatBits-1:0]               perf_span_stall_o,
  output logic [StatBits-1:0]               perf_span_wait_o,
  output logic [StatBits-1:0]               perf_sample_stall_o,
  output logic [StatBits-1:0]               perf_pass_stall_o,
  output logic [StatBits-1:0]               perf_out_stall_o
);
  localparam int NumVaryings = fxr_rec_pkg::NumVaryings;
  localparam int VarBits = $clog2(NumVaryings + 1);
  localparam int CreatedBits = $clog2(fxr_rec_pkg::ClipMaxPolyVerts * fxr_rec_pkg::ClipNumPlanes + 1);

  // ---- the register block ----------------------------------------------------------------------
  logic [PB-1:0] vp_x_q, vp_y_q, sc_x_q, sc_y_q;
  logic [PB:0]   vp_w_q, vp_h_q, sc_w_q, sc_h_q;
  logic [1:0]    cull_q;
  logic          front_ccw_q, depth_test_q, depth_write_q, interp_q;
  logic [2:0]    depth_func_q;
  logic [VarBits-1:0] nvar_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      vp_x_q <= '0; vp_y_q <= '0; vp_w_q <= '0; vp_h_q <= '0;
      sc_x_q <= '0; sc_y_q <= '0; sc_w_q <= '0; sc_h_q <= '0;
      cull_q <= '0; front_ccw_q <= 1'b1; depth_func_q <= '0; depth_test_q <= 1'b1; depth_write_q <= 1'b1;
      interp_q <= 1'b0; nvar_q <= VarBits'(NumVaryings);
    end else if (reg_we_i) begin
      case (reg_addr_i)
        4'd0:  vp_x_q <= reg_wdata_i[PB-1:0];
        4'd1:  vp_y_q <= reg_wdata_i[PB-1:0];
        4'd2:  vp_w_q <= reg_wdata_i;
        4'd3:  vp_h_q <= reg_wdata_i;
        4'd4:  sc_x_q <= reg_wdata_i[PB-1:0];
        4'd5:  sc_y_q <= reg_wdata_i[PB-1:0];
        4'd6:  sc_w_q <= reg_wdata_i;
        4'd7:  sc_h_q <= reg_wdata_i;
        4'd8:  cull_q <= reg_wdata_i[1:0];
        4'd9:  front_ccw_q <= reg_wdata_i[0];
        4'd10: depth_func_q <= reg_wdata_i[2:0];
        4'd11: depth_test_q <= reg_wdata_i[0];
        4'd12: depth_write_q <= reg_wdata_i[0];
        4'd13: interp_q <= reg_wdata_i[0];
        4'd14: nvar_q <= reg_wdata_i[VarBits-1:0];
        default: ;
      endcase
    end
  end

  // ---- the number of varyings: varyings from nvar_q on enter as +0 (fxr_input's var_zero_i) ------
  // Applied in fxr_input, not by masking in_i here: logic on the top-level input record is
  // evaluated by a simulator in every evaluation (docs/rtl.md, "Co-simulation speed", session 10).
  logic [NumVaryings-1:0] var_zero;
  for (genvar k = 0; k < NumVaryings; k++) begin : g_var_zero
    assign var_zero[k] = VarBits'(k) >= nvar_q;
  end

  // ---- stage 1: input conversion -----------------------------------------------------------------
  logic s1_valid, s1_ready, rej_nan, rej_inf, var_repl;
  fxr_rec_pkg::exact_triangle_t s1_out;
  fxr_input u_input (
    .clk_i, .rst_ni, .in_valid_i, .in_ready_o, .in_i,
    .out_valid_o(s1_valid), .out_ready_i(s1_ready), .out_o(s1_out),
    .rej_nan_o(rej_nan), .rej_inf_o(rej_inf), .var_replaced_o(var_repl), .var_zero_i(var_zero)
  );

  // ---- stage 2: clipper ----------------------------------------------------------------------------
  logic s2_valid, s2_ready, s2_last, clip_done;
  logic [fxr_rec_pkg::ClipOutcomeBits-1:0] clip_outcome;
  logic [CreatedBits-1:0] clip_created;
  fxr_rec_pkg::clipped_triangle_t s2_out;
  fxr_clip u_clip (
    .clk_i, .rst_ni, .viewport_x_i(vp_x_q), .viewport_y_i(vp_y_q), .viewport_w_i(vp_w_q), .viewport_h_i(vp_h_q),
    .in_valid_i(s1_valid), .in_ready_o(s1_ready), .in_i(s1_out),
    .out_valid_o(s2_valid), .out_ready_i(s2_ready), .out_o(s2_out), .out_last_o(s2_last),
    .done_o(clip_done), .done_outcome_o(clip_outcome), .done_created_o(clip_created)
  );

  // ---- stage 3: reciprocals ------------------------------------------------------------------------
  logic s3_valid, s3_ready, recip_err;
  fxr_rec_pkg::recip_triangle_t s3_out;
  fxr_recip_stage u_recip (
    .clk_i, .rst_ni, .in_valid_i(s2_valid), .in_ready_o(s2_ready), .in_i(s2_out),
    .out_valid_o(s3_valid), .out_ready_i(s3_ready), .out_o(s3_out), .err_o(recip_err)
  );

  // ---- stage 4: viewport and snap ------------------------------------------------------------------
  logic s4_valid, s4_ready, vp_rej;
  fxr_rec_pkg::setup_triangle_t s4_out;
  fxr_viewport #(.Lanes(ViewportLanes)) u_viewport (
    .clk_i, .rst_ni, .in_valid_i(s3_valid), .in_ready_o(s3_ready), .in_i(s3_out),
    .viewport_x_i(vp_x_q), .viewport_y_i(vp_y_q), .viewport_w_i(vp_w_q), .viewport_h_i(vp_h_q),
    .interp_i(interp_q), .out_valid_o(s4_valid), .out_ready_i(s4_ready), .out_o(s4_out), .rej_range_o(vp_rej)
  );

  // ---- stages 5–9: the back end --------------------------------------------------------------------
  fxr_raster_backend #(.WindowIntBits(WindowIntBits), .DepthFormat(DepthFormat), .StatBits(StatBits)) u_backend (
    .clk_i, .rst_ni, .in_valid_i(s4_valid), .in_ready_o(s4_ready), .in_i(s4_out),
    .viewport_x_i(vp_x_q), .viewport_y_i(vp_y_q), .viewport_w_i(vp_w_q), .viewport_h_i(vp_h_q),
    .scissor_x_i(sc_x_q), .scissor_y_i(sc_y_q), .scissor_w_i(sc_w_q), .scissor_h_i(sc_h_q),
    .cull_i(cull_q), .front_ccw_i(front_ccw_q), .interp_i(interp_q),
    .depth_func_i(depth_func_q), .depth_test_i(depth_test_q), .depth_write_i(depth_write_q),
    .out_valid_o, .out_ready_i, .out_o,
    .mem_req_valid_o, .mem_req_ready_i, .mem_req_write_o, .mem_req_addr_o, .mem_req_wdata_o,
    .mem_rsp_valid_i, .mem_rsp_rdata_i, .mem_wr_valid_o, .mem_wr_ready_i, .mem_wr_addr_o, .mem_wr_data_o,
    .stat_tri_in_o, .stat_tri_drawn_o, .stat_tri_zero_area_o, .stat_tri_backface_o, .stat_tri_no_samples_o,
    .stat_tri_range_o, .stat_spans_o, .stat_frag_generated_o, .stat_frag_depth_pass_o, .stat_frag_depth_fail_o,
    .perf_setup_stall_o, .perf_fifo_full_o, .perf_span_stall_o, .perf_span_wait_o, .perf_sample_stall_o,
    .perf_pass_stall_o, .perf_out_stall_o
  );

  // ---- geometry counters (RasterStats, stages 1–4) ------------------------------------------------
  logic [StatBits-1:0] n_in_q, n_nan_q, n_inf_q, n_repl_q, n_acc_q, n_clipped_q, n_created_q, n_clipout_q,
                       n_outside_q, n_range_q;
  logic in_fire, clip_fire, is_acc, is_clipped, is_outside, is_range;
  assign in_fire = in_valid_i & in_ready_o;
  assign clip_fire = s2_valid & s2_ready;
  assign is_acc = clip_done && clip_outcome == fxr_rec_pkg::ClipOutcomeBits'(fxr_rec_pkg::ClipOutcomeAccepted);
  assign is_clipped = clip_done && (clip_outcome == fxr_rec_pkg::ClipOutcomeBits'(fxr_rec_pkg::ClipOutcomeClipped) ||
                                    clip_outcome == fxr_rec_pkg::ClipOutcomeBits'(fxr_rec_pkg::ClipOutcomeClippedAway) ||
                                    clip_outcome == fxr_rec_pkg::ClipOutcomeBits'(fxr_rec_pkg::ClipOutcomeRejectedOverflow));
  assign is_outside = clip_done && (clip_outcome == fxr_rec_pkg::ClipOutcomeBits'(fxr_rec_pkg::ClipOutcomeCulledOutside) ||
                                    clip_outcome == fxr_rec_pkg::ClipOutcomeBits'(fxr_rec_pkg::ClipOutcomeClippedAway));
  assign is_range = (clip_done && (clip_outcome == fxr_rec_pkg::ClipOutcomeBits'(fxr_rec_pkg::ClipOutcomeRejectedViewport) ||
                                   clip_outcome == fxr_rec_pkg::ClipOutcomeBits'(fxr_rec_pkg::ClipOutcomeRejectedOverflow)));
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      n_in_q <= '0; n_nan_q <= '0; n_inf_q <= '0; n_repl_q <= '0; n_acc_q <= '0; n_clipped_q <= '0;
      n_created_q <= '0; n_clipout_q <= '0; n_outside_q <= '0; n_range_q <= '0;
    end else begin
      n_in_q <= n_in_q + StatBits'(in_fire);
      n_nan_q <= n_nan_q + StatBits'(rej_nan);
      n_inf_q <= n_inf_q + StatBits'(rej_inf);
      n_repl_q <= n_repl_q + StatBits'(var_repl);
      n_acc_q <= n_acc_q + StatBits'(is_acc);
      n_clipped_q <= n_clipped_q + StatBits'(is_clipped);
      if (is_clipped) n_created_q <= n_created_q + StatBits'(clip_created);
      n_clipout_q <= n_clipout_q + StatBits'(clip_fire);
      n_outside_q <= n_outside_q + StatBits'(is_outside);
      // Rejected in geometry: a primitive by the clipper, or one piece by the reciprocal unit or
      // the viewport (that piece alone: docs/pipeline.md, "Statistics").
      n_range_q <= n_range_q + StatBits'(is_range) + StatBits'(recip_err) + StatBits'(vp_rej);
    end
  end
  assign stat_prims_in_o = n_in_q;
  assign stat_prims_rejected_nan_o = n_nan_q;
  assign stat_prims_rejected_inf_o = n_inf_q;
  assign stat_prims_varying_nonfinite_o = n_repl_q;
  assign stat_prims_trivial_accept_o = n_acc_q;
  assign stat_prims_clipped_o = n_clipped_q;
  assign stat_clip_vertices_created_o = n_created_q;
  assign stat_clip_triangles_out_o = n_clipout_q - n_acc_q;  // the pieces of clipped primitives
  assign stat_prims_culled_outside_o = n_outside_q;
  assign stat_geom_rejected_range_o = n_range_q;

  // ---- per-stage utilisation ---------------------------------------------------------------------
  logic [NumStages-1:0] st_valid, st_ready;
  assign st_valid = {out_valid_o, s4_valid, s3_valid, s2_valid, s1_valid};
  assign st_ready = {out_ready_i, s4_ready, s3_ready, s2_ready, s1_ready};
  for (genvar i = 0; i < NumStages; i++) begin : g_perf
    logic [StatBits-1:0] busy_q, stall_q, starve_q;
    logic busy, stall, starve;
    assign busy = st_valid[i] & st_ready[i];
    assign stall = st_valid[i] & ~st_ready[i];
    assign starve = ~st_valid[i];
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        busy_q <= '0; stall_q <= '0; starve_q <= '0;
      end else begin
        busy_q <= busy_q + StatBits'(busy);
        stall_q <= stall_q + StatBits'(stall);
        starve_q <= starve_q + StatBits'(starve);
      end
    end
    assign perf_busy_o[i*StatBits +: StatBits] = busy_q;
    assign perf_stalled_o[i*StatBits +: StatBits] = stall_q;
    assign perf_starved_o[i*StatBits +: StatBits] = starve_q;
  end

  // The clipper's `last` marks the final piece of a primitive (used by the testbench's taps).
  logic unused_last;
  assign unused_last = s2_last;
endmodule

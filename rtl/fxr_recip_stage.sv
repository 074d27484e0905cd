// fxr_recip_stage: stage 3 of the raster unit as a stage of records (issue 11): a clipped
// triangle in, the same triangle with 1/w of each vertex out, or nothing when the reciprocal unit
// flags a vertex. Model: fxr::RecipStage (model/stages/recip_stage.hpp); vectors: the transaction
// dumps' recip.in / recip.out (docs/vectors.md, "Transaction vectors"; tb/txn/recip_txn_test.cpp);
// docs/rtl.md, "fxr_recip_stage".
//
// Ports:
//   clk_i, rst_ni               clock, active-low asynchronous reset
//   in_valid_i / in_ready_o     input handshake (transfer when both are high)
//   in_i                        fxr_rec_pkg::clipped_triangle_t (ClippedTriangle::visit())
//   out_valid_o / out_ready_i   output handshake
//   out_o                       fxr_rec_pkg::recip_triangle_t (RecipTriangle::visit(): the input
//                               record unchanged, then r0, r1, r2 = 1/w of each vertex as
//                               _neg, _sig (RecipOutSigBits), _exp (lsb exponent, FxExpBits))
//   err_o                       one-clock pulse: a triangle was dropped because the unit flagged a
//                               vertex (RecipOutcome::RecipError: w = 0, or a lead exponent of w
//                               or of 1/w outside the unit's I/O range)
//
// Function (bit-exact to the model): per vertex, w (ClipVertexSigBits significand, lsb exponent
// FxExpBits) is normalised to RecipInSigBits with its leading one at the top, rounded to nearest
// even when wider (never the case in the unit: float32 w has 24 bits and the clipper rounds its w
// to recip.in_sig_bits, model/stages/clip.hpp), its lead exponent checked against the unit's range
// [-2^(RecipExpBits-1), 2^(RecipExpBits-1) - 1] (fxr::RecipUnit), and fed to fxr_recip. The three
// vertices have a reciprocal unit each (three lanes, initiation interval 1, one triangle per
// clock); the record waits in a sideband FIFO of SideDepth entries (the unit's latency + 1, so
// the FIFO never limits the rate) and leaves with the three results.
//
// Timing: latency = fxr_recip's (7 clocks at the default configuration, fxr::recip_cost), no
// register before it (the normalisation is combinational on in_i). out_ready_i low stalls the
// lanes; a dropped triangle leaves the lanes without waiting for out_ready_i.
module fxr_recip_stage #(
  // Sideband FIFO depth: fxr_recip's latency, 1 (seed) + 2 per Newton-Raphson step + 1 (round)
  // + 1 (the remainder correction, counted always), + 1: the entry of the triangle that leaves
  // in the clock the next one enters (7 entries at latency 7 give 8 clocks per 7 triangles, as
  // measured; 8 give one per clock).
  parameter int SideDepth = 4 + 2 * fxr_config_pkg::RecipNrSteps
) (
  input  logic                           clk_i,
  input  logic                           rst_ni,
  input  logic                           in_valid_i,
  output logic                           in_ready_o,
  input  fxr_rec_pkg::clipped_triangle_t in_i,
  output logic                           out_valid_o,
  input  logic                           out_ready_i,
  output fxr_rec_pkg::recip_triangle_t   out_o,
  output logic                           err_o
);
  localparam int InBits = fxr_rec_pkg::ClippedTriangleBits;
  localparam int OutBits = fxr_rec_pkg::RecipTriangleBits;
  localparam int PrimBits = fxr_rec_pkg::PrimIdBits;
  localparam int SigBits = fxr_rec_pkg::ClipVertexSigBits;
  localparam int FxExp = fxr_rec_pkg::FxExpBits;
  localparam int ValBits = 1 + SigBits + FxExp;  // _neg, _sig, _exp of a vertex component
  localparam int NumVaryings = fxr_rec_pkg::NumVaryings;
  localparam int NumWa = fxr_rec_pkg::ClipVertexHasWa;  // 1: the record lists wa after w
  localparam int ValsPerVertex = 4 + NumWa + NumVaryings;
  localparam int N = fxr_config_pkg::RecipInSigBits;
  localparam int O = fxr_config_pkg::RecipOutSigBits;
  localparam int E = fxr_config_pkg::RecipExpBits;
  localparam int RBits = 1 + O + FxExp;  // r<i>: _neg, _sig, _exp
  localparam int LzBits = $clog2(SigBits + 1);
  localparam int DepthBits = $clog2(SideDepth + 1);
  localparam logic signed [FxExp+1:0] EMin = -(FxExp + 2)'(1 << (E - 1));
  localparam logic signed [FxExp+1:0] EMax = (FxExp + 2)'((1 << (E - 1)) - 1);

  // ---- the three lanes: normalise w, range check, fxr_recip ----------------------------------
  logic [InBits-1:0] in_flat;
  assign in_flat = in_i;

  logic [2:0] lane_in_ready, lane_out_valid, lane_neg, lane_dbz, lane_ovf, pre_err;
  logic [3*E-1:0] lane_exp;
  logic [3*O-1:0] lane_sig;
  logic lanes_advance;  // the lanes' common handshake (identical instances, identical inputs)
  logic lanes_in_valid, lanes_out_ready;

  for (genvar i = 0; i < 3; i++) begin : g_lane
    // w is component 3 of vertex i.
    localparam int At = InBits - PrimBits - ValBits * (i * ValsPerVertex + 3);
    logic                     w_neg;
    logic [SigBits-1:0]       w_sig;
    logic signed [FxExp-1:0]  w_exp;
    assign w_neg = in_flat[At-1];
    assign w_sig = in_flat[At-2 -: SigBits];
    assign w_exp = in_flat[At-2-SigBits -: FxExp];

    // Leading one of w_sig (msb index p; 0 for w_sig = 0), the significand left-aligned: the
    // shared log-step normaliser (rtl/fxr_norm_log.sv), enabled with a triangle at the input (its
    // outputs are read only then: the lanes take them and the FIFO the range flags on a push), so
    // that a simulator skips the shifts on idle clocks (docs/rtl.md, "Co-simulation speed",
    // session 11).
    logic [LzBits-1:0]  p;
    logic [SigBits-1:0] aligned;
    fxr_norm_log #(
      .Width  (SigBits),
      .MsbBits(LzBits)
    ) u_norm (
      .en_i  (in_valid_i),
      .x_i   (w_sig),
      .norm_o(aligned),
      .msb_o (p)
    );

    // The top N bits, rounded to nearest even when SigBits > N (a carry moves to the next binade).
    logic [N-1:0] m;
    logic         carry;
    if (SigBits > N) begin : g_round
      logic guard, sticky, up;
      logic [N:0] m_up;
      assign guard = aligned[SigBits-1-N];
      if (SigBits > N + 1) begin : g_sticky
        assign sticky = |aligned[SigBits-2-N:0];
      end else begin : g_nosticky
        assign sticky = 1'b0;
      end
      assign up = guard && (sticky || aligned[SigBits-N]);
      assign m_up = {1'b0, aligned[SigBits-1 -: N]} + (N + 1)'(up);
      assign carry = m_up[N];
      assign m = carry ? {1'b1, {(N-1){1'b0}}} : m_up[N-1:0];
    end else if (SigBits == N) begin : g_same
      assign m = aligned;
      assign carry = 1'b0;
    end else begin : g_pad
      assign m = {aligned, {(N - SigBits){1'b0}}};
      assign carry = 1'b0;
    end

    // Lead exponent of the normalised w: w_exp + p (+1 on a carry), then the unit's range.
    logic signed [FxExp+1:0] lead;
    assign lead = (FxExp + 2)'(w_exp) + $signed((FxExp + 2)'(p)) + $signed((FxExp + 2)'(carry));
    assign pre_err[i] = (w_sig != '0) && (lead < EMin || lead > EMax);

    fxr_recip u_recip (
      .clk_i      (clk_i),
      .rst_ni     (rst_ni),
      .in_valid_i (lanes_in_valid),
      .in_ready_o (lane_in_ready[i]),
      .in_neg_i   (w_neg),
      .in_exp_i   (lead[E-1:0]),
      .in_sig_i   ((w_sig == '0) ? '0 : m),
      .out_valid_o(lane_out_valid[i]),
      .out_ready_i(lanes_out_ready),
      .out_neg_o  (lane_neg[i]),
      .out_exp_o  (lane_exp[i*E +: E]),
      .out_sig_o  (lane_sig[i*O +: O]),
      .out_dbz_o  (lane_dbz[i]),
      .out_ovf_o  (lane_ovf[i])
    );
  end
  assign lanes_advance = lane_in_ready[0];

  // ---- sideband FIFO: the record and the range errors of its lanes -------------------------
  logic [InBits+3-1:0] side_mem [SideDepth];
  logic [$clog2(SideDepth)-1:0] wr_ptr, rd_ptr;
  logic [DepthBits-1:0] count;
  logic side_full, push, pop, drop;
  logic [InBits+3-1:0] side_head;

  assign side_full = count == DepthBits'(SideDepth);
  assign in_ready_o = lanes_advance && !side_full;
  assign lanes_in_valid = in_valid_i && !side_full;
  assign push = in_valid_i && in_ready_o;
  // The head entry is read only with a result at the lanes' output ('0 otherwise: nothing reads
  // it then), so that a simulator skips the wide read and the output record on idle clocks.
  always_comb begin
    side_head = '0;
    if (lane_out_valid[0]) side_head = side_mem[rd_ptr];
  end
  // A flagged triangle: w = 0 (dbz), 1/w out of range (ovf), or w's lead exponent out of range.
  assign drop = lane_out_valid[0] && ((|lane_dbz) || (|lane_ovf) || (|side_head[2:0]));
  assign lanes_out_ready = out_ready_i || drop;
  assign pop = lane_out_valid[0] && lanes_out_ready;
  assign err_o = drop;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wr_ptr <= '0;
      rd_ptr <= '0;
      count  <= '0;
    end else begin
      if (push) wr_ptr <= (wr_ptr == $clog2(SideDepth)'(SideDepth - 1)) ? '0 : wr_ptr + 1'b1;
      if (pop) rd_ptr <= (rd_ptr == $clog2(SideDepth)'(SideDepth - 1)) ? '0 : rd_ptr + 1'b1;
      count <= count + DepthBits'(push) - DepthBits'(pop);
    end
  end
  always_ff @(posedge clk_i) begin
    if (push) side_mem[wr_ptr] <= {in_flat, pre_err};
  end

  // ---- output: the record, then r0, r1, r2 ---------------------------------------------------
  logic [OutBits-1:0] out_flat;
  assign out_flat[OutBits-1 -: InBits] = side_head[InBits+2:3];
  for (genvar i = 0; i < 3; i++) begin : g_out
    logic signed [FxExp-1:0] r_exp;  // lsb exponent = lead - (O - 1)
    assign r_exp = $signed(FxExp'($signed(lane_exp[i*E +: E]))) - FxExp'(O - 1);
    assign out_flat[OutBits-InBits-RBits*i-1 -: RBits] = {lane_neg[i], lane_sig[i*O +: O], r_exp};
  end
  assign out_o = out_flat;
  assign out_valid_o = lane_out_valid[0] && !drop;

  // The lanes run in lock-step: their handshakes are equal by construction.
  logic unused_lanes;
  assign unused_lanes = ^{lane_in_ready[2:1], lane_out_valid[2:1]};
endmodule

// fxr_viewport_core: stage 4 on flat record vectors (fxr_viewport's datapath; fxr_viewport is
// this module with the fxr_rec_pkg struct ports). The records are the bits of recip_triangle_t /
// setup_triangle_t, first field most significant. Kept separate so that Icarus 11, which aborts
// on the package's struct types, can run it (tb/icarus/viewport_txn_tb.sv). docs/rtl.md, "fxr_viewport".
module fxr_viewport_core #(
  parameter int Lanes = fxr_rec_pkg::ViewportLanes  // model/stages/viewport.hpp kViewportLanes
) (
  input  logic                                               clk_i,
  input  logic                                               rst_ni,
  input  logic                                               in_valid_i,
  output logic                                               in_ready_o,
  input  logic [fxr_rec_pkg::RecipTriangleBits-1:0]          in_i,
  input  logic signed [fxr_config_pkg::RasterWindowIntBits-1:0] viewport_x_i,
  input  logic signed [fxr_config_pkg::RasterWindowIntBits-1:0] viewport_y_i,
  input  logic signed [fxr_config_pkg::RasterWindowIntBits:0]   viewport_w_i,
  input  logic signed [fxr_config_pkg::RasterWindowIntBits:0]   viewport_h_i,
  input  logic                                               interp_i,
  output logic                                               out_valid_o,
  input  logic                                               out_ready_i,
  output logic [fxr_rec_pkg::SetupTriangleBits-1:0]          out_o,
  output logic                                               rej_range_o
);
  localparam int NumVaryings = fxr_rec_pkg::NumVaryings;
  localparam int PrimBits = fxr_rec_pkg::PrimIdBits;
  localparam int SigBits = fxr_rec_pkg::ClipVertexSigBits;
  localparam int ExpBits = fxr_rec_pkg::FxExpBits;
  localparam int HasWa = fxr_rec_pkg::ClipVertexHasWa;
  localparam int InBits = fxr_rec_pkg::RecipTriangleBits;
  localparam int OutBits = fxr_rec_pkg::SetupTriangleBits;
  localparam int RecipBits = fxr_config_pkg::RecipOutSigBits;
  localparam int WindowIntBits = fxr_config_pkg::RasterWindowIntBits;
  localparam int SubBits = fxr_config_pkg::RasterSubpixelBits;
  localparam int AttrSubBits = fxr_config_pkg::RasterAttrSubpixelBits;
  localparam int ZFracBits = fxr_config_pkg::RasterZFracBits;
  localparam int AttrSigBits = fxr_config_pkg::RasterAttrSigBits;

  // Record layout (first field most significant).
  localparam int ValBits = 1 + SigBits + ExpBits;               // an input _neg, _sig, _exp
  localparam int RValBits = 1 + RecipBits + ExpBits;            // r<i>
  localparam int WordsPerVertex = 4 + HasWa + NumVaryings;      // x, y, z, w, (wa), varyings
  localparam int CodeBits = WindowIntBits + SubBits;            // x, y
  localparam int PosBits = WindowIntBits + AttrSubBits;         // ax, ay
  localparam int ZBits = ZFracBits + 1;                         // z
  localparam int FloatBits = 1 + AttrSigBits + ExpBits;         // rw, vw_k
  localparam int OutVertexBits = 2 * CodeBits + 2 * PosBits + ZBits + (1 + NumVaryings) * FloatBits;

  // Jobs and slots.
  localparam int JobsPerVertex = 4 + NumVaryings;               // ax, ay, z, rw, vw_k
  localparam int Jobs = 3 * JobsPerVertex;
  localparam int Slots = (Jobs + Lanes - 1) / Lanes;
  localparam int NumSnaps = 6;                                  // x, y of 3 vertices
  localparam int SnapLanes = (NumSnaps + Slots - 1) / Slots;
  localparam int SlotBits = Slots > 1 ? $clog2(Slots) : 1;

  // Lane widths (fxr_viewport_lane).
  localparam int KBits = ExpBits + 4;
  localparam int ResBits = (PosBits > ZBits ? (PosBits > FloatBits ? PosBits : FloatBits)
                                            : (ZBits > FloatBits ? ZBits : FloatBits));
  localparam int QXY = PosBits + 5, QZ = ZFracBits + 4, QF = AttrSigBits + 2;
  localparam int QuotBits = QXY > QZ ? (QXY > QF ? QXY : QF) : (QZ > QF ? QZ : QF);
  localparam int LaneLatency = QuotBits + 2;
  // Triangles between the issue of their last slot and the collection of it: at most
  // ceil(LaneLatency / Slots) + 1.
  localparam int FifoMin = (LaneLatency + Slots - 1) / Slots + 2;
  localparam int FifoAw = $clog2(FifoMin);
  localparam int FifoDepth = 1 << FifoAw;

  logic adv;  // the pipeline enable
  assign adv = !out_valid_o || out_ready_i;

  // ---- input register and slot counter -----------------------------------------------------
  logic [InBits-1:0]   tri_q;
  logic                tri_v;
  logic [SlotBits-1:0] slot;
  logic                last_slot;
  assign last_slot = slot == SlotBits'(Slots - 1);
  assign in_ready_o = adv && (!tri_v || last_slot);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tri_v <= 1'b0;
      slot <= '0;
    end else if (adv) begin
      if (tri_v && !last_slot) begin
        slot <= slot + SlotBits'(1);
      end else begin
        slot <= '0;
        tri_v <= in_valid_i;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (in_valid_i && in_ready_o) tri_q <= in_i;
  end

  // ---- input fields --------------------------------------------------------------------------
  // Value w of vertex i: (neg, sig, exp).
  logic                      v_neg[3][WordsPerVertex];
  logic [SigBits-1:0]        v_sig[3][WordsPerVertex];
  logic signed [ExpBits-1:0] v_exp[3][WordsPerVertex];
  logic                      r_neg[3];
  logic [RecipBits-1:0]      r_sig[3];
  logic signed [ExpBits-1:0] r_exp[3];
  logic [SigBits-1:0]        aw_sig[3];  // the attribute w: wa when set, else w
  logic signed [ExpBits-1:0] aw_exp[3];
  for (genvar i = 0; i < 3; i++) begin : g_vin
    for (genvar w = 0; w < WordsPerVertex; w++) begin : g_w
      localparam int Top = InBits - PrimBits - (i * WordsPerVertex + w) * ValBits;
      assign v_neg[i][w] = tri_q[Top-1];
      assign v_sig[i][w] = tri_q[Top-2 -: SigBits];
      assign v_exp[i][w] = tri_q[Top-2-SigBits -: ExpBits];
    end
    localparam int RTop = InBits - PrimBits - 3 * WordsPerVertex * ValBits - i * RValBits;
    assign r_neg[i] = tri_q[RTop-1];
    assign r_sig[i] = tri_q[RTop-2 -: RecipBits];
    assign r_exp[i] = tri_q[RTop-2-RecipBits -: ExpBits];
    if (HasWa != 0) begin : g_wa
      assign aw_sig[i] = (|v_sig[i][4]) ? v_sig[i][4] : v_sig[i][3];
      assign aw_exp[i] = (|v_sig[i][4]) ? v_exp[i][4] : v_exp[i][3];
    end else begin : g_w_only
      assign aw_sig[i] = v_sig[i][3];
      assign aw_exp[i] = v_exp[i][3];
    end
  end

  // ---- quotient jobs and lanes -----------------------------------------------------------------
  // A job, MSB first: kind (2: 0 XW, 1 YW, 2 ZD, 3 FLT), neg, n_sig, n_mul, d_sig, k (signed
  // KBits), zexp (signed ExpBits): fxr_viewport_lane's inputs. Flat vectors, not a struct (Yosys
  // 0.23 mis-resolves members of struct variables declared in generate blocks). Job j = c·Lanes + l
  // goes to lane l in slot c; each lane's job is built in its multiplexer, only while a triangle
  // is in the input register and only for the current slot (the loop unrolls to constant indices),
  // so that a simulator builds Lanes jobs per busy clock and none on an idle one (docs/rtl.md,
  // "Co-simulation speed", session 10). Job j's vertex and value:
  `define FXR_VP_I(c) (((c) * Lanes + l) / JobsPerVertex)
  `define FXR_VP_Q(c) (((c) * Lanes + l) % JobsPerVertex)
  `define FXR_VP_W(c) (4 + HasWa + `FXR_VP_Q(c) - 4)
  localparam int JZexp = 0;
  localparam int JK = JZexp + ExpBits;
  localparam int JDSig = JK + KBits;
  localparam int JNMul = JDSig + SigBits;
  localparam int JNSig = JNMul + WindowIntBits + 1;
  localparam int JNeg = JNSig + SigBits;
  localparam int JKind = JNeg + 1;
  localparam int JobBits = JKind + 2;

  logic [ResBits-1:0] lane_res[Lanes];
  logic               lane_rng[Lanes];
  logic               lane_v[Lanes];
  for (genvar l = 0; l < Lanes; l++) begin : g_lane
    logic [JobBits-1:0] jb;
    logic               jv;
    always_comb begin
      jb = '0;
      jv = 1'b0;
      if (tri_v) begin
        for (int c = 0; c < Slots; c++) begin
          if (SlotBits'(c) == slot && c * Lanes + l < Jobs) begin
            jv = 1'b1;
            if (`FXR_VP_Q(c) < 3) begin  // ax, ay, z: x_c, y_c, z_c over w_a
              jb = {2'(`FXR_VP_Q(c)), v_neg[`FXR_VP_I(c)][`FXR_VP_Q(c)], v_sig[`FXR_VP_I(c)][`FXR_VP_Q(c)],
                    `FXR_VP_Q(c) == 0 ? viewport_w_i : `FXR_VP_Q(c) == 1 ? viewport_h_i : (WindowIntBits + 1)'(1),
                    aw_sig[`FXR_VP_I(c)],
                    KBits'(v_exp[`FXR_VP_I(c)][`FXR_VP_Q(c)]) - KBits'(aw_exp[`FXR_VP_I(c)]) +
                        KBits'(`FXR_VP_Q(c) == 2 ? ZFracBits : AttrSubBits - 1),
                    ExpBits'(0)};
            end else if (`FXR_VP_Q(c) == 3) begin  // 1 / w_a
              jb = {2'd3, 1'b0, SigBits'(1), (WindowIntBits + 1)'(1), aw_sig[`FXR_VP_I(c)],
                    -(KBits'(aw_exp[`FXR_VP_I(c)])), ExpBits'(0)};
            end else begin  // v_k / w_a, or v_k / 1 (affine)
              // a zero varying: attr_quotient gives exponent 0, normalize_fx (affine) keeps the input's
              jb = {2'd3, v_neg[`FXR_VP_I(c)][`FXR_VP_W(c)], v_sig[`FXR_VP_I(c)][`FXR_VP_W(c)], (WindowIntBits + 1)'(1),
                    interp_i ? SigBits'(1) : aw_sig[`FXR_VP_I(c)],
                    KBits'(v_exp[`FXR_VP_I(c)][`FXR_VP_W(c)]) - (interp_i ? KBits'(0) : KBits'(aw_exp[`FXR_VP_I(c)])),
                    interp_i ? v_exp[`FXR_VP_I(c)][`FXR_VP_W(c)] : ExpBits'(0)};
            end
          end
        end
      end
    end
    fxr_viewport_lane #(
      .SigBits(SigBits), .ExpBits(ExpBits), .WindowIntBits(WindowIntBits), .AttrSubBits(AttrSubBits),
      .ZFracBits(ZFracBits), .AttrSigBits(AttrSigBits)
    ) u_lane (
      .clk_i, .en_i(adv), .rst_ni, .valid_i(jv), .kind_i(jb[JKind +: 2]), .neg_i(jb[JNeg]), .n_sig_i(jb[JNSig +: SigBits]),
      .n_mul_i(jb[JNMul +: WindowIntBits + 1]), .d_sig_i(jb[JDSig +: SigBits]), .k_i($signed(jb[JK +: KBits])),
      .zexp_i($signed(jb[JZexp +: ExpBits])),
      .size_x_i(viewport_w_i), .size_y_i(viewport_h_i), .origin_x_i(viewport_x_i), .origin_y_i(viewport_y_i),
      .valid_o(lane_v[l]), .res_o(lane_res[l]), .range_o(lane_rng[l])
    );
  end
  `undef FXR_VP_I
  `undef FXR_VP_Q
  `undef FXR_VP_W

  // ---- snaps ---------------------------------------------------------------------------------
  // Flat (Icarus 11 assigns no whole unpacked arrays, Yosys 0.23 reads no 2-D packed ones):
  // snap sj at [sj·CodeBits +: CodeBits].
  logic [NumSnaps*CodeBits-1:0] snap_q, snap_n;
  logic                snap_rng_q;
  logic [CodeBits-1:0] su_code[SnapLanes];
  logic                su_rng[SnapLanes];
  for (genvar u = 0; u < SnapLanes; u++) begin : g_snap
    logic                      c_neg, rn;
    logic [SigBits-1:0]        c_sig;
    logic signed [ExpBits-1:0] c_exp, re;
    logic [RecipBits-1:0]      rs;
    logic [WindowIntBits:0]    size;
    logic signed [WindowIntBits-1:0] origin;
    always_comb begin
      c_neg = 1'b0;
      c_sig = '0;
      c_exp = '0;
      rn = 1'b0;
      rs = '0;
      re = '0;
      size = viewport_w_i;
      origin = viewport_x_i;
      for (int c = 0; c < Slots; c++) begin
        if (tri_v && SlotBits'(c) == slot && c * SnapLanes + u < NumSnaps) begin
          c_neg = v_neg[(c * SnapLanes + u) / 2][(c * SnapLanes + u) % 2];
          c_sig = v_sig[(c * SnapLanes + u) / 2][(c * SnapLanes + u) % 2];
          c_exp = v_exp[(c * SnapLanes + u) / 2][(c * SnapLanes + u) % 2];
          rn = r_neg[(c * SnapLanes + u) / 2];
          rs = r_sig[(c * SnapLanes + u) / 2];
          re = r_exp[(c * SnapLanes + u) / 2];
          size = (c * SnapLanes + u) % 2 == 0 ? viewport_w_i : viewport_h_i;
          origin = (c * SnapLanes + u) % 2 == 0 ? viewport_x_i : viewport_y_i;
        end
      end
    end
    fxr_viewport_snap #(
      .SigBits(SigBits), .RecipBits(RecipBits), .ExpBits(ExpBits), .WindowIntBits(WindowIntBits), .SubBits(SubBits)
    ) u_snap (
      .c_neg_i(c_neg), .c_sig_i(c_sig), .c_exp_i(c_exp), .r_neg_i(rn), .r_sig_i(rs), .r_exp_i(re),
      .size_i(size), .origin_i(origin), .code_o(su_code[u]), .range_o(su_rng[u])
    );
  end
  // This slot's snaps merged into the triangle's.
  logic snap_rng_n;
  // Read only with a triangle in the input register (snap_q, the FIFO's push): evaluated then only.
  always_comb begin
    snap_rng_n = 1'b0;
    snap_n = '0;
    if (tri_v) begin
      snap_rng_n = snap_rng_q && slot != '0;
      snap_n = snap_q;
      for (int sj = 0; sj < NumSnaps; sj++) begin
        if (SlotBits'(sj / SnapLanes) == slot) begin
          snap_n[sj*CodeBits +: CodeBits] = su_code[sj % SnapLanes];
          snap_rng_n = snap_rng_n || su_rng[sj % SnapLanes];
        end
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (adv && tri_v) begin
      snap_q <= snap_n;
      snap_rng_q <= snap_rng_n;
    end
  end

  // ---- sideband FIFO: prim, the snapped x, y, the snap range flag ---------------------------
  localparam int SideBits = PrimBits + NumSnaps * CodeBits + 1;
  logic [SideBits-1:0] fifo_mem[FifoDepth];
  logic [FifoAw-1:0]   fifo_wp, fifo_rp;
  logic [SideBits-1:0] side_in, side_out;
  logic                push, pop;
  always_comb begin
    side_in = '0;
    if (tri_v && last_slot) begin  // read only by the push
      side_in[SideBits-1 -: PrimBits] = tri_q[InBits-1 -: PrimBits];
      for (int sj = 0; sj < NumSnaps; sj++) side_in[SideBits-PrimBits-1-sj*CodeBits -: CodeBits] = snap_n[sj*CodeBits +: CodeBits];
      side_in[0] = snap_rng_n;
    end
  end
  assign push = adv && tri_v && last_slot;
  assign side_out = fifo_mem[fifo_rp];
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fifo_wp <= '0;
      fifo_rp <= '0;
    end else begin
      if (push) fifo_wp <= fifo_wp + FifoAw'(1);
      if (pop) fifo_rp <= fifo_rp + FifoAw'(1);
    end
  end
  always_ff @(posedge clk_i) begin
    if (push) fifo_mem[fifo_wp] <= side_in;
  end

  // ---- collection into the output register ----------------------------------------------------
  logic [SlotBits-1:0] cslot;
  logic                col, col_last, rng_q, rng_all;
  logic [OutBits-1:0]  out_q;
  assign col = adv && lane_v[0];
  assign col_last = col && cslot == SlotBits'(Slots - 1);
  assign pop = col_last;
  always_comb begin
    rng_all = (rng_q && cslot != '0) || side_out[0];
    for (int l = 0; l < Lanes; l++) rng_all = rng_all || (lane_v[l] && lane_rng[l]);
  end
  assign rej_range_o = col_last && rng_all;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      cslot <= '0;
      out_valid_o <= 1'b0;
    end else if (adv) begin
      out_valid_o <= col_last && !rng_all;
      if (col) cslot <= col_last ? '0 : cslot + SlotBits'(1);
    end
  end
  always_ff @(posedge clk_i) begin
    if (col) rng_q <= rng_all;
  end

  for (genvar j = 0; j < Jobs; j++) begin : g_collect
    localparam int I = j / JobsPerVertex;
    localparam int Q = j % JobsPerVertex;
    localparam int VTop = OutBits - PrimBits - I * OutVertexBits;
    localparam int Off = Q == 0 ? 2 * CodeBits
                       : Q == 1 ? 2 * CodeBits + PosBits
                       : Q == 2 ? 2 * CodeBits + 2 * PosBits
                       : 2 * CodeBits + 2 * PosBits + ZBits + (Q - 3) * FloatBits;
    localparam int Width = Q < 2 ? PosBits : Q == 2 ? ZBits : FloatBits;
    always_ff @(posedge clk_i) begin
      if (col && cslot == SlotBits'(j / Lanes)) out_q[VTop-1-Off -: Width] <= lane_res[j % Lanes][Width-1:0];
    end
  end
  for (genvar i = 0; i < 3; i++) begin : g_collect_snap
    localparam int VTop = OutBits - PrimBits - i * OutVertexBits;
    always_ff @(posedge clk_i) begin
      if (col_last) begin
        out_q[VTop-1 -: CodeBits] <= side_out[SideBits-PrimBits-1-(2*i)*CodeBits -: CodeBits];
        out_q[VTop-1-CodeBits -: CodeBits] <= side_out[SideBits-PrimBits-1-(2*i+1)*CodeBits -: CodeBits];
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (col_last) out_q[OutBits-1 -: PrimBits] <= side_out[SideBits-1 -: PrimBits];
  end
  assign out_o = out_q;
endmodule

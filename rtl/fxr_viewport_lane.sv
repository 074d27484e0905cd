// fxr_viewport_lane: one divider lane of stage 4 (fxr_viewport): a correctly rounded quotient
// n·nmul·2^k / d per clock (initiation interval 1), as a pipelined restoring divider, one stage
// per quotient bit. Model: the attribute path (model/stages/attr.cpp): attr_window (kind XW / YW),
// attr_depth (ZD), attr_quotient (FLT); docs/rtl.md "fxr_viewport".
//
// Pre (one register): N = n_sig·n_mul (exact), both N and d normalised (fxr_divide_norm), the
// exponent P of the quotient f = N/d·2^k = f'·2^P, f' = N_norm / (d_norm·2^(NBits−DBits)) ∈ (½, 2):
// P = msb(N) − msb(d) + k.
// Divider (QuotBits registers): long division of N_norm by d_norm: bit t of f' (weight 2^−t) from
// rem = 2·rem + next numerator bit, q_t = rem ≥ d, rem −= q_t·d; sticky = remainder ≠ 0.
// Post (one register), F = the QuotBits quotient bits (F = floor(f'·2^(QuotBits−1))):
//   XW / YW  v = RNE(C ± Q), Q = f'·2^P, C = (size + 2·origin)·2^(A−1): Q is aligned to two
//            fraction bits with the rest jammed into the lowest (Q4 = jam(F·2^(P+3−QuotBits))),
//            v = RNE((4C ± Q4)/4); range when P > QuotIntXY (then |Q| ≥ 2^QuotIntXY and v is out of
//            range whatever C is) or v outside a signed PosBits = WindowIntBits + A code.
//   ZD       v = RNE(Q4/4), saturated to [0, 2^ZFracBits] (z ≤ 0 gives 0; P > QuotIntZ: 2^ZFracBits).
//   FLT      the AttrSigBits leading bits of F, RNE with guard and sticky, a carry renormalises;
//            exponent P − (AttrSigBits − 1) (f' ≥ 1) or P − AttrSigBits (f' < 1). A zero numerator
//            gives {neg, 0, zexp} (zexp: 0, or the varying's own exponent on the affine path).
// Q4 and the float's guard / sticky jam bits below the rounding position: the rounding of the jammed
// value equals that of the exact quotient (docs/rtl.md "fxr_viewport").
// en_i stalls every register (the unit's one pipeline enable). Every combinational block and data
// register is evaluated / loaded only for a valid job (0 / held otherwise; nothing reads them
// then), so that the simulator skips an idle lane's arithmetic (docs/rtl.md, "Co-simulation speed").
module fxr_viewport_lane #(
  parameter int SigBits = fxr_rec_pkg::ClipVertexSigBits,
  parameter int ExpBits = fxr_rec_pkg::FxExpBits,
  parameter int WindowIntBits = fxr_config_pkg::RasterWindowIntBits,
  parameter int AttrSubBits = fxr_config_pkg::RasterAttrSubpixelBits,
  parameter int ZFracBits = fxr_config_pkg::RasterZFracBits,
  parameter int AttrSigBits = fxr_config_pkg::RasterAttrSigBits,
  // derived
  parameter int PosBits = WindowIntBits + AttrSubBits,
  parameter int FloatBits = 1 + AttrSigBits + ExpBits,
  parameter int ResBits = (PosBits > ZFracBits + 1 ? (PosBits > FloatBits ? PosBits : FloatBits)
                                                   : (ZFracBits + 1 > FloatBits ? ZFracBits + 1 : FloatBits)),
  parameter int KBits = ExpBits + 4,
  // quotient bits: the widest of XW / YW (QuotIntXY + 3), ZD (QuotIntZ + 3) and FLT (AttrSigBits + 2)
  parameter int QuotBits = (PosBits + 5 > ZFracBits + 4 ? (PosBits + 5 > AttrSigBits + 2 ? PosBits + 5 : AttrSigBits + 2)
                                                      : (ZFracBits + 4 > AttrSigBits + 2 ? ZFracBits + 4 : AttrSigBits + 2))
) (
  input  logic                    clk_i,
  input  logic                    en_i,
  input  logic                    rst_ni,
  input  logic                    valid_i,
  input  logic [1:0]              kind_i,   // 0 XW, 1 YW, 2 ZD, 3 FLT
  input  logic                    neg_i,
  input  logic [SigBits-1:0]      n_sig_i,
  input  logic [WindowIntBits:0]  n_mul_i,  // viewport size for XW / YW, else 1
  input  logic [SigBits-1:0]      d_sig_i,  // > 0
  input  logic signed [KBits-1:0] k_i,      // n_exp − d_exp + (A − 1 | ZFracBits | 0)
  input  logic signed [ExpBits-1:0] zexp_i, // FLT: the exponent of a zero result
  input  logic [WindowIntBits:0]  size_x_i, // draw state: viewport_w, _h, _x, _y
  input  logic [WindowIntBits:0]  size_y_i,
  input  logic signed [WindowIntBits-1:0] origin_x_i,
  input  logic signed [WindowIntBits-1:0] origin_y_i,
  output logic                    valid_o,
  output logic [ResBits-1:0]      res_o,    // XW / YW: PosBits signed; ZD: ZFracBits + 1; FLT: {neg, sig, exp}
  output logic                    range_o   // XW / YW: the position is out of range
);
  localparam int NBits = SigBits + WindowIntBits + 1;
  localparam int DBits = SigBits;
  localparam int RestBits = NBits - DBits + 1;
  localparam int QuotIntXY = PosBits + 2;
  localparam int QuotIntZ = ZFracBits + 1;
  localparam int MsbBits = $clog2(NBits) + 1;
  localparam int PBits = KBits + 2;
  localparam int ShBits = $clog2(QuotBits + 1) + 1;

  // ---- pre ----------------------------------------------------------------------------------
  logic [NBits-1:0] n, n_norm;
  logic [DBits-1:0] d_norm;
  logic [MsbBits-1:0] n_msb, d_msb;
  assign n = valid_i ? NBits'(n_sig_i) * NBits'(n_mul_i) : '0;
  fxr_divide_norm #(.InBits(NBits), .OutBits(NBits), .MsbBits(MsbBits)) u_nn (
    .en_i(valid_i), .x_i(n), .sig_o(n_norm), .msb_o(n_msb));
  fxr_divide_norm #(.InBits(DBits), .OutBits(DBits), .MsbBits(MsbBits)) u_dn (
    .en_i(valid_i), .x_i(d_sig_i), .sig_o(d_norm), .msb_o(d_msb));

  // The job's kind, sign, zero flag and the quotient's exponent P (zero FLT: the result exponent)
  // travel with the quotient bits (separate arrays: Icarus 11 cannot write members of struct arrays).
  logic                    n_zero;
  logic signed [PBits-1:0] p_in;
  logic [DBits-1:0]     rem_in;
  logic [RestBits-1:0]  rest_in;
  always_comb begin
    n_zero  = 1'b0;
    p_in    = '0;
    rem_in  = '0;
    rest_in = '0;
    if (valid_i) begin
      n_zero = ~|n;
      p_in = n_zero ? PBits'(zexp_i)
                    : PBits'($signed({1'b0, n_msb})) - PBits'($signed({1'b0, d_msb})) + PBits'(k_i);
      // rem before the first step is N_norm's top DBits − 1 bits: step 0 then shifts in the next.
      rem_in = DBits'(n_norm[NBits-1 -: DBits-1]);
      rest_in = n_norm[RestBits-1:0];
    end
  end

  // ---- the divider: stage 0 holds the pre register, stage t + 1 the result of step t ---------
  // Each stage's registers are variables of their own (stage 0 here, stage t + 1 in g_step[t]),
  // read by the next step through the generate scope: not slices of flat vectors, whose
  // unaligned word inserts made the simulated lane several times dearer (docs/rtl.md,
  // "Co-simulation speed"); not unpacked arrays (Icarus 11 does not update continuous assignments
  // from unpacked array words written in other generate scopes, Yosys 0.23 reads no
  // multi-dimensional packed arrays).
  localparam int RemBits = DBits;  // the remainder stays below d
  logic [QuotBits:0]       v_q;
  logic [1:0]              kind0_q;
  logic                    neg0_q, zero0_q;
  logic signed [PBits-1:0] p0_q;
  logic [RemBits-1:0]      rem0_q;
  logic [RestBits-1:0]     rest0_q;
  logic [DBits-1:0]        d0_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) v_q[0] <= 1'b0;
    else if (en_i) v_q[0] <= valid_i;
  end
  always_ff @(posedge clk_i) begin
    if (en_i && valid_i) begin
      kind0_q <= kind_i;
      neg0_q <= neg_i;
      zero0_q <= n_zero;
      p0_q <= p_in;
      rem0_q <= rem_in;
      rest0_q <= rest_in;
      d0_q <= d_norm;
    end
  end

  for (genvar t = 0; t < QuotBits; t++) begin : g_step
    // stage t: the input of step t
    logic [1:0]              kind_t;
    logic                    neg_t, zero_t;
    logic signed [PBits-1:0] p_t;
    logic [RemBits-1:0]      rem_t;   // the remainder (< d)
    logic [RestBits-1:0]     rest_t;
    /* verilator lint_off UNUSEDSIGNAL */  // stage t holds t quotient bits: the top one is read only in the last
    logic [QuotBits-1:0]     quo_t;
    /* verilator lint_on UNUSEDSIGNAL */
    logic [DBits-1:0]        d_t;
    // stage t + 1: the result of step t
    logic [1:0]              kind_r;
    logic                    neg_r, zero_r;
    logic signed [PBits-1:0] p_r;
    logic [RemBits-1:0]      rem_r;
    logic [RestBits-1:0]     rest_r;
    logic [QuotBits-1:0]     quo_r;
    /* verilator lint_off UNUSEDSIGNAL */  // the divisor of step t + 1: the last stage's is not read
    logic [DBits-1:0]        d_r;
    /* verilator lint_on UNUSEDSIGNAL */
    if (t == 0) begin : g_from_pre
      assign kind_t = kind0_q;
      assign neg_t  = neg0_q;
      assign zero_t = zero0_q;
      assign p_t    = p0_q;
      assign rem_t  = rem0_q;
      assign rest_t = rest0_q;
      assign quo_t  = '0;
      assign d_t    = d0_q;
    end else begin : g_from_step
      assign kind_t = g_step[t-1].kind_r;
      assign neg_t  = g_step[t-1].neg_r;
      assign zero_t = g_step[t-1].zero_r;
      assign p_t    = g_step[t-1].p_r;
      assign rem_t  = g_step[t-1].rem_r;
      assign rest_t = g_step[t-1].rest_r;
      assign quo_t  = g_step[t-1].quo_r;
      assign d_t    = g_step[t-1].d_r;
    end

    logic [DBits:0]   r;
    logic [DBits+1:0] sub;   // r − d; its sign bit is the quotient bit's complement
    logic [DBits-1:0] diff;  // r − d when r ≥ d: below d
    logic             qb;
    always_comb begin
      r   = '0;
      sub = '0;
      if (v_q[t]) begin
        r   = {rem_t, rest_t[RestBits-1]};
        sub = {1'b0, r} - {2'b0, d_t};
      end
    end
    assign qb = !sub[DBits+1];
    assign diff = sub[DBits-1:0];
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) v_q[t+1] <= 1'b0;
      else if (en_i) v_q[t+1] <= v_q[t];
    end
    always_ff @(posedge clk_i) begin
      if (en_i && v_q[t]) begin
        kind_r <= kind_t;
        neg_r <= neg_t;
        zero_r <= zero_t;
        p_r <= p_t;
        rem_r <= qb ? diff : r[DBits-1:0];
        rest_r <= {rest_t[RestBits-2:0], 1'b0};
        quo_r <= {quo_t[QuotBits-2:0], qb};
        d_r <= d_t;
      end
    end
  end

  // ---- post ---------------------------------------------------------------------------------
  localparam int SrBits = PBits + 1;
  localparam int CBits = WindowIntBits + 2 + AttrSubBits + 2;  // 4C (signed)
  localparam int XBits = (CBits > QuotBits + 1 ? CBits : QuotBits + 1) + 1;
  localparam logic signed [XBits-1:0] PosMax = (XBits'(1) <<< (PosBits - 1)) - XBits'(1);
  localparam logic signed [XBits-1:0] PosMin = -(XBits'(1) <<< (PosBits - 1));
  localparam int ZBits = ZFracBits + 1;
  localparam logic [QuotBits-1:0] ZOne = QuotBits'(1) << ZFracBits;
  logic                     m_v;
  logic [1:0]               m_kind;
  logic                     m_neg, m_zero;
  logic signed [PBits-1:0]  m_p;
  logic [QuotBits-1:0]      f;
  logic                     rem_nz;
  logic signed [SrBits-1:0] sr;
  logic [QuotBits-1:0]      q4, q4_mask;
  logic [ShBits-1:0]        q4_sh;
  logic                     q4_all, q4_st;
  logic signed [XBits-1:0]  c4, x4, pos;
  logic                     pos_up, pos_ovf;
  logic                     zq_up;
  logic [QuotBits-1:0]      zq;
  logic [ZBits-1:0]         z;
  logic [AttrSigBits-1:0]   top_sig;
  logic                     g, st, fup;
  logic [AttrSigBits:0]     inc;
  logic [AttrSigBits-1:0]   fsig;
  logic signed [PBits-1:0]  fexp;
  logic [ResBits-1:0]       res;
  logic                     rng;
  assign m_v = v_q[QuotBits];
  always_comb begin
    m_kind  = '0;
    m_neg   = 1'b0;
    m_zero  = 1'b0;
    m_p     = '0;
    f       = '0;
    rem_nz  = 1'b0;
    sr      = '0;
    q4_all  = 1'b0;
    q4_sh   = '0;
    q4_mask = '0;
    q4_st   = 1'b0;
    q4      = '0;
    c4      = '0;
    x4      = '0;
    pos_up  = 1'b0;
    pos     = '0;
    pos_ovf = 1'b0;
    zq_up   = 1'b0;
    zq      = '0;
    z       = '0;
    top_sig = '0;
    g       = 1'b0;
    st      = 1'b0;
    fup     = 1'b0;
    inc     = '0;
    fsig    = '0;
    fexp    = '0;
    res     = '0;
    rng     = 1'b0;
    if (m_v) begin
      m_kind = g_step[QuotBits-1].kind_r;
      m_neg = g_step[QuotBits-1].neg_r;
      m_zero = g_step[QuotBits-1].zero_r;
      m_p = g_step[QuotBits-1].p_r;
      f = g_step[QuotBits-1].quo_r;
      rem_nz = (|g_step[QuotBits-1].rem_r) | (|g_step[QuotBits-1].rest_r);

      // Q4 = jam(F·2^(P+3−QuotBits)) for XW / YW / ZD: a right shift by sr = QuotBits − 3 − P ≥ 0.
      sr = SrBits'(QuotBits - 3) - SrBits'(m_p);
      q4_all = sr >= SrBits'(QuotBits);
      q4_sh = q4_all ? '0 : (sr < 0 ? '0 : ShBits'(sr));
      q4_mask = ~({QuotBits{1'b1}} << q4_sh);
      q4_st = (|(f & q4_mask)) | rem_nz;
      q4 = m_zero ? '0
                  : q4_all ? QuotBits'(1)  // f' > 0: only the sticky bit is left
                           : ((f >> q4_sh) | {{(QuotBits - 1){1'b0}}, q4_st});

      // XW / YW: v = RNE((4C ± Q4) / 4).
      if (m_kind == 2'd1) c4 = (XBits'($signed(size_y_i)) + (XBits'(origin_y_i) <<< 1)) <<< (AttrSubBits + 1);
      else c4 = (XBits'($signed(size_x_i)) + (XBits'(origin_x_i) <<< 1)) <<< (AttrSubBits + 1);
      x4 = m_neg ? c4 - XBits'(q4) : c4 + XBits'(q4);
      pos_up = x4[1] & (x4[0] | x4[2]);
      pos = (x4 >>> 2) + $signed(XBits'(pos_up));
      pos_ovf = !m_zero && (m_p > PBits'(QuotIntXY));

      // ZD: v = RNE(Q4 / 4), saturated.
      zq_up = q4[1] & (q4[0] | q4[2]);
      zq = (q4 >> 2) + {{(QuotBits - 1){1'b0}}, zq_up};
      if (m_zero || m_neg) z = '0;
      else if (m_p > PBits'(QuotIntZ) || zq > ZOne) z = ZBits'(ZOne);
      else z = zq[ZBits-1:0];

      // FLT: RNE to AttrSigBits bits.
      if (f[QuotBits-1]) begin
        top_sig = f[QuotBits-1 -: AttrSigBits];
        g = f[QuotBits-1-AttrSigBits];
        st = rem_nz | (|(f & ((QuotBits'(1) << (QuotBits - 1 - AttrSigBits)) - QuotBits'(1))));
        fexp = m_p - PBits'(AttrSigBits - 1);
      end else begin
        top_sig = f[QuotBits-2 -: AttrSigBits];
        g = f[QuotBits-2-AttrSigBits];
        st = rem_nz | (|(f & ((QuotBits'(1) << (QuotBits - 2 - AttrSigBits)) - QuotBits'(1))));
        fexp = m_p - PBits'(AttrSigBits);
      end
      fup = g & (st | top_sig[0]);
      inc = {1'b0, top_sig} + (AttrSigBits + 1)'(fup);
      if (m_zero) begin
        fsig = '0;
        fexp = m_p;
      end else if (inc[AttrSigBits]) begin
        fsig = {1'b1, {(AttrSigBits - 1){1'b0}}};
        fexp = fexp + PBits'(1);
      end else begin
        fsig = inc[AttrSigBits-1:0];
      end

      unique case (m_kind)
        2'd0, 2'd1: begin
          res = ResBits'(pos[PosBits-1:0]);
          rng = pos_ovf || pos > PosMax || pos < PosMin;
        end
        2'd2: res = ResBits'(z);
        default: res = ResBits'({m_neg, fsig, fexp[ExpBits-1:0]});
      endcase
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_o <= 1'b0;
    else if (en_i) valid_o <= m_v;
  end
  always_ff @(posedge clk_i) begin
    if (en_i && m_v) begin
      res_o <= res;
      range_o <= rng;
    end
  end
endmodule

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
  assign n_zero = ~|n;
  assign p_in = n_zero ? PBits'(zexp_i)
                            : PBits'($signed({1'b0, n_msb})) - PBits'($signed({1'b0, d_msb})) + PBits'(k_i);
  // rem before the first step is N_norm's top DBits − 1 bits: step 0 then shifts in the next.
  assign rem_in = DBits'(n_norm[NBits-1 -: DBits-1]);
  assign rest_in = n_norm[RestBits-1:0];

  // ---- the divider: stage 0 holds the pre register, stage t + 1 the result of step t ---------
  // Flat vectors, slice t the register after step t − 1 (Icarus 11 does not update continuous
  // assignments from unpacked array words written in other generate scopes, Yosys 0.23 reads no
  // multi-dimensional packed arrays).
  localparam int RemBits = DBits;  // the remainder stays below d
  logic [2*(QuotBits+1)-1:0]        kind_q;
  logic [QuotBits:0]                neg_q, zero_q, v_q;
  logic [PBits*(QuotBits+1)-1:0]    p_q;
  logic [RemBits*(QuotBits+1)-1:0]  rem_q;
  logic [RestBits*(QuotBits+1)-1:0] rest_q;
  /* verilator lint_off UNUSEDSIGNAL */  // slice t holds t quotient bits: the top one is read only in the last
  logic [QuotBits*(QuotBits+1)-1:0] quo_q;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [DBits*QuotBits-1:0]        d_q;  // the divisor of steps 0 … QuotBits − 1

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) v_q[0] <= 1'b0;
    else if (en_i) v_q[0] <= valid_i;
  end
  always_ff @(posedge clk_i) begin
    if (en_i && valid_i) begin
      kind_q[(0)*2 +: 2] <= kind_i;
      neg_q[0] <= neg_i;
      zero_q[0] <= n_zero;
      p_q[(0)*PBits +: PBits] <= p_in;
      rem_q[(0)*RemBits +: RemBits] <= rem_in;
      rest_q[(0)*RestBits +: RestBits] <= rest_in;
      quo_q[(0)*QuotBits +: QuotBits] <= '0;
      d_q[(0)*DBits +: DBits] <= d_norm;
    end
  end

  for (genvar t = 0; t < QuotBits; t++) begin : g_step
    logic [DBits:0]   r;
    logic [DBits+1:0] sub;   // r − d; its sign bit is the quotient bit's complement
    logic [DBits-1:0] diff;  // r − d when r ≥ d: below d
    logic             qb;
    logic [DBits-1:0]    rem_t;   // the remainder (< d)
    logic [RestBits-1:0] rest_t;
    logic [QuotBits-2:0] quo_t;   // the quotient bits that are kept
    assign rem_t = rem_q[(t)*RemBits +: RemBits];
    assign rest_t = rest_q[(t)*RestBits +: RestBits];
    assign quo_t = quo_q[(t)*QuotBits +: QuotBits-1];
    assign r = {rem_t, rest_t[RestBits-1]};
    assign sub = {1'b0, r} - {2'b0, d_q[(t)*DBits +: DBits]};
    assign qb = !sub[DBits+1];
    assign diff = sub[DBits-1:0];
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) v_q[t+1] <= 1'b0;
      else if (en_i) v_q[t+1] <= v_q[t];
    end
    always_ff @(posedge clk_i) begin
      if (en_i && v_q[t]) begin
        kind_q[(t+1)*2 +: 2] <= kind_q[(t)*2 +: 2];
        neg_q[t+1] <= neg_q[t];
        zero_q[t+1] <= zero_q[t];
        p_q[(t+1)*PBits +: PBits] <= p_q[(t)*PBits +: PBits];
        rem_q[(t+1)*RemBits +: RemBits] <= qb ? diff : r[DBits-1:0];
        rest_q[(t+1)*RestBits +: RestBits] <= {rest_t[RestBits-2:0], 1'b0};
        quo_q[(t+1)*QuotBits +: QuotBits] <= {quo_t, qb};
      end
    end
    if (t + 1 < QuotBits) begin : g_d
      always_ff @(posedge clk_i) begin
        if (en_i && v_q[t]) d_q[(t+1)*DBits +: DBits] <= d_q[(t)*DBits +: DBits];
      end
    end
  end

  // ---- post ---------------------------------------------------------------------------------
  logic [1:0]              m_kind;
  logic                    m_neg, m_zero;
  logic signed [PBits-1:0] m_p;
  logic [QuotBits-1:0]     f;
  logic                    rem_nz;
  assign m_kind = kind_q[(QuotBits)*2 +: 2];
  assign m_neg = neg_q[QuotBits];
  assign m_zero = zero_q[QuotBits];
  assign m_p = $signed(p_q[(QuotBits)*PBits +: PBits]);
  assign f = quo_q[(QuotBits)*QuotBits +: QuotBits];
  assign rem_nz = (|rem_q[(QuotBits)*RemBits +: RemBits]) | (|rest_q[(QuotBits)*RestBits +: RestBits]);

  // Q4 = jam(F·2^(P+3−QuotBits)) for XW / YW / ZD: a right shift by sr = QuotBits − 3 − P ≥ 0.
  localparam int SrBits = PBits + 1;
  logic signed [SrBits-1:0] sr;
  logic [QuotBits-1:0]      q4, q4_mask;
  logic [ShBits-1:0]        q4_sh;
  logic                     q4_all;
  assign sr = SrBits'(QuotBits - 3) - SrBits'(m_p);
  assign q4_all = sr >= SrBits'(QuotBits);
  assign q4_sh = q4_all ? '0 : (sr < 0 ? '0 : ShBits'(sr));
  assign q4_mask = ~({QuotBits{1'b1}} << q4_sh);
  logic q4_st, zq_up;
  assign q4_st = (|(f & q4_mask)) | rem_nz;
  assign q4 = m_zero ? '0
                     : q4_all ? QuotBits'(1)  // f' > 0: only the sticky bit is left
                              : ((f >> q4_sh) | {{(QuotBits - 1){1'b0}}, q4_st});

  // XW / YW: v = RNE((4C ± Q4) / 4).
  localparam int CBits = WindowIntBits + 2 + AttrSubBits + 2;  // 4C (signed)
  localparam int XBits = (CBits > QuotBits + 1 ? CBits : QuotBits + 1) + 1;
  localparam logic signed [XBits-1:0] PosMax = (XBits'(1) <<< (PosBits - 1)) - XBits'(1);
  localparam logic signed [XBits-1:0] PosMin = -(XBits'(1) <<< (PosBits - 1));
  logic signed [XBits-1:0] c4, x4, pos;
  logic                    pos_up, pos_ovf;
  always_comb begin
    if (m_kind == 2'd1) c4 = (XBits'($signed(size_y_i)) + (XBits'(origin_y_i) <<< 1)) <<< (AttrSubBits + 1);
    else c4 = (XBits'($signed(size_x_i)) + (XBits'(origin_x_i) <<< 1)) <<< (AttrSubBits + 1);
  end
  assign x4 = m_neg ? c4 - XBits'(q4) : c4 + XBits'(q4);
  assign pos_up = x4[1] & (x4[0] | x4[2]);
  assign pos = (x4 >>> 2) + $signed(XBits'(pos_up));
  assign pos_ovf = !m_zero && (m_p > PBits'(QuotIntXY));

  // ZD: v = RNE(Q4 / 4), saturated.
  localparam int ZBits = ZFracBits + 1;
  localparam logic [QuotBits-1:0] ZOne = QuotBits'(1) << ZFracBits;
  logic [QuotBits-1:0] zq;
  logic [ZBits-1:0]    z;
  assign zq_up = q4[1] & (q4[0] | q4[2]);
  assign zq = (q4 >> 2) + {{(QuotBits - 1){1'b0}}, zq_up};
  always_comb begin
    if (m_zero || m_neg) z = '0;
    else if (m_p > PBits'(QuotIntZ) || zq > ZOne) z = ZBits'(ZOne);
    else z = zq[ZBits-1:0];
  end

  // FLT: RNE to AttrSigBits bits.
  logic [AttrSigBits-1:0]   top_sig;
  logic                     g, st, fup;
  logic [AttrSigBits:0]     inc;
  logic [AttrSigBits-1:0]   fsig;
  logic signed [PBits-1:0]  fexp;
  always_comb begin
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
  end

  logic [ResBits-1:0] res;
  logic               rng;
  always_comb begin
    res = '0;
    rng = 1'b0;
    unique case (m_kind)
      2'd0, 2'd1: begin
        res = ResBits'(pos[PosBits-1:0]);
        rng = pos_ovf || pos > PosMax || pos < PosMin;
      end
      2'd2: res = ResBits'(z);
      default: res = ResBits'({m_neg, fsig, fexp[ExpBits-1:0]});
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_o <= 1'b0;
    else if (en_i) valid_o <= v_q[QuotBits];
  end
  always_ff @(posedge clk_i) begin
    if (en_i && v_q[QuotBits]) begin
      res_o <= res;
      range_o <= rng;
    end
  end
endmodule

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

  // The rest of the pre logic (P, the first remainder) is evaluated in the clocked process that
  // loads stage 0, only for a valid job.
  logic                    n_zero;
  assign n_zero = ~|n;

  // ---- the divider: stage 0 holds the pre register, stage t + 1 the result of step t ---------
  // One unpacked array per field, element t the register after step t − 1 (the last stage,
  // QuotBits, in plain registers: the post logic reads it), all written by one clocked process,
  // a loop over the steps. Why this form (docs/rtl.md, "Co-simulation speed", session 8): flat
  // vectors with a slice per stage made Verilator copy and re-insert whole vectors for every
  // stage (the lanes were 27 % of the unit's simulation); registers in generate scopes hang
  // Icarus 11, which also does not update continuous assignments from unpacked array words
  // written in other generate scopes, nor write members of struct arrays (docs/references.md).
  // Yosys (mem2reg) makes each element a register: the flip-flops are the flat vectors' bits.
  // The job's kind, sign, zero flag and the quotient's exponent P (zero FLT: the result exponent),
  // the side word {kind, neg, zero, P}, do not travel through the stages: the lane's latency in
  // enabled clocks is fixed, so the side word is written into a ring at the issue (side_wp counts
  // the enabled clocks) and read by the post logic QuotBits + 1 enabled clocks later, when the job
  // is in the last stage (docs/rtl.md, "Co-simulation speed", session 10).
  localparam int RemBits = DBits;  // the remainder stays below d
  localparam int SideBits = 2 + 1 + 1 + PBits;
  localparam int RingAw = $clog2(QuotBits + 2);
  localparam int RingDepth = 1 << RingAw;  // > QuotBits + 1: an entry is read before it is rewritten
  logic [QuotBits:0] v_q;
  logic [SideBits-1:0] side_ring [RingDepth];
  logic [RingAw-1:0]   side_wp;
  (* mem2reg *) logic [RemBits-1:0]  rem_a  [QuotBits];
  (* mem2reg *) logic [RestBits-1:0] rest_a [QuotBits];
  (* mem2reg *) logic [QuotBits-1:0] quo_a  [QuotBits];  // element t holds t quotient bits
  (* mem2reg *) logic [DBits-1:0]    d_a    [QuotBits];  // the divisor of steps 0 … QuotBits − 1
  logic [RemBits-1:0]  rem_l;  // stage QuotBits
  logic [RestBits-1:0] rest_l;
  logic [QuotBits-1:0] quo_l;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      v_q <= '0;
      side_wp <= '0;
    end else if (en_i) begin
      v_q <= {v_q[QuotBits-1:0], valid_i};
      side_wp <= side_wp + RingAw'(1);
    end
  end
  // Blocking assignments in descending step order: each element is read (the register's value)
  // before the step below overwrites it, so this is the shift register of nonblocking
  // assignments, without a simulator's delayed-assignment copy of every element written (an
  // update flag, a value and a commit per element and clock: half of the lanes' simulation time).
  // The arrays are read nowhere else (the last stage, read by the post logic, is nonblocking).
  /* verilator lint_off BLKSEQ */
  // The loop is skipped when no stage holds a job (|v_q: the idle lanes' cost per clock).
  always_ff @(posedge clk_i) begin
    if (en_i && |v_q[QuotBits-1:0]) begin
      for (int t = QuotBits - 1; t >= 0; t--) begin
        if (v_q[t]) begin
          logic [DBits:0]      r;
          logic [DBits+1:0]    sub;
          logic [RemBits-1:0]  rem;
          logic [QuotBits-1:0] quo;
          // Step t: r = 2·rem + the next numerator bit; q_t = r ≥ d (the complement of the sign of
          // r − d); the remainder r − q_t·d (< d). Written out here: a function returning {q_t,
          // remainder} made a simulator pack and unpack a word per step (docs/rtl.md,
          // "Co-simulation speed", session 11).
          r = {rem_a[t], rest_a[t][RestBits-1]};
          sub = {1'b0, r} - {2'b0, d_a[t]};
          rem = sub[DBits+1] ? r[DBits-1:0] : sub[DBits-1:0];
          quo = {quo_a[t][QuotBits-2:0], ~sub[DBits+1]};
          if (t + 1 < QuotBits) begin
            rem_a[t+1] = rem;
            rest_a[t+1] = {rest_a[t][RestBits-2:0], 1'b0};
            quo_a[t+1] = quo;
            d_a[t+1] = d_a[t];
          end else begin
            rem_l <= rem;
            rest_l <= {rest_a[t][RestBits-2:0], 1'b0};
            quo_l <= quo;
          end
        end
      end
    end
    if (en_i && valid_i) begin
      // pre: the quotient's exponent P = msb(N) − msb(d) + k (a zero numerator: zexp); rem before
      // the first step is N_norm's top DBits − 1 bits (step 0 then shifts in the next).
      logic signed [PBits-1:0] p_in;
      p_in = n_zero ? PBits'(zexp_i)
                    : PBits'($signed({1'b0, n_msb})) - PBits'($signed({1'b0, d_msb})) + PBits'(k_i);
      rem_a[0] = DBits'(n_norm[NBits-1 -: DBits-1]);
      rest_a[0] = n_norm[RestBits-1:0];
      quo_a[0] = '0;
      d_a[0] = d_norm;
      side_ring[side_wp] <= {kind_i, neg_i, n_zero, p_in};
    end
  end
  /* verilator lint_on BLKSEQ */

  // ---- post ---------------------------------------------------------------------------------
  // Evaluated in the clocked process that loads res_o, only with a job in the last stage (blocking
  // variables read nowhere else: combinational logic in synthesis), so that an idle lane costs a
  // simulator nothing here (docs/rtl.md, "Co-simulation speed", session 10).
  localparam int SrBits = PBits + 1;
  // XW / YW: v = RNE((4C ± Q4) / 4).
  localparam int CBits = WindowIntBits + 2 + AttrSubBits + 2;  // 4C (signed)
  localparam int XBits = (CBits > QuotBits + 1 ? CBits : QuotBits + 1) + 1;
  localparam logic signed [XBits-1:0] PosMax = (XBits'(1) <<< (PosBits - 1)) - XBits'(1);
  localparam logic signed [XBits-1:0] PosMin = -(XBits'(1) <<< (PosBits - 1));
  // ZD: v = RNE(Q4 / 4), saturated.
  localparam int ZBits = ZFracBits + 1;
  localparam logic [QuotBits-1:0] ZOne = QuotBits'(1) << ZFracBits;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) valid_o <= 1'b0;
    else if (en_i) valid_o <= v_q[QuotBits];
  end
  /* verilator lint_off BLKSEQ */
  always_ff @(posedge clk_i) begin
    if (en_i && v_q[QuotBits]) begin
      logic [1:0]              m_kind;
      logic                    m_neg, m_zero;
      logic signed [PBits-1:0] m_p;
      logic [QuotBits-1:0]     f;
      logic                    rem_nz;
      logic signed [SrBits-1:0] sr;
      logic [QuotBits-1:0]      q4, q4_mask;
      logic [ShBits-1:0]        q4_sh;
      logic                     q4_all, q4_st, zq_up;
      logic signed [XBits-1:0]  c4, x4, pos;
      logic                     pos_up, pos_ovf;
      logic [QuotBits-1:0]      zq;
      logic [ZBits-1:0]         z;
      logic [AttrSigBits-1:0]   top_sig;
      logic                     g, st, fup;
      logic [AttrSigBits:0]     inc;
      logic [AttrSigBits-1:0]   fsig;
      logic signed [PBits-1:0]  fexp;
      logic [RingAw-1:0]        side_rp;  // the entry written QuotBits + 1 enabled clocks ago
      side_rp = side_wp - RingAw'(QuotBits + 1);
      {m_kind, m_neg, m_zero, m_p} = side_ring[side_rp];
      f = quo_l;
      rem_nz = (|rem_l) | (|rest_l);

      // Q4 = jam(F·2^(P+3−QuotBits)) for XW / YW / ZD: a right shift by sr = QuotBits − 3 − P ≥ 0.
      sr = SrBits'(QuotBits - 3) - SrBits'(m_p);
      q4_all = sr >= SrBits'(QuotBits);
      q4_sh = q4_all ? '0 : (sr < 0 ? '0 : ShBits'(sr));
      q4_mask = ~({QuotBits{1'b1}} << q4_sh);
      q4_st = (|(f & q4_mask)) | rem_nz;
      q4 = m_zero ? '0
                  : q4_all ? QuotBits'(1)  // f' > 0: only the sticky bit is left
                           : ((f >> q4_sh) | {{(QuotBits - 1){1'b0}}, q4_st});

      unique case (m_kind)
        2'd0, 2'd1: begin
          // XW / YW: v = RNE((4C ± Q4) / 4).
          if (m_kind == 2'd1) c4 = (XBits'($signed(size_y_i)) + (XBits'(origin_y_i) <<< 1)) <<< (AttrSubBits + 1);
          else c4 = (XBits'($signed(size_x_i)) + (XBits'(origin_x_i) <<< 1)) <<< (AttrSubBits + 1);
          x4 = m_neg ? c4 - XBits'(q4) : c4 + XBits'(q4);
          pos_up = x4[1] & (x4[0] | x4[2]);
          pos = (x4 >>> 2) + $signed(XBits'(pos_up));
          pos_ovf = !m_zero && (m_p > PBits'(QuotIntXY));
          res_o <= ResBits'(pos[PosBits-1:0]);
          range_o <= pos_ovf || pos > PosMax || pos < PosMin;
        end
        2'd2: begin
          // ZD: v = RNE(Q4 / 4), saturated.
          zq_up = q4[1] & (q4[0] | q4[2]);
          zq = (q4 >> 2) + {{(QuotBits - 1){1'b0}}, zq_up};
          if (m_zero || m_neg) z = '0;
          else if (m_p > PBits'(QuotIntZ) || zq > ZOne) z = ZBits'(ZOne);
          else z = zq[ZBits-1:0];
          res_o <= ResBits'(z);
          range_o <= 1'b0;
        end
        default: begin
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
          res_o <= ResBits'({m_neg, fsig, fexp[ExpBits-1:0]});
          range_o <= 1'b0;
        end
      endcase
    end
  end
  /* verilator lint_on BLKSEQ */
endmodule

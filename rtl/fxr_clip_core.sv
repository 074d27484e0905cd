// fxr_clip_core: the clipper with flat record ports (fxr_clip wraps it in fxr_rec_pkg's packed
// structs; Icarus 11 aborts on packed-struct ports, so tb/icarus/clip_txn_tb.sv drives this one).
// fxr_clip: stage 2 of the raster unit, the clipper (issue 11). One exact triangle in, 0..n
// triangles inside the clip volume out, bit-identical to the model's ClipStage
// (model/stages/clip.hpp; docs/pipeline.md, stage 2; docs/rtl.md, "fxr_clip"). Vectors: the
// transaction dumps' clip.in / clip.out (docs/vectors.md; tb/txn/clip_txn_test.cpp).
//
// Ports:
//   clk_i, rst_ni                  clock, active-low asynchronous reset
//   viewport_x_i, viewport_y_i     viewport origin (signed pixels, RasterWindowIntBits), as fxr_setup
//   viewport_w_i, viewport_h_i     viewport size (RasterWindowIntBits + 1 bits, signed): the guard band
//   in_valid_i / in_ready_o        input handshake
//   in_i                           fxr_rec_pkg::exact_triangle_t (stage 1's output)
//   out_valid_o / out_ready_i      output handshake
//   out_o                          fxr_rec_pkg::clipped_triangle_t (v<i>_wa when ClipVertexHasWa)
//   out_last_o                     the input's final output (the dumps' `last`)
//   done_o                         pulse, registered: the outcome of one input primitive was decided
//                                  in the clock before (its input transfer for the trivial cases,
//                                  its last output loaded, or the clipper ending with none)
//   done_outcome_o                 its fxr::ClipOutcome (fxr_rec_pkg::ClipOutcome*)
//   done_created_o                 new vertices made (RasterStats::clip_vertices_created)
//
// Function (docs/pipeline.md, stage 2):
//  * Fast path, one clock per triangle (in_ready_o = idle and the output register free): 21
//    exact plane-side units (plane_side()) give the outcodes of the 3 vertices against the 7 planes (w_min,
//    near, far and the guard band derived here from the viewport); all outside one plane: trivial
//    reject (no output); all inside: trivial accept (the triangle, attribute w = w_c).
//  * Otherwise the iterative clipper, Sutherland-Hodgman over a two-bank polygon buffer of
//    ClipMaxPolyVerts vertices: per plane one clock per vertex for its side (one more plane_side())
//    and one to decide; a plane no vertex is outside of is skipped; per edge a kept vertex is copied and an edge with
//    strictly opposite sides makes a new vertex: the exact plane distances d_s, d_e as fixed-point
//    integers (lsb 2^LsbMin, DistBits wide: 4 clocks), q = |d_s - d_e| normalised (1 clock), then
//    per component c = (c_e*d_s - c_s*d_e)/(d_s - d_e): the exact numerator by an MSB-first
//    shift-and-add over both significands (SigBits + |exp_e - exp_s| clocks), normalised (1
//    clock), a restoring division of bits + 3 quotient bits (one per clock) with a sticky bit from
//    the remainder, and one round to nearest even to `bits` (RasterClipSigBits; w:
//    RecipInSigBits), flushed to +-0 below 2^ClipFlushLeadExp (1 clock). Finally the fan
//    (v0, v_i, v_i+1) is emitted, one triangle per clock the output is free.
//
// Both records are flat bit vectors here (first field most significant, as fxr_rec_pkg packs
// them); inside, a vertex is NumComp values (neg, sig, exp) in clipped_triangle_t's order.
module fxr_clip_core (
  input  logic                                       clk_i,
  input  logic                                       rst_ni,
  input  logic [fxr_config_pkg::RasterWindowIntBits-1:0] viewport_x_i,
  input  logic [fxr_config_pkg::RasterWindowIntBits-1:0] viewport_y_i,
  input  logic [fxr_config_pkg::RasterWindowIntBits:0]   viewport_w_i,
  input  logic [fxr_config_pkg::RasterWindowIntBits:0]   viewport_h_i,
  input  logic                                       in_valid_i,
  output logic                                       in_ready_o,
  input  logic [fxr_rec_pkg::ExactTriangleBits-1:0] in_i,      // exact_triangle_t, flat
  output logic                                       out_valid_o,
  input  logic                                       out_ready_i,
  output logic [fxr_rec_pkg::ClippedTriangleBits-1:0] out_o,   // clipped_triangle_t, flat
  output logic                                       out_last_o,
  output logic                                       done_o,
  output logic [fxr_rec_pkg::ClipOutcomeBits-1:0]    done_outcome_o,
  output logic [$clog2(fxr_rec_pkg::ClipMaxPolyVerts * fxr_rec_pkg::ClipNumPlanes + 1)-1:0] done_created_o
);
  // ---- widths, all derived from the packages ---------------------------------------------------
  localparam int PB = fxr_config_pkg::RasterWindowIntBits;
  localparam int NV = fxr_rec_pkg::NumVaryings;
  localparam int HasWa = fxr_rec_pkg::ClipVertexHasWa;
  localparam int NumComp = 4 + HasWa + NV;     // x, y, z, w, (wa), varyings
  localparam int NumCompIn = 4 + NV;           // exact_triangle_t: no wa
  localparam int SB = fxr_rec_pkg::ClipVertexSigBits;
  localparam int EB = fxr_rec_pkg::FxExpBits;
  localparam int VB = 1 + SB + EB;             // one value: _neg, _sig, _exp
  localparam int XB = NumComp * VB;            // one vertex inside the clipper
  localparam int XIn = NumCompIn * VB;
  localparam int PrimBits = fxr_rec_pkg::PrimIdBits;
  localparam int InBits = fxr_rec_pkg::ExactTriangleBits;
  localparam int OutBits = fxr_rec_pkg::ClippedTriangleBits;
  localparam int PosBits = fxr_config_pkg::RasterClipSigBits;  // new x, y, z, wa, varyings
  localparam int WBits = fxr_config_pkg::RecipInSigBits;       // new w
  localparam int MaxBits = PosBits > WBits ? PosBits : WBits;
  localparam int MaxV = fxr_rec_pkg::ClipMaxPolyVerts;
  localparam int NumPlanes = fxr_rec_pkg::ClipNumPlanes;  // w_min, near, far, left, right, bottom, top
  localparam int OB = fxr_rec_pkg::ClipOutcomeBits;
  localparam int PlaneBits = $clog2(NumPlanes);
  localparam int CompBits = $clog2(NumComp + 1);
  localparam int VIdxBits = $clog2(MaxV + 1);
  localparam int CreatedBits = $clog2(MaxV * NumPlanes + 1);
  // binary32 (docs/references.md, IEEE 754): values are below 2^(F32Bias + 1) = 2^128 (FLT_MAX), a
  // new value rounded up at most to 2^128: every value < 2^(MaxLead + 1).
  localparam int F32ExpBits = 8;
  localparam int F32FracBits = fxr_rec_pkg::F32Bits - 1 - F32ExpBits;
  localparam int F32Bias = (1 << (F32ExpBits - 1)) - 1;
  localparam int MaxLead = F32Bias + 1;
  // Lowest lsb of any value: a float32 subnormal (2^-149), a new value leading at 2^ClipFlushLeadExp
  // with MaxBits significand bits, the w_min plane's constant.
  localparam int F32Lsb = 1 - F32Bias - F32FracBits;
  localparam int NewLsb = fxr_rec_pkg::ClipFlushLeadExp - (MaxBits - 1);
  localparam int LsbMin0 = NewLsb < F32Lsb ? NewLsb : F32Lsb;
  localparam int LsbMin = LsbMin0 < fxr_rec_pkg::ClipWMinExp ? LsbMin0 : fxr_rec_pkg::ClipWMinExp;
  localparam int FixBits = MaxLead + 1 - LsbMin;  // |value| / 2^LsbMin < 2^FixBits
  localparam int CM = PB + 1;                     // |W|, |H|, |n_left| ... < 2^(PB + 1)
  localparam int DW = CM + FixBits + 2;           // plane distance, signed, units 2^LsbMin
  localparam int QW = DW;                         // |d_s - d_e| < 2^DW
  localparam int DW1 = DW + 1;
  localparam int PW = SB + DW + FixBits;          // numerator sig_e*d_s*2^oe - sig_s*d_e*2^os, signed
  localparam int AW = PW - 1;                     // its magnitude
  localparam int ALB = AW - QW;                   // numerator bits below the divisor's width
  localparam int OffBits = $clog2(FixBits + 1);   // |exp_e - exp_s| <= FixBits - 1
  localparam int PosCntBits = $clog2(SB + FixBits + 1);
  localparam int IB = EB + $clog2(PW) + 2;        // exponent arithmetic (signed)
  localparam int LzaBits = $clog2(AW + 1);
  localparam int NB = PB + 4;                     // guard-band arithmetic (signed)
  localparam int QtBits = MaxBits + 3;
  localparam int StepBits = $clog2(QtBits + 1);
  localparam int BitsW = $clog2(MaxBits + 1);

  // ---- guard band (model: guard_band()) ---------------------------------------------------------
  localparam logic signed [NB-1:0] Lim = NB'((1 << (PB - 1)) - fxr_rec_pkg::ClipGuardMarginPx);
  logic signed [NB-1:0] vx, vy, vw, vh, n_left, n_right, n_bottom, n_top;
  logic gb_valid;
  assign vx = NB'($signed(viewport_x_i));
  assign vy = NB'($signed(viewport_y_i));
  assign vw = NB'($signed(viewport_w_i));
  assign vh = NB'($signed(viewport_h_i));
  assign gb_valid = vw >= NB'(1) && vh >= NB'(1) && vx >= -Lim && vy >= -Lim && vx + vw <= Lim && vy + vh <= Lim;
  assign n_left = NB'(2) * (-Lim - vx) - vw;
  assign n_right = NB'(2) * (Lim - vx) - vw;
  assign n_bottom = NB'(2) * (-Lim - vy) - vh;
  assign n_top = NB'(2) * (Lim - vy) - vh;

  // Plane p: d = a*comp + b*w (sign, magnitude), or the w_min plane (model: plane_eq()).
  localparam int PlaneSlots = 1 << PlaneBits;  // every plane index a register can hold (the rest 0)
  logic [PlaneSlots-1:0] pl_wmin, pl_a_neg, pl_b_neg;
  // Flat vectors (Yosys 0.23 has no multidimensional packed arrays): plane p's fields at
  // [p*2 +: 2] and [p*CM +: CM].
  logic [2*PlaneSlots-1:0] pl_comp;
  logic [CM*PlaneSlots-1:0] pl_a_mag, pl_b_mag;
  function automatic logic [CM-1:0] mag_of(input logic signed [NB-1:0] x);
    mag_of = CM'(x < 0 ? -x : x);
  endfunction
  always_comb begin
    pl_wmin = '0;
    pl_a_neg = '0;
    pl_b_neg = '0;
    pl_comp = '0;
    pl_a_mag = '0;
    pl_b_mag = '0;
    pl_wmin[0] = 1'b1; pl_b_mag[0*CM +: CM] = CM'(1);                            // w_min: w - 2^WMinExp
    pl_comp[1*2 +: 2] = 2'd2; pl_a_mag[1*CM +: CM] = CM'(1);                            // near: z
    pl_comp[2*2 +: 2] = 2'd2; pl_a_mag[2*CM +: CM] = CM'(1); pl_a_neg[2] = 1'b1;        // far: w - z
    pl_b_mag[2*CM +: CM] = CM'(1);
    pl_comp[3*2 +: 2] = 2'd0; pl_a_mag[3*CM +: CM] = mag_of(vw);                        // left: W*x - n_left*w
    pl_b_mag[3*CM +: CM] = mag_of(n_left); pl_b_neg[3] = !(n_left < 0);
    pl_comp[4*2 +: 2] = 2'd0; pl_a_mag[4*CM +: CM] = mag_of(vw); pl_a_neg[4] = 1'b1;    // right: n_right*w - W*x
    pl_b_mag[4*CM +: CM] = mag_of(n_right); pl_b_neg[4] = n_right < 0;
    pl_comp[5*2 +: 2] = 2'd1; pl_a_mag[5*CM +: CM] = mag_of(vh);                        // bottom: H*y - n_bottom*w
    pl_b_mag[5*CM +: CM] = mag_of(n_bottom); pl_b_neg[5] = !(n_bottom < 0);
    pl_comp[6*2 +: 2] = 2'd1; pl_a_mag[6*CM +: CM] = mag_of(vh); pl_a_neg[6] = 1'b1;    // top: n_top*w - H*y
    pl_b_mag[6*CM +: CM] = mag_of(n_top); pl_b_neg[6] = n_top < 0;
  end

  // ---- vertices ---------------------------------------------------------------------------------
  function automatic logic [VB-1:0] comp_of(input logic [XB-1:0] x, input int c);
    comp_of = x[(NumComp - 1 - c) * VB +: VB];
  endfunction
  // An input vertex inside the clipper: its attribute w is its w_c (model: copy_clip_vertex).
  function automatic logic [XB-1:0] to_internal(input logic [XIn-1:0] x);
    int src;
    for (int c = 0; c < NumComp; c++) begin
      src = (c < 4) ? c : ((HasWa != 0 && c == 4) ? 3 : c - HasWa);
      to_internal[(NumComp - 1 - c) * VB +: VB] = x[(NumCompIn - 1 - src) * VB +: VB];
    end
  endfunction

  logic [InBits-1:0] in_flat;
  logic [3*XB-1:0] vin;  // vertex v at [(2-v)*XB +: XB]: v0 v1 v2 in record order
  assign in_flat = in_i;
  for (genvar v = 0; v < 3; v++) begin : g_vin
    assign vin[(2-v)*XB +: XB] = to_internal(in_flat[InBits - PrimBits - 1 - v * XIn -: XIn]);
  end

  // ---- the exact side of a plane (model: plane_side()) ------------------------------------------
  // d = a*c + b*w, or w - 2^ClipWMinExp (w_min plane). Each product is a term +-|k|*sig*2^exp; if
  // the two terms' leading ones differ the larger decides the sign, if they are equal the terms
  // overlap within CM + SB bits of the common leading one, so aligning the one with the larger
  // exponent onto the other and adding in CM + SB + 2 bits is exact. No rounding anywhere.
  // Returns {d < 0, d = 0}. A function called 21 times for the outcodes of an input triangle
  // (on its transfer, in the control process) and once for the iterative clipper's vertex (in the
  // data process).
  // Selections are ?: expressions rather than if statements: Yosys's proc_mux walks a process's
  // whole decision tree once per signal assigned in it, and 22 inlined copies of if-based code
  // made that pass take most of a synthesis's time.
  localparam int TB = CM + SB;            // term magnitude bits
  localparam int LB = EB + 2;             // leading-one exponents (signed)
  localparam int SumBits = TB + 2;
  localparam int ShBits = $clog2(TB) + 1;
  function automatic logic [LB-1:0] msb_idx(input logic [TB-1:0] x);
    msb_idx = '0;
    for (int k = 0; k < TB; k++)
      msb_idx = x[k] ? LB'(k) : msb_idx;
  endfunction
  function automatic logic [1:0] plane_side(input logic a_neg, input logic [CM-1:0] a_mag, input logic b_neg,
                                            input logic [CM-1:0] b_mag, input logic wmin, input logic [VB-1:0] c,
                                            input logic [VB-1:0] w);
    logic [TB-1:0] m1, m2, m1a, m2a;
    logic n1, n2, z1, z2, tn, tz, wn, wz;
    logic signed [LB-1:0] e1, e2, l1, l2, wl, dexp;
    logic [ShBits-1:0] sh;
    logic signed [SumBits-1:0] s1, s2, sum;
    m1 = TB'(a_mag) * TB'(c[VB-2 -: SB]);
    m2 = TB'(b_mag) * TB'(w[VB-2 -: SB]);
    n1 = a_neg ^ c[VB-1];
    n2 = b_neg ^ w[VB-1];
    z1 = ~|m1;
    z2 = ~|m2;
    e1 = LB'($signed(c[EB-1:0]));
    e2 = LB'($signed(w[EB-1:0]));
    l1 = e1 + $signed(msb_idx(m1));
    l2 = e2 + $signed(msb_idx(m2));
    dexp = e1 - e2;
    sh = (dexp > 0) ? ShBits'(dexp) : ShBits'(-dexp);  // used only when < TB
    m1a = (dexp > 0) ? m1 << sh : m1;
    m2a = (dexp > 0) ? m2 : m2 << sh;
    s1 = n1 ? -$signed(SumBits'(m1a)) : $signed(SumBits'(m1a));
    s2 = n2 ? -$signed(SumBits'(m2a)) : $signed(SumBits'(m2a));
    sum = s1 + s2;
    tn = (z1 && z2) ? 1'b0 : z1 ? n2 : z2 ? n1 : (l1 != l2) ? ((l1 > l2) ? n1 : n2) : sum[SumBits-1];
    tz = (z1 && z2) ? 1'b1 : (z1 || z2 || l1 != l2) ? 1'b0 : ~|sum;
    // w - 2^WMinExp: negative for w <= 0 or a leading one below; zero iff w is that power of two.
    wl = e2 + $signed(msb_idx(TB'(w[VB-2 -: SB])));
    wn = ~|w[VB-2 -: SB] || w[VB-1] || wl < LB'(fxr_rec_pkg::ClipWMinExp);
    wz = !wn && wl == LB'(fxr_rec_pkg::ClipWMinExp) && (w[VB-2 -: SB] & (w[VB-2 -: SB] - 1'b1)) == '0;
    plane_side = wmin ? {wn, wz} : {tn, tz};
  endfunction
  // Plane p's side of vertex x.
  function automatic logic [1:0] side_of(input logic [XB-1:0] x, input int p);
    side_of = plane_side(pl_a_neg[p], pl_a_mag[p*CM +: CM], pl_b_neg[p], pl_b_mag[p*CM +: CM], pl_wmin[p],
                         comp_of(x, pl_wmin[p] ? 3 : 32'(pl_comp[p*2 +: 2])), comp_of(x, 3));
  endfunction
  // Outcodes of the input triangle: bit v*NumPlanes + p set when vertex v is outside plane p.
  function automatic logic [3*NumPlanes-1:0] outcodes(input logic [3*XB-1:0] t);
    for (int tv = 0; tv < 3; tv++)
      for (int tp = 0; tp < NumPlanes; tp++)
        outcodes[tv*NumPlanes + tp] = |(side_of(t[(2-tv)*XB +: XB], tp) & 2'b10);
  endfunction

  // ---- the iterative clipper's state -----------------------------------------------------------
  typedef enum logic [3:0] {
    SIdle, SSide, SPlane, SEdge, SDist0, SDist1, SDist2, SDist3, SQuot, SCompSet, SAcc, SNorm, SDiv, SRound, SEmit
  } state_e;
  state_e state;

  // Two banks of MaxV vertices, slot b*MaxV + k. An unpacked array read and written at a slot
  // index: Yosys infers a memory (decoders and N:1 multiplexers), where a flat vector with run-time
  // part selects became barrel shifters over all 2*MaxV*XB bits (docs/rtl.md, "fxr_clip").
  localparam int Slots = 2 * MaxV;
  localparam int SlotBits = $clog2(Slots);
  logic [XB-1:0] pbuf [Slots];
  logic bank;                            // the current polygon's bank
  logic [VIdxBits-1:0] n, m, i, vi, fi;  // vertices, next polygon's count, edge, side index, fan index
  logic [PlaneBits-1:0] plane;
  logic [MaxV-1:0] s_neg, s_zero;
  logic any_out, ovf;
  logic [CreatedBits-1:0] created;
  logic [PrimBits-1:0] prim_q;
  logic [CompBits-1:0] comp;

  logic [XB-1:0] cur_i, cur_j, cur_vi, cur_0, cur_f1, cur_f2;
  logic [VIdxBits-1:0] j;
  assign j = (i + 1'b1 == n) ? '0 : i + 1'b1;
  // Slot k of a bank (k into one bank's side bits s_neg, s_zero; slot into pbuf); indices beyond
  // the buffer (never used) read slot 0.
  localparam int KBits = $clog2(MaxV);
  function automatic logic [KBits-1:0] kslot(input logic [VIdxBits-1:0] k);
    kslot = (32'(k) < MaxV) ? KBits'(k) : '0;
  endfunction
  function automatic logic [SlotBits-1:0] slot(input logic b, input logic [VIdxBits-1:0] k);
    slot = (b ? SlotBits'(MaxV) : '0) + SlotBits'(kslot(k));
  endfunction
  assign cur_i = pbuf[slot(bank, i)];
  assign cur_j = pbuf[slot(bank, j)];
  assign cur_vi = pbuf[slot(bank, vi)];
  assign cur_0 = pbuf[slot(bank, '0)];
  assign cur_f1 = pbuf[slot(bank, fi)];
  assign cur_f2 = pbuf[slot(bank, fi + 1'b1)];
  // Sides of the edge's ends; the edge crosses the plane when they are strictly opposite.
  logic ni, zi, nj, zj, crossing;
  assign ni = s_neg[kslot(i)];
  assign zi = s_zero[kslot(i)];
  assign nj = s_neg[kslot(j)];
  assign zj = s_zero[kslot(j)];
  assign crossing = (!ni && !zi && nj) || (ni && !nj && !zj);


  // ---- exact plane distance: one term k*value per clock, fixed point, lsb 2^LsbMin ------------
  localparam logic signed [DW-1:0] WMinConst = DW'(1) << (fxr_rec_pkg::ClipWMinExp - LsbMin);
  logic t_kneg;
  logic [CM-1:0] t_kmag;
  logic [VB-1:0] t_v;
  // The heavy datapath blocks are written out in their state's branch of the data process (one
  // instance each; a simulator evaluates them only in that state), with variables of the process
  // rather than function locals: Verilator declares an inlined function's locals in the C++
  // function of the whole process and zeroes them on every call of it, i.e. every clock
  // (VL_ZERO_W of 1,024-bit words; docs/rtl.md, "Co-simulation speed", session 9).
  logic [XB-1:0] dv;  // the vertex whose distance is being summed: s (SDist0/1) or e (SDist2/3)
  assign dv = (state == SDist0 || state == SDist1) ? cur_i : cur_j;
  always_comb begin
    if (state == SDist0 || state == SDist2) begin
      t_kneg = pl_a_neg[plane];
      t_kmag = pl_a_mag[plane*CM +: CM];
      t_v = comp_of(dv, 32'(pl_comp[plane*2 +: 2]));
    end else begin
      t_kneg = pl_b_neg[plane];
      t_kmag = pl_b_mag[plane*CM +: CM];
      t_v = comp_of(dv, 3);
    end
  end

  logic signed [DW-1:0] d_acc, d_s, d_e;
  logic q_neg;
  logic [QW-1:0] q_n;                  // |d_s - d_e|, normalised (msb set)
  logic signed [IB-1:0] q_lead;        // its msb index before normalising

  // Normalisation of a magnitude: its leading one's index and the magnitude shifted up to it, by
  // the shared log-step normaliser (rtl/fxr_norm_log.sv) rather than a priority chain AW
  // multiplexers deep. One instance, shared by SQuot and SNorm and enabled only there: SQuot's
  // q = |d_s - d_e| placed at A's top (QW <= AW bits: the normalised q in the top QW bits, its
  // leading one ALB above q's own), SNorm's |acc| (A, AW bits).
  logic nrm_en;
  logic signed [DW:0] q_raw;         // d_s - d_e (SQuot)
  logic [AW-1:0] nrm_x, nrm_n;       // the operand, normalised
  logic [LzaBits-1:0] nrm_msb;       // its leading one (0 for 0)
  assign nrm_en = state == SQuot || state == SNorm;
  always_comb begin
    q_raw = '0;
    nrm_x = '0;
    if (nrm_en) begin
      q_raw = DW1'(d_s) - DW1'(d_e);
      nrm_x = (state == SQuot) ? {QW'(q_raw < 0 ? -q_raw : q_raw), ALB'(0)} : AW'(acc < 0 ? -acc : acc);
    end
  end
  fxr_norm_log #(
    .Width  (AW),
    .MsbBits(LzaBits)
  ) u_nrm (
    .en_i  (nrm_en),
    .x_i   (nrm_x),
    .norm_o(nrm_n),
    .msb_o (nrm_msb)
  );

  // ---- one component of the new vertex ---------------------------------------------------------
  // Component c of vertex x; the attribute w of a vertex is its wa, or its w_c where wa is 0
  // (model: ClipVtx::attr_w()).
  function automatic logic [VB-1:0] comp_val(input logic [XB-1:0] x, input logic [CompBits-1:0] c);
    logic [VB-1:0] r;
    r = x[(NumComp - 1 - 32'(c)) * VB +: VB];
    if (HasWa != 0 && c == 4 && ~|r[VB-2 -: SB]) r = x[(NumComp - 1 - 3) * VB +: VB];
    comp_val = r;
  endfunction
  logic [VB-1:0] cs, ce;
  assign cs = comp_val(cur_i, comp);
  assign ce = comp_val(cur_j, comp);

  logic signed [DW:0] te, ts, tsum;    // +-d_s, -+d_e and their sum, by the components' signs
  logic [SB-1:0] sig_s, sig_e;
  logic [OffBits-1:0] off_s, off_e;
  logic signed [EB-1:0] emin;
  logic [PosCntBits-1:0] pos;
  logic signed [PW-1:0] acc;
  logic [QW:0] rem;
  logic [ALB-1:0] alow;
  logic [QtBits-1:0] quo;
  logic [StepBits-1:0] steps;
  logic first, r_neg, r_zero;
  logic signed [IB-1:0] ebase;
  logic [BitsW-1:0] bits_c;            // significand bits of this component

  // The values' exponents as seen by the shift-and-add (a zero takes the other's exponent).
  logic signed [EB-1:0] xs, xe, xmin;
  always_comb begin
    xs = $signed(cs[EB-1:0]);
    xe = $signed(ce[EB-1:0]);
    if (~|cs[VB-2 -: SB]) xs = xe;
    if (~|ce[VB-2 -: SB]) xe = xs;
    xmin = xs < xe ? xs : xe;
  end

  // Shift-and-add step (SAcc, the data process): acc*2 + (bit pos of sig_e*2^off_e)*te + (bit pos
  // of sig_s*2^off_s)*ts.

  // Rounding (RNE to bits_c, flush below 2^ClipFlushLeadExp; signed comparison).
  logic signed [IB-1:0] bits_s;
  assign bits_s = IB'(bits_c);
  function automatic logic [VB-1:0] rnd_val();
    logic [QtBits-1:0] s0;
    logic [QtBits:0] s1;
    logic g, st, inc;
    logic signed [IB-1:0] e;
    if (quo[bits_c + 2]) begin
      s0 = quo >> 3;
      g = quo[2];
      st = quo[1] | quo[0];
      e = ebase + IB'(3);
    end else begin
      s0 = quo >> 2;
      g = quo[1];
      st = quo[0];
      e = ebase + IB'(2);
    end
    st = st | (|rem) | (|alow);
    inc = g & (st | s0[0]);
    s1 = (QtBits + 1)'(s0) + (QtBits + 1)'(inc);
    if (s1[bits_c]) begin  // carried up to 2^bits
      s1 = s1 >> 1;
      e = e + IB'(1);
    end
    if (r_zero) rnd_val = '0;
    else if (e + bits_s - IB'(1) < IB'(fxr_rec_pkg::ClipFlushLeadExp)) rnd_val = {r_neg, {(SB + EB){1'b0}}};
    else rnd_val = {r_neg, SB'(s1), EB'(e)};
  endfunction

  // ---- control ----------------------------------------------------------------------------------
  logic take;
  logic [OutBits-1:0] out_q;
  logic emit_go, emit_last;
  assign in_ready_o = state == SIdle && (!out_valid_o || out_ready_i);
  assign take = in_valid_i && in_ready_o;
  assign emit_go = state == SEmit && !ovf && n >= VIdxBits'(3) && (!out_valid_o || out_ready_i);
  assign emit_last = fi + VIdxBits'(2) == n;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state <= SIdle;
      out_valid_o <= 1'b0;
      done_o <= 1'b0;
      done_outcome_o <= '0;
      done_created_o <= '0;
    end else begin
      done_o <= 1'b0;
      if (out_valid_o && out_ready_i) out_valid_o <= 1'b0;
      case (state)
        SIdle: begin
          if (take) begin
            // the fast path: the 21 exact plane sides of the input triangle (oc_in), computed here
            // on its transfer only, not as a continuous assignment every clock (docs/rtl.md,
            // "Co-simulation speed", session 9: a gated always_comb does not settle in Icarus 11)
            logic [3*NumPlanes-1:0] oc_in;
            oc_in = outcodes(vin);
            done_created_o <= '0;
            if (!gb_valid) begin
              done_o <= 1'b1;
              done_outcome_o <= OB'(fxr_rec_pkg::ClipOutcomeRejectedViewport);
            end else if (|(oc_in[0 +: NumPlanes] & oc_in[NumPlanes +: NumPlanes] & oc_in[2*NumPlanes +: NumPlanes])) begin
              done_o <= 1'b1;
              done_outcome_o <= OB'(fxr_rec_pkg::ClipOutcomeCulledOutside);
            end else if (~|oc_in) begin
              done_o <= 1'b1;
              done_outcome_o <= OB'(fxr_rec_pkg::ClipOutcomeAccepted);
              out_valid_o <= 1'b1;
            end else begin
              state <= SSide;
            end
          end
        end
        SSide: if (vi + 1'b1 == n) state <= SPlane;
        SPlane: begin
          if (any_out) state <= SEdge;
          else if (32'(plane) == NumPlanes - 1) state <= SEmit;
          else state <= SSide;
        end
        SEdge: begin
          if (i == n) begin
            if (m < VIdxBits'(3) || 32'(plane) == NumPlanes - 1) state <= SEmit;
            else state <= SSide;
          end else if (32'(m) + 2 <= MaxV && crossing) begin
            state <= SDist0;
          end
        end
        SDist0: state <= SDist1;
        SDist1: state <= SDist2;
        SDist2: state <= SDist3;
        SDist3: state <= SQuot;
        SQuot: state <= SCompSet;
        SCompSet: state <= SAcc;
        SAcc: if (pos == '0) state <= SNorm;
        SNorm: state <= (acc == '0) ? SRound : SDiv;
        SDiv: if (steps == StepBits'(1)) state <= SRound;
        SRound: state <= (32'(comp) == NumComp - 1) ? SEdge : SCompSet;
        SEmit: begin
          done_created_o <= created;
          if (ovf) begin
            done_o <= 1'b1;
            done_outcome_o <= OB'(fxr_rec_pkg::ClipOutcomeRejectedOverflow);
            state <= SIdle;
          end else if (n < VIdxBits'(3)) begin
            done_o <= 1'b1;
            done_outcome_o <= OB'(fxr_rec_pkg::ClipOutcomeClippedAway);
            state <= SIdle;
          end else if (emit_go) begin
            out_valid_o <= 1'b1;
            if (emit_last) begin
              done_o <= 1'b1;
              done_outcome_o <= OB'(fxr_rec_pkg::ClipOutcomeClipped);
              state <= SIdle;
            end
          end
        end
        default: state <= SIdle;
      endcase
    end
  end

  always_ff @(posedge clk_i) begin : p_data
    case (state)
      SIdle: begin
        if (take) begin
          out_q <= {in_flat[InBits-1 -: PrimBits], vin};
          out_last_o <= 1'b1;
          prim_q <= in_flat[InBits-1 -: PrimBits];
          pbuf[0] <= vin[2*XB +: XB];
          pbuf[1] <= vin[XB +: XB];
          pbuf[2] <= vin[0 +: XB];
          bank <= 1'b0;
          n <= VIdxBits'(3);
          plane <= '0;
          vi <= '0;
          any_out <= 1'b0;
          created <= '0;
          ovf <= 1'b0;
        end
      end
      SSide: begin
        logic [1:0] sd;
        sd = side_of(cur_vi, 32'(plane));
        s_neg[kslot(vi)] <= sd[1];
        s_zero[kslot(vi)] <= sd[0];
        any_out <= any_out | sd[1];
        vi <= (vi + 1'b1 == n) ? '0 : vi + 1'b1;
      end
      SPlane: begin  // a plane no vertex is outside of is skipped
        fi <= VIdxBits'(1);
        m <= '0;
        i <= '0;
        any_out <= 1'b0;
        if (!any_out) plane <= plane + 1'b1;
      end
      SEdge: begin
        if (i == n) begin
          n <= (m < VIdxBits'(3)) ? '0 : m;
          bank <= ~bank;
          plane <= plane + 1'b1;
          fi <= VIdxBits'(1);
        end else if (32'(m) + 2 > MaxV) begin
          ovf <= 1'b1;  // the model stops this plane's edge loop (cannot happen for float32 inputs)
          i <= n;
        end else begin
          if (!ni) begin
            pbuf[slot(~bank, m)] <= cur_i;
            m <= m + 1'b1;
          end
          if (!crossing) i <= i + 1'b1;
        end
      end
      SDist0, SDist1, SDist2, SDist3: begin
        logic [CM+SB-1:0] t_prod;
        logic signed [EB:0] t_sh;
        logic [DW-1:0] t_mag;
        logic signed [DW-1:0] tv;
        t_prod = (CM + SB)'(t_kmag) * (CM + SB)'(t_v[VB-2 -: SB]);
        t_sh = (EB + 1)'($signed(t_v[EB-1:0])) - (EB + 1)'(LsbMin);
        t_mag = DW'(t_prod) << $unsigned(t_sh);  // t_sh >= 0: every value's lsb is at or above 2^LsbMin
        tv = (t_kneg ^ t_v[VB-1]) ? -$signed(t_mag) : $signed(t_mag);
        if (state == SDist0 || state == SDist2) d_acc <= tv - (pl_wmin[plane] ? WMinConst : '0);
        else if (state == SDist1) d_s <= d_acc + tv;
        else d_e <= d_acc + tv;
      end
      SQuot: begin
        q_neg <= q_raw < 0;
        q_n <= nrm_n[AW-1 -: QW];
        q_lead <= IB'(nrm_msb) - IB'(ALB);  // q's leading one: ALB below the operand's
        comp <= '0;
      end
      SCompSet: begin
        te <= ce[VB-1] ? -(DW1'(d_s)) : DW1'(d_s);
        ts <= cs[VB-1] ? DW1'(d_e) : -(DW1'(d_e));
        tsum <= (ce[VB-1] ? -(DW1'(d_s)) : DW1'(d_s)) + (cs[VB-1] ? DW1'(d_e) : -(DW1'(d_e)));
        sig_s <= cs[VB-2 -: SB];
        sig_e <= ce[VB-2 -: SB];
        off_s <= OffBits'(IB'(xs) - IB'(xmin));
        off_e <= OffBits'(IB'(xe) - IB'(xmin));
        emin <= xmin;
        pos <= PosCntBits'(SB - 1) + PosCntBits'(IB'(xs) + IB'(xe) - IB'(xmin) - IB'(xmin));
        acc <= '0;
        bits_c <= BitsW'(comp == 3 ? WBits : PosBits);
      end
      SAcc: begin
        logic be, bs;
        logic signed [PosCntBits:0] pe, ps;
        logic signed [PW-1:0] addend;
        pe = $signed({1'b0, pos}) - $signed({1'b0, PosCntBits'(off_e)});
        ps = $signed({1'b0, pos}) - $signed({1'b0, PosCntBits'(off_s)});
        be = pe >= 0 && pe < $signed((PosCntBits + 1)'(SB)) && sig_e[pe[$clog2(SB)-1:0]];
        bs = ps >= 0 && ps < $signed((PosCntBits + 1)'(SB)) && sig_s[ps[$clog2(SB)-1:0]];
        case ({be, bs})
          2'b11: addend = PW'(tsum);
          2'b10: addend = PW'(te);
          2'b01: addend = PW'(ts);
          default: addend = '0;
        endcase
        acc <= (acc <<< 1) + addend;
        pos <= pos - 1'b1;
      end
      SNorm: begin
        logic [AW-1:0] a_n;
        a_n = nrm_n;
        r_zero <= acc == '0;
        r_neg <= (acc < 0) ^ q_neg;
        rem <= {1'b0, a_n[AW-1 -: QW]};
        alow <= a_n[ALB-1:0];
        quo <= '0;
        first <= 1'b1;
        steps <= StepBits'(bits_c) + StepBits'(3);
        // value = quo * 2^ebase, ebase = emin - (bits + 2 - (lead(A) - lead(q)))
        ebase <= IB'(emin) - IB'(bits_c) - IB'(2) + IB'(nrm_msb) - q_lead;
      end
      SDiv: begin
        logic [QW:0] rt;
        logic ge;
        rt = first ? rem : {rem[QW-1:0], alow[ALB-1]};
        ge = rt >= {1'b0, q_n};
        rem <= ge ? rt - {1'b0, q_n} : rt;
        quo <= {quo[QtBits-2:0], ge};
        if (!first) alow <= alow << 1;
        first <= 1'b0;
        steps <= steps - 1'b1;
      end
      SRound: begin
        // one component slice per constant c: no run-time part select inside the word
        logic [VB-1:0] rv;
        rv = rnd_val();  // once, not in each of the loop's NumComp branches
        for (int c = 0; c < NumComp; c++)
          if (32'(comp) == c) pbuf[slot(~bank, m)][(NumComp - 1 - c) * VB +: VB] <= rv;
        if (32'(comp) == NumComp - 1) begin
          m <= m + 1'b1;
          created <= created + 1'b1;
          i <= i + 1'b1;
        end else begin
          comp <= comp + 1'b1;
        end
      end
      SEmit: begin
        if (emit_go) begin
          out_q <= {prim_q, cur_0, cur_f1, cur_f2};
          out_last_o <= emit_last;
          fi <= fi + 1'b1;
        end
      end
      default: ;
    endcase
  end
  assign out_o = out_q;
endmodule

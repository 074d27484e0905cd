// fxr_interp: stage 7, the interpolators (issue 10). One span (and its triangle's equations) in,
// one plane sample per covered pixel out, left to right. Model: fxr::InterpStage
// (model/stages/interp.hpp: DepthStepper, PlaneSample); algorithm and figures: docs/rtl.md,
// "fxr_interp"; vectors: the transaction dumps' interp.in / interp.out with the context of
// setup.out (docs/vectors.md, "Transaction vectors"; tb/txn/interp_txn_test.cpp).
//
// Ports:
//   clk_i, rst_ni                 clock, active-low asynchronous reset
//   in_valid_i / in_ready_o       input handshake (transfer when both are high)
//   in_i                          fxr_rec_pkg::span_t: prim, row y, pixels x0 ≤ i ≤ x1 (x0 ≤ x1)
//   ctx_i                         fxr_rec_pkg::triangle_equations_t of the span's triangle, valid
//                                 with in_valid_i (sampled with the span; only the planes are used)
//   out_valid_o / out_ready_i     output handshake
//   out_o                         fxr_rec_pkg::plane_sample_t: prim, x, y, the depth code, the 1/w
//                                 sum den and every v/w sum num<m> with their block exponents
//   out_last_o                    the span's last pixel (the dump's `last`)
//   ctx_en_o                      ctx_i and in_i.prim are read in this clock (a span at the input
//                                 that may be accepted, from registers and in_valid_i only): a
//                                 caller may leave ctx_i '0 otherwise (fxr_raster_backend's
//                                 equations FIFO read)
//
// Algorithm (exact, the model's values bit for bit). At the span start (x0, y) every plane is
// evaluated directly, P = c + (x0 − i0)·dx + (y − j0)·dy (modulo 2^width: the exact value fits
// the field), and stepped by dx along the row. The depth code is RNE(Z / den) clamped to
// [0, 2^db − 1], stepped exactly as a quotient / remainder pair (DepthStepper): Z = q·den + r and
// dx = dq·den + dr with floor division (0 ≤ r, dr < den); per pixel r += dr, q += dq, and one
// carry when r ≥ den. The two floor divisions of a span run in a sequential restoring divider
// (magnitudes, the divisor shifted to the dividend's leading one so only the quotient's own bits
// are iterated, DivStepsPerClock quotient bits per clock; then the sign fix of floor division).
//
// Timing (InterpStage::cost()): two parts. The front accepts a span (planes evaluated in the
// accepting clock), normalises (1 clock), divides (ceil(bits of the longer quotient /
// DivStepsPerClock) clocks, at least 1) and hands the span start to the back (1 clock, in which
// it accepts the next span); the back emits one sample per clock and takes the next span start
// in the clock of its last sample, so the front works on span k + 1 while span k is emitted.
// A span thus occupies the front 2 + ceil(qbits / DivStepsPerClock) clocks (qbits: the longer
// of the two quotients' bit counts, about 25 for the depth code at d24) and the back one clock
// per pixel. out_ready_i low holds the sample.
module fxr_interp #(
  parameter int SubpixelBits     = fxr_config_pkg::RasterSubpixelBits,
  parameter int WindowIntBits    = fxr_config_pkg::RasterWindowIntBits,
  parameter int ZFracBits        = fxr_config_pkg::RasterZFracBits,
  parameter int DepthFormat      = fxr_config_pkg::RasterDepthFormat,  // raster_depth_format_e
  parameter int InterpBlockBits  = fxr_config_pkg::RasterInterpBlockBits,
  parameter int AttrSubpixelBits = fxr_config_pkg::RasterAttrSubpixelBits,
  parameter int AttrCoordBits    = fxr_config_pkg::RasterAttrCoordBits,
  parameter int RecipExpBits     = fxr_config_pkg::RecipExpBits,
  parameter int NumVaryings      = fxr_rec_pkg::NumVaryings,
  // Micro-architecture: quotient bits of the span-start divisions per clock (restoring steps
  // chained in one clock; kInterpDivStepsPerClock of the model's cost).
  parameter int DivStepsPerClock = 8,
  // derived (model/stages/setup.hpp, model/unit/record.hpp)
  localparam bit Attr       = AttrSubpixelBits > SubpixelBits,    // attr_planes
  localparam int G          = SubpixelBits > 0 ? SubpixelBits : 1,
  localparam int CB         = WindowIntBits + G,                  // coord_bits
  localparam int EVB        = 2 * CB + 2,                         // edge_value_bits
  localparam int Db         = DepthFormat == fxr_config_pkg::RasterDepthFormatD24 ? 24 : 16,
  localparam int PEB        = Attr ? 2 * AttrCoordBits + 2 : EVB, // plane_edge_bits
  localparam int IPB        = PEB + InterpBlockBits + 1 + 2,      // interp_plane_bits
  localparam int ZPB        = PEB + ZFracBits + 1 + (Attr ? 0 : Db) + 2,  // depth_plane_bits
  localparam int ZDB        = PEB - 1 + ZFracBits - (Attr ? Db : 0),      // depth_den_bits
  localparam int F32ExpBits = 8,
  localparam int EB         = (RecipExpBits > F32ExpBits + 1 ? RecipExpBits : F32ExpBits + 1) + 2,
  localparam int PrimBits   = 32,                                 // kPrimIdBits
  localparam int PB         = WindowIntBits,                      // pixel index (signed)
  localparam int NP         = NumVaryings + 1                     // planes: 1/w, then v_m/w
) (
  input  logic                             clk_i,
  input  logic                             rst_ni,
  input  logic                             in_valid_i,
  output logic                             in_ready_o,
  input  fxr_rec_pkg::span_t               in_i,
  /* verilator lint_off UNUSEDSIGNAL */
  input  fxr_rec_pkg::triangle_equations_t ctx_i,  // edges and rectangle: not used here
  /* verilator lint_on UNUSEDSIGNAL */
  output logic                             out_valid_o,
  input  logic                             out_ready_i,
  output fxr_rec_pkg::plane_sample_t       out_o,
  output logic                             out_last_o,
  output logic                             ctx_en_o
);

  // ---- record layout (the generated structs; members first-field-most-significant) ----------
  // A plane of triangle_equations_t: c, dx, dy [, i0, j0 when Attr]; a varying adds its exponent.
  localparam int AnchorBits = Attr ? 2 * PB : 0;
  localparam int VB         = 3 * IPB + AnchorBits + EB;          // den / num<m> block
  localparam int ZVB        = 3 * ZPB + AnchorBits;               // z plane
  localparam int TEB        = fxr_rec_pkg::TriangleEquationsBits;
  localparam int PSB        = fxr_rec_pkg::PlaneSampleBits;
  localparam int SB         = IPB + EB;                            // den / num<m> of a sample
  localparam int ZBase      = NP * VB + ZDB;                      // lsb of the z plane block
  localparam int QB         = ZPB;                                 // quotients (signed)
  localparam int RB         = ZDB + 1;                             // remainder sums r + dr < 2·den
  localparam int CntB       = $clog2(ZPB + 1);                     // quotient bits 0 … ZPB
  localparam int MaxCode    = (1 << Db) - 1;                       // depth_max_code

  // The generated structs must be the records of this configuration (else refuse to elaborate).
  if (TEB != ZBase + ZVB + 2 * PB + 2 * PB + 1 + EVB + 3 * (2 * (CB + 1) + EVB + 1) + PrimBits ||
      PSB != PrimBits + 2 * PB + Db + NP * SB) begin : g_layout_check
    $error("fxr_interp: fxr_rec_pkg does not match the configuration (TEB %0d, PSB %0d)", TEB, PSB);
  end

  logic [TEB-1:0] ctx;
  assign ctx = ctx_i;

  // ---- input decode: the planes at the span start (x0, y) ----------------------------------
  logic signed [PB-1:0] in_x0, in_x1, in_y;
  assign in_x0 = $signed(in_i.x0);
  assign in_x1 = $signed(in_i.x1);
  assign in_y  = $signed(in_i.y);

  // Plane p (0: 1/w, 1 + m: v_m/w) of the context: c, dx, dy, anchor, exponent.
  logic signed [IPB-1:0] pc [NP], pdx [NP], pdy [NP];
  logic signed [PB-1:0]  pi0 [NP], pj0 [NP];
  logic [EB-1:0]         pexp [NP];
  logic signed [IPB-1:0] p_start [NP];
  logic signed [PB:0]    p_xoff [NP], p_yoff [NP];   // x0 − i0, y − j0
  /* verilator lint_off UNUSEDSIGNAL */  // the products' top bits (the sums are taken modulo 2^IPB)
  logic signed [IPB+PB:0] p_xprod [NP], p_yprod [NP];
  /* verilator lint_on UNUSEDSIGNAL */
  // The combinational blocks below are evaluated only while their result may be read (here: a
  // span at the input in a clock it can be accepted, `plane_en` below; not while it waits for
  // the divider) and are 0 otherwise, so that the simulator skips the wide arithmetic then
  // (docs/rtl.md, "Co-simulation speed").
  logic plane_en;
  always_comb begin
    for (int p = 0; p < NP; p++) begin
      pc[p] = '0;
      pdx[p] = '0;
      pdy[p] = '0;
      pexp[p] = '0;
      pi0[p] = '0;
      pj0[p] = '0;
      p_xoff[p] = '0;
      p_yoff[p] = '0;
      p_xprod[p] = '0;
      p_yprod[p] = '0;
      p_start[p] = '0;
      if (plane_en) begin
        // block p at [(NP − 1 − p)·VB +: VB], fields from its top
        pc[p]   = $signed(ctx[(NP - p) * VB - 1 -: IPB]);
        pdx[p]  = $signed(ctx[(NP - p) * VB - 1 - IPB -: IPB]);
        pdy[p]  = $signed(ctx[(NP - p) * VB - 1 - 2 * IPB -: IPB]);
        pexp[p] = ctx[(NP - 1 - p) * VB +: EB];
        if (Attr) begin
          pi0[p] = $signed(ctx[(NP - 1 - p) * VB + EB + PB +: PB]);
          pj0[p] = $signed(ctx[(NP - 1 - p) * VB + EB +: PB]);
        end
        // products at their own width ((PB + 1) × IPB signed), then the low IPB bits
        p_xoff[p]  = (PB + 1)'(in_x0) - (PB + 1)'(pi0[p]);
        p_yoff[p]  = (PB + 1)'(in_y) - (PB + 1)'(pj0[p]);
        p_xprod[p] = p_xoff[p] * pdx[p];
        p_yprod[p] = p_yoff[p] * pdy[p];
        p_start[p] = pc[p] + p_xprod[p][IPB-1:0] + p_yprod[p][IPB-1:0];
      end
    end
  end

  logic signed [ZPB-1:0] zc, zdx, zdy;
  logic signed [PB-1:0]  zi0, zj0;
  logic [ZDB-1:0]        zden;
  logic signed [PB:0]    z_xoff, z_yoff;
  /* verilator lint_off UNUSEDSIGNAL */
  logic signed [ZPB+PB:0] z_xprod, z_yprod;
  /* verilator lint_on UNUSEDSIGNAL */
  logic signed [ZPB-1:0] z_start;
  always_comb begin
    zc      = '0;
    zdx     = '0;
    zdy     = '0;
    zden    = '0;
    zi0     = '0;
    zj0     = '0;
    z_xoff  = '0;
    z_yoff  = '0;
    z_xprod = '0;
    z_yprod = '0;
    z_start = '0;
    if (plane_en) begin
      zc   = $signed(ctx[ZBase + ZVB - 1 -: ZPB]);
      zdx  = $signed(ctx[ZBase + ZVB - 1 - ZPB -: ZPB]);
      zdy  = $signed(ctx[ZBase + ZVB - 1 - 2 * ZPB -: ZPB]);
      zden = ctx[NP * VB +: ZDB];
      if (Attr) begin
        zi0 = $signed(ctx[ZBase + PB +: PB]);
        zj0 = $signed(ctx[ZBase +: PB]);
      end
      z_xoff  = (PB + 1)'(in_x0) - (PB + 1)'(zi0);
      z_yoff  = (PB + 1)'(in_y) - (PB + 1)'(zj0);
      z_xprod = z_xoff * zdx;
      z_yprod = z_yoff * zdy;
      z_start = zc + z_xprod[ZPB-1:0] + z_yprod[ZPB-1:0];
    end
  end

  // ---- front: the span start ---------------------------------------------------------------
  typedef enum logic [1:0] {FrIdle, FrNorm, FrDiv, FrDone} front_e;
  front_e                front_q;
  logic [PrimBits-1:0]   f_prim_q;
  logic signed [PB-1:0]  f_y_q, f_x0_q, f_x1_q;
  logic signed [IPB-1:0] f_p_q [NP], f_pdx_q [NP];
  logic [EB-1:0]         f_pexp_q [NP];
  logic [ZDB-1:0]        f_den_q;
  // the two divisions: 0 = Z at the span start, 1 = z_dx
  logic                  f_neg_q [2];
  logic [QB-1:0]         f_rem_q [2], f_dsh_q [2], f_quo_q [2];
  logic [CntB-1:0]       f_cnt_q [2];

  // Normalisation: shift the divisor to the dividend's leading one (read in FrNorm only).
  logic [CntB-1:0] nz_msb [2];
  logic [CntB-1:0] nd_msb;
  logic            n_any [2];
  always_comb begin
    nd_msb = '0;
    for (int d = 0; d < 2; d++) begin
      nz_msb[d] = '0;
      n_any[d]  = 1'b0;
    end
    if (front_q == FrNorm) begin
      for (int i = 0; i < ZDB; i++)
        if (f_den_q[i]) nd_msb = CntB'(i);
      for (int d = 0; d < 2; d++) begin
        for (int i = 0; i < QB; i++)
          if (f_rem_q[d][i]) begin
            nz_msb[d] = CntB'(i);
            n_any[d]  = 1'b1;
          end
      end
    end
  end

  // Restoring steps: DivStepsPerClock per clock while quotient bits are left (read in FrDiv only).
  logic [QB-1:0]   s_rem [2], s_dsh [2], s_quo [2];
  logic [CntB-1:0] s_cnt [2];
  logic            div_done;
  always_comb begin
    for (int d = 0; d < 2; d++) begin
      s_rem[d] = '0;
      s_dsh[d] = '0;
      s_quo[d] = '0;
      s_cnt[d] = '0;
    end
    if (front_q == FrDiv) begin
      for (int d = 0; d < 2; d++) begin
        s_rem[d] = f_rem_q[d];
        s_dsh[d] = f_dsh_q[d];
        s_quo[d] = f_quo_q[d];
        s_cnt[d] = f_cnt_q[d];
        for (int k = 0; k < DivStepsPerClock; k++)
          if (s_cnt[d] != '0) begin
            if (s_rem[d] >= s_dsh[d]) begin
              s_rem[d] = s_rem[d] - s_dsh[d];
              s_quo[d] = {s_quo[d][QB-2:0], 1'b1};
            end else begin
              s_quo[d] = {s_quo[d][QB-2:0], 1'b0};
            end
            s_dsh[d] = s_dsh[d] >> 1;
            s_cnt[d] = s_cnt[d] - CntB'(1);
          end
      end
    end
    div_done = s_cnt[0] == '0 && s_cnt[1] == '0;  // the last quotient bits are taken this clock
  end

  // Sign fix of floor division: q = −|q| (exact) or −|q| − 1 with r = den − rem (read at the
  // handoff, in FrDone, only).
  logic signed [QB-1:0] fx_q [2];
  logic [ZDB-1:0]       fx_r [2];
  always_comb begin
    for (int d = 0; d < 2; d++) begin
      if (front_q != FrDone) begin
        fx_q[d] = '0;
        fx_r[d] = '0;
      end else if (f_neg_q[d] && f_rem_q[d] != '0) begin
        fx_q[d] = -$signed(f_quo_q[d]) - QB'(1);
        fx_r[d] = f_den_q - f_rem_q[d][ZDB-1:0];
      end else begin
        fx_q[d] = f_neg_q[d] ? -$signed(f_quo_q[d]) : $signed(f_quo_q[d]);
        fx_r[d] = f_rem_q[d][ZDB-1:0];
      end
    end
  end

  // ---- back: one sample per clock ----------------------------------------------------------
  logic                  b_valid_q;
  logic [PrimBits-1:0]   b_prim_q;
  logic signed [PB-1:0]  b_x_q, b_x1_q, b_y_q;
  logic signed [IPB-1:0] b_p_q [NP], b_pdx_q [NP];
  logic [EB-1:0]         b_pexp_q [NP];
  logic [ZDB-1:0]        b_den_q;
  logic signed [QB-1:0]  b_q_q, b_dq_q;
  logic [ZDB-1:0]        b_r_q, b_dr_q;

  logic b_last, b_fire, b_free, handoff;
  assign b_last  = b_x_q == b_x1_q;
  assign b_fire  = b_valid_q & out_ready_i;
  assign b_free  = ~b_valid_q | (b_fire & b_last);
  assign handoff = front_q == FrDone & b_free;

  // A span is accepted while the front is idle or in the clock it hands its span to the back.
  logic accept;
  assign in_ready_o = front_q == FrIdle || handoff;
  assign accept     = in_valid_i & in_ready_o;
  // plane_en: accept without out_ready_i (b_free's b_fire), from registers only. Not accept
  // itself: out_ready_i is combinational from the unit's and the back end's output and memory
  // ports, and Verilator evaluates logic that depends on top-level inputs in every eval() (twice
  // per clock), where it evaluates the rest once (docs/rtl.md, "Co-simulation speed").
  assign plane_en   = in_valid_i & (front_q == FrIdle | (front_q == FrDone & (~b_valid_q | b_last)));
  assign ctx_en_o   = plane_en;

  // The depth code of the current sample: RNE(q + r/den), clamped to [0, 2^db − 1].
  logic [RB-1:0]        two_r;
  logic                 round_up;
  logic signed [QB:0]   code_full;
  logic [Db-1:0]        code;
  always_comb begin
    two_r     = '0;
    round_up  = 1'b0;
    code_full = '0;
    code      = '0;
    if (b_valid_q) begin
      two_r     = {b_r_q, 1'b0};
      round_up  = two_r > RB'(b_den_q) || (two_r == RB'(b_den_q) && b_q_q[0]);
      code_full = $signed({b_q_q[QB-1], b_q_q}) + (QB + 1)'(round_up);
      if (code_full < 0) code = '0;
      else if (code_full > (QB + 1)'(MaxCode)) code = Db'(MaxCode);
      else code = code_full[Db-1:0];
    end
  end

  // The step along x: r += dr, q += dq (+ 1 when r reaches den).
  logic [RB-1:0]        st_r;
  logic                 st_carry;
  always_comb begin
    st_r     = '0;
    st_carry = 1'b0;
    if (b_valid_q) begin
      st_r     = RB'(b_r_q) + RB'(b_dr_q);
      st_carry = st_r >= RB'(b_den_q);
      if (st_carry) st_r = st_r - RB'(b_den_q);
    end
  end

  // Output record.
  logic [PSB-1:0] out_flat;
  always_comb begin
    out_flat = '0;
    if (b_valid_q) begin
      out_flat[PSB-1 -: PrimBits]                  = b_prim_q;
      out_flat[PSB-1-PrimBits -: PB]               = b_x_q;
      out_flat[PSB-1-PrimBits-PB -: PB]            = b_y_q;
      out_flat[PSB-1-PrimBits-2*PB -: Db]          = code;
      for (int p = 0; p < NP; p++) begin
        out_flat[(NP - p) * SB - 1 -: IPB] = b_p_q[p];
        out_flat[(NP - 1 - p) * SB +: EB]  = b_pexp_q[p];
      end
    end
  end
  assign out_o       = out_flat;
  assign out_valid_o = b_valid_q;
  assign out_last_o  = b_last;

  // ---- registers -----------------------------------------------------------------------------
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      front_q   <= FrIdle;
      b_valid_q <= 1'b0;
    end else begin
      unique case (front_q)
        FrIdle: if (accept) front_q <= FrNorm;
        FrNorm: front_q <= FrDiv;
        FrDiv: if (div_done) front_q <= FrDone;
        FrDone: if (b_free) front_q <= accept ? FrNorm : FrIdle;
        default: front_q <= FrIdle;
      endcase
      if (handoff) b_valid_q <= 1'b1;
      else if (b_fire && b_last) b_valid_q <= 1'b0;
    end
  end

  // Datapath registers (no reset: qualified by front_q / b_valid_q).
  always_ff @(posedge clk_i) begin
    if (accept) begin
        f_prim_q <= in_i.prim;
        f_y_q    <= in_y;
        f_x0_q   <= in_x0;
        f_x1_q   <= in_x1;
        for (int p = 0; p < NP; p++) begin
          f_p_q[p]    <= p_start[p];
          f_pdx_q[p]  <= pdx[p];
          f_pexp_q[p] <= pexp[p];
        end
        f_den_q    <= zden;
        f_neg_q[0] <= z_start[ZPB-1];
        f_rem_q[0] <= z_start[ZPB-1] ? QB'(-z_start) : QB'(z_start);
        f_neg_q[1] <= zdx[ZPB-1];
        f_rem_q[1] <= zdx[ZPB-1] ? QB'(-zdx) : QB'(zdx);
    end
    unique case (front_q)
      FrNorm: for (int d = 0; d < 2; d++) begin
        f_quo_q[d] <= '0;
        if (n_any[d] && nz_msb[d] >= nd_msb) begin
          f_cnt_q[d] <= nz_msb[d] - nd_msb + CntB'(1);
          f_dsh_q[d] <= QB'(f_den_q) << (nz_msb[d] - nd_msb);
        end else begin
          f_cnt_q[d] <= '0;
          f_dsh_q[d] <= '0;
        end
      end
      FrDiv: for (int d = 0; d < 2; d++) begin
        f_rem_q[d] <= s_rem[d];
        f_dsh_q[d] <= s_dsh[d];
        f_quo_q[d] <= s_quo[d];
        f_cnt_q[d] <= s_cnt[d];
      end
      default: ;
    endcase

    if (handoff) begin
      b_prim_q <= f_prim_q;
      b_x_q    <= f_x0_q;
      b_x1_q   <= f_x1_q;
      b_y_q    <= f_y_q;
      for (int p = 0; p < NP; p++) begin
        b_p_q[p]    <= f_p_q[p];
        b_pdx_q[p]  <= f_pdx_q[p];
        b_pexp_q[p] <= f_pexp_q[p];
      end
      b_den_q <= f_den_q;
      b_q_q   <= fx_q[0];
      b_r_q   <= fx_r[0];
      b_dq_q  <= fx_q[1];
      b_dr_q  <= fx_r[1];
    end else if (b_fire) begin
      b_x_q <= b_x_q + PB'(1);
      for (int p = 0; p < NP; p++) b_p_q[p] <= b_p_q[p] + b_pdx_q[p];
      b_q_q <= b_q_q + b_dq_q + QB'(st_carry);
      b_r_q <= st_r[ZDB-1:0];
    end
  end

endmodule

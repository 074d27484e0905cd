// fxr_recip: reciprocal unit, stage 3 (1/w per vertex).
// Model: fxr::RecipUnit / fxr::recip (model/stages/recip.hpp); docs/arith.md "# Reciprocal unit".
//
// Function (bit-exact to the model):
//   w = (-1)^in_neg_i * in_sig_i * 2^(in_exp_i - (InSigBits-1)), in_sig_i in [2^(InSigBits-1), 2^InSigBits)
//   (msb set) or all-zero (w = 0; in_exp_i is then ignored).
//   1/w = (-1)^out_neg_o * out_sig_o * 2^(out_exp_o - (OutSigBits-1)), out_sig_o msb set.
//   Significand: minimax seed table (2^SeedIndexBits entries of SeedFracBits bits), NrSteps
//   Newton-Raphson steps y <- trunc(y * ~trunc(x*y)) on NrFracBits fraction bits, round to
//   nearest at OutSigBits, and with Correction = 1 the back-multiply midpoint test that makes
//   the result correctly rounded (RNE; ties cannot occur).
//   Special cases: sign passes through. w = 0: out_dbz_o = 1, out_sig_o = all ones,
//   out_exp_o = 2^(ExpBits-1) - 1. 1/|w| = 2^(2^(ExpBits-1)) (only w = +-2^(-2^(ExpBits-1))):
//   out_ovf_o = 1, same saturated value. No other overflow or underflow is possible.
//
// Ports:
//   clk_i, rst_ni                  clock, active-low asynchronous reset
//   in_valid_i / in_ready_o        input handshake (transfer when both are high)
//   in_neg_i                       sign of w
//   in_exp_i [ExpBits]             signed exponent of the leading one of w
//   in_sig_i [InSigBits]           significand of w (msb set), or zero
//   out_valid_o / out_ready_i      output handshake
//   out_neg_o                      sign of 1/w (= in_neg_i)
//   out_exp_o [ExpBits]            signed exponent of the leading one of 1/w
//   out_sig_o [OutSigBits]         significand of 1/w (msb set)
//   out_dbz_o                      division by zero (w == 0)
//   out_ovf_o                      exponent overflow (saturated result)
//
// Latency (cycles from the input transfer to out_valid_o, = fxr::recip_cost().latency):
//   1 (seed table) + 2 * NrSteps (x*y -> t, y*t -> y) + 1 (round) + Correction (midpoint test);
//   7 at the default configuration. Initiation interval 1. out_ready_i low stalls every stage
//   (in_ready_o = out_ready_i | ~out_valid_o); no result is lost or duplicated.
//
// The seed table is computed at elaboration by seed_entry(), the same minimax rule and integer
// arithmetic as fxr::recip_seed_table (model/stages/recip.cpp); a Verilator check compares the two.
module fxr_recip #(
  parameter int InSigBits     = fxr_config_pkg::RecipInSigBits,
  parameter int OutSigBits    = fxr_config_pkg::RecipOutSigBits,
  parameter int ExpBits       = fxr_config_pkg::RecipExpBits,
  parameter int SeedIndexBits = fxr_config_pkg::RecipSeedIndexBits,
  parameter int SeedFracBits  = fxr_config_pkg::RecipSeedFracBits,
  parameter int NrSteps       = fxr_config_pkg::RecipNrSteps,
  parameter int NrFracBits    = fxr_config_pkg::RecipNrFracBits,
  parameter int Correction    = fxr_config_pkg::RecipCorrection  // 0 none, 1 remainder
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  in_valid_i,
  output logic                  in_ready_o,
  input  logic                  in_neg_i,
  input  logic [ExpBits-1:0]    in_exp_i,
  input  logic [InSigBits-1:0]  in_sig_i,
  output logic                  out_valid_o,
  input  logic                  out_ready_i,
  output logic                  out_neg_o,
  output logic [ExpBits-1:0]    out_exp_o,
  output logic [OutSigBits-1:0] out_sig_o,
  output logic                  out_dbz_o,
  output logic                  out_ovf_o
);
  // ---- derived widths and stage numbers ---------------------------------------------------
  localparam int F = NrFracBits;            // fraction bits of y, p, t after the seed
  localparam int Y0W = SeedFracBits + 1;    // y0 with its leading one: y0 = Y0 * 2^-(Y0W)
  localparam int YW = (Y0W > F) ? Y0W : F;  // width of the y registers (y < 1 throughout)
  localparam int Drop = F - OutSigBits;     // bits below the output lsb at the rounding (>= 1)
  localparam int KW = OutSigBits + 1;       // rounded K in units of 2^-OutSigBits: up to 2^OutSigBits
  localparam int Entries = 2 ** SeedIndexBits;
  localparam int StRound = 1 + 2 * NrSteps; // stage index of the rounding register
  localparam int Latency = StRound + 1 + Correction;
  localparam int Last = Latency - 1;        // the output register stage

  // ---- seed table (elaboration-time constants) --------------------------------------------
  // Largest relative endpoint error of candidate y (units 2^-(SeedIndexBits+SeedFracBits+1)) on
  // the segment [a, b) * 2^-SeedIndexBits.
  // (64-bit signed arithmetic: products below 2^(2*SeedIndexBits+SeedFracBits+3), at most 2^51.)
  function automatic logic signed [63:0] seed_cost(input logic signed [63:0] a,
                                                   input logic signed [63:0] y);
    logic signed [63:0] d, ea, eb;
    d  = 64'sd1 <<< (SeedIndexBits + SeedFracBits + 1);
    ea = d - a * y;
    eb = d - (a + 64'sd1) * y;
    if (ea < 0) ea = -ea;
    if (eb < 0) eb = -eb;
    seed_cost = (ea > eb) ? ea : eb;
  endfunction

  // Entry i: the grid value (k bits after the leading one) minimising the largest |1 - x*y0| over
  // x in [1 + i*2^-s, 1 + (i+1)*2^-s); candidates floor / floor+1 of 2^(s+k+2) / (2a+1), clamped
  // to [1/2, 1); ties keep the smaller.
  function automatic logic [SeedFracBits-1:0] seed_entry(input int i);
    logic signed [63:0] a, y_lo, y_hi, y_floor, best, up;
    a       = (64'sd1 <<< SeedIndexBits) + 64'(i);
    y_lo    = 64'sd1 <<< SeedFracBits;
    y_hi    = (64'sd1 <<< (SeedFracBits + 1)) - 64'sd1;
    y_floor = (64'sd1 <<< (SeedIndexBits + SeedFracBits + 2)) / (64'sd2 * a + 64'sd1);
    best    = (y_floor < y_lo) ? y_lo : ((y_floor > y_hi) ? y_hi : y_floor);
    up      = (y_floor + 64'sd1 < y_lo) ? y_lo :
              ((y_floor + 64'sd1 > y_hi) ? y_hi : y_floor + 64'sd1);
    if (seed_cost(a, up) < seed_cost(a, best)) best = up;
    seed_entry = SeedFracBits'(best - y_lo);
  endfunction

  logic [Entries*SeedFracBits-1:0] seed_rom;
  for (genvar i = 0; i < Entries; i++) begin : gen_seed
    assign seed_rom[i*SeedFracBits +: SeedFracBits] = seed_entry(i);
  end

  // ---- handshake: one global enable, the pipeline holds while the output is stalled --------
  logic [Latency-1:0] valid_q;
  logic               advance;
  assign advance     = out_ready_i | ~valid_q[Last];
  assign in_ready_o  = advance;
  assign out_valid_o = valid_q[Last];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
    end else if (advance) begin
      valid_q <= {valid_q[Latency-2:0], in_valid_i};
    end
  end

  // ---- per-stage data ---------------------------------------------------------------------
  // Stages 0 .. Last-1 (the output stage Last has its own registers below). Flat vectors, one
  // field per stage: X[s*W +: W] is stage s (Yosys 0.23 has no packed 2-D arrays).
  logic [Last*InSigBits-1:0] m_d, m_q;      // significand of w
  logic [Last-1:0]           neg_d, neg_q;
  logic [Last-1:0]           zero_d, zero_q;
  logic [Last*ExpBits-1:0]   exp_d, exp_q;
  logic [Last*YW-1:0]        y_d, y_q;      // y (fraction bits: Y0W at stage 0, F after)
  logic [Last*(F+1)-1:0]     t_d, t_q;      // t = ~p at the first stage of each NR step
  logic [Last*KW-1:0]        k_d, k_q;      // rounded result in units of 2^-OutSigBits

  // Stage 0: seed lookup. Index = the SeedIndexBits fraction bits below the leading one.
  logic [SeedIndexBits-1:0] seed_idx;
  assign seed_idx = in_sig_i[InSigBits-2 -: SeedIndexBits];
  assign m_d[0 +: InSigBits] = in_sig_i;
  assign neg_d[0]            = in_neg_i;
  assign zero_d[0]           = (in_sig_i == '0);
  assign exp_d[0 +: ExpBits] = in_exp_i;
  assign y_d[0 +: YW]        = YW'({1'b1, seed_rom[seed_idx*SeedFracBits +: SeedFracBits]});
  assign t_d[0 +: F+1]       = '0;
  assign k_d[0 +: KW]        = '0;

  // Stages 1 .. Last: the word moves on; each stage overrides what it computes.
  for (genvar s = 1; s < Last; s++) begin : gen_pass
    assign m_d[(s)*InSigBits +: InSigBits]    = m_q[(s-1)*InSigBits +: InSigBits];
    assign neg_d[s]  = neg_q[s-1];
    assign zero_d[s] = zero_q[s-1];
    assign exp_d[(s)*ExpBits +: ExpBits]  = exp_q[(s-1)*ExpBits +: ExpBits];
  end

  // Newton-Raphson step j: stage 1+2j computes t = ~trunc_F(x*y), stage 2+2j y = trunc_F(y*t).
  for (genvar j = 0; j < NrSteps; j++) begin : gen_step
    localparam int SA = 1 + 2 * j;
    localparam int SB = 2 + 2 * j;
    localparam int FY = (j == 0) ? Y0W : F;     // fraction bits (= width) of the incoming y
    localparam int Sh = InSigBits - 1 + FY - F; // x*y has InSigBits-1+FY fraction bits; keep F

    logic [FY-1:0]           y_in;
    logic [InSigBits+FY-1:0] xy;
    logic [F:0]              p;
    assign y_in = y_q[(SA-1)*YW +: FY];
    assign xy   = (InSigBits+FY)'(m_q[(SA-1)*InSigBits +: InSigBits]) * (InSigBits+FY)'(y_in);
    // p = x*y < 2: F+1 bits. Precision lost: truncation, < 2^-F.
    if (Sh >= 0) begin : gen_trunc
      assign p = xy[Sh +: F+1];
      logic unused_xy;  // the truncated low bits
      assign unused_xy = ^xy;
    end else begin : gen_widen
      assign p = (F+1)'(xy) << (-Sh);
    end
    // t = 2 - 2^-F - p (ones' complement): never above 2 - x*y, so y stays <= 1/x.
    assign t_d[(SA)*(F+1) +: (F+1)] = ~p;
    assign y_d[(SA)*YW +: YW] = y_q[(SA-1)*YW +: YW];
    assign k_d[(SA)*KW +: KW] = '0;

    logic [FY-1:0]     y_b;
    logic [FY+F:0]     yt;
    assign y_b = y_q[(SB-1)*YW +: FY];
    assign yt  = (FY+F+1)'(y_b) * (FY+F+1)'(t_q[(SB-1)*(F+1) +: (F+1)]);
    // y*t has FY+F fraction bits; keep F (the value is below 1). Precision lost: truncation.
    assign y_d[(SB)*YW +: YW] = YW'(yt[FY +: F]);
    logic unused_yt;  // truncated low bits; the top bit is zero (y*t < 1)
    assign unused_yt = ^yt;
    assign t_d[(SB)*(F+1) +: (F+1)] = '0;
    assign k_d[(SB)*KW +: KW] = '0;
  end

  // Rounding stage: K = round_half_up(y * 2^OutSigBits), at least 2^(OutSigBits-1) (1/x > 1/2).
  logic [F-1:0] y_fin;
  logic [F:0]   y_rnd;
  logic [KW-1:0] k_rnd;
  assign y_fin = y_q[(StRound-1)*YW +: F];
  assign y_rnd = {1'b0, y_fin} + ((F+1)'(1) << (Drop - 1));  // precision lost: rounding
  assign k_rnd = y_rnd[F:Drop];
  logic unused_rnd;  // the bits below the output lsb, dropped by the rounding
  assign unused_rnd = ^y_rnd;
  logic [KW-1:0] k_round;
  assign k_round = (k_rnd < (KW'(1) << (OutSigBits - 1))) ? (KW'(1) << (OutSigBits - 1)) : k_rnd;

  // Final K (after the midpoint test when Correction = 1), then normalisation and specials.
  logic [KW-1:0] k_fin;
  if (Correction != 0) begin : gen_correct
    assign k_d[StRound*KW +: KW]     = k_round;  // the rounding stage is registered
    assign y_d[StRound*YW +: YW]     = '0;
    assign t_d[StRound*(F+1) +: F+1] = '0;
    // 1/x > (K + 1/2) * 2^-OutSigBits  <=>  m * (2K + 1) < 2^(InSigBits + OutSigBits): exact.
    logic [KW:0]             k_odd;
    logic [InSigBits+KW:0]   mk;
    logic                    above;
    assign k_odd = {k_q[(Last-1)*KW +: KW], 1'b1};
    assign mk    = (InSigBits+KW+1)'(m_q[(Last-1)*InSigBits +: InSigBits]) * (InSigBits+KW+1)'(k_odd);
    assign above = (mk[InSigBits+KW:InSigBits+OutSigBits] == '0);
    logic unused_mk;  // only the bits at and above 2^(InSigBits+OutSigBits) decide
    assign unused_mk = ^mk;
    assign k_fin = k_q[(Last-1)*KW +: KW] + KW'(above);
  end else begin : gen_no_correct
    assign k_fin = k_round;  // the rounding stage is the output stage
  end

  // Output register stage: normalise (1.0 -> next binade), exponent, division by zero, overflow.
  logic                  one;       // K = 2^OutSigBits: the result is exactly 1.0 (exp_adj 0)
  logic [OutSigBits-1:0] sig_norm;
  logic signed [ExpBits:0] lead;    // -e + exp_adj, one extra bit: -(-2^(ExpBits-1)) fits
  logic                  ovf;
  logic                  zero_in;
  logic [ExpBits-1:0]    exp_in;
  localparam logic [ExpBits-1:0] ExpMax = {1'b0, {(ExpBits-1){1'b1}}};
  assign zero_in  = zero_q[Last-1];
  assign exp_in   = exp_q[(Last-1)*ExpBits +: ExpBits];
  assign one      = k_fin[OutSigBits];
  assign sig_norm = one ? {1'b1, {(OutSigBits-1){1'b0}}} : k_fin[OutSigBits-1:0];
  assign lead     = -$signed({exp_in[ExpBits-1], exp_in}) - (one ? '0 : (ExpBits+1)'(1));
  assign ovf      = !zero_in && (lead > $signed({1'b0, ExpMax}));

  logic                  out_neg_q, out_dbz_q, out_ovf_q;
  logic [ExpBits-1:0]    out_exp_q;
  logic [OutSigBits-1:0] out_sig_q;
  always_ff @(posedge clk_i) begin
    if (advance) begin
      for (int s = 0; s < Last; s++) begin
        m_q[(s)*InSigBits +: InSigBits]    <= m_d[(s)*InSigBits +: InSigBits];
        neg_q[s]  <= neg_d[s];
        zero_q[s] <= zero_d[s];
        exp_q[(s)*ExpBits +: ExpBits]  <= exp_d[(s)*ExpBits +: ExpBits];
        y_q[(s)*YW +: YW]    <= y_d[(s)*YW +: YW];
        t_q[(s)*(F+1) +: (F+1)]    <= t_d[(s)*(F+1) +: (F+1)];
        k_q[(s)*KW +: KW]    <= k_d[(s)*KW +: KW];
      end
      out_neg_q <= neg_q[Last-1];
      out_dbz_q <= zero_in;
      out_ovf_q <= ovf;
      out_sig_q <= (zero_in || ovf) ? '1 : sig_norm;
      out_exp_q <= (zero_in || ovf) ? ExpMax : lead[ExpBits-1:0];
    end
  end

  assign out_neg_o = out_neg_q;
  assign out_dbz_o = out_dbz_q;
  assign out_ovf_o = out_ovf_q;
  assign out_sig_o = out_sig_q;
  assign out_exp_o = out_exp_q;

  // Fields a stage does not carry (t outside the first half of an NR step, y's padding above the
  // seed width, m and k after their last reader) are constant or dead; synthesis removes them.
  logic unused_fields;
  assign unused_fields = ^{m_q, y_q, t_q, k_q};

endmodule

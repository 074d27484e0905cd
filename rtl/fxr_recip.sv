// fxr_recip: reciprocal unit, stage 3 (1/w per vertex).
// Model: fxr::RecipUnit / fxr::recip (model/stages/recip.hpp); docs/arith.md "# Reciprocal unit".
//
// Function (bit-exact to the model):
//   w = (-1)^in_neg_i * in_sig_i * 2^(in_exp_i - (InSigBits-1)), in_sig_i in [2^(InSigBits-1), 2^InSigBits)
//   (msb set) or all-zero (w = 0; in_exp_i is then ignored).
//   1/w = (-1)^out_neg_o * out_sig_o * 2^(out_exp_o - (OutSigBits-1)), out_sig_o msb set.
//   Significand: the reciprocal core shared with fxr_div_recip_mul (fxr_seed_rom: minimax seed
//   table of 2^SeedIndexBits entries of SeedFracBits bits; NrSteps fxr_nr_step stages
//   y <- trunc(y * ~trunc(x*y)) on NrFracBits fraction bits), K = y rounded half up at OutSigBits,
//   and with Correction = 1 the back-multiply midpoint test that makes the result correctly
//   rounded (RNE; ties cannot occur); fxr_round increments and renormalises.
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
// The seed table is computed at elaboration by fxr_seed_rom, the same minimax rule and integer
// arithmetic as fxr::recip_core_seed_table (model/arith/recip_core.cpp); tb/seed_rom_test.cpp
// compares the two for the default and the variant configurations.
module fxr_recip #(
  parameter int InSigBits     = fxr_config_pkg::RecipInSigBits,
  parameter int OutSigBits    = fxr_config_pkg::RecipOutSigBits,
  parameter int ExpBits       = fxr_config_pkg::RecipExpBits,
  parameter int SeedIndexBits = fxr_config_pkg::RecipSeedIndexBits,
  parameter int SeedFracBits  = fxr_config_pkg::RecipSeedFracBits,
  parameter int NrSteps       = fxr_config_pkg::RecipNrSteps,
  parameter int NrFracBits    = fxr_config_pkg::RecipNrFracBits,
  parameter int Correction    = fxr_config_pkg::RecipCorrection  // fxr_config_pkg::recip_correction_e
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
  localparam int F = NrFracBits;            // fraction bits of y after the first NR step
  localparam int Y0W = SeedFracBits + 1;    // y0 with its leading one: y0 = Y0 * 2^-(Y0W)
  localparam int Drop = F - OutSigBits;     // bits below the output lsb at the rounding (>= 1)
  localparam int KW = OutSigBits + 1;       // K rounded half up, units of 2^-OutSigBits: up to 2^OutSigBits
  localparam int StRound = 1 + 2 * NrSteps; // stage index of the rounding register
  // The remainder correction adds one register stage (the back-multiply midpoint test).
  localparam bit Correct = Correction == fxr_config_pkg::RecipCorrectionRemainder;
  localparam int Latency = StRound + 1 + (Correct ? 1 : 0);
  localparam int Last = Latency - 1;        // the output register stage

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
  // field per stage: X[s*W +: W] is stage s (Yosys 0.23 has no packed 2-D arrays). y lives in
  // the fxr_nr_step instances; K (rounded) in k_q at the rounding stage.
  logic [Last*InSigBits-1:0] m_d, m_q;      // significand of w
  logic [Last-1:0]           neg_d, neg_q;
  logic [Last-1:0]           zero_d, zero_q;
  logic [Last*ExpBits-1:0]   exp_d, exp_q;

  // Stage 0: seed lookup. Index = the SeedIndexBits fraction bits below the leading one.
  logic [SeedIndexBits-1:0] seed_idx;
  logic [SeedFracBits-1:0]  seed_frac;
  assign seed_idx = in_sig_i[InSigBits-2 -: SeedIndexBits];
  fxr_seed_rom #(
    .SeedIndexBits(SeedIndexBits),
    .SeedFracBits (SeedFracBits)
  ) u_rom (
    .idx_i (seed_idx),
    .seed_o(seed_frac)
  );
  assign m_d[0 +: InSigBits] = in_sig_i;
  assign neg_d[0]            = in_neg_i;
  assign zero_d[0]           = (in_sig_i == '0);
  assign exp_d[0 +: ExpBits] = in_exp_i;

  // Stages 1 .. Last: the word moves on.
  for (genvar s = 1; s < Last; s++) begin : gen_pass
    assign m_d[(s)*InSigBits +: InSigBits]    = m_q[(s-1)*InSigBits +: InSigBits];
    assign neg_d[s]  = neg_q[s-1];
    assign zero_d[s] = zero_q[s-1];
    assign exp_d[(s)*ExpBits +: ExpBits]  = exp_q[(s-1)*ExpBits +: ExpBits];
  end

  // Newton-Raphson step j (fxr_nr_step): reads y and m of stage 2j, y' is registered at stage 2j+2.
  logic [Y0W-1:0]           y0_q;     // stage 0: the seed with its leading one
  wire  [NrSteps*F-1:0]     y_s;      // y after step j at [j*F +: F]
  for (genvar j = 0; j < NrSteps; j++) begin : gen_step
    if (j == 0) begin : gen_first
      fxr_nr_step #(
        .XBits    (InSigBits),
        .YFracBits(Y0W),
        .FracBits (F)
      ) u_step (
        .clk_i(clk_i),
        .en_i (advance),
        .act_i(|valid_q),
        .x_i  (m_q[0 +: InSigBits]),
        .y_i  (y0_q),
        .y_o  (y_s[0 +: F])
      );
    end else begin : gen_next
      fxr_nr_step #(
        .XBits    (InSigBits),
        .YFracBits(F),
        .FracBits (F)
      ) u_step (
        .clk_i(clk_i),
        .en_i (advance),
        .act_i(|valid_q),
        .x_i  (m_q[(2*j)*InSigBits +: InSigBits]),
        .y_i  (y_s[(j-1)*F +: F]),
        .y_o  (y_s[j*F +: F])
      );
    end
  end

  // Rounding stage: K = round_half_up(y * 2^OutSigBits), at least 2^(OutSigBits-1) (1/x > 1/2).
  logic [F-1:0]  y_fin;
  logic [F:0]    y_rnd;
  logic [KW-1:0] k_rnd;
  assign y_fin = y_s[(NrSteps-1)*F +: F];
  assign y_rnd = {1'b0, y_fin} + ((F+1)'(1) << (Drop - 1));  // precision lost: rounding
  assign k_rnd = y_rnd[F:Drop];
  logic unused_rnd;  // the bits below the output lsb, dropped by the rounding
  assign unused_rnd = ^y_rnd;

  // Final rounding (fxr_round: increment, renormalise 1.0 into the next binade).
  logic [OutSigBits-1:0] q_fin;
  logic                  t_neg_fin;
  logic [OutSigBits-1:0] sig_fin;
  logic [1:0]            exp_adj_fin;  // 2'b11: below 1 (exp_adj -1); 2'b00: exactly 1.0
  localparam logic [OutSigBits-1:0] KLo = {1'b1, {(OutSigBits-1){1'b0}}};
  if (Correct) begin : gen_correct
    // K clamped to [2^(o-1), 2^o - 1] and registered (K = 2^o means RN(1/x) = 1.0, which the
    // midpoint test below restores: docs/arith.md).
    logic [OutSigBits-1:0] k_clamp;
    logic [OutSigBits-1:0] k_q;
    assign k_clamp = (k_rnd < KW'(KLo)) ? KLo : (k_rnd[OutSigBits] ? '1 : k_rnd[OutSigBits-1:0]);
    always_ff @(posedge clk_i) begin
      if (advance) begin
        k_q <= k_clamp;
      end
    end
    // 1/x > (K + 1/2) * 2^-OutSigBits  <=>  m * (2K + 1) < 2^(InSigBits + OutSigBits): exact.
    logic [KW-1:0]           k_odd;
    logic [InSigBits+KW-1:0] mk;
    assign k_odd = {k_q, 1'b1};
    assign mk    = (InSigBits+KW)'(m_q[(Last-1)*InSigBits +: InSigBits]) * (InSigBits+KW)'(k_odd);
    logic unused_mk;  // only the bits at and above 2^(InSigBits+OutSigBits) decide
    assign unused_mk = ^mk;
    assign q_fin     = k_q;
    assign t_neg_fin = (mk[InSigBits+KW-1:InSigBits+OutSigBits] != '0);  // at or below the midpoint
  end else begin : gen_no_correct
    // The rounding stage is the output stage: q = floor(y * 2^o), up by the rounding bit (half
    // up); a q below 1/2 is clamped to 1/2 without rounding up (the model's max(K, 2^(o-1))).
    logic q_low;
    assign q_low     = ~y_fin[F-1];
    assign q_fin     = q_low ? KLo : y_fin[F-1:Drop];
    assign t_neg_fin = q_low | ~y_fin[Drop-1];
    logic unused_k;
    assign unused_k = ^k_rnd;
  end
  fxr_round #(
    .QuotBits(OutSigBits)
  ) u_round (
    .q_i      (q_fin),
    .t_neg_i  (t_neg_fin),
    .t_zero_i (1'b0),
    .k_i      (1'b1),
    .sig_o    (sig_fin),
    .exp_adj_o(exp_adj_fin)
  );

  // Stage 0 registers of y0 (the NR steps hold the rest of y).
  always_ff @(posedge clk_i) begin
    if (advance) begin
      y0_q <= {1'b1, seed_frac};
    end
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
  assign one      = (exp_adj_fin == 2'b00);
  assign sig_norm = sig_fin;
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

  // Fields after their last reader (m beyond the NR steps and the midpoint test) are dead;
  // synthesis removes them.
  logic unused_fields;
  assign unused_fields = ^{m_q, exp_adj_fin};

endmodule

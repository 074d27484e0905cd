// model/arith/div.hpp — stage 9: the per-pixel divider v = (v/w) / (1/w).
//
// At a pixel the interpolators produce two exact non-negative integer sums, N = Σ E_i·(v_i/w_i)
// and D = Σ E_i·(1/w_i); the pipeline normalises both (leading-zero count) into significands
// with their msb set and calls div_sig, a significand divider. docs/arith.md "# Divider"
// derives the defaults and gives the error and cost figures that chose them.
//
// Algorithms (DivConfig::algorithm):
//   radix2     radix-2 non-restoring digit recurrence: one exact quotient bit per step and an
//              exact remainder, so round-to-nearest-even is exact (correctly rounded for every
//              width by construction).
//   recip_mul  the reciprocal core shared with stage 3 (model/arith/recip_core.hpp: minimax
//              seed table + one-sided Newton–Raphson steps at nr_frac_bits), one quotient multiply,
//              then one back-multiply remainder correction (±1 ulp) and an exact RNE decision
//              from the corrected remainder. Correctly rounded whenever the truncated quotient
//              is within one ulp of the true one (measured: analysis/measure.hpp; tested exhaustively at
//              reduced widths and on 10^7 random at the default widths).
//   shared_recip the interpolator design most GPUs use: one reciprocal of the denominator per
//              pixel (the same reciprocal core, seed_* / nr_* fields), shared by every varying of
//              the pixel, and per varying one multiply a'·y rounded once (RNE) to quot_bits. No
//              remainder correction: cheaper, NOT correctly rounded; error bound div_bound()
//              (docs/arith.md "shared_recip"). As a function of one (n, d) pair it is
//              div_sig_shared_recip = div_mul_round(n, d, div_recip(d)); stage 9
//              (model/stages/divide.hpp) computes div_recip once per pixel.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "model/arith/fixed.hpp"
#include "model/arith/fxfloat.hpp"
#include "model/arith/recip_core.hpp"
#include "model/arith/round.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

enum class DivAlgorithm : uint8_t { RecipMul, Radix2, SharedRecip };

enum class DivSchedule : uint8_t { Pipelined, Iterative };

struct DivConfig {
  // Radix-2 is the default: correctly rounded by construction and, fully pipelined at 32/32/24,
  // 0.9 k adder bits and no multiplier (Yosys: 3.9 k LUT4) against 5.5 k multiplier cells for
  // the correctly rounded recip_mul 256×8 (11.9 k LUT4); docs/arith.md "# Divider".
  DivAlgorithm algorithm = DivAlgorithm::Radix2;
  // Operand significand widths. 32: the normalised interpolator sums keep 32 bits
  // (≥ quot_bits + 8 guard bits, so the pre-rounding of N and D costs < 2^-8 ulp of the result).
  int num_bits = 32;
  int den_bits = 32;
  // Quotient significand width: 24 (float32 significand, RasterConfig::varying_out_sig_bits).
  int quot_bits = 24;
  // recip_mul and shared_recip: seed table of 2^seed_index_bits entries indexed by the divisor bits after its
  // leading one; each entry holds seed_bits bits after the (implicit) leading one.
  int seed_index_bits = 8;
  int seed_bits = 8;
  // recip_mul and shared_recip: Newton–Raphson steps y ← y·(2 − b·y) and the fraction bits of
  // the iterate y (shared_recip at these defaults: error bound 0.689 ulp, div_bound()).
  // 2 steps from an 8-bit seed give ≈ 2^-34 relative error before truncation; 28 = 24 + 4
  // guard bits keeps the truncation error of y below 2^-26 relative, so the quotient is
  // within one ulp and the remainder step makes it correctly rounded.
  int nr_steps = 2;
  int nr_frac_bits = 28;
  // radix2: quotient bits retired per clock (per pipeline register stage, or per iteration of
  // the iterative unit).
  int bits_per_stage = 1;
  // radix2: pipelined (one result per clock) or iterative (one recurrence stage reused;
  // initiation interval = number of recurrence cycles). recip_mul is always pipelined.
  DivSchedule schedule = DivSchedule::Pipelined;

  template <class V>
  void visit(V& v) {
    v.choice("algorithm", algorithm, {"recip_mul", "radix2", "shared_recip"},
             "divider algorithm (shared_recip: one reciprocal per pixel, one multiply per varying, not correctly rounded)");
    v.integer("num_bits", num_bits, 4, 60, "numerator significand bits (msb set)");
    v.integer("den_bits", den_bits, 4, 60, "denominator significand bits (msb set)");
    v.integer("quot_bits", quot_bits, 4, 60, "quotient significand bits (msb set), RNE");
    v.integer("seed_index_bits", seed_index_bits, 1, 14, "recip_mul, shared_recip: log2 of the seed table entries");
    v.integer("seed_bits", seed_bits, 1, 20, "recip_mul, shared_recip: seed bits after the leading one");
    v.integer("nr_steps", nr_steps, 0, 4, "recip_mul, shared_recip: Newton-Raphson steps");
    v.integer("nr_frac_bits", nr_frac_bits, 4, 60, "recip_mul, shared_recip: fraction bits of the reciprocal iterate");
    v.integer("bits_per_stage", bits_per_stage, 1, 8, "radix2: quotient bits retired per clock");
    v.choice("schedule", schedule, {"pipelined", "iterative"}, "radix2: pipelined (II 1) or iterative");
  }
};

// Derived widths (the RTL uses the same formulas; docs/arith.md "# Divider").
// Aligned operand width: both operands are shifted left (exactly) to this many bits.
inline int div_align_bits(const DivConfig& c) { return c.num_bits > c.den_bits ? c.num_bits : c.den_bits; }
// Radix-2 partial remainder width: |r| < 2b < 2^(align+1), plus the sign bit.
inline int div_rem_bits(const DivConfig& c) { return div_align_bits(c) + 2; }
// Radix-2 recurrence steps after the first (always-one) quotient digit.
inline int div_radix2_steps(const DivConfig& c) { return c.quot_bits - 1; }

using DivSig = RoundedSig;

// Contract (every algorithm): n ∈ [2^(nb−1), 2^nb), d ∈ [2^(db−1), 2^db) (nb = num_bits,
// db = den_bits, qb = quot_bits):
//   (n·2^−(nb−1)) / (d·2^−(db−1)) ≈ sig·2^−(qb−1)·2^exp_adj, sig ∈ [2^(qb−1), 2^qb),
//   exp_adj = 0 when the normalised n ≥ the normalised d, else −1; rounded to nearest, ties to
//   even (the only rounding of the unit); when rounding carries out (sig would be 2^qb) the
//   result renormalises to sig = 2^(qb−1), exp_adj + 1 (so exp_adj ∈ {−1, 0, +1}).
//   radix2 is correctly rounded for every configuration; recip_mul is when its reciprocal is
//   accurate enough (the default is; analysis/measure.hpp measures the others); shared_recip
//   is rounded once from an approximate product: within div_bound().error_bound_ulp, not
//   correctly rounded (exp_adj ∈ {−1, 0, +1} the same way).
// Special cases (the RTL does the same): d == 0 → sig = 2^qb − 1 (saturated), exp_adj = 0
//   (the RTL raises out_dbz_o; divide() reports it); otherwise n == 0 → sig = 0, exp_adj = 0.
//   Operands with bits above their width or a clear msb are outside the contract: the model
//   throws std::invalid_argument, the RTL result is unspecified.
// This is the fast model the pipeline calls: for radix2 it is div_sig_exact (proven
// bit-identical to the step-by-step recurrence by tests/model/div_test.cpp), for recip_mul
// the step model div_sig_recip_mul.
DivSig div_sig(const DivConfig& c, uint64_t n, uint64_t d);

// Correctly rounded quotient by one exact integer division (same contract; RNE). Fast.
DivSig div_sig_exact(const DivConfig& c, uint64_t n, uint64_t d);
// Step-by-step radix-2 non-restoring recurrence, as the RTL computes it (same contract).
DivSig div_sig_radix2_steps(const DivConfig& c, uint64_t n, uint64_t d);
// Step-by-step reciprocal-multiply with remainder correction, as the RTL computes it.
DivSig div_sig_recip_mul(const DivConfig& c, uint64_t n, uint64_t d);

// ---- 64-bit fast path of div_sig_exact (docs/speed.md "Divider") ----------------------------
// div_sig_exact in one inline 64-bit division: no u128, no call, no operand check. Applies
// when div_fast64_ok(c): radix2 (div_sig is div_sig_exact) and W + qb ≤ 63 (W = div_align_bits),
// so the dividend a'·2^(qb−1) < 2^(W+1+qb−1) fits uint64_t exactly (defaults: 32 + 24 = 56).
// Contract: for operands inside div_sig's contract (and the d == 0 / n == 0 specials) returns
//   exactly div_sig_exact(c, n, d) (tests/model/div_test.cpp DivFast64.*: exhaustive 12-bit
//   shapes, 10^7 random plus ties here, 10^8 in tests/model/div_slow_test.cpp). Operands
//   outside the contract are NOT checked (div_sig_exact throws; the stage never produces them:
//   normalize() sets the msb).
inline bool div_fast64_ok(const DivConfig& c) {
  return c.algorithm == DivAlgorithm::Radix2 && div_align_bits(c) + c.quot_bits <= 63;
}
inline DivSig div_sig_fast64(const DivConfig& c, uint64_t n, uint64_t d) {
  if (d == 0) return {(uint64_t{1} << c.quot_bits) - 1, 0};  // saturated (div_sig contract)
  if (n == 0) return {0, 0};
  const int w = div_align_bits(c);
  const uint64_t a = n << (w - c.num_bits), b = d << (w - c.den_bits);
  const int k = a < b ? 1 : 0;
  const uint64_t num = (a << k) << (c.quot_bits - 1);  // exact: < 2^(W+qb) ≤ 2^63
  const uint64_t q = num / b, r = num % b;             // one hardware division
  return round_increment(q, rne_round_up<uint64_t>(q, r, b), c.quot_bits, -k);
}

// ---- one reciprocal per pixel, several exact quotients (docs/speed.md "One reciprocal per pixel")
// div_sig_fast64's result with the hardware division moved to the divisor alone: per pixel
// R = floor((2^64 − 1) / b) (b = d·2^(W−db), the aligned divisor, one 64-bit division), then per
// varying the estimate q0 = floor(num·R / 2^64) (one 64×64→128 multiply) and the exact remainder
// r = num − q0·b decide. With num < 2^(W+qb) ≤ 2^63 (div_fast64_ok):
//   R = (2^64 − 1)/b − ε, 0 ≤ ε < 1, so num·R/2^64 = num/b − num·(1 + ε·b)/(b·2^64)
//   > num/b − 2·num/2^64 ≥ num/b − 1   (num/2^64 < ½), and ≤ num/b;
// hence q0 ∈ {q − 1, q} (q = floor(num/b)), r ∈ [0, 2b), and one conditional step (r ≥ b:
// q0 + 1, r − b) gives the exact q and r; the RNE decision is div_sig_fast64's. No floating
// point: the estimate is an integer one (a double estimate of 1/b was measured slower on this
// CPU, docs/speed.md). Contract: div_fast64_ok(c); operands as div_sig_fast64 (not checked);
// R = div_recip64(c, d); returns exactly div_sig_fast64(c, n, d) (= div_sig_exact, tests/model/
// div_test.cpp DivRecip64.*: exhaustive 12-bit-class shapes, random, ties and the estimate's
// off-by-one reached; 10^8 in tests/model/div_slow_test.cpp).
// R with the widths as arguments (w = div_align_bits, db of the configuration; d ≠ 0).
inline uint64_t div_recip64_w(int w, int db, uint64_t d) { return ~uint64_t{0} / (d << (w - db)); }
inline uint64_t div_recip64(const DivConfig& c, uint64_t d) {
  return d == 0 ? 0 : div_recip64_w(div_align_bits(c), c.den_bits, d);
}
// The estimate alone: floor(num·R / 2^64) (exposed for the tests, which count its corrections).
inline uint64_t div_recip64_estimate(uint64_t num, uint64_t R) { return (uint64_t)(((u128)num * R) >> 64); }
// The quotient for n, d ≠ 0 with the widths as arguments (w = div_align_bits, nb, db, qb of the
// configuration; constants where the caller knows them, model/stages/interp_span.hpp).
// The correction and RNE from the estimate q0 ∈ {q − 1, q} of num / b (exp_adj −k).
inline DivSig div_recip64_correct(uint64_t q, uint64_t num, uint64_t b, int qb, int k) {
  uint64_t r = num - q * b;                        // in [0, 2b)
  const uint64_t fix = r >= b ? 1 : 0;
  q += fix;
  r -= fix * b;
  return round_increment(q, rne_round_up<uint64_t>(q, r, b), qb, -k);
}
inline DivSig div_sig_recip64_w(int w, int nb, int db, int qb, uint64_t n, uint64_t d, uint64_t R) {
  const uint64_t a = n << (w - nb), b = d << (w - db);
  const int k = a < b ? 1 : 0;
  const uint64_t num = (a << k) << (qb - 1);       // exact: < 2^(W+qb) ≤ 2^63
  return div_recip64_correct(div_recip64_estimate(num, R), num, b, qb, k);  // estimate: q − 1 or q
}

// ---- the estimate's fraction decides (docs/speed.md "Session 9: the pixel loop") -------------
// div_sig_recip64_w without the remainder where the estimate's low word already decides. The
// product num·R = q0·2^64 + f (f < 2^64) and num / b = q0 + (f + δ)/2^64 with
//   δ = num·(2^64 − b·R)/b,  0 < δ ≤ num < B = 2^(W+qb)
// (b·R ≤ 2^64 − 1 < 2^64, and 2^64 − b·R ≤ b since R = ⌊(2^64 − 1)/b⌋). So when
//   f < 2^63 − B:       f + δ < 2^63: q = q0 and the fraction is below ½ (round down);
//   2^63 ≤ f < 2^64 − B: 2^63 < f + δ < 2^64: q = q0 and the fraction is above ½, never a tie
//                        (δ > 0; round up);
// only f in the two bands [2^63 − B, 2^63) (a tie or near one) and [2^64 − B, 2^64) (the
// estimate may be q − 1) need the remainder (div_recip64_correct). f is in a band iff
// (f + B) mod 2^63 < B (B = 2^63 at W + qb = 63: always). At the defaults B = 2^56: 1 / 128 of
// uniform fractions take the remainder. Contract: as div_sig_recip64_w (returns exactly its
// result; tests/model/div_test.cpp DivRecip64Frac.*: every operand pair of six 12-bit shapes,
// 10^7 random + ties, the bands' edges; 10^8 in div_slow_test.cpp).
inline bool div_recip64_frac_decides(uint64_t f, uint64_t band) {
  return ((f + band) & (~uint64_t{0} >> 1)) >= band;
}
inline DivSig div_sig_recip64_frac_w(int w, int nb, int db, int qb, uint64_t n, uint64_t d, uint64_t R) {
  const uint64_t a = n << (w - nb), b = d << (w - db);
  const int k = a < b ? 1 : 0;
  const uint64_t num = (a << k) << (qb - 1);  // exact: < 2^(W+qb) ≤ 2^63
  const u128 p = (u128)num * R;
  const uint64_t q0 = (uint64_t)(p >> 64), f = (uint64_t)p;
  if (__builtin_expect(div_recip64_frac_decides(f, uint64_t{1} << (w + qb)), 1))
    return round_increment(q0, (f >> 63) != 0, qb, -k);
  return div_recip64_correct(q0, num, b, qb, k);
}
inline DivSig div_sig_recip64(const DivConfig& c, uint64_t n, uint64_t d, uint64_t R) {
  if (d == 0) return {(uint64_t{1} << c.quot_bits) - 1, 0};  // saturated (div_sig contract)
  if (n == 0) return {0, 0};
  return div_sig_recip64_w(div_align_bits(c), c.num_bits, c.den_bits, c.quot_bits, n, d, R);
}

// shared_recip, the per-pixel half: Y, the reciprocal core's approximation of 1/bn at
//   nr_frac_bits fraction bits (y = Y·2^−F), bn = b·2^−(W−1) ∈ [1, 2) the aligned divisor
//   b = d·2^(W−db). d must be a den_bits significand with its msb set (else invalid_argument).
uint64_t div_recip(const DivConfig& c, uint64_t d);
// shared_recip, the per-varying half: with k = [a < b], a' = a·2^k (as every algorithm), the
//   exact product P = a'·y·2^(qb−1)/2^(W−1) rounded once (RNE) at the ulp of the exact
//   quotient's binade: q = RNE(P), then sig = q, exp_adj = −k; q = 2^qb renormalises
//   (sig = 2^(qb−1), exp_adj + 1). Clamps (reached only when the reciprocal is off by more than
//   the bound allows, e.g. nr_steps 0): q < 2^(qb−1) → 2^(qb−1); q > 2^qb → 2^qb. Special
//   operands as div_sig (d == 0: saturated; n == 0: zero). y = div_recip(c, d).
DivSig div_mul_round(const DivConfig& c, uint64_t n, uint64_t d, uint64_t y);
// The two halves for one pair (what div_sig calls for shared_recip).
DivSig div_sig_shared_recip(const DivConfig& c, uint64_t n, uint64_t d);

// A-priori error bound of the configuration (docs/arith.md "shared_recip"), doubles with an
// upward nudge (a report-side bound, not the datapath):
//   recip_rel_err: bound on the reciprocal's relative error δ = 1 − bn·y (seed error S from
//     recip_core_seed_error, then per NR step e ← e² + (1 + e)·2^−F + 2·2^−F; one-sided,
//     0 ≤ δ, after ≥ 1 step; two-sided |δ| ≤ S (+ 2·2^−F if the seed is truncated) at 0 steps);
//   error_bound_ulp: max |result − exact| in ulps of the exact quotient's binade:
//     radix2 0.5; recip_mul 0.5 when 2^qb·δ < 1 (the ±1 correction suffices), else +inf (no
//     bound claimed); shared_recip 0.5 + 2^qb·δ (the result is also never more than ½ ulp
//     above the exact quotient after ≥ 1 NR step).
struct DivBound {
  double seed_rel_err = 0;
  double recip_rel_err = 0;
  double error_bound_ulp = 0;
};
DivBound div_bound(const DivConfig& c);

// The reciprocal core of recip_mul and shared_recip: x_bits = div_align_bits, seed_frac_bits = seed_bits.
RecipCoreShape div_recip_core_shape(const DivConfig& c);

// Seed table for recip_mul: the reciprocal core's minimax table (recip_core_seed_table),
// 2^seed_index_bits entries of seed_bits bits after the implied leading one.
std::vector<uint32_t> div_seed_table(const DivConfig& c);

struct DivResult {
  FxFloat value;
  bool div_by_zero = false;
};

// Contract: num / den of two exact FxFloats, result with a quot_bits significand (msb set) and
//   the sign num.neg XOR den.neg.
//   Operands are normalised to num_bits / den_bits significands first; an operand with more
//   significant bits than that is rounded to nearest even there (a first rounding: the result
//   is then within 0.5 ulp + 2^(qb−nb) ulp (resp. 2^(qb−db)) of the exact quotient instead of
//   correctly rounded). Narrower operands are widened exactly.
//   Zero numerator, nonzero den → value 0 (sign kept). Zero den → div_by_zero = true and the
//   value saturated to the all-ones significand at the numerator's binade:
//   ±(2^qb − 1)·2^(lead_exp(num) − (qb − 1)), or 0 when num is zero too.
DivResult divide(const DivConfig& c, const FxFloat& num, const FxFloat& den);

// Cost model of the RTL (rtl/fxr_div.sv) for this configuration in the one StageCost shape
// (model/unit/stage.hpp); the latency formula is the one the RTL implements (docs/arith.md
// "# Divider").
StageCost div_cost(const DivConfig& c);
inline StageCost cost(const DivConfig& c) { return div_cost(c); }  // the uniform name

}  // namespace fxr

// Stage 9: the per-pixel significand divider (model/arith/div.hpp has the contracts).
#include "model/arith/div.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "model/arith/recip_core.hpp"
#include "model/arith/round.hpp"

namespace fxr {

namespace {

inline u128 pow2(int e) { return ((u128)1) << e; }

// Operands after the exact alignment every algorithm starts with:
//   a = n·2^(W−nb), b = d·2^(W−db) ∈ [2^(W−1), 2^W) (W = div_align_bits; no bits lost);
//   k = 1 when a < b (then a' = 2a, exp_adj = −1), else 0 (a' = a); a' ∈ [b, 2b).
// Then X = a'·2^(qb−1) / b ∈ [2^(qb−1), 2^qb) is the exact quotient significand.
struct Aligned {
  uint64_t a = 0, b = 0;
  u128 a1 = 0;  // a' = a << k, W + 1 bits
  int k = 0;
};

[[noreturn]] void bad_operand(const char* which, uint64_t v, int bits) {
  throw std::invalid_argument(std::string("div_sig: ") + which + " = " + std::to_string(v) +
                              " is not a " + std::to_string(bits) + "-bit significand with its msb set");
}

inline void check_operands(const DivConfig& c, uint64_t n, uint64_t d) {
  if ((n >> (c.num_bits - 1)) != 1) bad_operand("n", n, c.num_bits);
  if ((d >> (c.den_bits - 1)) != 1) bad_operand("d", d, c.den_bits);
}

inline Aligned align(const DivConfig& c, uint64_t n, uint64_t d) {
  const int w = div_align_bits(c);
  Aligned x;
  x.a = n << (w - c.num_bits);
  x.b = d << (w - c.den_bits);
  x.k = x.a < x.b ? 1 : 0;
  x.a1 = (u128)x.a << x.k;
  return x;
}

// Special operands shared by every algorithm (see the div_sig contract): true if handled.
inline bool special(const DivConfig& c, uint64_t n, uint64_t d, DivSig* out) {
  if (d == 0) {
    *out = {(uint64_t)(pow2(c.quot_bits) - 1), 0};  // saturated; divide() flags div_by_zero
    return true;
  }
  if (n == 0) {
    *out = {0, 0};
    return true;
  }
  check_operands(c, n, d);
  return false;
}

// Round to nearest even from a truncated quotient q = floor(X) and its exact remainder
// r ∈ [0, b) (model/arith/round.hpp): the unit's only rounding. A carry out of qb bits
// renormalises (sig = 2^(qb−1), exp_adj + 1).
inline DivSig round_rne(const DivConfig& c, u128 q, u128 r, uint64_t b, int k) {
  return round_increment((uint64_t)q, rne_round_up<u128>(q, r, b), c.quot_bits, -k);
}

}  // namespace

// ---- exact (fast) model ----------------------------------------------------------------------

DivSig div_sig_exact(const DivConfig& c, uint64_t n, uint64_t d) {
  DivSig s;
  if (special(c, n, d, &s)) return s;
  const Aligned x = align(c, n, d);
  // X·b = a'·2^(qb−1): at most W + 1 + qb − 1 ≤ 120 bits. One exact division, no loss.
  const u128 num = x.a1 << (c.quot_bits - 1);
  u128 q, r;
  if ((num >> 64) == 0) {  // default widths: 32 + 24 = 56 bits, a 64-bit division suffices
    const uint64_t n64 = (uint64_t)num;
    q = n64 / x.b;
    r = n64 % x.b;
  } else {
    q = num / x.b;
    r = num % x.b;
  }
  return round_rne(c, q, r, x.b, x.k);
}

// ---- radix-2 non-restoring recurrence --------------------------------------------------------

DivSig div_sig_radix2_steps(const DivConfig& c, uint64_t n, uint64_t d) {
  DivSig s;
  if (special(c, n, d, &s)) return s;
  const Aligned x = align(c, n, d);
  // int64_t suffices: |2r ± b| < 3·2^W ≤ 3·2^60 (W = div_align_bits ≤ 60 by the ranges).
  const int64_t b = (int64_t)x.b;
  // Digit 0 is always +1 because a' ≥ b: r_0 = a' − b ∈ [0, b). Invariant after step i:
  //   a'·2^i = Q_i·b + r_i with r_i ∈ [−b, b) (div_rem_bits bits, signed), digits ∈ {−1, +1}.
  int64_t r = (int64_t)x.a1 - b;
  uint64_t p = 1;  // digit bits p_i = (digit_i == +1), msb first
  for (int i = 0; i < div_radix2_steps(c); ++i) {
    // r ≥ 0: r = 2r − b, digit +1;  r < 0: r = 2r + b, digit −1. Written without a branch
    // (the digit is data-dependent, a branch would mispredict half the time): pos is all
    // ones when r ≥ 0, and (b ^ pos) − pos is then −b, else b.
    const int64_t pos = ~(r >> 63);
    r = 2 * r + ((b ^ pos) - pos);
    p = (p << 1) | (uint64_t)(pos & 1);
  }
  // Signed-digit to binary: Q = Σ (2p_i − 1)·2^(qb−1−i) = 2P + 1 − 2^qb (an inverted top bit).
  int64_t q = (int64_t)((p << 1) | 1) - (int64_t)pow2(c.quot_bits);  // qb ≤ 60: fits
  // Final correction of a negative remainder: Q − 1, r + b. Now Q = floor(X), r ∈ [0, b) exact.
  if (r < 0) {
    q -= 1;
    r += b;
  }
  return round_rne(c, (u128)q, (u128)r, x.b, x.k);
}

// ---- reciprocal, multiply, remainder correction ---------------------------------------------

RecipCoreShape div_recip_core_shape(const DivConfig& c) {
  RecipCoreShape s;
  s.x_bits = div_align_bits(c);
  s.seed_index_bits = c.seed_index_bits;
  s.seed_frac_bits = c.seed_bits;
  s.nr_steps = c.nr_steps;
  s.nr_frac_bits = c.nr_frac_bits;
  return s;
}

std::vector<uint32_t> div_seed_table(const DivConfig& c) {
  const std::vector<uint64_t> t = recip_core_seed_table(c.seed_index_bits, c.seed_bits);
  return std::vector<uint32_t>(t.begin(), t.end());  // seed_bits ≤ 20 (parameter range)
}

namespace {

// The reciprocal core of the last shape per thread: built once per shape, read-only then.
const RecipCore& core_cached(const DivConfig& c) {
  thread_local std::unique_ptr<RecipCore> core;
  const RecipCoreShape s = div_recip_core_shape(c);
  if (!core || core->shape() != s) core = std::make_unique<RecipCore>(s);
  return *core;
}

}  // namespace

DivSig div_sig_recip_mul(const DivConfig& c, uint64_t n, uint64_t d) {
  DivSig s;
  if (special(c, n, d, &s)) return s;
  const Aligned x = align(c, n, d);
  const int w = div_align_bits(c), qb = c.quot_bits, f = c.nr_frac_bits;
  // y ≈ 1/bn at f fraction bits, bn = b·2^−(W−1) ∈ [1, 2): the reciprocal core (seed table,
  // one-sided Newton–Raphson; precision lost at its truncations), 0 ≤ 1/bn − y.
  const u128 y = core_cached(c).approx(x.b);
  // Truncated quotient q̃ ≈ X = a'·y·2^(qb−1) / 2^(W−1+f) (precision lost: the low product bits).
  const int qshift = w + f - qb;
  const u128 prod = x.a1 * y;
  i128 q = qshift >= 0 ? (i128)(prod >> qshift) : (i128)(prod << -qshift);
  // Back-multiply remainder r = a'·2^(qb−1) − q̃·b (exact), one correction step either way.
  const i128 bb = (i128)x.b;
  i128 r = (i128)(x.a1 << (qb - 1)) - q * bb;
  if (r < 0) {
    q -= 1;
    r += bb;
  } else if (r >= bb) {
    q += 1;
    r -= bb;
  }
  // If the approximation was more than one ulp off (inaccurate configurations only), r is
  // still outside [0, b): clamp it so the rounding below stays defined. Not correctly rounded
  // then; the measurement (analysis/measure.hpp) reports by how much.
  if (r < 0) r = 0;
  if (r >= bb) r = bb - 1;
  // Clamp q̃ into the significand range for the same configurations (exact ones never clamp).
  const i128 lo = (i128)pow2(qb - 1), hi = (i128)pow2(qb) - 1;
  if (q < lo) q = lo;
  if (q > hi) q = hi;
  return round_rne(c, (u128)q, (u128)r, x.b, x.k);
}

// ---- shared reciprocal, one multiply, one rounding ------------------------------------------

uint64_t div_recip(const DivConfig& c, uint64_t d) {
  if (d == 0 || (d >> (c.den_bits - 1)) != 1) bad_operand("d", d, c.den_bits);
  const uint64_t b = d << (div_align_bits(c) - c.den_bits);  // exact
  // PRECISION LOST inside the core (its truncations): 0 ≤ 1/bn − y after ≥ 1 NR step.
  return core_cached(c).approx(b);
}

DivSig div_mul_round(const DivConfig& c, uint64_t n, uint64_t d, uint64_t y) {
  DivSig s;
  if (special(c, n, d, &s)) return s;
  const Aligned x = align(c, n, d);
  const int qb = c.quot_bits;
  // P = a'·y·2^(qb−1)/2^(W−1) = prod·2^−qshift: the exact product, rounded once below.
  const int qshift = div_align_bits(c) + c.nr_frac_bits - qb;
  const u128 prod = x.a1 * (u128)y;  // ≤ (W+1) + F ≤ 121 bits
  u128 q;
  bool up = false;
  if (qshift > 0) {
    // PRECISION LOST: the qshift low product bits, by the one RNE of the unit.
    q = prod >> qshift;
    up = rne_round_up<u128>(q, prod & ((((u128)1) << qshift) - 1), ((u128)1) << qshift);
  } else {
    q = prod << -qshift;  // exact
  }
  q += up ? 1 : 0;
  // Clamps into [2^(qb−1), 2^qb]: only an inaccurate reciprocal reaches them (div_bound).
  const u128 lo = pow2(qb - 1), hi = pow2(qb);
  if (q < lo) q = lo;
  if (q > hi) q = hi;
  if (q == hi) return {(uint64_t)lo, 1 - x.k};  // 2^qb: renormalised
  return {(uint64_t)q, -x.k};
}

DivSig div_sig_shared_recip(const DivConfig& c, uint64_t n, uint64_t d) {
  DivSig s;
  if (special(c, n, d, &s)) return s;
  return div_mul_round(c, n, d, div_recip(c, d));
}

DivBound div_bound(const DivConfig& c) {
  DivBound r;
  const std::vector<uint64_t> table = recip_core_seed_table(c.seed_index_bits, c.seed_bits);
  const SeedError se = recip_core_seed_error(c.seed_index_bits, c.seed_bits, table);
  r.seed_rel_err = std::ldexp((double)se.num, -se.log2_den);
  // δ = 1 − bn·y. One step (docs/arith.md, reciprocal unit): e' = e² + (1 − e)·δt + bn·δy with
  // 0 < δt ≤ 2^−F, 0 ≤ δy < 2^−F, bn < 2, so 0 ≤ e' ≤ e² + (1 + |e|)·2^−F + 2·2^−F.
  const double ulp_f = std::ldexp(1.0, -c.nr_frac_bits);
  double e = r.seed_rel_err;
  if (c.nr_steps == 0) {
    if (c.seed_bits + 1 > c.nr_frac_bits) e += 2 * ulp_f;  // y0 truncated to F bits: < 2^−F·bn
  } else {
    for (int step = 0; step < c.nr_steps; ++step) e = e * e + (1 + e) * ulp_f + 2 * ulp_f;
  }
  r.recip_rel_err = e * (1 + 1e-9);
  // X·δ < 2^qb·δ ulps between the exact quotient X and the product before its rounding.
  const double spread = std::ldexp(r.recip_rel_err, c.quot_bits);
  switch (c.algorithm) {
    case DivAlgorithm::Radix2:
      r.error_bound_ulp = 0.5;
      break;
    case DivAlgorithm::RecipMul:
      r.error_bound_ulp = spread < 1 ? 0.5 : std::numeric_limits<double>::infinity();
      break;
    case DivAlgorithm::SharedRecip:
      r.error_bound_ulp = 0.5 + spread;
      break;
  }
  return r;
}

// ---- dispatch --------------------------------------------------------------------------------

DivSig div_sig(const DivConfig& c, uint64_t n, uint64_t d) {
  switch (c.algorithm) {
    case DivAlgorithm::Radix2:
      // Correctly rounded by construction (exact remainder): the exact division is the same
      // function (DivSig.ExactIsBitIdenticalToRadix2Steps*) and several times faster.
      return div_sig_exact(c, n, d);
    case DivAlgorithm::RecipMul:
      return div_sig_recip_mul(c, n, d);
    case DivAlgorithm::SharedRecip:
      return div_sig_shared_recip(c, n, d);
  }
  return div_sig_exact(c, n, d);
}

// ---- FxFloat division ------------------------------------------------------------------------

DivResult divide(const DivConfig& c, const FxFloat& num, const FxFloat& den) {
  DivResult res;
  res.value.neg = num.neg != den.neg;
  const int qb = c.quot_bits;
  if (den.is_zero()) {
    res.div_by_zero = true;
    if (!num.is_zero()) {
      res.value.sig = (uint64_t)(pow2(qb) - 1);  // saturated at the numerator's binade
      res.value.exp = num.lead_exp() - (qb - 1);
    }
    return res;
  }
  if (num.is_zero()) return res;
  // Precision lost (only for operands wider than num_bits / den_bits): RNE to the width.
  const FxFloat nn = normalize_fx(num, c.num_bits, Round::HalfEven);
  const FxFloat dn = normalize_fx(den, c.den_bits, Round::HalfEven);
  const DivSig s = div_sig(c, nn.sig, dn.sig);
  res.value.sig = s.sig;
  res.value.exp = nn.lead_exp() - dn.lead_exp() + s.exp_adj - (qb - 1);
  return res;
}

// ---- cost ------------------------------------------------------------------------------------

StageCost div_cost(const DivConfig& c) {
  StageCost k;
  const int w = div_align_bits(c), qb = c.quot_bits, rb = div_rem_bits(c);
  if (c.algorithm == DivAlgorithm::Radix2) {
    const int steps = div_radix2_steps(c);
    const int stages = (steps + c.bits_per_stage - 1) / c.bits_per_stage;  // recurrence cycles
    // Registers: pre stage (align, compare, digit 0) → `stages` recurrence registers →
    // post stage (correction, signed-digit conversion, RNE, renormalise) into the output.
    k.latency = 1 + stages + 1;
    const bool iter = c.schedule == DivSchedule::Iterative;
    // Iterative: one working register runs the recurrence; it takes a new operand the cycle
    // the post stage consumes the previous one.
    k.ii = iter ? stages + 1 : 1;
    const int step_adders = iter ? c.bits_per_stage : steps;
    k.adder_bits = rb                      // pre: a − b (its sign is k)
                         + rb                    // pre: 2a − b, in parallel
                         + step_adders * rb      // recurrence add/sub
                         + (rb + 1)              // post: t = 2r ∓ b, the RNE decision
                         + (qb + 1);             // post: increment
    // Register sets: r, b, the digit bits P (1 + steps so far, at most qb), k / dbz / nz / valid.
    // Pipelined: sets 0 (pre) .. stages; iterative: one set plus busy and the cycle counter.
    const int out_ff = qb + 2 + 1 + 1;  // sig, exp_adj, dbz, valid
    if (iter) {
      int cnt_bits = 0;
      while ((1 << cnt_bits) < stages + 1) ++cnt_bits;
      k.ff_bits = rb + w + qb + 4 + 1 + cnt_bits + out_ff;
    } else {
      k.ff_bits = out_ff;
      for (int st = 0; st <= stages; ++st)
        k.ff_bits += rb + w + std::min(qb, 1 + st * c.bits_per_stage) + 4;
    }
  } else if (c.algorithm == DivAlgorithm::SharedRecip) {
    const int f = c.nr_frac_bits;
    // pre (align, compare, seed ROM) → 2 per NR step → a'·y into q and its rounding flags →
    // RNE, clamps, renormalise into the output (rtl/fxr_div_shared_recip.sv).
    k.latency = 1 + 2 * c.nr_steps + 1 + 1;
    k.ii = 1;
    k.table_bits = (int64_t(1) << c.seed_index_bits) * c.seed_bits;
    k.multipliers = recip_core_multipliers(div_recip_core_shape(c));
    k.multipliers.push_back({w + 1, f});  // a'·y, exact
    k.adder_bits = (w + 1)                // compare a < b
                   + (qb + 2)             // increment
                   + 2 * (qb + 2);        // the two clamp comparisons
    const int stage_ff = (w + 1) + w + f + 2;  // a', b, y, flags
    k.ff_bits = (k.latency - 1) * stage_ff + (qb + 2 + 1 + 1);
  } else {
    const int f = c.nr_frac_bits;
    // pre (align, compare, seed ROM) → 2 per NR step (b·y → t, y·t → y) → quotient multiply →
    // back-multiply and correction → RNE, renormalise into the output.
    k.latency = 1 + 2 * c.nr_steps + 1 + 1 + 1;
    k.ii = 1;
    k.table_bits = (int64_t(1) << c.seed_index_bits) * c.seed_bits;
    // The reciprocal core's multipliers (per NR step b·y and y·t: no adder, t is a ones'
    // complement), then the quotient and the back-multiply.
    k.multipliers = recip_core_multipliers(div_recip_core_shape(c));
    k.multipliers.push_back({w + 1, f});      // q̃ = a'·y (y < 1: f bits)
    k.multipliers.push_back({qb + 1, w});     // q̃·b
    k.adder_bits = (w + 1)                       // compare a < b
                   + (w + qb + 1)                // r = a'·2^(qb−1) − q̃·b
                   + 2 * rb                      // r + b, r − b
                   + 2 * (qb + 1)                // q̃ ± 1
                   + rb                          // 2r − b
                   + (qb + 1);                   // increment
    const int stage_ff = (w + 1) + w + f + 2;   // a', b, y, flags
    k.ff_bits = (k.latency - 1) * stage_ff + (qb + 2 + 1 + 1);
  }
  for (const auto& m : k.multipliers) k.mult_bits += (int64_t)m.first * m.second;
  return k;
}

}  // namespace fxr

// Stage 9: the per-pixel significand divider (model/arith/div.hpp has the contracts).
#include "model/arith/div.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

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
// r ∈ [0, b): up when 2r > b, or 2r == b and q is odd. This is the unit's only rounding.
// A carry out of qb bits renormalises (sig = 2^(qb−1), exp_adj + 1).
// Ties-to-even increment of a floor quotient q with remainder r ∈ [0, den): 2r > den, or a
// tie with q odd. Shared by the quotient rounding and the seed-table generator.
inline bool rne_up(u128 q, u128 r, u128 den) {
  const u128 two_r = r << 1;
  return two_r > den || (two_r == den && (q & 1));
}

inline DivSig round_rne(const DivConfig& c, u128 q, u128 r, uint64_t b, int k) {
  if (rne_up(q, r, b)) ++q;
  DivSig s{(uint64_t)q, -k};
  if (q == pow2(c.quot_bits)) s = {(uint64_t)pow2(c.quot_bits - 1), 1 - k};
  return s;
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

std::vector<uint32_t> div_seed_table(const DivConfig& c) {
  const int si = c.seed_index_bits, sb = c.seed_bits;
  std::vector<uint32_t> t(size_t(1) << si);
  for (uint64_t i = 0; i < t.size(); ++i) {
    // 1 / (1 + (i + ½)·2^−si) = 2^(si+1) / (2^(si+1) + 2i + 1); scaled by 2^(sb+1), RNE.
    const u128 num = pow2(sb + 1 + si + 1);
    const u128 den = pow2(si + 1) + 2 * i + 1;
    u128 q = num / den;
    const u128 r = num % den;
    if (rne_up(q, r, den)) ++q;
    u128 e = q - pow2(sb);                          // drop the implicit leading one
    if (e >= pow2(sb)) e = pow2(sb) - 1;            // i = 0 may round up to exactly 1.0: clamp
    t[i] = (uint32_t)e;
  }
  return t;
}

namespace {

// Seed table cache keyed by (seed_index_bits, seed_bits): built once per shape, read-only then.
const std::vector<uint32_t>& seed_table_cached(const DivConfig& c) {
  thread_local int cached_si = -1, cached_sb = -1;
  thread_local std::vector<uint32_t> table;
  if (cached_si != c.seed_index_bits || cached_sb != c.seed_bits) {
    table = div_seed_table(c);
    cached_si = c.seed_index_bits;
    cached_sb = c.seed_bits;
  }
  return table;
}

}  // namespace

DivSig div_sig_recip_mul(const DivConfig& c, uint64_t n, uint64_t d) {
  DivSig s;
  if (special(c, n, d, &s)) return s;
  const Aligned x = align(c, n, d);
  const int w = div_align_bits(c), qb = c.quot_bits, f = c.nr_frac_bits;
  const int si = c.seed_index_bits, sb = c.seed_bits;
  // Seed index: the si divisor bits after its leading one (zero-extended if W − 1 < si).
  const int frac_b = w - 1;  // b = bn·2^(W−1), bn ∈ [1, 2)
  const uint64_t idx = frac_b >= si ? (x.b >> (frac_b - si)) & (uint64_t)(pow2(si) - 1)
                                    : (x.b << (si - frac_b)) & (uint64_t)(pow2(si) - 1);
  const u128 seed = pow2(sb) + seed_table_cached(c)[idx];  // y0 = seed·2^−(sb+1) ∈ (½, 1]
  // Iterate Y = y·2^f. Precision lost: a seed wider than f + 1 bits is truncated here.
  u128 y = f >= sb + 1 ? seed << (f - sb - 1) : seed >> (sb + 1 - f);
  for (int i = 0; i < c.nr_steps; ++i) {
    // t = bn·y, truncated to f fraction bits (precision lost: the W − 1 low product bits).
    const u128 t = ((u128)x.b * y) >> frac_b;
    // e = 2 − t ≥ 0 because y ≤ 1 + 2^−f and bn < 2 keep t < 2 (f fraction bits, exact).
    const u128 e = pow2(f + 1) - t;
    // y ← y·e, truncated to f fraction bits (precision lost: f low product bits).
    y = (y * e) >> f;
  }
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
  // then; div_measure reports by how much.
  if (r < 0) r = 0;
  if (r >= bb) r = bb - 1;
  // Clamp q̃ into the significand range for the same configurations (exact ones never clamp).
  const i128 lo = (i128)pow2(qb - 1), hi = (i128)pow2(qb) - 1;
  if (q < lo) q = lo;
  if (q > hi) q = hi;
  return round_rne(c, (u128)q, (u128)r, x.b, x.k);
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

DivCost div_cost(const DivConfig& c) {
  DivCost k;
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
    k.adder_bits_total = rb                      // pre: a − b (its sign is k)
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
  } else {
    const int f = c.nr_frac_bits;
    // pre (align, compare, seed ROM) → 2 per NR step (b·y, y·e) → quotient multiply →
    // back-multiply and correction → RNE, renormalise into the output.
    k.latency = 1 + 2 * c.nr_steps + 1 + 1 + 1;
    k.ii = 1;
    k.table_bits = (int64_t(1) << c.seed_index_bits) * c.seed_bits;
    for (int i = 0; i < c.nr_steps; ++i) {
      k.multipliers.push_back({w, f + 2});
      k.multipliers.push_back({f + 2, f + 2});
    }
    k.multipliers.push_back({w + 1, f + 2});  // q̃ = a'·y
    k.multipliers.push_back({qb + 1, w});     // q̃·b
    k.adder_bits_total = (w + 1)                       // compare a < b
                         + c.nr_steps * (f + 2)        // e = 2 − t
                         + (w + qb + 1)                // r = a'·2^(qb−1) − q̃·b
                         + 2 * rb                      // r + b, r − b
                         + 2 * (qb + 1)                // q̃ ± 1
                         + rb                          // 2r − b
                         + (qb + 1);                   // increment
    const int stage_ff = (w + 1) + w + (f + 2) + 2;   // a', b, y, flags
    k.ff_bits = (k.latency - 1) * stage_ff + (qb + 2 + 1 + 1);
  }
  for (const auto& m : k.multipliers) k.mult_cells += (int64_t)m.first * m.second;
  return k;
}

// ---- error measurement -----------------------------------------------------------------------

namespace {

struct Accum {
  double max = 0, sum = 0, sum2 = 0;
  uint64_t count = 0, correct = 0;
};

// Exact error of s against a / b (aligned operands) in ulps of the exact quotient's binade:
//   |sig·2^exp_adj·2^−(qb−1) − a/b| / 2^(−k−(qb−1)) = |sig·2^(exp_adj+k)·b − a·2^(qb−1+k)| / b.
double err_ulp(const DivConfig& c, const DivSig& s, uint64_t n, uint64_t d) {
  const Aligned x = align(c, n, d);
  const int sh = s.exp_adj + x.k;  // ∈ {0, 1} by the div_sig contract
  const u128 got = ((u128)s.sig * x.b) << (sh < 0 ? 0 : sh);
  const u128 want = (u128)x.a << (c.quot_bits - 1 + x.k);
  const u128 diff = got > want ? got - want : want - got;
  return (double)diff / (double)x.b;  // double only for the statistic
}

void account(const DivConfig& c, uint64_t n, uint64_t d, Accum& acc) {
  const DivSig got = div_sig(c, n, d);
  const double e = err_ulp(c, got, n, d);
  acc.max = std::max(acc.max, e);
  acc.sum += e;
  acc.sum2 += e * e;
  acc.count++;
  acc.correct += got == div_sig_exact(c, n, d);
}

}  // namespace

DivErrorStats div_measure(const DivConfig& c, uint64_t count, uint64_t seed) {
  Accum acc;
  const int nb = c.num_bits, db = c.den_bits, qb = c.quot_bits, w = div_align_bits(c);
  const uint64_t nlo = (uint64_t)pow2(nb - 1), nhi = (uint64_t)pow2(nb) - 1;
  const uint64_t dlo = (uint64_t)pow2(db - 1), dhi = (uint64_t)pow2(db) - 1;
  std::mt19937_64 rng(seed);
  auto rand_in = [&](uint64_t lo, uint64_t hi) { return lo + rng() % (hi - lo + 1); };
  // Directed: range ends.
  for (uint64_t n : {nlo, nlo + 1, nhi - 1, nhi})
    for (uint64_t d : {dlo, dlo + 1, dhi - 1, dhi}) account(c, n, d, acc);
  // Directed: n equal (after alignment) to d and its neighbours; divisors on seed-interval edges.
  for (int i = 0; i < 256; ++i) {
    const uint64_t d = rand_in(dlo, dhi);
    const uint64_t a = (nb >= db) ? d << (nb - db) : d >> (db - nb);
    for (int64_t delta : {-1, 0, 1}) {
      const uint64_t n = a + delta;
      if (n >= nlo && n <= nhi) account(c, n, d, acc);
    }
    const int si = c.seed_index_bits < db - 1 ? c.seed_index_bits : db - 1;
    const uint64_t edge = dlo + (rand_in(0, (uint64_t)pow2(si) - 1) << (db - 1 - si));
    for (int64_t delta : {-1, 0, 1}) {
      const uint64_t dd = edge + delta;
      if (dd >= dlo && dd <= dhi) account(c, rand_in(nlo, nhi), dd, acc);
    }
  }
  // Directed: exact rounding ties X = q + ½ and their neighbours n ± 1. a'·2^qb = (2q+1)·b
  // needs b = m·2^qb (possible when W − 1 ≥ qb); then a' = (2q+1)·m, a = a' (if < 2^W) or a'/2.
  if (w - 1 >= qb) {
    for (int i = 0, made = 0; i < 8000 && made < 2000; ++i) {
      const uint64_t m = rand_in((uint64_t)pow2(w - 1 - qb), (uint64_t)pow2(w - qb) - 1);
      const uint64_t b = m << qb;
      const uint64_t q = rand_in((uint64_t)pow2(qb - 1), (uint64_t)pow2(qb) - 1);
      const u128 a1 = (u128)(2 * q + 1) * m;
      if (a1 >= pow2(w) && (a1 & 1)) continue;  // k = 1 needs an even a'
      const uint64_t a = (uint64_t)(a1 >= pow2(w) ? a1 >> 1 : a1);
      if ((a & (uint64_t)(pow2(w - nb) - 1)) || (b & (uint64_t)(pow2(w - db) - 1))) continue;
      const uint64_t n = a >> (w - nb), d = b >> (w - db);
      for (int64_t delta : {-1, 0, 1}) {
        const uint64_t nn = n + delta;
        if (nn >= nlo && nn <= nhi) account(c, nn, d, acc);
      }
      ++made;
    }
  }
  for (uint64_t i = 0; i < count; ++i) {
    const uint64_t n = rand_in(nlo, nhi), d = rand_in(dlo, dhi);
    account(c, n, d, acc);
  }
  DivErrorStats st;
  st.count = acc.count;
  st.max_err_ulp = acc.max;
  st.mean_err_ulp = acc.sum / acc.count;
  st.rms_err_ulp = std::sqrt(acc.sum2 / acc.count);
  st.correctly_rounded_share = (double)acc.correct / acc.count;
  st.correctly_rounded = acc.correct == acc.count;
  return st;
}

// ---- sweep -----------------------------------------------------------------------------------

std::vector<DivConfig> div_sweep_configs() {
  std::vector<DivConfig> v;
  const DivConfig base;
  for (DivSchedule sch : {DivSchedule::Pipelined, DivSchedule::Iterative})
    for (int k : {1, 2, 4}) {
      DivConfig c = base;
      c.algorithm = DivAlgorithm::Radix2;
      c.schedule = sch;
      c.bits_per_stage = k;
      v.push_back(c);
    }
  // recip_mul: (seed index bits, seed bits, NR steps, iterate fraction bits), including the
  // ANCHORS table designs and ones too coarse for the ±1 correction.
  const int rm[][4] = {{5, 7, 2, 28},  {6, 8, 2, 28},  {8, 8, 2, 28},  {8, 8, 2, 26},
                       {8, 8, 2, 25},  {12, 14, 1, 28}, {13, 15, 1, 28}, {8, 8, 1, 28},
                       {10, 10, 1, 28}, {6, 8, 1, 28},  {4, 4, 2, 28},  {4, 4, 3, 28}};
  for (const auto& p : rm) {
    DivConfig c = base;
    c.algorithm = DivAlgorithm::RecipMul;
    c.seed_index_bits = p[0];
    c.seed_bits = p[1];
    c.nr_steps = p[2];
    c.nr_frac_bits = p[3];
    v.push_back(c);
  }
  return v;
}

std::string div_label(const DivConfig& c) {
  if (c.algorithm == DivAlgorithm::Radix2)
    return "radix2 k=" + std::to_string(c.bits_per_stage) +
           (c.schedule == DivSchedule::Iterative ? " iter" : " pipe");
  return "recip_mul " + std::to_string(1 << c.seed_index_bits) + "x" + std::to_string(c.seed_bits) +
         " nr" + std::to_string(c.nr_steps) + " f" + std::to_string(c.nr_frac_bits);
}

}  // namespace fxr

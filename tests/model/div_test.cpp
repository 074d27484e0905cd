// The per-pixel divider against exact integer division and GMP rationals.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>
#include <vector>

#include "model/config/config.hpp"
#include "analysis/measure.hpp"
#include "model/arith/div.hpp"
#include "tests/model/div_ties.hpp"

using namespace fxr;

namespace {

// Independent reference, written from the div_sig contract without the model's alignment:
//   R = (n·2^−(nb−1)) / (d·2^−(db−1)); e = 0 if R ≥ 1 else −1;
//   sig = RNE(R·2^(qb−1−e)) = RNE(n·2^(db+qb−2−e) / (d·2^(nb−1))), carry-out renormalised.
// Needs db + qb + nb ≤ 126 (exact in unsigned __int128).
DivSig ref_div(int nb, int db, int qb, uint64_t n, uint64_t d) {
  const bool ge1 = ((u128)n << db) >= ((u128)d << nb);
  const int e = ge1 ? 0 : -1;
  const u128 num = (u128)n << (db + qb - 2 - e);
  const u128 den = (u128)d << (nb - 1);
  u128 q = num / den;
  const u128 r = num - q * den;
  if (2 * r > den || (2 * r == den && (q & 1))) ++q;
  if (q == ((u128)1 << qb)) return {(uint64_t)1 << (qb - 1), e + 1};
  return {(uint64_t)q, e};
}

DivConfig shape(DivAlgorithm a, int nb, int db, int qb) {
  DivConfig c;
  c.algorithm = a;
  c.num_bits = nb;
  c.den_bits = db;
  c.quot_bits = qb;
  return c;
}

// A recip_mul configuration for 12-bit operands: 64×7 seed, 1 NR step, 16-bit iterate.
DivConfig recip_mul_12bit() {
  DivConfig c = shape(DivAlgorithm::RecipMul, 12, 12, 12);
  c.seed_index_bits = 6;
  c.seed_bits = 7;
  c.nr_steps = 1;
  c.nr_frac_bits = 16;
  return c;
}

DivConfig recip_mul_default() {
  DivConfig c;
  c.algorithm = DivAlgorithm::RecipMul;
  return c;
}

std::string show(const DivSig& s) { return std::to_string(s.sig) + "·2^" + std::to_string(s.exp_adj); }

template <class F>
void exhaustive(const DivConfig& c, F&& fn) {
  const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
  for (uint64_t n = nlo; n < 2 * nlo; ++n)
    for (uint64_t d = dlo; d < 2 * dlo; ++d) {
      const DivSig got = fn(c, n, d), want = ref_div(c.num_bits, c.den_bits, c.quot_bits, n, d);
      if (got != want) {
        FAIL() << "n=" << n << " d=" << d << " got " << show(got) << " want " << show(want);
        return;
      }
    }
}

// Random operands at the configured widths plus directed ties: for b = m·2^qb, a = (2q+1)·m
// the exact quotient is q + ½ (a tie); n ± 1 are its neighbours.
template <class F>
void random_and_ties(const DivConfig& c, uint64_t count, uint64_t seed, F&& check) {
  std::mt19937_64 rng(seed);
  const int nb = c.num_bits, db = c.den_bits, qb = c.quot_bits;
  const uint64_t nlo = 1ull << (nb - 1), dlo = 1ull << (db - 1);
  for (uint64_t i = 0; i < count; ++i) check(nlo + rng() % nlo, dlo + rng() % dlo);
  ASSERT_EQ(nb, db) << "tie construction below assumes equal operand widths";
  div_ties::for_each_tie(nb, db, qb, 100000, rng, check);
}

mpq_class mpq_pow2(long e) {
  mpq_class r(1);
  if (e >= 0) r.get_num() <<= e; else r.get_den() <<= -e;
  r.canonicalize();
  return r;
}

mpq_class value_of(const FxFloat& x) {
  mpq_class v(mpz_class((unsigned long)x.sig));
  v *= mpq_pow2(x.exp);
  return x.neg ? mpq_class(-v) : v;
}

// RNE of |q| > 0 to a `bits`-bit significand (GMP): returns sig and exponent.
FxFloat mpq_round(const mpq_class& q, int bits) {
  FxFloat r;
  r.neg = q < 0;
  mpq_class m = abs(q);
  long e = 0;  // find e with m·2^−e ∈ [2^(bits−1), 2^bits)
  while (m >= mpq_pow2(bits)) { m /= 2; ++e; }
  while (m < mpq_pow2(bits - 1)) { m *= 2; --e; }
  mpz_class fl = m.get_num() / m.get_den();
  const mpq_class frac = m - mpq_class(fl);
  const int c = cmp(frac, mpq_class(1, 2));
  if (c > 0 || (c == 0 && mpz_odd_p(fl.get_mpz_t()))) ++fl;
  if (fl == (mpz_class(1) << bits)) { fl >>= 1; ++e; }
  r.sig = fl.get_ui();
  r.exp = (int)e;
  return r;
}

}  // namespace

// ---- correct rounding, exhaustive at reduced widths ------------------------------------------

TEST(DivSig, Radix2StepsCorrectlyRoundedForAll12BitOperands) {
  exhaustive(shape(DivAlgorithm::Radix2, 12, 12, 12), div_sig_radix2_steps);
}

TEST(DivSig, Radix2StepsCorrectlyRoundedForAllOperandsOfUnequalWidths) {
  // Wider quotient than the operands, and operands of different widths in both orders.
  exhaustive(shape(DivAlgorithm::Radix2, 12, 9, 14), div_sig_radix2_steps);
  exhaustive(shape(DivAlgorithm::Radix2, 9, 12, 7), div_sig_radix2_steps);
}

TEST(DivSig, RecipMulCorrectlyRoundedForAll12BitOperands) {
  exhaustive(recip_mul_12bit(), div_sig_recip_mul);
}

TEST(DivSig, ExactIsBitIdenticalToRadix2StepsForAll12BitOperands) {
  for (const DivConfig& c : {shape(DivAlgorithm::Radix2, 12, 12, 12), shape(DivAlgorithm::Radix2, 12, 9, 14)}) {
    const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
    for (uint64_t n = nlo; n < 2 * nlo; ++n)
      for (uint64_t d = dlo; d < 2 * dlo; ++d)
        ASSERT_EQ(div_sig_exact(c, n, d), div_sig_radix2_steps(c, n, d)) << "n=" << n << " d=" << d;
  }
}

// ---- default widths: 10^7 random plus directed ties ------------------------------------------

TEST(DivSig, ExactIsBitIdenticalToRadix2StepsOnTenMillionAtDefaultWidths) {
  const DivConfig c;
  uint64_t mismatches = 0;
  random_and_ties(c, 10'000'000, 11, [&](uint64_t n, uint64_t d) {
    if (div_sig_exact(c, n, d) != div_sig_radix2_steps(c, n, d) && ++mismatches <= 5)
      ADD_FAILURE() << "n=" << n << " d=" << d;
  });
  EXPECT_EQ(mismatches, 0u);
}

TEST(DivSig, EveryAlgorithmCorrectlyRoundedOnTenMillionAtDefaultWidths) {
  DivConfig radix2;
  radix2.algorithm = DivAlgorithm::Radix2;
  for (const DivConfig& c : {radix2, recip_mul_default()}) {
    uint64_t mismatches = 0, checked = 0;
    random_and_ties(c, 10'000'000, 12, [&](uint64_t n, uint64_t d) {
      ++checked;
      const DivSig got = div_sig(c, n, d), want = ref_div(c.num_bits, c.den_bits, c.quot_bits, n, d);
      if (got != want && ++mismatches <= 5)
        ADD_FAILURE() << div_label(c) << " n=" << n << " d=" << d << " got " << show(got) << " want " << show(want);
    });
    EXPECT_EQ(mismatches, 0u) << div_label(c) << " checked=" << checked;
  }
}

TEST(DivSig, ReferenceAgreesWithGmpRationals) {
  // The integer reference above, checked against GMP on the contract's formula itself.
  std::mt19937_64 rng(13);
  const int nb = 32, db = 32, qb = 24;
  for (int i = 0; i < 20000; ++i) {
    const uint64_t n = (1ull << 31) | (rng() >> 33), d = (1ull << 31) | (rng() >> 33);
    const mpq_class ratio = mpq_class(mpz_class((unsigned long)n), mpz_class((unsigned long)d));
    const FxFloat r = mpq_round(ratio, qb);  // ratio ≈ r.sig·2^r.exp
    const DivSig s = ref_div(nb, db, qb, n, d);
    ASSERT_EQ(s.sig, r.sig) << n << "/" << d;
    ASSERT_EQ(s.exp_adj, r.exp + (qb - 1)) << n << "/" << d;
  }
}

TEST(DivSig, RoundingCarryOutRenormalises) {
  // n = 2^32 − 1, d = 2^31: R = 2 − 2^−31 rounds to 2.0 at 24 bits → sig 2^23, exp_adj +1.
  const DivConfig c;
  const uint64_t n = (1ull << 32) - 1, d = 1ull << 31;
  for (auto fn : {div_sig_exact, div_sig_radix2_steps, div_sig_recip_mul}) {
    const DivSig s = fn(c, n, d);
    EXPECT_EQ(s.sig, 1ull << 23);
    EXPECT_EQ(s.exp_adj, 1);
  }
}

// ---- special cases ----------------------------------------------------------------------------

TEST(DivSig, ZeroDivisorSaturatesAndZeroNumeratorGivesZero) {
  for (DivAlgorithm a : {DivAlgorithm::Radix2, DivAlgorithm::RecipMul}) {
    DivConfig c;
    c.algorithm = a;
    EXPECT_EQ(div_sig(c, 1ull << 31, 0), (DivSig{(1ull << 24) - 1, 0}));
    EXPECT_EQ(div_sig(c, 0, 0), (DivSig{(1ull << 24) - 1, 0}));
    EXPECT_EQ(div_sig(c, 0, 1ull << 31), (DivSig{0, 0}));
  }
}

TEST(DivSig, RejectsOperandsWithoutTheirMsbSet) {
  const DivConfig c;
  EXPECT_THROW(div_sig(c, 1ull << 30, 1ull << 31), std::invalid_argument);
  EXPECT_THROW(div_sig(c, 1ull << 31, 1ull << 32), std::invalid_argument);
  EXPECT_THROW(div_sig_radix2_steps(c, 3, 1ull << 31), std::invalid_argument);
}

TEST(Divide, MatchesGmpQuotientWithSignsAndExponents) {
  const DivConfig c;
  std::mt19937_64 rng(14);
  for (int i = 0; i < 30000; ++i) {
    FxFloat num, den;
    // float32-like significands (24 bits, exact at 32) and random exponents and signs.
    num.sig = (1ull << 23) | (rng() >> 41);
    den.sig = (rng() >> 40) | 1;  // also unnormalised (narrow) significands: widened exactly
    num.exp = (int)(rng() % 200) - 100;
    den.exp = (int)(rng() % 200) - 100;
    num.neg = rng() & 1;
    den.neg = rng() & 1;
    const DivResult r = divide(c, num, den);
    ASSERT_FALSE(r.div_by_zero);
    const FxFloat want = mpq_round(value_of(num) / value_of(den), c.quot_bits);
    ASSERT_EQ(r.value.neg, want.neg);
    ASSERT_EQ(r.value.sig, want.sig);
    ASSERT_EQ(r.value.exp, want.exp);
  }
}

TEST(Divide, WideOperandsAreRoundedToNearestEvenFirst) {
  // 40-bit operands: documented pre-rounding to 32 bits (RNE), then a correctly rounded divide.
  const DivConfig c;
  std::mt19937_64 rng(15);
  for (int i = 0; i < 20000; ++i) {
    FxFloat num, den;
    num.sig = (1ull << 39) | (rng() >> 25);
    den.sig = (1ull << 39) | (rng() >> 25);
    num.exp = -7;
    den.exp = 3;
    const FxFloat nr = mpq_round(value_of(num), c.num_bits), dr = mpq_round(value_of(den), c.den_bits);
    const FxFloat want = mpq_round(value_of(nr) / value_of(dr), c.quot_bits);
    const DivResult r = divide(c, num, den);
    ASSERT_EQ(r.value.sig, want.sig);
    ASSERT_EQ(r.value.exp, want.exp);
  }
}

TEST(Divide, ZeroCases) {
  const DivConfig c;
  FxFloat one{false, 1, 0}, zero{true, 0, 0}, three{false, 3, 5};
  DivResult r = divide(c, zero, one);
  EXPECT_FALSE(r.div_by_zero);
  EXPECT_TRUE(r.value.is_zero());
  EXPECT_TRUE(r.value.neg);  // sign kept: −0 / +1 = −0
  r = divide(c, three, zero);
  EXPECT_TRUE(r.div_by_zero);
  // Saturated at the numerator's binade: 3·2^5 = 96 ∈ [64, 128) → (2^24 − 1)·2^(6 − 23).
  EXPECT_EQ(r.value.sig, (1ull << 24) - 1);
  EXPECT_EQ(r.value.exp, 6 - 23);
  EXPECT_TRUE(r.value.neg);  // +3 / −0
  r = divide(c, FxFloat{}, FxFloat{});
  EXPECT_TRUE(r.div_by_zero);
  EXPECT_TRUE(r.value.is_zero());
}

// ---- seed table, measurement, configuration ----------------------------------------------------

TEST(DivSeedTable, EntriesAreRoundedMidpointReciprocals) {
  for (auto [si, sb] : {std::pair{8, 8}, std::pair{5, 7}, std::pair{12, 14}, std::pair{4, 6}}) {
    DivConfig c;
    c.seed_index_bits = si;
    c.seed_bits = sb;
    const auto t = div_seed_table(c);
    ASSERT_EQ(t.size(), size_t(1) << si);
    for (size_t i = 0; i < t.size(); ++i) {
      const mpq_class mid = 1 + mpq_class((long)(2 * i + 1), 2) * mpq_pow2(-si);
      mpq_class y = mpq_pow2(sb + 1) / mid;  // in (2^sb, 2^(sb+1))
      mpz_class fl = y.get_num() / y.get_den();
      const int cm = cmp(y - mpq_class(fl), mpq_class(1, 2));
      if (cm > 0 || (cm == 0 && mpz_odd_p(fl.get_mpz_t()))) ++fl;
      mpz_class e = fl - (mpz_class(1) << sb);
      if (e >= (mpz_class(1) << sb)) e = (mpz_class(1) << sb) - 1;  // documented clamp
      ASSERT_EQ(t[i], e.get_ui()) << "si=" << si << " sb=" << sb << " i=" << i;
    }
  }
}

TEST(DivMeasure, DefaultsAreCorrectlyRoundedAndCoarseSeedsAreNot) {
  DivConfig c;
  for (DivAlgorithm a : {DivAlgorithm::Radix2, DivAlgorithm::RecipMul}) {
    c.algorithm = a;
    const ErrorStats s = measure(c, MeasureOptions{false, 100000, 3});
    EXPECT_TRUE(s.correctly_rounded) << div_label(c);
    EXPECT_LE(s.max_err_ulp, 0.5) << div_label(c);
    EXPECT_GT(s.count, 100000u);
  }
  // 16×4 seed, one NR step: ≈ 2^−10 relative error, far beyond the ±1 ulp correction.
  c.algorithm = DivAlgorithm::RecipMul;
  c.seed_index_bits = 4;
  c.seed_bits = 4;
  c.nr_steps = 1;
  const ErrorStats s = measure(c, MeasureOptions{false, 100000, 3});
  EXPECT_FALSE(s.correctly_rounded);
  EXPECT_GT(s.max_err_ulp, 1.0);
}

TEST(DivConfig, EveryParameterIsListedOnceAndRoundTripsThroughJson) {
  DivConfig c;
  c.algorithm = DivAlgorithm::RecipMul;
  c.nr_steps = 3;
  c.schedule = DivSchedule::Iterative;
  const auto rows = param_rows(c);
  std::set<std::string> names;
  for (const auto& r : rows) EXPECT_TRUE(names.insert(r.name).second) << r.name;
  DivConfig d;
  from_json_params(to_json_params(c), d, "test");
  EXPECT_EQ(to_json_params(d), to_json_params(c));
  nlohmann::json bad = to_json_params(c);
  bad["quot_bits"] = 99;
  EXPECT_THROW(from_json_params(bad, d, "test"), ConfigError);
}

TEST(DivConfig, SweepConfigurationsAreValidAndMeasurable) {
  for (const DivConfig& c : div_sweep_configs()) {
    DivConfig d;
    from_json_params(to_json_params(c), d, div_label(c));  // within every range
    const StageCost k = div_cost(c);
    EXPECT_GE(k.latency, 2) << div_label(c);
    EXPECT_GE(k.ii, 1) << div_label(c);
    const ErrorStats s = measure(c, MeasureOptions{false, 2000, 4});
    EXPECT_LT(s.max_err_ulp, 1e6) << div_label(c);
  }
}

// ---- the inline 64-bit fast path (div_sig_fast64) against div_sig_exact and the reference ----

namespace {

// Shapes at the fast path's limit W + qb = 63 (W = div_align_bits), where the dividend uses
// every bit of uint64_t but the sign bit.
std::vector<DivConfig> fast64_edge_shapes() {
  return {shape(DivAlgorithm::Radix2, 39, 39, 24), shape(DivAlgorithm::Radix2, 32, 32, 31),
          shape(DivAlgorithm::Radix2, 20, 39, 24)};
}

// Every operand pair (n, d) of each shape (operands of at most 12 bits): a 64-bit fast path
// `fast(c, n, d)` against div_sig_exact and the independent reference ref_div; `seen(c, n, d)`
// after each pair, for the tests that count which way the path went. Stops at a shape's first
// mismatch.
template <class Fast, class Seen>
void expect_fast_path_on_every_operand_pair(const std::vector<DivConfig>& shapes, Fast fast, Seen seen) {
  for (const DivConfig& c : shapes) {
    ASSERT_TRUE(div_fast64_ok(c)) << div_label(c);
    const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
    for (uint64_t d = dlo; d < 2 * dlo; ++d)
      for (uint64_t n = nlo; n < 2 * nlo; ++n) {
        const DivSig f = fast(c, n, d);
        ASSERT_EQ(f, div_sig_exact(c, n, d)) << div_label(c) << " n=" << n << " d=" << d;
        ASSERT_EQ(f, ref_div(c.num_bits, c.den_bits, c.quot_bits, n, d)) << div_label(c) << " n=" << n << " d=" << d;
        seen(c, n, d);
      }
  }
}

}  // namespace

TEST(DivFast64, AppliesExactlyWhereTheDividendFits64Bits) {
  EXPECT_TRUE(div_fast64_ok(DivConfig{}));  // the default: 32 + 24 = 56
  for (const DivConfig& c : fast64_edge_shapes()) EXPECT_TRUE(div_fast64_ok(c)) << div_label(c);
  EXPECT_FALSE(div_fast64_ok(shape(DivAlgorithm::Radix2, 40, 40, 24)));  // 64: falls back
  EXPECT_FALSE(div_fast64_ok(shape(DivAlgorithm::Radix2, 60, 60, 60)));
  EXPECT_FALSE(div_fast64_ok(recip_mul_default()));  // other algorithms keep their own model
  DivConfig sr;
  sr.algorithm = DivAlgorithm::SharedRecip;
  EXPECT_FALSE(div_fast64_ok(sr));
}

TEST(DivFast64, BitIdenticalToExactForAll12BitOperands) {
  expect_fast_path_on_every_operand_pair(
      {shape(DivAlgorithm::Radix2, 12, 12, 12), shape(DivAlgorithm::Radix2, 12, 9, 14),
       shape(DivAlgorithm::Radix2, 9, 12, 10), shape(DivAlgorithm::Radix2, 11, 11, 4)},
      div_sig_fast64, [](const DivConfig&, uint64_t, uint64_t) {});
}

TEST(DivFast64, BitIdenticalOnTenMillionPlusTiesAtDefaultAndEdgeWidths) {
  std::vector<DivConfig> cs = {DivConfig{}};
  for (const DivConfig& c : fast64_edge_shapes())
    if (c.num_bits == c.den_bits) cs.push_back(c);
  for (const DivConfig& c : cs) {
    uint64_t mismatches = 0;
    random_and_ties(c, c.num_bits == 32 && c.quot_bits == 24 ? 10'000'000 : 1'000'000, 21,
                    [&](uint64_t n, uint64_t d) {
                      if (div_sig_fast64(c, n, d) != div_sig_exact(c, n, d) && ++mismatches <= 5)
                        ADD_FAILURE() << div_label(c) << " n=" << n << " d=" << d;
                    });
    EXPECT_EQ(mismatches, 0u) << div_label(c);
  }
}

// The directed hard cases of a 64-bit fast path `fast(c, n, d)`: largest and smallest quotients,
// equal operands, one-off neighbours, D at its extremes, the zero operands, at the edge shapes and
// the default; against div_sig_exact and the independent reference.
template <class Fast>
void expect_fast_path_on_hard_cases(Fast fast) {
  std::vector<DivConfig> cs = fast64_edge_shapes();
  cs.push_back(DivConfig{});
  for (const DivConfig& c : cs) {
    const uint64_t nlo = 1ull << (c.num_bits - 1), nhi = 2 * nlo - 1;
    const uint64_t dlo = 1ull << (c.den_bits - 1), dhi = 2 * dlo - 1;
    const uint64_t ns[] = {nlo, nlo + 1, nhi, nhi - 1, nlo | (nlo >> 1)};
    const uint64_t ds[] = {dlo, dlo + 1, dhi, dhi - 1, dlo | (dlo >> 1)};
    for (uint64_t n : ns)
      for (uint64_t d : ds) {
        EXPECT_EQ(fast(c, n, d), div_sig_exact(c, n, d)) << div_label(c) << " n=" << n << " d=" << d;
        EXPECT_EQ(fast(c, n, d), ref_div(c.num_bits, c.den_bits, c.quot_bits, n, d))
            << div_label(c) << " n=" << n << " d=" << d;
      }
    for (uint64_t d : ds) EXPECT_EQ(fast(c, 0, d), div_sig_exact(c, 0, d));
    for (uint64_t n : ns) EXPECT_EQ(fast(c, n, 0), div_sig_exact(c, n, 0));
  }
  // The rounding carry-out (RoundingCarryOutRenormalises): 2 − 2^−31 → 2^23·2^+1.
  const DivConfig c;
  EXPECT_EQ(fast(c, 0xFFFFFFFFull, 1ull << 31), (DivSig{1ull << 23, 1}));
}

TEST(DivFast64, DirectedHardCases) {
  expect_fast_path_on_hard_cases([](const DivConfig& c, uint64_t n, uint64_t d) { return div_sig_fast64(c, n, d); });
}

// ---- one reciprocal per pixel (div_sig_recip64, docs/speed.md "The fused span") -------------
// The quotient from the integer reciprocal R = floor((2^64 − 1)/b), the estimate floor(num·R/2^64)
// and one exact remainder correction, against div_sig_exact and the independent reference. The
// estimate is one below the quotient in a fraction of the cases (the correction): each test
// checks that both outcomes occurred.

namespace {

struct RecipOutcomes {
  uint64_t exact = 0, corrected = 0;
  // Counts whether the estimate for (n, d) needed the correction (from the definition: num / b).
  void count(const DivConfig& c, uint64_t n, uint64_t d) {
    const int w = div_align_bits(c);
    const uint64_t a = n << (w - c.num_bits), b = d << (w - c.den_bits);
    const uint64_t num = ((a < b ? a << 1 : a)) << (c.quot_bits - 1);
    const uint64_t est = div_recip64_estimate(num, div_recip64(c, d));
    if (est == num / b) ++exact;
    else if (est + 1 == num / b) ++corrected;
    else ADD_FAILURE() << "estimate off by more than one: n=" << n << " d=" << d;
  }
};

}  // namespace

TEST(DivRecip64, BitIdenticalToExactForAll12BitOperands) {
  RecipOutcomes o;
  expect_fast_path_on_every_operand_pair(
      {shape(DivAlgorithm::Radix2, 12, 12, 12), shape(DivAlgorithm::Radix2, 12, 9, 14),
       shape(DivAlgorithm::Radix2, 9, 12, 10), shape(DivAlgorithm::Radix2, 11, 11, 4),
       shape(DivAlgorithm::Radix2, 12, 12, 51)},  // 12 + 51 = 63: the limit
      [](const DivConfig& c, uint64_t n, uint64_t d) { return div_sig_recip64(c, n, d, div_recip64(c, d)); },
      [&](const DivConfig& c, uint64_t n, uint64_t d) { o.count(c, n, d); });
  EXPECT_GT(o.exact, 0u);
  EXPECT_GT(o.corrected, 0u);
}

TEST(DivRecip64, BitIdenticalOnTenMillionPlusTiesAtDefaultAndEdgeWidths) {
  std::vector<DivConfig> cs = {DivConfig{}};
  for (const DivConfig& c : fast64_edge_shapes())
    if (c.num_bits == c.den_bits) cs.push_back(c);
  for (const DivConfig& c : cs) {
    uint64_t mismatches = 0;
    RecipOutcomes o;
    random_and_ties(c, c.num_bits == 32 && c.quot_bits == 24 ? 10'000'000 : 1'000'000, 22,
                    [&](uint64_t n, uint64_t d) {
                      if (div_sig_recip64(c, n, d, div_recip64(c, d)) != div_sig_exact(c, n, d) && ++mismatches <= 5)
                        ADD_FAILURE() << div_label(c) << " n=" << n << " d=" << d;
                      if ((n & 255) == 0) o.count(c, n, d);
                    });
    EXPECT_EQ(mismatches, 0u) << div_label(c);
    EXPECT_GT(o.exact, 0u) << div_label(c);
    EXPECT_GT(o.corrected, 0u) << div_label(c);
  }
}

TEST(DivRecip64, DirectedHardCases) {
  expect_fast_path_on_hard_cases(
      [](const DivConfig& c, uint64_t n, uint64_t d) { return div_sig_recip64(c, n, d, div_recip64(c, d)); });
}

// ---- the estimate's fraction decides (div_sig_recip64_frac_w, docs/speed.md "Session 9: the
// pixel loop") -------------------------------------------------------------------------------
// Against div_sig_exact and the independent reference; each test checks that both the fraction
// alone and the remainder decided (the band taken and not).

namespace {

DivSig recip64_frac(const DivConfig& c, uint64_t n, uint64_t d) {
  if (d == 0) return {(uint64_t{1} << c.quot_bits) - 1, 0};
  if (n == 0) return {0, 0};
  return div_sig_recip64_frac_w(div_align_bits(c), c.num_bits, c.den_bits, c.quot_bits, n, d, div_recip64(c, d));
}
// Whether the fraction alone decided (n, d) (the predicate the path takes).
bool frac_decided(const DivConfig& c, uint64_t n, uint64_t d) {
  const int w = div_align_bits(c);
  const uint64_t a = n << (w - c.num_bits), b = d << (w - c.den_bits);
  const uint64_t num = (a < b ? a << 1 : a) << (c.quot_bits - 1);
  const uint64_t f = (uint64_t)((u128)num * div_recip64(c, d));
  return div_recip64_frac_decides(f, uint64_t{1} << (w + c.quot_bits));
}

}  // namespace

// The band test at its edges: B = 2^56 (the defaults) and B = 2^63 (W + qb = 63: never decides).
TEST(DivRecip64Frac, TheBandTestAtItsEdges) {
  const uint64_t B = 1ull << 56, h = 1ull << 63;
  for (uint64_t f : {uint64_t{0}, h - B - 1, h, ~uint64_t{0} - B}) EXPECT_TRUE(div_recip64_frac_decides(f, B)) << f;
  for (uint64_t f : {h - B, h - 1, ~uint64_t{0} - B + 1, ~uint64_t{0}}) EXPECT_FALSE(div_recip64_frac_decides(f, B)) << f;
  for (uint64_t f : {uint64_t{0}, h - 1, h, ~uint64_t{0}, uint64_t{12345}}) EXPECT_FALSE(div_recip64_frac_decides(f, h));
}

// Every operand pair of six 12-bit shapes (W + qb = 24 … 63; at 12/12/48 the band is 1/8 of the
// fractions, so decisions next to it are frequent).
TEST(DivRecip64Frac, BitIdenticalToExactForAll12BitOperands) {
  uint64_t decided = 0, remainder = 0;
  expect_fast_path_on_every_operand_pair(
      {shape(DivAlgorithm::Radix2, 12, 12, 12), shape(DivAlgorithm::Radix2, 12, 9, 14),
       shape(DivAlgorithm::Radix2, 9, 12, 10), shape(DivAlgorithm::Radix2, 11, 11, 4),
       shape(DivAlgorithm::Radix2, 12, 12, 48), shape(DivAlgorithm::Radix2, 12, 12, 51)},
      recip64_frac,
      [&](const DivConfig& c, uint64_t n, uint64_t d) { (frac_decided(c, n, d) ? decided : remainder) += 1; });
  EXPECT_GT(decided, 1000000u);
  EXPECT_GT(remainder, 100000u);
}

// 10^7 random plus constructed ties (all in the band: a tie's fraction is ½ − δ) at the defaults,
// 10^6 at the limit shapes.
TEST(DivRecip64Frac, BitIdenticalOnTenMillionPlusTiesAtDefaultAndEdgeWidths) {
  std::vector<DivConfig> cs = {DivConfig{}};
  for (const DivConfig& c : fast64_edge_shapes())
    if (c.num_bits == c.den_bits) cs.push_back(c);
  cs.push_back(shape(DivAlgorithm::Radix2, 32, 32, 28));  // W + qb = 60: the band 1/8
  for (const DivConfig& c : cs) {
    uint64_t mismatches = 0, decided = 0, remainder = 0;
    random_and_ties(c, c.num_bits == 32 && c.quot_bits == 24 ? 10'000'000 : 1'000'000, 23,
                    [&](uint64_t n, uint64_t d) {
                      if (recip64_frac(c, n, d) != div_sig_exact(c, n, d) && ++mismatches <= 5)
                        ADD_FAILURE() << div_label(c) << " n=" << n << " d=" << d;
                      if ((n & 63) == 0) (frac_decided(c, n, d) ? decided : remainder) += 1;
                    });
    EXPECT_EQ(mismatches, 0u) << div_label(c);
    EXPECT_GT(remainder, 0u) << div_label(c);
    if (div_align_bits(c) + c.quot_bits < 63) {
      EXPECT_GT(decided, 0u) << div_label(c);
    }
  }
}

TEST(DivRecip64Frac, DirectedHardCases) { expect_fast_path_on_hard_cases(recip64_frac); }

// ---- operands with a normaliser's carry-out left in place (docs/speed.md "Session 12: the pixel
// loop") ----------------------------------------------------------------------------------------
// The fused span's 64-bit-word segments hand div_sig_recip64_frac_w the rounded significands as
// they come: n = 2^nb (the value 2 at the significand's exponent) and d = 2^db. The result must be
// the correctly rounded quotient of those values all the same: against the independent reference
// ref_div (the rational n·2^−(nb−1) / d·2^−(db−1) ∈ [½, 2], written from the contract) and against
// div_sig_exact on the renormalised operands (2^(nb−1) with exponent + 1, 2^(db−1) with − 1).

namespace {

DivSig renormalised_exact(const DivConfig& c, uint64_t n, uint64_t d) {
  int e = 0;
  if (n >> c.num_bits) n >>= 1, e += 1;
  if (d >> c.den_bits) d >>= 1, e -= 1;
  DivSig q = div_sig_exact(c, n, d);
  q.exp_adj += e;
  return q;
}

// One carry-out pair (n = 2^nb or d = 2^db, or both) against both references; counts which way
// the path went (the band: the remainder decided) and the exact ties of the reference.
struct CarryOutCheck {
  uint64_t pairs = 0, mismatches = 0, decided = 0, remainder = 0;
  void operator()(const DivConfig& c, uint64_t n, uint64_t d) {
    ++pairs;
    const DivSig got = recip64_frac(c, n, d);
    const DivSig want = ref_div(c.num_bits, c.den_bits, c.quot_bits, n, d);
    if ((got != want || got != renormalised_exact(c, n, d)) && ++mismatches <= 5)
      ADD_FAILURE() << div_label(c) << " n=" << n << " d=" << d << " got " << show(got) << " want " << show(want);
    (frac_decided(c, n, d) ? decided : remainder) += 1;
  }
};

}  // namespace

// Every carry-out pair of the six 12-bit shapes of BitIdenticalToExactForAll12BitOperands: n = 2^nb
// with every d ∈ [2^(db−1), 2^db], d = 2^db with every n ∈ [2^(nb−1), 2^nb].
TEST(DivRecip64Frac, CarryOutOperandsForEvery12BitPair) {
  CarryOutCheck k;
  for (const DivConfig& c :
       {shape(DivAlgorithm::Radix2, 12, 12, 12), shape(DivAlgorithm::Radix2, 12, 9, 14),
        shape(DivAlgorithm::Radix2, 9, 12, 10), shape(DivAlgorithm::Radix2, 11, 11, 4),
        shape(DivAlgorithm::Radix2, 12, 12, 48), shape(DivAlgorithm::Radix2, 12, 12, 51)}) {
    const uint64_t ntop = 1ull << c.num_bits, dtop = 1ull << c.den_bits;
    for (uint64_t d = dtop / 2; d <= dtop; ++d) k(c, ntop, d);
    for (uint64_t n = ntop / 2; n < ntop; ++n) k(c, n, dtop);
  }
  EXPECT_EQ(k.mismatches, 0u);
  EXPECT_EQ(k.pairs, 18950u);  // Σ (2^(db−1) + 1) + 2^(nb−1) over the shapes
  EXPECT_GT(k.decided, 1000u);
  EXPECT_GT(k.remainder, 1000u);
}

// 10^6 random carry-out pairs at the defaults, the limit shapes and 32/32/28, plus for d = 2^db
// the constructed ties (the quotient's dropped bits exactly ½: n ≡ 2^(t−1) mod 2^t, t = nb − qb)
// and their neighbours, and the directed extremes.
TEST(DivRecip64Frac, CarryOutOperandsOnAMillionPlusTiesAtDefaultAndEdgeWidths) {
  std::vector<DivConfig> cs = {DivConfig{}};
  for (const DivConfig& c : fast64_edge_shapes()) cs.push_back(c);
  cs.push_back(shape(DivAlgorithm::Radix2, 32, 32, 28));
  std::mt19937_64 rng(24);
  for (const DivConfig& c : cs) {
    CarryOutCheck k;
    const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
    for (int i = 0; i < 500000; ++i) {
      k(c, 2 * nlo, dlo + rng() % dlo);
      k(c, nlo + rng() % nlo, 2 * dlo);
    }
    const int t = c.num_bits - c.quot_bits;
    uint64_t ties = 0;
    if (t >= 1) {
      for (int i = 0; i < 100000; ++i) {
        const uint64_t n = ((nlo + rng() % nlo) & ~((1ull << t) - 1)) | (1ull << (t - 1));
        for (uint64_t v : {n - 1, n, n + 1}) k(c, v, 2 * dlo);
        const DivSig q = ref_div(c.num_bits, c.den_bits, c.quot_bits, n, 2 * dlo);  // a tie: even
        ties += (q.sig & 1) == 0 ? 1 : 0;
      }
      EXPECT_EQ(ties, 100000u) << div_label(c) << ": the constructed ties round to even";
    }
    for (uint64_t v : {nlo, nlo + 1, 2 * nlo - 1, 2 * nlo}) k(c, v, 2 * dlo);
    for (uint64_t v : {dlo, dlo + 1, 2 * dlo - 1, 2 * dlo}) k(c, 2 * nlo, v);
    EXPECT_EQ(k.mismatches, 0u) << div_label(c);
    EXPECT_GT(k.remainder, 0u) << div_label(c);
    if (div_align_bits(c) + c.quot_bits < 63) {
      EXPECT_GT(k.decided, 0u) << div_label(c);
    }
  }
}

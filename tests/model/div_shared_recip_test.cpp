// div.algorithm = shared_recip (one reciprocal per pixel, one multiply per varying, rounded once)
// against exact arithmetic: the error never exceeds the derived bound (div_bound, docs/arith.md
// "shared_recip"), exhaustively at reduced widths and on 10^6 random pairs plus ties at the
// default widths; the bound itself against the exact (GMP) recursion; stage 9 against GMP.
// Expected values: exact integer arithmetic and GMP rationals written here from the contract,
// never the model's functions.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "analysis/measure.hpp"
#include "model/arith/div.hpp"
#include "model/config/config.hpp"
#include "model/stages/divide.hpp"
#include "tests/model/div_ties.hpp"

using namespace fxr;

namespace {

DivConfig shared(int nb, int db, int qb, int si, int sb, int nr, int f) {
  DivConfig c;
  c.algorithm = DivAlgorithm::SharedRecip;
  c.num_bits = nb;
  c.den_bits = db;
  c.quot_bits = qb;
  c.seed_index_bits = si;
  c.seed_bits = sb;
  c.nr_steps = nr;
  c.nr_frac_bits = f;
  return c;
}

// Exact error of a result against n/d, written from the div_sig contract: with
// R = (n·2^−(nb−1)) / (d·2^−(db−1)) and e = 0 if R ≥ 1 else −1, the ulp is 2^(e−(qb−1)) and
//   |sig·2^exp_adj·2^−(qb−1) − R| / ulp = |sig·2^(exp_adj−e)·d·2^(nb−1) − n·2^(db+qb−2−e)| / (d·2^(nb−1)).
// Returned as (numerator, denominator). Needs nb + db + qb ≤ 120.
struct ExactErr {
  u128 num = 0, den = 1;
  bool above = false;  // the result exceeds the exact quotient
};
ExactErr exact_err(int nb, int db, int qb, uint64_t n, uint64_t d, const DivSig& s) {
  const bool ge1 = ((u128)n << db) >= ((u128)d << nb);
  const int e = ge1 ? 0 : -1;
  const int sh = s.exp_adj - e;  // 0 or 1 by the contract
  EXPECT_TRUE(sh == 0 || sh == 1) << "exp_adj " << s.exp_adj << " e " << e;
  ExactErr r;
  r.den = (u128)d << (nb - 1);
  const u128 got = ((u128)s.sig * r.den) << (sh > 0 ? sh : 0);
  const u128 want = (u128)n << (db + qb - 2 - e);
  r.above = got > want;
  r.num = r.above ? got - want : want - got;
  return r;
}

// Correctly rounded result (RNE) by one exact integer division, from the contract.
DivSig ref_rne(int nb, int db, int qb, uint64_t n, uint64_t d) {
  const bool ge1 = ((u128)n << db) >= ((u128)d << nb);
  const int e = ge1 ? 0 : -1;
  const u128 num = (u128)n << (db + qb - 2 - e), den = (u128)d << (nb - 1);
  u128 q = num / den;
  const u128 r = num - q * den;
  if (2 * r > den || (2 * r == den && (q & 1))) ++q;
  if (q == ((u128)1 << qb)) return {(uint64_t)1 << (qb - 1), e + 1};
  return {(uint64_t)q, e};
}

// num / den ≤ bound, exactly (bound = m·2^(x−53) with a 53-bit integer m).
bool within(const ExactErr& er, double bound) {
  int x = 0;
  const double fr = std::frexp(bound, &x);
  const u128 m = (u128)(uint64_t)std::ldexp(fr, 53);
  const int sh = 53 - x;  // bound ≥ ½: 0 ≤ sh ≤ 54
  return (er.num << sh) <= m * er.den;
}

struct Tally {
  double max_ulp = 0, sum_ulp = 0;
  uint64_t count = 0, correct = 0, over = 0, above_half = 0;
  void add(const ExactErr& er, bool correctly_rounded, double bound) {
    const double u = (double)er.num / (double)er.den;  // double only for the statistic
    max_ulp = std::max(max_ulp, u);
    sum_ulp += u;
    ++count;
    correct += correctly_rounded;
    over += !within(er, bound);
    above_half += er.above && 2 * er.num > er.den;  // more than ½ ulp above the exact quotient
  }
};

void check_pair(const DivConfig& c, uint64_t n, uint64_t d, double bound, Tally& t) {
  const DivSig got = div_sig(c, n, d);
  t.add(exact_err(c.num_bits, c.den_bits, c.quot_bits, n, d, got),
        got == ref_rne(c.num_bits, c.den_bits, c.quot_bits, n, d), bound);

}

void print(const char* what, const DivConfig& c, const Tally& t, double bound) {
  std::printf("%s %s nb=%d db=%d qb=%d: %llu pairs, max %.4f ulp (bound %.4f), mean %.4f, correctly rounded %.4f %%\n",
              what, div_label(c).c_str(), c.num_bits, c.den_bits, c.quot_bits, (unsigned long long)t.count, t.max_ulp,
              bound, t.sum_ulp / (double)t.count, 100.0 * (double)t.correct / (double)t.count);
}

mpq_class mpq_pow2(long e) {
  mpq_class r(1);
  if (e >= 0) r.get_num() <<= e; else r.get_den() <<= -e;
  r.canonicalize();
  return r;
}

}  // namespace

// Every operand pair at 12 bits (and 12/9 bits) for reciprocals from accurate to coarse: the
// exact error never exceeds div_bound; after ≥ 1 NR step the result is never more than ½ ulp
// above the exact quotient (the reciprocal is one-sided).
TEST(SharedRecip, ErrorWithinTheDerivedBoundForAllReducedWidthOperands) {
  const DivConfig configs[] = {
      shared(12, 12, 10, 6, 7, 1, 16),  // accurate: bound < 1 ulp
      shared(12, 12, 12, 6, 7, 2, 16),  // no guard bits between operands and quotient
      shared(12, 12, 10, 4, 4, 1, 14),  // coarse: bound above 1 ulp
      shared(12, 12, 10, 3, 4, 0, 12),  // no NR step: two-sided, reaches the clamps
      shared(12, 12, 8, 5, 5, 1, 9),    // iterate narrower than the operands
      shared(12, 9, 10, 5, 6, 2, 14),   // unequal operand widths
      shared(9, 12, 10, 5, 6, 1, 14),
  };
  for (const DivConfig& c : configs) {
    const double bound = div_bound(c).error_bound_ulp;
    Tally t;
    const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
    for (uint64_t d = dlo; d < 2 * dlo; ++d)
      for (uint64_t n = nlo; n < 2 * nlo; ++n) check_pair(c, n, d, bound, t);
    print("exhaustive", c, t, bound);
    EXPECT_EQ(t.over, 0u) << div_label(c) << " bound " << bound << " max " << t.max_ulp;
    EXPECT_EQ(t.count, nlo * dlo);
    if (c.nr_steps > 0) {
      EXPECT_EQ(t.above_half, 0u) << div_label(c);
    }
    EXPECT_GE(t.max_ulp, 0.5) << div_label(c);  // the bound is not vacuous: rounding alone gives ½
  }
}

// The default widths (32 / 32 → 24) with the default reciprocal (256×8, 2 NR, F = 28): 10^6
// random pairs, exact ties and their neighbours, divisors on seed-interval edges, range ends.
TEST(SharedRecip, DefaultWidthsWithinTheBoundOnAMillionRandomAndTies) {
  DivConfig c;
  c.algorithm = DivAlgorithm::SharedRecip;
  const double bound = div_bound(c).error_bound_ulp;
  EXPECT_LT(bound, 1.0) << "the default reciprocal is faithful";
  const int nb = c.num_bits, db = c.den_bits, qb = c.quot_bits;
  const uint64_t nlo = 1ull << (nb - 1), dlo = 1ull << (db - 1);
  std::mt19937_64 rng(21);
  Tally t;
  for (int i = 0; i < 1'000'000; ++i) check_pair(c, nlo + rng() % nlo, dlo + rng() % dlo, bound, t);
  for (uint64_t n : {nlo, nlo + 1, 2 * nlo - 2, 2 * nlo - 1})
    for (uint64_t d : {dlo, dlo + 1, 2 * dlo - 2, 2 * dlo - 1}) check_pair(c, n, d, bound, t);
  // Ties of the exact quotient and their neighbours (tests/model/div_ties.hpp).
  div_ties::for_each_tie(nb, db, qb, 100000, rng, [&](uint64_t n, uint64_t d) { check_pair(c, n, d, bound, t); });
  // Divisors on the seed table's segment edges, numerators equal to the divisor ± 1.
  for (int i = 0; i < 100000; ++i) {
    const uint64_t edge = dlo + ((rng() % (1ull << c.seed_index_bits)) << (db - 1 - c.seed_index_bits));
    for (int delta = -1; delta <= 1; ++delta) {
      const uint64_t d = edge + delta;
      if (d < dlo || d >= 2 * dlo) continue;
      check_pair(c, nlo + rng() % nlo, d, bound, t);
      for (int dn = -1; dn <= 1; ++dn)
        if (d + dn >= nlo && d + dn < 2 * nlo) check_pair(c, d + dn, d, bound, t);
    }
  }
  print("default", c, t, bound);
  EXPECT_EQ(t.over, 0u);
  EXPECT_EQ(t.above_half, 0u);
  EXPECT_GT(t.count, 1'000'000u);
  EXPECT_LT(t.correct, t.count) << "not correctly rounded: no remainder correction";
  EXPECT_GT((double)t.correct / (double)t.count, 0.9);
}

// Every shared_recip configuration of the sweep at the default widths: within its bound on
// 2·10^5 random pairs.
TEST(SharedRecip, SweepConfigurationsWithinTheirBounds) {
  int seen = 0;
  for (const DivConfig& c : div_sweep_configs()) {
    if (c.algorithm != DivAlgorithm::SharedRecip) continue;
    ++seen;
    const double bound = div_bound(c).error_bound_ulp;
    std::mt19937_64 rng(5 + seen);
    const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
    Tally t;
    for (int i = 0; i < 200000; ++i) check_pair(c, nlo + rng() % nlo, dlo + rng() % dlo, bound, t);
    print("sweep", c, t, bound);
    EXPECT_EQ(t.over, 0u) << div_label(c);
  }
  EXPECT_GE(seen, 5);
}

// div_bound's doubles against the exact recursion in GMP rationals, from the seed table's exact
// endpoint errors: e_0 = S, e ← e² + (1 + e)·2^−F + 2·2^−F per NR step; bound = ½ + 2^qb·e.
TEST(SharedRecip, BoundIsAboveTheExactRecursion) {
  for (const DivConfig& c : div_sweep_configs()) {
    if (c.algorithm != DivAlgorithm::SharedRecip) continue;
    const std::vector<uint32_t> table = div_seed_table(c);
    const int s = c.seed_index_bits, k = c.seed_bits;
    mpq_class S(0);
    for (size_t i = 0; i < table.size(); ++i) {
      const mpq_class y0 = mpq_class(mpz_class((unsigned long)((1u << k) + table[i]))) * mpq_pow2(-(k + 1));
      for (int end = 0; end <= 1; ++end) {
        const mpq_class x = 1 + mpq_class(mpz_class((unsigned long)(i + end))) * mpq_pow2(-s);
        const mpq_class err = abs(mpq_class(1 - x * y0));
        if (err > S) S = err;
      }
    }
    const mpq_class u = mpq_pow2(-c.nr_frac_bits);
    mpq_class e = S;
    if (c.nr_steps == 0 && c.seed_bits + 1 > c.nr_frac_bits) e += 2 * u;
    for (int st = 0; st < c.nr_steps; ++st) e = e * e + (1 + e) * u + 2 * u;
    const mpq_class exact = mpq_class(1, 2) + e * mpq_pow2(c.quot_bits);
    const double b = div_bound(c).error_bound_ulp;
    EXPECT_GE(mpq_class(b), exact) << div_label(c);
    EXPECT_LE(mpq_class(b), exact * mpq_class(1000001, 1000000)) << div_label(c) << ": not needlessly loose";
  }
}

// Stage 9 with shared_recip on random plane sums: every varying within the bound of the exact
// quotient of the operands rounded (RNE, GMP) to num_bits / den_bits; one reciprocal per pixel
// gives the same value as dividing each varying on its own.
TEST(SharedRecip, DivideStageWithinTheBoundOfTheRoundedOperands) {
  Config cfg;
  cfg.div.algorithm = DivAlgorithm::SharedRecip;
  const double bound = div_bound(cfg.div).error_bound_ulp;
  DrawState st;
  st.num_varyings = 4;
  DivideStage stage(cfg, st);
  std::mt19937_64 rng(8);
  auto rnd_sum = [&](int bits) {  // magnitudes of 1 … bits bits
    const int b = 1 + (int)(rng() % (unsigned)bits);
    u128 v = ((u128)rng() << 64) | rng();
    v &= (((u128)1) << b) - 1;
    return (i128)(v | ((u128)1 << (b - 1)));
  };
  auto round_to = [](const mpz_class& m, int bits, long& lead) -> mpq_class {  // RNE of m > 0 to `bits` bits
    lead = (long)mpz_sizeinbase(m.get_mpz_t(), 2) - 1;
    mpq_class v(m);
    v *= mpq_pow2(bits - 1 - lead);
    mpz_class fl = v.get_num() / v.get_den();
    const int c = cmp(mpq_class(v - mpq_class(fl)), mpq_class(1, 2));
    if (c > 0 || (c == 0 && mpz_odd_p(fl.get_mpz_t()))) ++fl;
    return mpq_class(fl) * mpq_pow2(lead - (bits - 1));
  };
  auto to_mpz = [](u128 v) {
    mpz_class z((unsigned long)(uint64_t)(v >> 64));
    z <<= 64;
    z += mpz_class((unsigned long)(uint64_t)v);
    return z;
  };
  uint64_t checked = 0;
  for (int i = 0; i < 20000; ++i) {
    PlaneSample p;
    p.den = rnd_sum(92);
    p.den_exp = (int)(rng() % 200) - 100;
    for (int m = 0; m < st.num_varyings; ++m) {
      p.num[m] = rnd_sum(92);
      if (rng() & 1) p.num[m] = -p.num[m];
      p.num_exp[m] = (int)(rng() % 200) - 100;
    }
    stage.step(p, [&](const Fragment& f) {
      long ld = 0;
      const mpq_class dq = round_to(to_mpz((u128)p.den), cfg.div.den_bits, ld) * mpq_pow2(p.den_exp);
      for (int m = 0; m < st.num_varyings; ++m) {
        const bool neg = p.num[m] < 0;
        const u128 mag = neg ? (u128)0 - (u128)p.num[m] : (u128)p.num[m];
        long ln = 0;
        const mpq_class nq = round_to(to_mpz(mag), cfg.div.num_bits, ln) * mpq_pow2(p.num_exp[m]);
        const mpq_class exact = nq / dq;
        // ulp of the exact quotient's binade at quot_bits significant bits
        long lead = (long)(ln + p.num_exp[m]) - (long)(ld + p.den_exp);
        if (exact < mpq_pow2(lead)) --lead;
        const mpq_class ulp = mpq_pow2(lead - (cfg.div.quot_bits - 1));
        const mpq_class got = mpq_class(mpz_class((unsigned long)f.var[m].sig)) * mpq_pow2(f.var[m].exp);
        ASSERT_EQ(f.var[m].neg, neg);
        const mpq_class err = abs(mpq_class(got - exact)) / ulp;
        ASSERT_LE(err, mpq_class(bound)) << "pixel " << i << " varying " << m << ": " << err.get_d() << " ulp; got "
                                         << got.get_d() << " exact " << exact.get_d() << " sig " << f.var[m].sig << " exp " << f.var[m].exp;
        ++checked;
      }
    });
  }
  EXPECT_EQ(checked, 20000u * 4u);
}

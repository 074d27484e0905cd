// The divider's inline 64-bit fast path (div_sig_fast64, docs/speed.md "Divider") and one reciprocal
// per pixel (div_sig_recip64, "The fused span") against
// div_sig_exact on 10^8 random operand pairs plus constructed ties at the default widths and
// 10^7 at the fast path's limit W + qb = 63, and 10^8 operand pairs with a normaliser's carry-out
// (label slow: about a minute of one core).
#include <gtest/gtest.h>

#include <random>

#include "model/arith/div.hpp"
#include "tests/model/div_ties.hpp"

using namespace fxr;

namespace {

// div_sig_fast64 (and, with recip, div_sig_recip64: one reciprocal per pixel) against div_sig_exact.
// frac: div_sig_recip64_frac_w (the estimate's fraction decides outside its band).
uint64_t count_mismatches(const DivConfig& c, uint64_t count, uint64_t seed, bool recip = false, bool frac = false) {
  auto fast = [&](uint64_t n, uint64_t d) {
    if (frac)
      return div_sig_recip64_frac_w(div_align_bits(c), c.num_bits, c.den_bits, c.quot_bits, n, d, div_recip64(c, d));
    return recip ? div_sig_recip64(c, n, d, div_recip64(c, d)) : div_sig_fast64(c, n, d);
  };
  std::mt19937_64 rng(seed);
  const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
  uint64_t bad = 0;
  for (uint64_t i = 0; i < count; ++i) {
    const uint64_t n = nlo + rng() % nlo, d = dlo + rng() % dlo;
    if (fast(n, d) != div_sig_exact(c, n, d) && ++bad <= 5) ADD_FAILURE() << "n=" << n << " d=" << d;
  }
  // Exact ties and their neighbours (tests/model/div_ties.hpp).
  div_ties::for_each_tie(c.num_bits, c.den_bits, c.quot_bits, 1000000, rng, [&](uint64_t n, uint64_t d) {
    if (fast(n, d) != div_sig_exact(c, n, d) && ++bad <= 5) ADD_FAILURE() << "tie n=" << n << " d=" << d;
  });
  return bad;
}

DivConfig shape(int nb, int db, int qb) {
  DivConfig c;
  c.num_bits = nb;
  c.den_bits = db;
  c.quot_bits = qb;
  return c;
}

}  // namespace

TEST(DivFast64Slow, BitIdenticalToExactOnHundredMillionAtDefaultWidths) {
  const DivConfig c;
  ASSERT_TRUE(div_fast64_ok(c));
  EXPECT_EQ(count_mismatches(c, 100'000'000, 101), 0u);
}

TEST(DivFast64Slow, BitIdenticalToExactAtTheWidthLimit) {
  for (const DivConfig& c : {shape(39, 39, 24), shape(32, 32, 31), shape(20, 39, 24)}) {
    ASSERT_TRUE(div_fast64_ok(c));
    EXPECT_EQ(count_mismatches(c, 10'000'000, 102), 0u) << c.num_bits << "/" << c.den_bits << "/" << c.quot_bits;
  }
}

// One reciprocal per pixel (div_sig_recip64, docs/speed.md "The fused span").
TEST(DivRecip64Slow, BitIdenticalToExactOnHundredMillionAtDefaultWidths) {
  const DivConfig c;
  EXPECT_EQ(count_mismatches(c, 100'000'000, 201, true), 0u);
}

TEST(DivRecip64Slow, BitIdenticalToExactAtTheWidthLimit) {
  for (const DivConfig& c : {shape(39, 39, 24), shape(32, 32, 31), shape(20, 39, 24)}) {
    ASSERT_TRUE(div_fast64_ok(c));
    EXPECT_EQ(count_mismatches(c, 10'000'000, 202, true), 0u) << c.num_bits << "/" << c.den_bits << "/" << c.quot_bits;
  }
}

// The estimate's fraction decides (div_sig_recip64_frac_w, docs/speed.md "Session 9: the pixel loop").
TEST(DivRecip64FracSlow, BitIdenticalToExactOnHundredMillionAtDefaultWidths) {
  const DivConfig c;
  EXPECT_EQ(count_mismatches(c, 100'000'000, 301, true, true), 0u);
}

TEST(DivRecip64FracSlow, BitIdenticalToExactAtTheWidthLimit) {
  for (const DivConfig& c : {shape(39, 39, 24), shape(32, 32, 31), shape(20, 39, 24)}) {
    EXPECT_EQ(count_mismatches(c, 10'000'000, 302, true, true), 0u) << c.num_bits << "/" << c.den_bits << "/" << c.quot_bits;
  }
}

// Operands with a normaliser's carry-out left in place (n = 2^nb or d = 2^db, the fused span's
// word segments, docs/speed.md "Session 12: the pixel loop"): 10^8 random pairs at the default
// widths (half of each kind) against div_sig_exact on the renormalised operands.
TEST(DivRecip64FracSlow, CarryOutOperandsOnHundredMillionAtDefaultWidths) {
  const DivConfig c;
  const int w = div_align_bits(c);
  const uint64_t nlo = 1ull << (c.num_bits - 1), dlo = 1ull << (c.den_bits - 1);
  std::mt19937_64 rng(401);
  uint64_t bad = 0;
  for (uint64_t i = 0; i < 50'000'000; ++i) {
    const uint64_t d = dlo + rng() % dlo, n = nlo + rng() % nlo;
    // n = 2^nb: the renormalised 2^(nb−1), exponent + 1
    DivSig want = div_sig_exact(c, nlo, d);
    want.exp_adj += 1;
    if (div_sig_recip64_frac_w(w, c.num_bits, c.den_bits, c.quot_bits, 2 * nlo, d, div_recip64(c, d)) != want &&
        ++bad <= 5)
      ADD_FAILURE() << "n=2^nb d=" << d;
    // d = 2^db: the renormalised 2^(db−1), exponent − 1
    want = div_sig_exact(c, n, dlo);
    want.exp_adj -= 1;
    if (div_sig_recip64_frac_w(w, c.num_bits, c.den_bits, c.quot_bits, n, 2 * dlo, div_recip64_w(w, c.den_bits, 2 * dlo)) !=
            want &&
        ++bad <= 5)
      ADD_FAILURE() << "n=" << n << " d=2^db";
  }
  EXPECT_EQ(bad, 0u);
}

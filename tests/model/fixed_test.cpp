// Properties of the fixed-point primitives against exact integer / rational arithmetic (GMP).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <random>

#include "model/arith/fixed.hpp"

using namespace fxr;

namespace {

mpz_class to_mpz(i128 v) {
  const bool neg = v < 0;
  u128 m = neg ? (u128)(-(v + 1)) + 1 : (u128)v;
  mpz_class hi((unsigned long)(uint64_t)(m >> 64)), lo((unsigned long)(uint64_t)m);
  mpz_class r = (hi << 64) + lo;
  return neg ? mpz_class(-r) : r;
}

// Independent reference: round x / 2^s with GMP rationals.
mpz_class ref_round(const mpz_class& x, int s, Round r) {
  mpz_class d = mpz_class(1) << s;
  mpz_class fl, rem;
  mpz_fdiv_qr(fl.get_mpz_t(), rem.get_mpz_t(), x.get_mpz_t(), d.get_mpz_t());
  if (rem == 0) return fl;
  const int c = cmp(2 * rem, d);  // compare fraction with 1/2
  switch (r) {
    case Round::Trunc: return fl;
    case Round::TruncZero: return x < 0 ? mpz_class(fl + 1) : fl;
    case Round::HalfUp: return c >= 0 ? mpz_class(fl + 1) : fl;
    case Round::HalfEven: return c > 0 || (c == 0 && mpz_odd_p(fl.get_mpz_t())) ? mpz_class(fl + 1) : fl;
    case Round::HalfAway: return c > 0 || (c == 0 && x > 0) ? mpz_class(fl + 1) : fl;
  }
  return fl;
}

}  // namespace

TEST(Fixed, ShiftRoundMatchesRationalRoundingForAllModes) {
  std::mt19937_64 rng(1);
  for (int i = 0; i < 200000; ++i) {
    const i128 x = (i128)(int64_t)rng() * (int64_t)(rng() >> (rng() % 64)) ;
    const int s = (int)(rng() % 100) + 1;
    for (Round r : {Round::Trunc, Round::TruncZero, Round::HalfUp, Round::HalfEven, Round::HalfAway}) {
      ASSERT_EQ(to_mpz(shift_round(x, s, r)), ref_round(to_mpz(x), s, r))
          << "s=" << s << " mode=" << to_string(r);
    }
  }
}

TEST(Fixed, TiesRoundAsDocumented) {
  // 2.5, 3.5, -2.5, -3.5 with one fraction bit.
  const i128 v[] = {5, 7, -5, -7};
  const int64_t even[] = {2, 4, -2, -4}, up[] = {3, 4, -2, -3}, away[] = {3, 4, -3, -4};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(shift_round(v[i], 1, Round::HalfEven), even[i]);
    EXPECT_EQ(shift_round(v[i], 1, Round::HalfUp), up[i]);
    EXPECT_EQ(shift_round(v[i], 1, Round::HalfAway), away[i]);
  }
}

TEST(Fixed, SaturateAndWrapAtWidthLimits) {
  bool ovf = false;
  EXPECT_EQ(fit_width(127, 8, true, Overflow::Saturate, &ovf), 127);
  EXPECT_FALSE(ovf);
  EXPECT_EQ(fit_width(128, 8, true, Overflow::Saturate, &ovf), 127);
  EXPECT_TRUE(ovf);
  EXPECT_EQ(fit_width(-129, 8, true, Overflow::Saturate), -128);
  EXPECT_EQ(fit_width(128, 8, true, Overflow::Wrap), -128);
  EXPECT_EQ(fit_width(-129, 8, true, Overflow::Wrap), 127);
  EXPECT_EQ(fit_width(256, 8, false, Overflow::Wrap), 0);
  EXPECT_EQ(fit_width(-1, 8, false, Overflow::Saturate), 0);
  EXPECT_EQ(fit_width(-1, 8, false, Overflow::Wrap), 255);
  EXPECT_EQ(fit_width(((i128)1) << 70, 64, true, Overflow::Saturate), INT64_MAX);
}

TEST(Fixed, NormalizeKeepsLeadingOneAndRoundsCarryOut) {
  std::mt19937_64 rng(2);
  for (int i = 0; i < 100000; ++i) {
    const u128 x = ((u128)rng() << (rng() % 60)) | 1;
    const int bits = 1 + (int)(rng() % 64);
    const Normalized n = normalize(x, bits, Round::HalfEven);
    ASSERT_EQ(n.sig >> (bits - 1), 1u);
    // n.sig · 2^(exp − bits + 1) equals x rounded to `bits` significant bits.
    const int m = msb_index(x);
    const mpz_class exact = to_mpz((i128)x);
    const mpz_class ref = m - (bits - 1) > 0 ? ref_round(exact, m - (bits - 1), Round::HalfEven)
                                             : mpz_class(exact << (bits - 1 - m));
    mpz_class got(std::to_string(n.sig));
    if (n.exp != m) got <<= 1;  // carry-out renormalised
    ASSERT_EQ(got, ref);
  }
  EXPECT_EQ(normalize(0, 24, Round::HalfEven).sig, 0u);
  EXPECT_EQ(clz64(0), 64);
  EXPECT_EQ(clz128(1), 127);
}

// Properties of the fixed-point primitives against exact integer / rational arithmetic (GMP).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "model/arith/fixed.hpp"
#include "model/arith/round_flat.hpp"

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

// ---- the 64-bit-word normalisation (docs/speed.md "The normalisation in 64-bit words") ------

namespace {

// x rounded (RNE) to `bits` significant bits by GMP: the significand and the msb index after
// a carry-out, and whether bits were dropped.
Normalized ref_normalize(u128 x, int bits) {
  Normalized n;
  if (x == 0) return n;
  const mpz_class ex = to_mpz((i128)x);
  const int m = (int)mpz_sizeinbase(ex.get_mpz_t(), 2) - 1;
  const int shift = m - (bits - 1);
  mpz_class s = shift > 0 ? ref_round(ex, shift, Round::HalfEven) : mpz_class(ex << (-shift));
  n.exp = m;
  n.inexact = shift > 0 && mpz_class(s << shift) != ex;
  if ((int)mpz_sizeinbase(s.get_mpz_t(), 2) > bits) s >>= 1, n.exp += 1;
  n.sig = (uint64_t)std::stoull(s.get_str());
  return n;
}

// Both paths of normalize(), NormalizeAtMsb and GMP agree on x at `bits`; returns false (with a message) on the first mismatch.
::testing::AssertionResult same_normalize(u128 x, int bits) {
  const Normalized f = detail::normalize_rne64(x, bits), g = detail::normalize_u128(x, bits, Round::HalfEven);
  const Normalized r = ref_normalize(x, bits);
  const Normalized* all[] = {&f, &g};
  for (const Normalized* p : all)
    if (p->sig != r.sig || p->exp != r.exp || p->inexact != r.inexact)
      return ::testing::AssertionFailure() << "x = 0x" << std::hex << (uint64_t)(x >> 64) << "_" << (uint64_t)x
                                           << std::dec << " bits " << bits << ": got sig " << p->sig << " exp "
                                           << p->exp << " inexact " << p->inexact << ", GMP sig " << r.sig
                                           << " exp " << r.exp << " inexact " << r.inexact;
  // The normaliser set up for x's binade (NormalizeAtMsb, the fused span's path), both entry points.
  if (x != 0) {
    const NormalizeAtMsb at(bits, msb_index(x));
    int e1 = -1, e2 = -1;
    const uint64_t s1 = at.sig(x, e1), s2 = at.sig_bits(x, e2, bits);
    if (s1 != r.sig || e1 != r.exp || s2 != r.sig || e2 != r.exp)
      return ::testing::AssertionFailure() << "NormalizeAtMsb x = 0x" << std::hex << (uint64_t)(x >> 64) << "_"
                                           << (uint64_t)x << std::dec << " bits " << bits << ": got sig " << s1
                                           << " exp " << e1 << ", GMP sig " << r.sig << " exp " << r.exp;
    // And in 64-bit words where the significand lies above the low word (rne_high_word).
    if (at.high_word()) {
      uint64_t q = rne_high_word<uint64_t>((uint64_t)(x >> 64), (uint64_t)x, at.high_shift(), at.high_bias());
      const int carry = (int)(q >> bits);
      q >>= carry;
      if (q != r.sig || at.m + carry != r.exp)
        return ::testing::AssertionFailure() << "rne_high_word x = 0x" << std::hex << (uint64_t)(x >> 64) << "_"
                                             << (uint64_t)x << std::dec << " bits " << bits << ": got sig " << q
                                             << " exp " << at.m + carry << ", GMP sig " << r.sig << " exp " << r.exp;
    }
  }
  return ::testing::AssertionSuccess();
}

// A value with its msb at m (0 ≤ m ≤ 126), random below.
u128 random_at_msb(std::mt19937_64& rng, int m) {
  const u128 r = ((u128)rng() << 64) | rng();
  return ((u128)1 << m) | (m == 0 ? 0 : (r & ((((u128)1) << m) - 1)));
}

}  // namespace

// Every msb position (both words, the word boundary) × every width, random low bits.
TEST(Normalize64, EqualsTheU128PathAndGmpOnRandomValuesAtEveryMsbAndWidth) {
  std::mt19937_64 rng(64);
  for (int bits = 1; bits <= 63; ++bits)
    for (int m = 0; m <= 126; ++m)
      for (int k = 0; k < 12; ++k) ASSERT_TRUE(same_normalize(random_at_msb(rng, m), bits));
  ASSERT_TRUE(same_normalize(0, 32));
}

// The hard cases, directed: exact ties with an even and an odd kept part, a tie ± 1 (the
// sticky bit in the other word), the rounding carry-out (all ones), exact values (nothing
// dropped), the largest input 2^127 − 1 — at every msb and width, shifts across the word
// boundary included.
TEST(Normalize64, EqualsTheU128PathAndGmpOnTiesCarriesAndExactValues) {
  std::mt19937_64 rng(65);
  for (int bits = 1; bits <= 63; ++bits)
    for (int m = 0; m <= 126; ++m) {
      const int shift = m - (bits - 1);
      const u128 top = ((u128)1 << m);
      const u128 ones = top | (top - 1);
      ASSERT_TRUE(same_normalize(ones, bits));  // carry-out
      ASSERT_TRUE(same_normalize(top, bits));   // exact
      if (shift <= 0) continue;
      const u128 half = (u128)1 << (shift - 1);
      for (int k = 0; k < 4; ++k) {
        u128 kept = random_at_msb(rng, bits - 1);
        if (k >= 2) kept |= 1;           // odd kept part
        else kept &= ~(u128)1 | (bits == 1 ? 1 : 0);  // even (bits 1: the msb itself)
        const u128 tie = (kept << shift) | half;
        ASSERT_TRUE(same_normalize(tie, bits));
        ASSERT_TRUE(same_normalize(tie + 1, bits));
        ASSERT_TRUE(same_normalize(tie - 1, bits));
        ASSERT_TRUE(same_normalize(kept << shift, bits));  // exact multiple
      }
    }
  ASSERT_TRUE(same_normalize(~(u128)0 >> 1, 63));
  ASSERT_TRUE(same_normalize(~(u128)0 >> 1, 1));
}

// ---- rne_high_word: NormalizeAtMsb's rounding in words (docs/speed.md "Session 9: the pixel loop")

namespace {
// RNE(x·2^−shift) from the definition (floor, then the dropped part against half; ties to even),
// before any carry-out renormalisation.
uint64_t ref_rne_shift(u128 x, int shift) {
  const u128 q = x >> shift, rest = x - (q << shift), half = (u128)1 << (shift - 1);
  return (uint64_t)(q + ((rest > half || (rest == half && (q & 1))) ? 1 : 0));
}
}  // namespace

// Two 8-bit words (W = 8): every x with msb m ≤ 2W − 2 = 14 at every shift W + s, 1 ≤ s ≤ m − W
// (bits = m − shift + 1 ≥ 1), exhaustively: 1.6·10^5 cases, every tie, carry and sticky pattern.
TEST(NormalizeHighWord, EqualsTheDefinitionForEveryValueOfTwoEightBitWords) {
  uint64_t cases = 0, ties = 0, carries = 0;
  for (uint32_t x = 1; x < (1u << 15); ++x) {
    const int m = msb_index((u128)x);
    for (int s = 1; 8 + s <= m; ++s) {
      const int shift = 8 + s;
      const uint8_t hb = (uint8_t)((1u << (s - 1)) - 1);
      const uint8_t got = rne_high_word<uint8_t>((uint8_t)(x >> 8), (uint8_t)x, s, hb);
      const uint64_t want = ref_rne_shift(x, shift);
      ASSERT_EQ((uint64_t)got, want) << "x " << x << " shift " << shift;
      ++cases;
      ties += (x & ((1u << shift) - 1)) == (1u << (shift - 1)) ? 1 : 0;
      carries += (want >> (m - shift + 1)) != 0 ? 1 : 0;
    }
  }
  EXPECT_GT(cases, 150000u);
  EXPECT_GT(ties, 100u);
  EXPECT_GT(carries, 100u);
}

// 64-bit words: 10^6 random values (a quarter of them ties and tie ± 1) at every msb 65..126
// and width with shift > 64, against the definition (the GMP-checked directed cases are in
// same_normalize above, every msb × width).
TEST(NormalizeHighWord, EqualsTheDefinitionOnAMillionRandom64BitWordValues) {
  std::mt19937_64 rng(1165);
  uint64_t mism = 0, high = 0;
  for (int i = 0; i < 1000000; ++i) {
    const uint64_t r0 = rng();
    const int m = 65 + (int)(r0 % 62), bits = 1 + (int)((r0 >> 8) % 63);
    const NormalizeAtMsb at(bits, m);
    if (!at.high_word()) continue;
    ++high;
    u128 x = random_at_msb(rng, m);
    const int shift = m - (bits - 1);
    if ((r0 >> 20) % 4 == 0) {
      x = ((x >> shift) << shift) | ((u128)1 << (shift - 1));
      x += (u128)((int)((r0 >> 24) % 3) - 1);
    }
    const uint64_t got = rne_high_word<uint64_t>((uint64_t)(x >> 64), (uint64_t)x, at.high_shift(), at.high_bias());
    if (got != ref_rne_shift(x, shift) && ++mism <= 5) ADD_FAILURE() << "m " << m << " bits " << bits;
  }
  EXPECT_EQ(mism, 0u);
  EXPECT_GT(high, 500000u);
}

// ---- udivmod128 / floor_divmod (docs/speed.md "Wide divisions with a narrow quotient") ------

namespace {

::testing::AssertionResult same_floor_divmod(i128 a, i128 d) {
  i128 q, r;
  floor_divmod(a, d, q, r);
  mpz_class gq, gr;
  const mpz_class ga = to_mpz(a), gd = to_mpz(d);
  mpz_fdiv_qr(gq.get_mpz_t(), gr.get_mpz_t(), ga.get_mpz_t(), gd.get_mpz_t());
  if (to_mpz(q) != gq || to_mpz(r) != gr)
    return ::testing::AssertionFailure() << "a = " << ga.get_str() << " d = " << gd.get_str() << ": q "
                                         << to_mpz(q).get_str() << " r " << to_mpz(r).get_str() << ", GMP q "
                                         << gq.get_str() << " r " << gr.get_str();
  if (a >= 0) {  // the unsigned entry point directly
    u128 uq, ur;
    udivmod128((u128)a, (u128)d, uq, ur);
    if (to_mpz((i128)uq) != gq || to_mpz((i128)ur) != gr)
      return ::testing::AssertionFailure() << "udivmod128 a = " << ga.get_str() << " d = " << gd.get_str();
  }
  return ::testing::AssertionSuccess();
}

i128 random_bits(std::mt19937_64& rng, int bits) {  // magnitude < 2^bits, 1 ≤ bits ≤ 126
  const u128 r = ((u128)rng() << 64) | rng();
  return (i128)(r & ((((u128)1) << bits) - 1));
}

}  // namespace

// Both outcomes of the fast-path test (quotient fits 64 bits with d < 2^64, or not): dividends
// and divisors of every size, both signs of the dividend, against GMP's floor division.
TEST(DivMod128, FloorDivisionEqualsGmpOnRandomOperandsOfEverySize) {
  std::mt19937_64 rng(128);
  for (int ab = 1; ab <= 126; ++ab)
    for (int db = 1; db <= 126; db += 1)
      for (int k = 0; k < 6; ++k) {
        i128 a = random_bits(rng, ab), d = random_bits(rng, db);
        if (d == 0) d = 1;
        if (k & 1) a = -a;
        ASSERT_TRUE(same_floor_divmod(a, d));
      }
}

// Directed: the fast path's boundary a / 2^64 = d − 1 (taken) and = d (not), d = 1, d = 2^64 − 1,
// d = 2^64, exact multiples of both signs (remainder 0), a = 0, a = ±(2^127 − 1), a = −2^127.
TEST(DivMod128, FloorDivisionEqualsGmpAtTheFastPathBoundary) {
  std::mt19937_64 rng(129);
  const u128 two64 = (u128)1 << 64;
  for (int k = 0; k < 20000; ++k) {
    uint64_t d = rng() >> (rng() % 64);
    if (d == 0) d = 1;
    for (const uint64_t hi : {d - 1, d, d == UINT64_MAX ? d : d + 1}) {
      if (hi >> 62) continue;  // keep a < 2^126 positive (signed range with room to negate)
      for (const uint64_t lo : {uint64_t{0}, d - 1, (uint64_t)rng(), UINT64_MAX}) {
        const i128 a = (i128)(((u128)hi << 64) | lo);
        ASSERT_TRUE(same_floor_divmod(a, (i128)d));
        ASSERT_TRUE(same_floor_divmod(-a, (i128)d));
      }
    }
    const i128 m = (i128)d * (i128)(rng() >> 1);  // an exact multiple
    ASSERT_TRUE(same_floor_divmod(m, (i128)d));
    ASSERT_TRUE(same_floor_divmod(-m, (i128)d));
  }
  const i128 big = (i128)(~(u128)0 >> 1);
  for (const i128 d : {(i128)1, (i128)3, (i128)UINT64_MAX, (i128)two64, (i128)two64 + 1, big}) {
    for (const i128 a : {(i128)0, (i128)1, (i128)-1, big, -big, -big - 1, (i128)two64 * 5 - 1})
      ASSERT_TRUE(same_floor_divmod(a, d));
  }
}

// ---- the branch-free RNE of the per-vertex paths (docs/speed.md "Session 13: per vertex and per
// triangle") ------------------------------------------------------------------------------------

namespace {
// The rule from its definition, in exact GMP arithmetic: up when r/den > ½, or = ½ and q odd.
bool ref_rne_up(const mpz_class& q, const mpz_class& r, const mpz_class& den) {
  const int c = cmp(2 * r, den);
  return c > 0 || (c == 0 && mpz_odd_p(q.get_mpz_t()));
}
mpz_class to_mpz_u(u128 v) { return to_mpz((i128)(v >> 1)) * 2 + (unsigned long)(v & 1); }
}  // namespace

// rne_round_up_flat against rne_round_up and the rule: every q parity, den < 2^9 and r < den
// (exhaustive) in four integer types; directed cases near the top of the uint64 domain (2r must
// fit: den and r below 2^63) and the u128 one; 10^6 random cases of random magnitude.
TEST(RneFlat, DecisionEqualsRneRoundUpAndTheRuleExhaustivelyAndOnRandomOperands) {
  for (uint64_t q = 0; q < 4; ++q)
    for (uint64_t den = 1; den < 512; ++den)
      for (uint64_t r = 0; r < den; ++r) {
        const bool ref = ref_rne_up(mpz_class((unsigned long)q), mpz_class((unsigned long)r), mpz_class((unsigned long)den));
        ASSERT_EQ(rne_round_up_flat<uint64_t>(q, r, den), ref) << q << " " << r << " " << den;
        ASSERT_EQ(rne_round_up_flat<uint64_t>(q, r, den), rne_round_up<uint64_t>(q, r, den));
        ASSERT_EQ(rne_round_up_flat<int64_t>((int64_t)q - 2, (int64_t)r, (int64_t)den), ref);  // q − 2: same parity
        ASSERT_EQ(rne_round_up_flat<u128>(q, r, den), ref);
        ASSERT_EQ(rne_round_up_flat<i128>((i128)q - 2, r, den), ref);
      }
  const uint64_t top = (uint64_t{1} << 63) - 1;
  for (const uint64_t den : {top, top - 1, uint64_t{1} << 62, (uint64_t{1} << 62) + 1})
    for (const uint64_t r : {den / 2 - 1, den / 2, den / 2 + 1, (den + 1) / 2, den - 1, uint64_t{0}})
      for (const uint64_t q : {uint64_t{0}, uint64_t{1}, UINT64_MAX}) {
        ASSERT_EQ(rne_round_up_flat<uint64_t>(q, r, den),
                  ref_rne_up(to_mpz_u(q), to_mpz_u(r), to_mpz_u(den)));
        ASSERT_EQ(rne_round_up_flat<uint64_t>(q, r, den), rne_round_up<uint64_t>(q, r, den));
      }
  std::mt19937_64 rng(1301);
  long ties = 0;
  for (int i = 0; i < 1000000; ++i) {
    const uint64_t den = std::max<uint64_t>(1, rng() >> (1 + rng() % 63));
    uint64_t r = rng() % den;
    if (i % 8 == 0 && den % 2 == 0) r = den / 2, ++ties;  // ties of both q parities
    const uint64_t q = rng();
    ASSERT_EQ(rne_round_up_flat<uint64_t>(q, r, den), ref_rne_up(to_mpz_u(q), to_mpz_u(r), to_mpz_u(den)));
  }
  EXPECT_GT(ties, 10000);
}

// shift_round_right_rne_flat against shift_round_right (Round::HalfEven) and GMP's rational
// rounding: every x in [−2^13, 2^13] at every shift 1 … 15 (exhaustive); directed x at the int64
// ends and ties at every shift up to kInt64ShiftMax; 10^6 random x of random magnitude and shift.
TEST(RneFlat, ShiftRoundRightEqualsTheBranchingPathAndGmp) {
  const auto check = [](int64_t x, int s) {
    const int64_t f = detail::shift_round_right_rne_flat<int64_t, uint64_t>(x, s);
    ASSERT_EQ(f, (detail::shift_round_right<int64_t, uint64_t>(x, s, Round::HalfEven))) << x << " " << s;
    ASSERT_EQ(to_mpz(f), ref_round(to_mpz(x), s, Round::HalfEven)) << x << " " << s;
  };
  for (int s = 1; s <= 15; ++s)
    for (int64_t x = -(1 << 13); x <= (1 << 13); ++x) check(x, s);
  for (int s = 1; s <= kInt64ShiftMax; ++s) {
    const int64_t h = (int64_t)1 << (s - 1);
    for (const int64_t x : {INT64_MAX, INT64_MIN, INT64_MIN + 1, INT64_MAX - 1, h, -h, 3 * h, -3 * h, h - 1, h + 1,
                            (int64_t)0, (int64_t)-1, (int64_t)1})
      check(x, s);
  }
  std::mt19937_64 rng(1302);
  for (int i = 0; i < 1000000; ++i) {
    const int64_t x = (int64_t)rng() >> (rng() % 64);
    const int s = 1 + (int)(rng() % kInt64ShiftMax);
    check(x, s);
  }
}

// The 64-bit fast paths of model/arith/fixed.hpp at 10^8 random cases each (slow label; the
// directed and GMP-checked cases are in fixed_test.cpp, docs/speed.md):
//   normalize()'s 64-bit-word path (normalize_rne64) against the generic u128 path;
//   rne_high_word (the fused span's normalisation in 64-bit words) against NormalizeAtMsb's u128 path;
//   udivmod128 / floor_divmod (the hardware 128-by-64 division) against the compiler's i128 / and %;
//   shift_round_right_rne_flat (the branch-free RNE) against shift_round_right.
#include <gtest/gtest.h>

#include <random>

#include "model/arith/fixed.hpp"
#include "model/arith/round_flat.hpp"

using namespace fxr;

namespace {
constexpr long kCases = 100000000;
}

TEST(Normalize64Slow, EqualsTheU128PathOn1e8RandomValues) {
  std::mt19937_64 rng(1064);
  long mism = 0;
  for (long i = 0; i < kCases; ++i) {
    const uint64_t r0 = rng(), r1 = rng();
    const int m = (int)(r0 % 127), bits = 1 + (int)((r0 >> 8) % 63);
    u128 x = (((u128)r1 << 64) | rng()) & ((((u128)1) << m) - 1);
    x |= (u128)1 << m;
    if ((r0 >> 20) % 8 == 0 && m - (bits - 1) > 0) {  // a tie or a tie ± 1 at this width
      const int shift = m - (bits - 1);
      x = ((x >> shift) << shift) | ((u128)1 << (shift - 1));
      x += (u128)((int)((r0 >> 24) % 3) - 1);
    }
    const Normalized f = detail::normalize_rne64(x, bits), g = detail::normalize_u128(x, bits, Round::HalfEven);
    if (f.sig != g.sig || f.exp != g.exp || f.inexact != g.inexact) ++mism;
  }
  EXPECT_EQ(mism, 0);
}

// rne_high_word (NormalizeAtMsb's rounding in 64-bit words, shift > 64) against the u128 path.
TEST(NormalizeHighWordSlow, EqualsTheU128PathOn1e8RandomValues) {
  std::mt19937_64 rng(1165);
  long mism = 0, n = 0;
  while (n < kCases) {
    const uint64_t r0 = rng(), r1 = rng();
    const int m = 65 + (int)(r0 % 62), bits = 1 + (int)((r0 >> 8) % 63);
    const NormalizeAtMsb at(bits, m);
    if (!at.high_word()) continue;
    ++n;
    u128 x = ((((u128)r1 << 64) | rng()) & ((((u128)1) << m) - 1)) | ((u128)1 << m);
    if ((r0 >> 20) % 8 == 0) {  // a tie or a tie ± 1 at this width
      const int shift = m - (bits - 1);
      x = ((x >> shift) << shift) | ((u128)1 << (shift - 1));
      x += (u128)((int)((r0 >> 24) % 3) - 1);
    }
    int e = 0;
    const uint64_t want = at.sig_bits(x, e, bits);
    uint64_t q = rne_high_word<uint64_t>((uint64_t)(x >> 64), (uint64_t)x, at.high_shift(), at.high_bias());
    const int carry = (int)(q >> bits);
    q >>= carry;
    if (q != want || m + carry != e) ++mism;
  }
  EXPECT_EQ(mism, 0);
}

TEST(DivMod128Slow, FloorDivisionEqualsTheI128DivisionOn1e8RandomOperands) {
  std::mt19937_64 rng(1128);
  long mism = 0, fast = 0;
  for (long i = 0; i < kCases; ++i) {
    const uint64_t r0 = rng();
    const int ab = 1 + (int)(r0 % 126), db = 1 + (int)((r0 >> 8) % 100);
    i128 a = (i128)((((u128)rng() << 64) | rng()) & ((((u128)1) << ab) - 1));
    i128 d = (i128)((((u128)rng() << 64) | rng()) & ((((u128)1) << db) - 1));
    if (d == 0) d = 1;
    if ((r0 >> 16) & 1) a = -a;
    i128 q, r;
    floor_divmod(a, d, q, r);
    i128 q2 = a / d, r2 = a % d;  // truncating, then to floor
    if (r2 < 0) r2 += d, q2 -= 1;
    if (q != q2 || r != r2) ++mism;
    const u128 ua = a < 0 ? (u128)0 - (u128)a : (u128)a;
    fast += (d >> 64) == 0 && (uint64_t)(ua >> 64) < (uint64_t)d;
  }
  EXPECT_EQ(mism, 0);
  EXPECT_GT(fast, kCases / 4);  // both outcomes of the fast-path test are reached
  EXPECT_LT(fast, kCases - kCases / 4);
}

// shift_round_right_rne_flat (the per-vertex snap's branch-free RNE, docs/speed.md "Session 13:
// per vertex and per triangle") against shift_round_right(…, Round::HalfEven), a tie at every
// eighth case.
TEST(RneFlatSlow, ShiftRoundRightEqualsTheBranchingPathOn1e8RandomValues) {
  std::mt19937_64 rng(1303);
  long mism = 0;
  for (long i = 0; i < kCases; ++i) {
    const uint64_t r0 = rng();
    int64_t x = (int64_t)rng() >> (r0 % 64);
    const int s = 1 + (int)((r0 >> 8) % kInt64ShiftMax);
    if ((r0 >> 16) % 8 == 0) x = (x & ~(int64_t)((uint64_t{1} << s) - 1)) | (int64_t)(uint64_t{1} << (s - 1));
    if (detail::shift_round_right_rne_flat<int64_t, uint64_t>(x, s) !=
        detail::shift_round_right<int64_t, uint64_t>(x, s, Round::HalfEven))
      ++mism;
  }
  EXPECT_EQ(mism, 0);
}

// The 64-bit paths of stage 4's per-vertex arithmetic against their i128 references (docs/speed.md
// "Session 9: per triangle"): exhaustive at reduced widths, directed cases on both sides of every
// range test, and 10^6 random cases (10^8 in attr_fast64_slow_test.cpp, slow label).
#include "tests/model/attr_fast64_cases.hpp"

#include "model/stages/input.hpp"

namespace fxr::fast64 {
namespace {

TEST(AttrFast64, RneQuotientPlusExhaustiveAtSevenBitsEqualsTheReference) {
  Tally t;
  for (uint64_t N = 0; N < 128; ++N)
    for (uint64_t D = 1; D < 128; ++D)
      for (int k = -9; k <= 9; ++k)
        for (int64_t C : {-3, -2, -1, 0, 1, 2, 5})
          for (bool neg : {false, true}) check_rqp(t, neg, N, k, D, C);
  expect_clean(t, "rne_quotient_plus64");
  EXPECT_EQ(t.fast, t.cases);  // every operand here is inside the range test
}

TEST(AttrFast64, RneQuotientPlusRangeTestFlipsWhereTheOperandsReachTwoToThe61) {
  Tally t;
  const int64_t cmax = ((int64_t)1 << kAttrFast64Bits) - 1;
  for (bool neg : {false, true}) {
    // N·2^k just below / at 2^61.
    for (int k : {0, 1, 20}) {
      const uint64_t below = (((uint64_t)1 << (kAttrFast64Bits - k)) - 1), at = (uint64_t)1 << (kAttrFast64Bits - k);
      check_rqp(t, neg, below, k, 3, 7);
      EXPECT_EQ(t.fast, t.cases) << "N·2^k = 2^61 − 2^k must take the 64-bit path";
      Tally u;
      check_rqp(u, neg, at, k, 3, 7);
      EXPECT_EQ(u.fast, 0u) << "N·2^k = 2^61 must not";
      expect_clean(u, "at");
    }
    // D·2^−k just below / at 2^61.
    for (int k : {-1, -30}) {
      const uint64_t below = ((uint64_t)1 << (kAttrFast64Bits + k)) - 1, at = (uint64_t)1 << (kAttrFast64Bits + k);
      Tally a, b;
      check_rqp(a, neg, 12345, k, below, -9);
      check_rqp(b, neg, 12345, k, at, -9);
      EXPECT_EQ(a.fast, 1u);
      EXPECT_EQ(b.fast, 0u);
      expect_clean(a, "D below"), expect_clean(b, "D at");
      // The unshifted operand N just below / at 2^61 (a quotient past int64 otherwise).
      Tally c, d;
      check_rqp(c, neg, ((uint64_t)1 << kAttrFast64Bits) - 1, k, 5, 0);
      check_rqp(d, neg, (uint64_t)1 << kAttrFast64Bits, k, 5, 0);
      EXPECT_EQ(c.fast, 1u);
      EXPECT_EQ(d.fast, 0u);
      expect_clean(c, "N below"), expect_clean(d, "N at");
    }
    // k ≥ 0: the unshifted D just below / at 2^61 (2·frac_num past 2^63 otherwise).
    for (uint64_t D : {((uint64_t)1 << kAttrFast64Bits) - 1, (uint64_t)1 << kAttrFast64Bits, ~(uint64_t)0}) {
      Tally a;
      check_rqp(a, neg, 897, 21, D, -30823654169783);
      EXPECT_EQ(a.fast, D < ((uint64_t)1 << kAttrFast64Bits) ? 1u : 0u);
      expect_clean(a, "D, k >= 0");
    }
    // |C| at 2^61 − 1 (in) and 2^61 (out), with quotients that carry it to the int64 limits.
    Tally a, b;
    check_rqp(a, neg, ((uint64_t)1 << 60) - 1, 0, 1, cmax);
    check_rqp(a, neg, ((uint64_t)1 << 60) - 1, 0, 1, -cmax);
    check_rqp(b, neg, 5, 0, 3, cmax + 1);
    check_rqp(b, neg, 5, 0, 3, -cmax - 1);
    EXPECT_EQ(a.fast, 2u);
    EXPECT_EQ(b.fast, 0u);
    expect_clean(a, "C in"), expect_clean(b, "C out");
    // Ties: N/D = m + ½ with both parities of the floor, and −(m + ½).
    for (uint64_t m = 0; m < 6; ++m) check_rqp(t, neg, 2 * m + 1, 0, 2, 0), check_rqp(t, neg, 2 * m + 1, -1, 1, 3);
  }
  expect_clean(t, "rne_quotient_plus64 boundaries");
}

TEST(AttrFast64, AttrQuotientExhaustiveAtEightBitsEqualsTheReference) {
  Tally t;
  for (uint64_t a = 0; a < 256; ++a)
    for (uint64_t b = 1; b < 256; ++b)
      for (int bits : {2, 3, 5, 8, 11}) {
        const FxFloat n{(a & 1) != 0, a, (int)(a % 7) - 3}, w{false, b, (int)(b % 5) - 2};
        check_quot(t, n, w, bits);
      }
  expect_clean(t, "attr_quotient64");
  EXPECT_EQ(t.fast, t.cases);
}

TEST(AttrFast64, AttrQuotientRangeTestFlipsAtTheShiftedOperandsTop) {
  // num = n.sig·2^s with s = bits + 1 + msb(w) − msb(n): its msb is bits + 1 + msb(w), so the
  // 64-bit path holds exactly while bits + 1 + msb(w) ≤ 62; a denominator w·2^−s likewise.
  for (int bits : {24, 32, 45}) {
    const int mw_in = 62 - bits - 1;  // msb(w) at the limit
    Tally a, b;
    const FxFloat n{false, (uint64_t)0xABCDEF, -7};
    const FxFloat w_in{false, ((uint64_t)1 << mw_in) | 12345, 3}, w_out{false, ((uint64_t)1 << (mw_in + 1)) | 12345, 3};
    check_quot(a, n, w_in, bits);
    check_quot(b, n, w_out, bits);
    EXPECT_EQ(a.fast, 1u) << bits;
    EXPECT_EQ(b.fast, 0u) << bits;
    expect_clean(a, "num in"), expect_clean(b, "num out");
    // s < 0: den = w.sig·2^−s has msb(n) − bits − 1: in while msb(n) ≤ 62 + ... (always for 64-bit n)
    Tally c;
    const FxFloat big{true, ~(uint64_t)0, 5}, small{false, 3, 0};
    check_quot(c, big, small, bits);
    EXPECT_EQ(c.fast, 1u);
    expect_clean(c, "den");
  }
  // bits 61 (in) and 62 (out); results that round up to 2^bits (carry).
  Tally a, b, t;
  const FxFloat one{false, 1, 0}, eight{false, 1, 3};  // num = 2^(bits + 1): in at bits 61
  check_quot(a, one, eight, kAttrFast64Bits);
  check_quot(b, one, eight, kAttrFast64Bits + 1);
  EXPECT_EQ(a.fast, 1u);
  EXPECT_EQ(b.fast, 0u);
  for (int bits = 2; bits <= 40; ++bits) {
    const uint64_t allones = ((uint64_t)1 << bits) - 1;
    check_quot(t, FxFloat{false, 2 * allones + 1, 0}, FxFloat{false, 2, 0}, bits);  // carry to 2^bits
    check_quot(t, FxFloat{false, 2 * allones + 1, 0}, FxFloat{false, 1, 0}, bits);  // ties
  }
  expect_clean(a, "bits 61"), expect_clean(b, "bits 62"), expect_clean(t, "carries");
}

TEST(AttrFast64, RoundScaledSumExhaustiveAtNineBitsEqualsTheReference) {
  Tally t;
  for (int64_t m = -512; m <= 512; ++m)
    for (int e = -12; e <= 6; ++e)
      for (int64_t c = -6; c <= 6; ++c)
        for (int sh = 0; sh <= 3; ++sh) check_rss(t, m, e, c, sh);
  expect_clean(t, "round_scaled_sum64");
  EXPECT_EQ(t.fast, t.cases);
}

TEST(AttrFast64, RoundScaledSumRangeTestFlipsAtItsBounds) {
  const int64_t mtop = (int64_t)1 << kSnapFast64Bits, ctop = (int64_t)1 << (kSnapFast64Bits - 1);
  Tally in, out;
  for (int64_t s : {1, -1}) {
    check_rss(in, s * (mtop - 1), -3, 17, 1);
    check_rss(out, s * mtop, -3, 17, 1);
    check_rss(in, 12345, -3, s * (ctop - 1), 1);
    check_rss(out, 12345, -3, s * ctop, 1);
    // e ≥ 0: |m·2^e| just below / at 2^(kSnapFast64Bits − 1).
    check_rss(in, s * (((int64_t)1 << (kSnapFast64Bits - 4)) - 1), 3, s * (ctop - 1), 1);
    check_rss(out, s * ((int64_t)1 << (kSnapFast64Bits - 4)), 3, 5, 1);
    // e < 0: shifts kSnapFast64Bits (in) and kSnapFast64Bits + 1 (out).
    check_rss(in, s * (mtop - 1), -kSnapFast64Bits, s * (ctop - 1), 0);
    check_rss(out, s * (mtop - 1), -kSnapFast64Bits - 1, 3, 0);
    // sh + 2 ≤ 62.
    check_rss(in, s * 99, -2, 7, 60);
    check_rss(out, s * 99, -2, 7, 61);
  }
  EXPECT_EQ(in.fast, in.cases);
  EXPECT_EQ(out.fast, 0u);
  expect_clean(in, "in"), expect_clean(out, "out");
  // Ties at every step: m·2^e + c = (2j + 1)/2 for sh = 1 and the guard / sticky combinations.
  Tally t;
  for (int64_t m = -40; m <= 40; ++m)
    for (int k = 1; k <= 8; ++k)
      check_rss(t, m * ((int64_t)1 << k) + 1, -k - 1, -m, 1), check_rss(t, m * ((int64_t)1 << k), -k - 1, m, 1);
  expect_clean(t, "ties");
}

TEST(AttrFast64, AlignBlockExhaustiveAtSixBitsEqualsTheReference) {
  Tally t;
  for (int bits : {3, 6})
    for (uint64_t a = 0; a < 64; ++a)
      for (uint64_t b = 0; b < 64; ++b)
        for (int ea = -5; ea <= 5; ++ea)
          for (int eb = -5; eb <= 5; ++eb)
            for (const FxFloat& c : {FxFloat{}, FxFloat{true, 5, 0}, FxFloat{false, 63, 3}}) {
              const FxFloat v[3] = {FxFloat{(a & 1) != 0, a, ea}, FxFloat{(b & 2) != 0, b, eb}, c};
              check_align(t, v, bits);
            }
  expect_clean(t, "align_block");
  EXPECT_EQ(t.fast, t.cases);
}

TEST(AttrFast64, AlignBlockRangeTestFlipsAtShift62AndAt63BitSignificands) {
  Tally in, out;
  for (int bits : {24, 40, 62}) {
    // A right shift of 62 (in) and 63 (out): lead − (bits − 1) − exp.
    for (int sh : {61, 62, 63, 64}) {
      for (uint64_t sig : {(uint64_t)1, (uint64_t)3 << 60, ((uint64_t)1 << 62) + 1, ((uint64_t)1 << 61) | 1}) {
        const FxFloat big{false, 1, 100}, small{true, sig, 100 - (bits - 1) - sh};
        if (small.lead_exp() > 100) continue;
        const FxFloat v[3] = {big, small, FxFloat{}};
        check_align(sh <= 62 ? in : out, v, bits);
      }
    }
    // A significand of 63 bits (in) and 64 bits (out).
    const FxFloat s63{false, ((uint64_t)1 << 62) | 12345, 0}, s64{true, ((uint64_t)1 << 63) | 12345, -1};
    const FxFloat v63[3] = {s63, FxFloat{false, 7, 10}, FxFloat{}}, v64[3] = {s64, FxFloat{false, 7, 10}, FxFloat{}};
    check_align(in, v63, bits);
    check_align(out, v64, bits);
  }
  EXPECT_EQ(in.fast, in.cases);
  EXPECT_EQ(out.fast, 0u);
  expect_clean(in, "in"), expect_clean(out, "out");
  // Ties: x·2^−sh = j + ½ for even and odd j (bits 62, the top value's lead exponent 100, so the
  // block exponent is 39 and a value at exponent 39 − sh is shifted right by sh).
  Tally t;
  for (uint64_t j = 0; j < 8; ++j)
    for (int sh = 1; sh <= 57; sh += 7) {
      const FxFloat top{false, 1, 100}, tie{(j & 1) != 0, (2 * j + 1) << (sh - 1), 39 - sh};
      const FxFloat v[3] = {top, tie, FxFloat{false, ((uint64_t)1 << 40) - 1, 5}};
      check_align(t, v, 62);
    }
  EXPECT_EQ(t.fast, t.cases);
  expect_clean(t, "ties");
}

// attr_depth_q's int64 path (docs/speed.md "Session 12: per triangle": a branchless rounding)
// against depth_q_reference (RNE(z·M / 2^db) from the exact product): both depth formats, every z below 2^18, the ties (z ≡ 2^(db−1) mod 2^db: z·M ≡ −z)
// of both parities, z at 2^z_frac_bits for z_frac_bits 16 … 40, both sides of the int64
// product bound (z·M at INT64_MAX, where the i128 path takes over: z_frac_bits 40 at D24
// reaches 2^64), and 10^6 random z ≤ 2^40.
TEST(AttrFast64, AttrDepthQEqualsTheExactRoundingOnBothSidesOfTheProductBound) {
  std::mt19937_64 g(0xD3B7);
  uint64_t cases = 0, above_bound = 0;
  for (const DepthFormat f : {DepthFormat::D16, DepthFormat::D24}) {
    RasterConfig rc;
    rc.depth_format = f;
    const int db = rc.depth_bits();
    const uint64_t M = ((uint64_t)1 << db) - 1;
    const auto check = [&](uint64_t z) {
      ++cases;
      if (z > (uint64_t)INT64_MAX / M) ++above_bound;
      ASSERT_EQ(attr_depth_q(rc, z), depth_q_reference(db, z)) << "db " << db << " z " << z;
    };
    for (uint64_t z = 0; z < ((uint64_t)1 << 18); ++z) check(z);
    for (uint64_t j = 0; j < 64; ++j) check(((uint64_t)1 << (db - 1)) + j * ((uint64_t)1 << db));  // ties
    for (int zf = 16; zf <= 40; ++zf)
      for (int64_t d = -2; d <= 0; ++d) check(((uint64_t)1 << zf) + (uint64_t)d);
    const uint64_t bound = (uint64_t)INT64_MAX / M;
    for (uint64_t z : {bound - 1, bound, bound + 1, bound + 2}) check(z);
    for (int i = 0; i < 500000; ++i) check(g() >> 24 >> (g() % 24));  // z < 2^40
  }
  EXPECT_GT(cases, 1000000u);
  EXPECT_GT(above_bound, 100u);  // the i128 path is reached too
}

TEST(AttrFast64, MillionRandomCasesEqualTheReferenceOnBothSidesOfEveryRangeTest) {
  run_random_rounds(0x5E551049, 1000000);
}

TEST(AttrFast64, Float32VerticesTakeTheFastPathsAtTheDefaultWidths) {
  // Vertices as the bunny's: float32 x, y, z, w with |x|, |y| ≤ w, 0 < z < w, a 1024 viewport.
  std::mt19937_64 g(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.01f, 1.0f);
  const RasterConfig rc;
  Tally t, window, quot;
  for (int i = 0; i < 200000; ++i) {
    const float w = pos(g) * 8.0f, x = u(g) * w, z = pos(g) * w;
    const auto fx = [](float f) {
      bool nan = false, inf = false;
      return convert_input(f, nan, inf);
    };
    const FxFloat W = fx(w), X = fx(x), Z = fx(z);
    int64_t v;
    const bool fw = rne_quotient_plus64(X.neg, X.sig * 1024, X.exp - W.exp + rc.attr_subpixel_bits - 1, W.sig,
                                        (int64_t)1024 << (rc.attr_subpixel_bits - 1), &v);
    window.note(fw, true, [] { return std::string(); });
    FxFloat q;
    quot.note(attr_quotient64(FxFloat{false, 1, 0}, W, rc.attr_sig_bits, &q), true, [] { return std::string(); });
    check_window(t, X, W, 1024, 0, rc);
    check_depth(t, Z, W, rc);
    check_quot(t, X, W, rc.attr_sig_bits);
  }
  expect_clean(t, "float32 vertices");
  EXPECT_EQ(window.fast, window.cases);
  EXPECT_EQ(quot.fast, quot.cases);
}

}  // namespace
}  // namespace fxr::fast64

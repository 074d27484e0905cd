// Texture address unit (model/stages/texaddr.hpp) against an exact reference written here in
// GMP rationals: u = (−1)^neg · sig · 2^exp as an mpq_class (no exponent reduction, no shift
// cap), floor / round-half-even on the rational, mathematical modulo with mpz. Exhaustive over
// small texture sizes, every mode and filter, every coordinate on a 2^−10 grid of [−2.5, 2.5]
// (0, ±1, the texel edges, the bilinear ties), plus huge and tiny exponents.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "model/config/param.hpp"
#include "model/stages/texaddr.hpp"

namespace fxr {
namespace {

const TexWrap kWraps[] = {TexWrap::Repeat, TexWrap::MirroredRepeat, TexWrap::ClampToEdge, TexWrap::ClampToBorder};

mpq_class exact_value(const FxFloat& u) {
  mpz_class m(0);
  mpz_import(m.get_mpz_t(), 1, 1, sizeof u.sig, 0, 0, &u.sig);
  mpq_class q(m);
  mpz_class p2(1);
  const unsigned long ae = u.exp < 0 ? (unsigned long)-u.exp : (unsigned long)u.exp;
  mpz_mul_2exp(p2.get_mpz_t(), p2.get_mpz_t(), ae);
  if (u.exp >= 0) q *= mpq_class(p2);
  else q /= mpq_class(p2);
  q.canonicalize();
  return u.neg ? mpq_class(-q) : q;
}

mpz_class floor_q(const mpq_class& q) {
  mpz_class r;
  mpz_fdiv_q(r.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  return r;
}

// The wrap rules written out independently on mpz.
void ref_wrap(TexWrap wrap, const mpz_class& i, uint32_t w, uint32_t* idx, bool* border) {
  const mpz_class W(w);
  *border = false;
  mpz_class r;
  switch (wrap) {
    case TexWrap::Repeat:
      mpz_fdiv_r(r.get_mpz_t(), i.get_mpz_t(), W.get_mpz_t());
      break;
    case TexWrap::MirroredRepeat: {
      const mpz_class w2 = 2 * W;
      mpz_fdiv_r(r.get_mpz_t(), i.get_mpz_t(), w2.get_mpz_t());
      if (r >= W) r = w2 - 1 - r;
      break;
    }
    case TexWrap::ClampToEdge:
    case TexWrap::ClampToBorder:
      if (wrap == TexWrap::ClampToBorder) *border = i < 0 || i >= W;
      r = i < 0 ? mpz_class(0) : (i >= W ? mpz_class(W - 1) : i);
      break;
  }
  *idx = (uint32_t)r.get_ui();
}

TexAxis reference(const TexAddrConfig& c, const FxFloat& u, uint32_t w) {
  const mpq_class x = exact_value(u) * mpq_class(w);
  TexAxis a;
  if (c.filter == TexFilter::Nearest) {
    ref_wrap(c.wrap, floor_q(x), w, &a.i0, &a.border0);
    a.i1 = a.i0;
    a.border1 = a.border0;
    return a;
  }
  const mpq_class t = x - mpq_class(1, 2);
  mpz_class i0 = floor_q(t);
  const mpz_class one_f = mpz_class(1) << c.weight_frac_bits;
  const mpq_class scaled = (t - mpq_class(i0)) * mpq_class(one_f);  // fraction · 2^F ∈ [0, 2^F)
  mpz_class wt = floor_q(scaled);
  const mpq_class rest = scaled - mpq_class(wt);
  if (rest > mpq_class(1, 2) || (rest == mpq_class(1, 2) && mpz_odd_p(wt.get_mpz_t()))) wt += 1;
  if (wt == one_f) {  // the fraction rounded up to 1: the blend of i0 + 1 with weight 0
    wt = 0;
    i0 += 1;
  }
  a.weight = (uint32_t)wt.get_ui();
  ref_wrap(c.wrap, i0, w, &a.i0, &a.border0);
  ref_wrap(c.wrap, mpz_class(i0 + 1), w, &a.i1, &a.border1);
  return a;
}

// k · 2^−g as a normalised FxFloat (msb of sig at sig_bits − 1), or zero.
FxFloat grid_point(int64_t k, int g, int sig_bits) {
  FxFloat u;
  u.neg = k < 0;
  uint64_t m = (uint64_t)(k < 0 ? -k : k);
  int e = -g;
  if (m == 0) return u;
  while (!(m >> (sig_bits - 1))) {
    m <<= 1;
    --e;
  }
  u.sig = m;
  u.exp = e;
  return u;
}

std::string show(const TexAxis& a) {
  return "i0=" + std::to_string(a.i0) + " i1=" + std::to_string(a.i1) + " b0=" + std::to_string(a.border0) +
         " b1=" + std::to_string(a.border1) + " w=" + std::to_string(a.weight);
}

struct Counts {
  int64_t checked = 0, errors = 0;
};

void check_one(const TexAddrConfig& c, const FxFloat& u, uint32_t w, Counts* n) {
  const TexAxis got = texaddr_axis(c, u, w);
  const TexAxis exp = reference(c, u, w);
  ++n->checked;
  if (!(got == exp)) {
    if (++n->errors <= 20)
      ADD_FAILURE() << "MISMATCH texaddr filter=" << (int)c.filter << " wrap=" << (int)c.wrap << " W=" << w
                    << " F=" << c.weight_frac_bits << " u=" << (u.neg ? "-" : "") << u.sig << "*2^" << u.exp
                    << " got " << show(got) << " exp " << show(exp);
  }
}

TEST(TexAddr, ExhaustiveFineGridEveryModeMatchesExactReference) {
  constexpr int kGrid = 10;                         // step 2^−10
  constexpr int64_t kHalfRange = 5 << (kGrid - 1);  // ±2.5
  Counts n;
  for (uint32_t w : {1u, 2u, 3u, 4u, 5u, 7u, 8u})
    for (TexFilter f : {TexFilter::Nearest, TexFilter::Bilinear})
      for (int fb : {1, 4, 8})
        for (TexWrap wrap : kWraps) {
          if (f == TexFilter::Nearest && fb != 8) continue;  // F does not affect nearest
          TexAddrConfig c;
          c.size_bits = 3;
          c.filter = f;
          c.weight_frac_bits = fb;
          c.wrap = wrap;
          for (int64_t k = -kHalfRange; k <= kHalfRange; ++k) check_one(c, grid_point(k, kGrid, c.sig_bits), w, &n);
          FxFloat negzero;
          negzero.neg = true;
          check_one(c, negzero, w, &n);
        }
  // 7 sizes × (4 nearest + 12 bilinear) modes × (5121 grid points + −0).
  EXPECT_EQ(n.checked, 7 * 16 * (2 * kHalfRange + 2));
  std::printf("texaddr: checked=%lld errors=%lld\n", (long long)n.checked, (long long)n.errors);
  EXPECT_EQ(n.errors, 0);
}

TEST(TexAddr, HugeAndTinyExponentsMatchExactReference) {
  std::mt19937_64 rng(15);
  Counts n;
  for (uint32_t w : {1u, 3u, 4u, 6u, 4096u, 4095u})
    for (TexFilter f : {TexFilter::Nearest, TexFilter::Bilinear})
      for (TexWrap wrap : kWraps) {
        TexAddrConfig c;
        c.filter = f;
        c.wrap = wrap;
        for (int exp = -300; exp <= 300; exp += (exp > -40 && exp < 10) ? 1 : 7)
          for (int rep = 0; rep < 6; ++rep) {
            FxFloat u;
            u.neg = rep & 1;
            u.sig = (uint64_t{1} << (c.sig_bits - 1)) | (rng() & ((uint64_t{1} << (c.sig_bits - 1)) - 1));
            if (rep == 2) u.sig = uint64_t{1} << (c.sig_bits - 1);  // a power of two
            if (rep == 3) u.sig = (uint64_t{1} << c.sig_bits) - 1;  // all ones
            u.exp = exp;
            check_one(c, u, w, &n);
          }
      }
  EXPECT_GT(n.checked, 30000);
  std::printf("texaddr: checked=%lld errors=%lld\n", (long long)n.checked, (long long)n.errors);
  EXPECT_EQ(n.errors, 0);
}

TEST(TexAddr, RandomCoordinatesLargeTexturesMatchExactReference) {
  std::mt19937_64 rng(1515);
  Counts n;
  for (int i = 0; i < 200000; ++i) {
    TexAddrConfig c;
    c.size_bits = 1 + (int)(rng() % 16);
    c.sig_bits = 8 + (int)(rng() % 25);
    c.weight_frac_bits = 1 + (int)(rng() % 16);
    c.filter = (rng() & 1) ? TexFilter::Bilinear : TexFilter::Nearest;
    c.wrap = kWraps[rng() % 4];
    const uint32_t w = 1 + (uint32_t)(rng() % (uint64_t{1} << c.size_bits));
    FxFloat u;
    u.neg = rng() & 1;
    u.sig = (uint64_t{1} << (c.sig_bits - 1)) | (rng() & ((uint64_t{1} << (c.sig_bits - 1)) - 1));
    u.exp = -(c.sig_bits - 1) + (int)(rng() % 12) - 8;  // |u| around [2^−8, 2^4)
    check_one(c, u, w, &n);
  }
  std::printf("texaddr: checked=%lld errors=%lld\n", (long long)n.checked, (long long)n.errors);
  EXPECT_EQ(n.errors, 0);
}

TEST(TexAddr, DirectedSpecialCases) {
  TexAddrConfig c;
  const FxFloat zero;
  const FxFloat one = grid_point(1, 0, c.sig_bits);
  const FxFloat minus_one = grid_point(-1, 0, c.sig_bits);
  // Nearest, repeat: 0 → texel 0; 1 → texel 0 (next period); −1 → texel 0.
  EXPECT_EQ(texaddr_axis(c, zero, 8).i0, 0u);
  EXPECT_EQ(texaddr_axis(c, one, 8).i0, 0u);
  EXPECT_EQ(texaddr_axis(c, minus_one, 8).i0, 0u);
  EXPECT_EQ(texaddr_axis(c, grid_point(-1, 10, c.sig_bits), 8).i0, 7u);  // just below 0
  c.wrap = TexWrap::ClampToBorder;
  EXPECT_TRUE(texaddr_axis(c, one, 8).border0);  // u = 1 lies outside [0, 1)
  EXPECT_FALSE(texaddr_axis(c, zero, 8).border0);
  c.filter = TexFilter::Bilinear;
  const TexAxis z = texaddr_axis(c, zero, 8);  // t = −½: i0 = −1 (border), weight ½
  EXPECT_TRUE(z.border0);
  EXPECT_FALSE(z.border1);
  EXPECT_EQ(z.i1, 0u);
  EXPECT_EQ(z.weight, 1u << (c.weight_frac_bits - 1));
  EXPECT_THROW(texaddr_axis(c, zero, 0), std::invalid_argument);
  EXPECT_THROW(texaddr_axis(c, zero, (1u << c.size_bits) + 1), std::invalid_argument);
  FxFloat wide;
  wide.sig = uint64_t{1} << c.sig_bits;
  EXPECT_THROW(texaddr_axis(c, wide, 8), std::invalid_argument);
}

TEST(TexAddr, ConfigIsValidatedAndCosted) {
  TexAddrConfig c;
  EXPECT_NO_THROW(texaddr_validate(c));
  EXPECT_EQ(texaddr_cost(c).latency, 1);
  c.weight_frac_bits = 0;
  EXPECT_THROW(texaddr_validate(c), ConfigError);
}

}  // namespace
}  // namespace fxr

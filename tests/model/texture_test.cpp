// Texel fetch and filter (model/stages/texfilter.hpp) against an exact GMP blend, the texture
// references of reference/texture_ref.hpp against the texture address unit and each other, the
// checker texture, and PNG write / read.
#include <cmath>
#include <cstdio>
#include <random>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include "frontend/texture.hpp"
#include "model/stages/texaddr.hpp"
#include "model/stages/texfilter.hpp"
#include "reference/reference.hpp"
#include "reference/texture_ref.hpp"

using namespace fxr;

namespace {

const TexWrap kWraps[] = {TexWrap::Repeat, TexWrap::MirroredRepeat, TexWrap::ClampToEdge, TexWrap::ClampToBorder};

Image random_image(std::mt19937_64& rng, int w, int h) {
  Image im(w, h, 0);
  for (auto& c : im.rgba) c = (uint32_t)rng();
  return im;
}

FxFloat random_coord(std::mt19937_64& rng, int sig_bits) {
  FxFloat u;
  u.neg = rng() & 1;
  u.sig = (rng() & ((1ull << sig_bits) - 1)) | (1ull << (sig_bits - 1));
  u.exp = -(int)(rng() % 12) - sig_bits + 3;  // |u| in [2^−10, 8)
  return u;
}

// Independent: the blend written on rationals, one round-half-even at the end.
uint32_t exact_filter(const TexAddrOut& a, int f, const Image& im, uint32_t border) {
  const mpq_class one(1);
  const mpq_class ws1(mpz_class(a.s.weight), mpz_class(1) << f), wt1(mpz_class(a.t.weight), mpz_class(1) << f);
  const mpq_class ws[2] = {one - ws1, ws1}, wt[2] = {one - wt1, wt1};
  const uint32_t si[2] = {a.s.i0, a.s.i1}, ti[2] = {a.t.i0, a.t.i1};
  const bool sb[2] = {a.s.border0, a.s.border1}, tb[2] = {a.t.border0, a.t.border1};
  uint32_t out = 0;
  for (int k = 0; k < 4; ++k) {
    mpq_class c(0);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const uint32_t texel = sb[i] || tb[j] ? border : im.at((int)si[i], (int)ti[j]);
        c += ws[i] * wt[j] * mpq_class((texel >> (8 * k)) & 0xff);
      }
    mpz_class fl;
    mpz_fdiv_q(fl.get_mpz_t(), c.get_num_mpz_t(), c.get_den_mpz_t());
    const mpq_class rest = c - mpq_class(fl);
    if (rest > mpq_class(1, 2) || (rest == mpq_class(1, 2) && mpz_odd_p(fl.get_mpz_t()))) fl += 1;
    out |= (uint32_t)fl.get_ui() << (8 * k);
  }
  return out;
}

}  // namespace

TEST(TexFilter, EveryFilterAndWrapMatchesTheExactBlend) {
  std::mt19937_64 rng(15);
  int64_t checked = 0;
  for (int i = 0; i < 20000; ++i) {
    TexAddrConfig c;
    c.filter = rng() & 1 ? TexFilter::Bilinear : TexFilter::Nearest;
    c.wrap = kWraps[rng() % 4];
    c.weight_frac_bits = 1 + (int)(rng() % 16);
    const int w = 1 + (int)(rng() % 9), h = 1 + (int)(rng() % 9);
    const Image im = random_image(rng, w, h);
    const uint32_t border = (uint32_t)rng();
    TexAddrIn in;
    in.u = random_coord(rng, c.sig_bits);
    in.v = random_coord(rng, c.sig_bits);
    in.width = (uint32_t)w;
    in.height = (uint32_t)h;
    const TexAddrOut a = texaddr(c, in);
    const uint32_t got = texfilter(c, a, TexelView{im.rgba.data(), (uint32_t)w, (uint32_t)h}, border);
    ASSERT_EQ(got, exact_filter(a, c.weight_frac_bits, im, border))
        << "filter " << (int)c.filter << " wrap " << (int)c.wrap << " F " << c.weight_frac_bits;
    if (c.filter == TexFilter::Nearest) {  // the texel itself (or the border colour)
      const uint32_t texel = a.s.border0 || a.t.border0 ? border : im.at((int)a.s.i0, (int)a.t.i0);
      ASSERT_EQ(got, texel);
    }
    ++checked;
  }
  EXPECT_EQ(checked, 20000);
}

TEST(TexFilter, ClampToBorderShowsTheBorderColourOutsideAndBlendsAtTheEdge) {
  TexAddrConfig c;
  c.filter = TexFilter::Bilinear;
  c.wrap = TexWrap::ClampToBorder;
  Image im(2, 2, pack_rgba(200, 200, 200, 255));
  const uint32_t border = pack_rgba(0, 0, 0, 0);
  TexAddrIn in;
  in.width = in.height = 2;
  // u = v = −1: both texels of each axis outside: the border colour.
  in.u = FxFloat{true, 1, 0};
  in.v = FxFloat{true, 1, 0};
  EXPECT_EQ(texfilter(c, texaddr(c, in), TexelView{im.rgba.data(), 2, 2}, border), border);
  // u = 0 (texel −1 and 0 with weight ½ each), v = ½ (inside): half the texel, half the border.
  in.u = FxFloat{};
  in.v = FxFloat{false, 1, -1};
  EXPECT_EQ(texfilter(c, texaddr(c, in), TexelView{im.rgba.data(), 2, 2}, border), pack_rgba(100, 100, 100, 128));
}

TEST(TextureRef, CorrectlyRoundedExactAddressEqualsTheUnit) {
  // The report's exact reference (GMP) and the unit (integers) are written independently.
  std::mt19937_64 rng(16);
  for (int i = 0; i < 50000; ++i) {
    TexAddrConfig c;
    c.filter = rng() & 1 ? TexFilter::Bilinear : TexFilter::Nearest;
    c.wrap = kWraps[rng() % 4];
    c.weight_frac_bits = 1 + (int)(rng() % 16);
    const uint32_t size = 1 + (uint32_t)(rng() % 4096);
    const FxFloat u = random_coord(rng, c.sig_bits);
    ASSERT_TRUE(exact_tex_axis_rounded(c, to_mpq(u), size) == texaddr_axis(c, u, size))
        << u.neg << " " << u.sig << " " << u.exp << " size " << size;
  }
}

TEST(TextureRef, DoubleAddressAgreesWithTheExactOneAwayFromTies) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> coord(-3.0, 3.0);
  int64_t compared = 0;
  for (int i = 0; i < 50000; ++i) {
    const TexFilter f = rng() & 1 ? TexFilter::Bilinear : TexFilter::Nearest;
    const TexWrap w = kWraps[rng() % 4];
    const uint32_t size = 1 + (uint32_t)(rng() % 300);
    const double u = coord(rng);
    const RefTexAxis d = ref_tex_axis(f, w, u, size), e = exact_ref_axis(f, w, mpq_class(u), size);
    // u·size − ½ in double is within a few ulps of the exact value; skip points that close to a
    // texel boundary, where the two may take different sides.
    const double x = u * size - (f == TexFilter::Bilinear ? 0.5 : 0.0);
    if (std::abs(x - std::round(x)) < 1e-9) continue;
    ++compared;
    ASSERT_EQ(d.i0, e.i0) << u << " " << size;
    ASSERT_EQ(d.i1, e.i1) << u << " " << size;
    ASSERT_EQ(d.border0, e.border0);
    ASSERT_EQ(d.border1, e.border1);
    ASSERT_NEAR(d.weight, e.weight, 1e-9);
    // The correctly rounded double address (the report's double level) away from weight ties.
    TexAddrConfig c;
    c.filter = f;
    c.wrap = w;
    c.weight_frac_bits = 1 + (int)(rng() % 16);
    const double y = x * std::ldexp(1.0, c.weight_frac_bits);
    if (std::abs(y - std::floor(y) - 0.5) < 1e-6) continue;
    ASSERT_TRUE(ref_tex_axis_rounded(c, u, size) == exact_tex_axis_rounded(c, mpq_class(u), size)) << u << " " << size;
  }
  EXPECT_GT(compared, 49000);
  // Spot values: u = 1 wraps to texel 0 and clamps to the last; −ε wraps to the last texel.
  EXPECT_EQ(ref_tex_axis(TexFilter::Nearest, TexWrap::Repeat, 1.0, 64).i0, 0u);
  EXPECT_EQ(ref_tex_axis(TexFilter::Nearest, TexWrap::ClampToEdge, 1.0, 64).i0, 63u);
  EXPECT_EQ(ref_tex_axis(TexFilter::Nearest, TexWrap::Repeat, -1e-300, 64).i0, 63u);
  EXPECT_EQ(ref_tex_axis(TexFilter::Nearest, TexWrap::MirroredRepeat, -1e-300, 64).i0, 0u);
  EXPECT_EQ(ref_tex_axis(TexFilter::Nearest, TexWrap::Repeat, std::nan(""), 64).i0, 0u);
  for (double huge : {1e308, -1e308, HUGE_VAL})  // u·size overflows: texel 0, no undefined conversion
    for (TexWrap w : kWraps) {
      EXPECT_EQ(ref_tex_axis(TexFilter::Bilinear, w, huge, 64).i0, 0u);
      TexAddrConfig c;
      c.filter = TexFilter::Bilinear;
      c.wrap = w;
      EXPECT_LT(ref_tex_axis_rounded(c, huge, 64).i1, 64u);
    }
}

TEST(Checker, SquaresAlternateFromColourA) {
  const uint32_t a = pack_rgba(255, 0, 0), b = pack_rgba(0, 0, 255);
  const Texture t = make_checker(64, 8, a, b);
  EXPECT_EQ(t.image.at(0, 0), a);
  EXPECT_EQ(t.image.at(7, 7), a);
  EXPECT_EQ(t.image.at(8, 0), b);
  EXPECT_EQ(t.image.at(0, 8), b);
  EXPECT_EQ(t.image.at(8, 8), a);
  EXPECT_EQ(t.image.at(63, 0), b);
  EXPECT_THROW(make_checker(64, 7, a, b), ConfigError);
}

TEST(Png, WriteThenLoadKeepsPixelsAndOrientation) {
  Image img(5, 3, pack_rgba(1, 2, 3));
  img.at(0, 0) = pack_rgba(255, 0, 0);  // bottom left
  img.at(4, 2) = pack_rgba(0, 255, 0, 128);  // top right
  const std::string path = ::testing::TempDir() + "fxr_png_test.png";
  write_png(path, img);
  const Texture t = load_png_texture(path);
  EXPECT_EQ(t.image.width, 5);
  EXPECT_EQ(t.image.height, 3);
  EXPECT_EQ(t.image.rgba, img.rgba);
  std::remove(path.c_str());
  EXPECT_THROW(load_png_texture("/nonexistent.png"), ConfigError);
}

TEST(Color, HexParsing) {
  uint32_t c = 0;
  EXPECT_TRUE(parse_hex_color("#10a0ff", &c));
  EXPECT_EQ(c, pack_rgba(0x10, 0xa0, 0xff));
  EXPECT_FALSE(parse_hex_color("10a0ff", &c));
  EXPECT_FALSE(parse_hex_color("#10a0fg", &c));
  // Lowercase only (docs/scene-format.md), like bits: patterns and vector files.
  EXPECT_FALSE(parse_hex_color("#10a0Ff", &c));
  EXPECT_FALSE(parse_hex_color("#10A0FF", &c));
}

// Texture addressing (floor(u·W), wrap / clamp) from FxFloat codes against exact GMP floors,
// the checker texture, and PNG write / read.
#include <cstdio>
#include <random>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include "frontend/texture.hpp"

using namespace fxr;

namespace {

// Independent: floor(u · size) from the exact rational, then wrap / clamp by definition.
int exact_texel(const FxFloat& u, int size, WrapMode wrap) {
  mpz_class s(std::to_string(u.sig));
  mpq_class q(s * size);
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 2, (unsigned long)std::abs(u.exp));
  if (u.exp >= 0) q *= p;
  else q /= p;
  if (u.neg) q = -q;
  mpz_class fl;
  mpz_fdiv_q(fl.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  if (wrap == WrapMode::Repeat) {
    mpz_class m;
    mpz_fdiv_r_ui(m.get_mpz_t(), fl.get_mpz_t(), (unsigned long)size);
    return (int)m.get_si();
  }
  if (fl < 0) return 0;
  if (fl >= size) return size - 1;
  return (int)fl.get_si();
}

}  // namespace

TEST(Texel, FloorOfUTimesSizeMatchesExactForRandomCodes) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200000; ++i) {
    FxFloat u;
    u.neg = rng() & 1;
    const int bits = 1 + (int)(rng() % 32);
    u.sig = (rng() & ((1ull << bits) - 1)) | (1ull << (bits - 1));
    u.exp = -(int)(rng() % 70) + 8;
    const int size = 1 + (int)(rng() % 4096);
    for (WrapMode w : {WrapMode::Repeat, WrapMode::Clamp})
      ASSERT_EQ(texel_index(u, size, w), exact_texel(u, size, w))
          << u.neg << " " << u.sig << " " << u.exp << " size " << size;
  }
}

TEST(Texel, EdgesOfTheUnitInterval) {
  const FxFloat one{false, 1, 0}, half{false, 1, -1}, minus_tiny{true, 1, -60}, zero{};
  EXPECT_EQ(texel_index(one, 64, WrapMode::Repeat), 0);    // u = 1 wraps to texel 0
  EXPECT_EQ(texel_index(one, 64, WrapMode::Clamp), 63);    // and clamps to the last texel
  EXPECT_EQ(texel_index(half, 64, WrapMode::Repeat), 32);
  EXPECT_EQ(texel_index(minus_tiny, 64, WrapMode::Repeat), 63);  // floor(−ε) = −1 → 63
  EXPECT_EQ(texel_index(minus_tiny, 64, WrapMode::Clamp), 0);
  EXPECT_EQ(texel_index(zero, 64, WrapMode::Clamp), 0);
  EXPECT_EQ(texel_index_ref(-1e-300, 64, WrapMode::Repeat), 63);
  EXPECT_EQ(texel_index_ref(2.5, 64, WrapMode::Repeat), 32);
  EXPECT_EQ(texel_index_ref(2.5, 64, WrapMode::Clamp), 63);
}

TEST(Checker, SquaresAlternateFromColourA) {
  const uint32_t a = pack_rgba(255, 0, 0), b = pack_rgba(0, 0, 255);
  const Texture t = make_checker(64, 8, a, b, WrapMode::Repeat);
  EXPECT_EQ(t.image.at(0, 0), a);
  EXPECT_EQ(t.image.at(7, 7), a);
  EXPECT_EQ(t.image.at(8, 0), b);
  EXPECT_EQ(t.image.at(0, 8), b);
  EXPECT_EQ(t.image.at(8, 8), a);
  EXPECT_EQ(t.image.at(63, 0), b);
  EXPECT_THROW(make_checker(64, 7, a, b, WrapMode::Repeat), ConfigError);
}

TEST(Png, WriteThenLoadKeepsPixelsAndOrientation) {
  Image img(5, 3, pack_rgba(1, 2, 3));
  img.at(0, 0) = pack_rgba(255, 0, 0);  // bottom left
  img.at(4, 2) = pack_rgba(0, 255, 0, 128);  // top right
  const std::string path = ::testing::TempDir() + "fxr_png_test.png";
  write_png(path, img);
  const Texture t = load_png_texture(path, WrapMode::Clamp);
  EXPECT_EQ(t.image.width, 5);
  EXPECT_EQ(t.image.height, 3);
  EXPECT_EQ(t.image.rgba, img.rgba);
  std::remove(path.c_str());
  EXPECT_THROW(load_png_texture("/nonexistent.png", WrapMode::Clamp), ConfigError);
}

TEST(Color, HexParsing) {
  uint32_t c = 0;
  EXPECT_TRUE(parse_hex_color("#10a0Ff", &c));
  EXPECT_EQ(c, pack_rgba(0x10, 0xa0, 0xff));
  EXPECT_FALSE(parse_hex_color("10a0ff", &c));
  EXPECT_FALSE(parse_hex_color("#10a0fg", &c));
}

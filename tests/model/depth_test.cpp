// Stage 8 (depth): codes against the exactly rounded linear-in-screen-space value (GMP), the
// compare functions, the write mask and the clear value, for D16 and D24.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "model/stages/depth.hpp"
#include "raster_ref.hpp"

using namespace fxr;
using namespace fxr::ref;

namespace {

int64_t rnd(std::mt19937_64& g, int64_t lo, int64_t hi) { return lo + (int64_t)(g() % (uint64_t)(hi - lo + 1)); }

Config cfg_for(DepthFormat f) {
  Config c;
  c.raster.depth_format = f;
  return c;
}

DrawState state(int w, int h) {
  DrawState st;
  st.viewport_w = w;
  st.viewport_h = h;
  return st;
}

// Exact code: RNE(Σ E_k z_k / Σ E_k · (2^db − 1) / 2^zf) — one rounding of the exact rational.
mpz_class ref_code(const Config& cfg, const SetupTriangle& t, int i, int j) {
  const Bary b = bary(t, cfg.raster.subpixel_bits, i, j);
  mpz_class zs = 0;
  for (int k = 0; k < 3; ++k) zs += b.e[k] * to_mpz_u(t.v[k].z);
  const mpz_class maxc = (mpz_class(1) << cfg.raster.depth_bits()) - 1;
  return rne(mpq_class(zs * maxc, b.sum << cfg.raster.z_frac_bits));
}

// Random triangle over a 64×64 viewport with z values drawn by `zgen`.
template <class Z>
SetupTriangle random_tri(std::mt19937_64& g, Z zgen) {
  SetupTriangle t;
  const int64_t S = 256;
  t.v[0].x = rnd(g, -8 * S, 72 * S), t.v[0].y = rnd(g, -8 * S, 72 * S);
  for (int k = 1; k < 3; ++k) {
    const int64_t r = (g() & 1) ? 6 * S : 60 * S;
    t.v[k].x = t.v[0].x + rnd(g, -r, r), t.v[k].y = t.v[0].y + rnd(g, -r, r);
  }
  for (int k = 0; k < 3; ++k) t.v[k].z = zgen();
  return t;
}

long check_exact(const Config& cfg, const SetupTriangle& t, long* frags) {
  long diffs = 0;
  for (const Fragment& f : all_fragments(cfg, state(64, 64), t)) {
    ++*frags;
    const mpz_class want = ref_code(cfg, t, f.x, f.y);
    if (want != f.depth && ++diffs <= 5)
      ADD_FAILURE() << "depth at (" << f.x << "," << f.y << ") got " << f.depth << " want " << want.get_str();
  }
  return diffs;
}

}  // namespace

TEST(Depth, CodesAreTheExactlyRoundedScreenLinearValue) {
  for (DepthFormat fmt : {DepthFormat::D16, DepthFormat::D24}) {
    const Config cfg = cfg_for(fmt);
    const uint64_t one = (uint64_t)1 << cfg.raster.z_frac_bits;
    std::mt19937_64 g(5);
    long frags = 0, diffs = 0;
    for (int n = 0; n < 1500; ++n) {
      const SetupTriangle t = random_tri(g, [&] { return (uint64_t)rnd(g, 0, (int64_t)one); });
      diffs += check_exact(cfg, t, &frags);
    }
    std::printf("depth %s: %ld fragments, %ld differences from the exact RNE code\n",
                fmt == DepthFormat::D16 ? "D16" : "D24", frags, diffs);
    EXPECT_GT(frags, 100000);
    EXPECT_EQ(diffs, 0);
  }
}

TEST(Depth, NearZeroAndNearOneAreExact) {
  for (DepthFormat fmt : {DepthFormat::D16, DepthFormat::D24}) {
    const Config cfg = cfg_for(fmt);
    const int64_t one = (int64_t)1 << cfg.raster.z_frac_bits;
    std::mt19937_64 g(6);
    long frags = 0, diffs = 0;
    for (int n = 0; n < 300; ++n) {
      const bool near_one = n & 1;
      const SetupTriangle t =
          random_tri(g, [&] { return (uint64_t)(near_one ? one - rnd(g, 0, 1 << 12) : rnd(g, 0, 1 << 12)); });
      diffs += check_exact(cfg, t, &frags);
      for (const Fragment& f : all_fragments(cfg, state(64, 64), t))
        ASSERT_LE(f.depth, depth_max_code(cfg.raster));
    }
    EXPECT_EQ(diffs, 0);
    // z exactly 0 and exactly 1 give codes 0 and 2^db − 1 everywhere.
    for (uint64_t z : {(uint64_t)0, (uint64_t)one}) {
      SetupTriangle t = random_tri(g, [&] { return z; });
      t.v[0].x = -1000, t.v[0].y = -1000, t.v[1].x = 40000, t.v[1].y = -1000, t.v[2].x = -1000, t.v[2].y = 40000;
      for (const Fragment& f : all_fragments(cfg, state(64, 64), t))
        ASSERT_EQ(f.depth, z ? depth_max_code(cfg.raster) : 0u);
    }
  }
}

TEST(Depth, ZAboveOneIsRejectedAsOutOfRange) {
  const Config cfg = cfg_for(DepthFormat::D24);
  SetupTriangle t;
  t.v[1].x = 5000, t.v[2].y = 5000;
  t.v[2].z = ((uint64_t)1 << cfg.raster.z_frac_bits) + 1;
  SetupOutcome o;
  EXPECT_TRUE(all_fragments(cfg, state(64, 64), t, &o).empty());
  EXPECT_EQ(o, SetupOutcome::RejectedRange);
}

namespace {

// A flat square [2, 12)² px at depth z (fraction of one), as two triangles.
std::vector<SetupTriangle> square(const Config& cfg, double z) {
  const uint64_t zc = (uint64_t)std::llround(z * (double)((uint64_t)1 << cfg.raster.z_frac_bits));
  SetupTriangle a, b;
  const int64_t lo = 2 * 256, hi = 12 * 256;
  a.v[0].x = lo, a.v[0].y = lo, a.v[1].x = hi, a.v[1].y = lo, a.v[2].x = hi, a.v[2].y = hi;
  b.v[0].x = lo, b.v[0].y = lo, b.v[1].x = hi, b.v[1].y = hi, b.v[2].x = lo, b.v[2].y = hi;
  for (int k = 0; k < 3; ++k) a.v[k].z = b.v[k].z = zc;
  return {a, b};
}

}  // namespace

TEST(Depth, EachCompareFunctionAgainstAStoredSquare) {
  // Square A at z = 0.5 first (Always), then square B at 0.25 / 0.5 / 0.75 with func.
  // Expected outcome per (func, B's depth vs A's) written out from the GL definitions.
  struct Case {
    DepthFunc f;
    bool pass_lt, pass_eq, pass_gt;  // B nearer, equal, farther
  };
  const Case cases[] = {{DepthFunc::Never, 0, 0, 0},   {DepthFunc::Less, 1, 0, 0},
                        {DepthFunc::Equal, 0, 1, 0},   {DepthFunc::LessEqual, 1, 1, 0},
                        {DepthFunc::Greater, 0, 0, 1}, {DepthFunc::NotEqual, 1, 0, 1},
                        {DepthFunc::GreaterEqual, 0, 1, 1}, {DepthFunc::Always, 1, 1, 1}};
  for (DepthFormat fmt : {DepthFormat::D16, DepthFormat::D24}) {
    const Config cfg = cfg_for(fmt);
    for (const Case& c : cases) {
      for (int rel = 0; rel < 3; ++rel) {
        const double zb = rel == 0 ? 0.25 : rel == 1 ? 0.5 : 0.75;
        DrawState st = state(16, 16);
        FrameOutput f;
        frame_begin(cfg, st, f);
        st.depth_func = DepthFunc::Always;
        for (auto& t : square(cfg, 0.5)) raster_triangle(cfg, st, t, f);
        const uint32_t code_a = f.depth[5 * 16 + 5];
        const uint64_t n_a = f.fragments.size();
        ASSERT_EQ(n_a, 100u);
        st.depth_func = c.f;
        for (auto& t : square(cfg, zb)) raster_triangle(cfg, st, t, f);
        const bool pass = rel == 0 ? c.pass_lt : rel == 1 ? c.pass_eq : c.pass_gt;
        EXPECT_EQ(f.fragments.size() - n_a, pass ? 100u : 0u) << (int)c.f << " rel " << rel;
        EXPECT_EQ(f.stats.fragments_depth_fail, pass ? 0u : 100u);
        const uint32_t code_b = (uint32_t)ref_code(cfg, square(cfg, zb)[0], 5, 5).get_ui();
        EXPECT_EQ(f.depth[5 * 16 + 5], pass ? code_b : code_a);
        EXPECT_EQ(f.depth[0], depth_max_code(cfg.raster));  // untouched pixels keep the clear value
      }
    }
  }
}

TEST(Depth, WriteMaskKeepsTheBuffer) {
  const Config cfg = cfg_for(DepthFormat::D24);
  DrawState st = state(16, 16);
  st.depth_write = false;
  FrameOutput f;
  frame_begin(cfg, st, f);
  for (auto& t : square(cfg, 0.5)) raster_triangle(cfg, st, t, f);
  EXPECT_EQ(f.stats.fragments_depth_pass, 100u);
  for (uint32_t d : f.depth) ASSERT_EQ(d, (1u << 24) - 1);
  st.depth_write = true;
  st.depth_test = false;  // test off: passes, never writes (GL)
  for (auto& t : square(cfg, 0.5)) raster_triangle(cfg, st, t, f);
  EXPECT_EQ(f.stats.fragments_depth_pass, 200u);
  for (uint32_t d : f.depth) ASSERT_EQ(d, (1u << 24) - 1);
}

TEST(Depth, BufferClearsToMaxCode) {
  for (DepthFormat fmt : {DepthFormat::D16, DepthFormat::D24}) {
    const Config cfg = cfg_for(fmt);
    FrameOutput f;
    frame_begin(cfg, state(7, 3), f);
    ASSERT_EQ(f.depth.size(), 21u);
    for (uint32_t d : f.depth) EXPECT_EQ(d, fmt == DepthFormat::D16 ? 65535u : 16777215u);
  }
}

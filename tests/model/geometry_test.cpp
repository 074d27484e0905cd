// Stages 1, 3 and 4 (input conversion, reciprocal + perspective divide, viewport + snap) against
// the GMP reference of tests/model/geom_ref.hpp, plus the hard cases of docs/references.md#spec-hard-cases that concern
// them. Expected values never come from the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "geom_ref.hpp"

using namespace fxr;
using namespace georef;

namespace {

// A clip-space vertex from NDC (x_n, y_n, z_n) and w: x_c = x_n·w etc. rounded to float32 (the
// scene front end's job; the model sees only the float32 values).
ClipVertex vtx(double xn, double yn, double zn, double w) {
  ClipVertex v;
  v.pos[0] = (float)(xn * w);
  v.pos[1] = (float)(yn * w);
  v.pos[2] = (float)(zn * w);
  v.pos[3] = (float)w;
  return v;
}

// Random triangle inside the view volume (trivially accepted), with nv varyings.
ClipTriangle random_inside(std::mt19937_64& rng, int nv, double wmin = 0.1, double wmax = 100.0) {
  std::uniform_real_distribution<double> u(-1, 1), z(0, 1), lw(std::log(wmin), std::log(wmax)),
      var(-1000, 1000);
  ClipTriangle t;
  for (auto& v : t.v) {
    v = vtx(u(rng), u(rng), z(rng), std::exp(lw(rng)));
    v.pos[2] = std::min(v.pos[2], v.pos[3]);  // keep 0 ≤ z ≤ w after float rounding
    for (int k = 0; k < nv; ++k) v.var[k] = (float)var(rng);
  }
  return t;
}

}  // namespace

TEST(Geometry, SnapIsRoundToNearestEvenOfExactProductAt4096) {
  Config cfg;
  std::mt19937_64 rng(1);
  const DrawState st = state(4096, 4096, 0, 0, 4);
  int diffs = 0, n = 0;
  for (int i = 0; i < 4000; ++i) {
    GeomOutcome o;
    diffs += compare_with_reference(cfg, st, random_inside(rng, 4), &o);
    n += o == GeomOutcome::Emitted;
  }
  EXPECT_EQ(diffs, 0);
  EXPECT_EQ(n, 4000);
}

TEST(Geometry, SnapIsExactForRandomViewportsAndFormats) {
  std::mt19937_64 rng(2);
  std::uniform_int_distribution<int> sub(0, 12), zb(16, 40), vb(8, 40), size(1, 5000), org(-3000, 3000);
  int diffs = 0;
  for (int i = 0; i < 3000; ++i) {
    Config cfg;
    cfg.raster.subpixel_bits = sub(rng);
    cfg.raster.z_frac_bits = zb(rng);
    cfg.raster.varying_sig_bits = vb(rng);
    DrawState st = state(size(rng), size(rng), org(rng), org(rng), 3);
    st.interp = (i & 1) ? InterpMode::Affine : InterpMode::Perspective;
    diffs += compare_with_reference(cfg, st, random_inside(rng, 3));
  }
  EXPECT_EQ(diffs, 0);
}

// docs/references.md#snapping: "float32 divide + float32 viewport formula snaps differently from exact rational
// round-to-nearest for about 3 % of random vertices at 4096 px". Measured here for the model's
// choice (exact snap of x_c·rcp(w)) and for the float32 formula, both against the exact snap of
// x_c / w_c. Reported, and bounded: the model never differs by more than one subpixel.
TEST(Geometry, SnapDifferencesFromExactDivisionAreMeasured) {
  Config cfg;
  std::mt19937_64 rng(3);
  const DrawState st = state(4096, 4096);
  const int s = cfg.raster.subpixel_bits;
  long model_diff = 0, f32_diff = 0, total = 0;
  long model_max = 0;
  for (int i = 0; i < 20000; ++i) {
    ClipTriangle t = random_inside(rng, 0);
    std::vector<SetupTriangle> out;
    RasterStats stats;
    ASSERT_EQ(geometry(cfg, st, t, 0, out, stats), GeomOutcome::Emitted);
    for (int j = 0; j < 3; ++j) {
      const float xc = t.v[j].pos[0], wc = t.v[j].pos[3];
      const mpz_class exact = rne_int((q_of_float(xc) / q_of_float(wc) + 1) * 2048 * pow2(s));
      const float xw = (xc / wc + 1.0f) * (4096 * 0.5f);
      const mpz_class f32 = rne_int(mpq_class((double)xw) * pow2(s));
      const long dm = std::labs(out[0].v[j].x - exact.get_si());
      model_diff += dm != 0;
      model_max = std::max(model_max, dm);
      f32_diff += f32 != exact;
      ++total;
    }
  }
  std::printf("snap at 4096 px, %ld vertices: model (x_c*rcp) differs from exact x_c/w_c in %.3f %% "
              "(max %ld subpixel); float32 divide+viewport differs in %.3f %%\n",
              total, 100.0 * model_diff / total, model_max, 100.0 * f32_diff / total);
  EXPECT_LE(model_max, 1);
}

TEST(Geometry, TrivialAcceptPassesTriangleThroughAndCounts) {
  Config cfg;
  const DrawState st = state(64, 32);
  ClipTriangle t;
  t.v[0] = vtx(-0.5, -0.5, 0.25, 2);
  t.v[1] = vtx(0.5, -0.5, 0.5, 2);
  t.v[2] = vtx(0, 0.5, 0.75, 2);
  std::vector<SetupTriangle> out;
  RasterStats stats;
  ASSERT_EQ(geometry(cfg, st, t, 42, out, stats), GeomOutcome::Emitted);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].prim, 42u);
  EXPECT_EQ(stats.prims_trivial_accept, 1u);
  EXPECT_EQ(stats.prims_clipped, 0u);
  EXPECT_EQ(stats.clip_vertices_created, 0u);
  // Hand-computed: x_w = (x_n + 1)·32, y_w = (y_n + 1)·16, times 2^8; z = z_n·2^32.
  EXPECT_EQ(out[0].v[0].x, 16 * 256);
  EXPECT_EQ(out[0].v[0].y, 8 * 256);
  EXPECT_EQ(out[0].v[1].x, 48 * 256);
  EXPECT_EQ(out[0].v[2].y, 24 * 256);
  EXPECT_EQ(out[0].v[0].z, 1ull << 30);
  EXPECT_EQ(out[0].v[2].z, 3ull << 30);
  EXPECT_EQ(q_of(out[0].v[0].rw), frac(1, 2));
}

// docs/references.md#spec-hard-cases: w ratios of 10^4 and more inside one triangle.
TEST(Geometry, WRatiosOf1e4AndMoreInOneTriangle) {
  Config cfg;
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1, 1), z(0, 1);
  const DrawState st = state(1920, 1080, 0, 0, 2);
  int diffs = 0;
  for (int i = 0; i < 2000; ++i) {
    const double ratio = std::pow(10.0, 4 + (i % 5));  // 1e4 … 1e8
    ClipTriangle t;
    t.v[0] = vtx(u(rng), u(rng), z(rng), 1e-3);
    t.v[1] = vtx(u(rng), u(rng), z(rng), 1e-3 * ratio);
    t.v[2] = vtx(u(rng), u(rng), z(rng), 1e-3 * std::sqrt(ratio));
    for (auto& v : t.v) {
      v.pos[2] = std::min(v.pos[2], v.pos[3]);
      v.var[0] = (float)u(rng);
      v.var[1] = (float)(1e6 * u(rng));
    }
    diffs += compare_with_reference(cfg, st, t);
  }
  EXPECT_EQ(diffs, 0);
}

// docs/references.md#spec-hard-cases: depth near 0 and near 1 (z_c = 0, tiny, z_c = w, one ulp below w).
TEST(Geometry, DepthNearZeroAndNearOne) {
  Config cfg;
  const DrawState st = state(256, 256);
  const float w = 3.0f;
  const float zs[] = {0.0f, -0.0f, 1e-30f, 1e-10f, std::nextafter(w, 0.0f), w, w * 0.5f};
  for (float z0 : zs) {
    ClipTriangle t;
    t.v[0] = vtx(-0.5, -0.5, 0, w);
    t.v[1] = vtx(0.5, -0.5, 0, w);
    t.v[2] = vtx(0, 0.5, 0, w);
    for (auto& v : t.v) v.pos[2] = z0;
    EXPECT_EQ(compare_with_reference(cfg, st, t), 0) << "z_c = " << z0;
    std::vector<SetupTriangle> out;
    RasterStats stats;
    ASSERT_EQ(geometry(cfg, st, t, 0, out, stats), GeomOutcome::Emitted);
    const uint64_t one = 1ull << cfg.raster.z_frac_bits;
    if (z0 == 0) {
      EXPECT_EQ(out[0].v[0].z, 0u);
    }
    if (z0 == w) {
      EXPECT_EQ(out[0].v[0].z, one);
    }
    if (z0 == std::nextafter(w, 0.0f)) {
      EXPECT_LT(out[0].v[0].z, one);
    }
  }
}

// Varyings with large magnitudes and ranges (docs/references.md#spec-hard-cases), both interpolation modes.
TEST(Geometry, VaryingsWithLargeMagnitudesMatchReference) {
  Config cfg;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> e(-120, 120), u(-1, 1);
  int diffs = 0;
  for (int i = 0; i < 1000; ++i) {
    DrawState st = state(800, 600, 0, 0, kMaxVaryings);
    st.interp = (i & 1) ? InterpMode::Affine : InterpMode::Perspective;
    ClipTriangle t = random_inside(rng, 0, 1e-20, 1e20);
    for (auto& v : t.v)
      for (int k = 0; k < kMaxVaryings; ++k) v.var[k] = (float)(u(rng) * std::pow(2.0, e(rng)));
    diffs += compare_with_reference(cfg, st, t);
  }
  EXPECT_EQ(diffs, 0);
}

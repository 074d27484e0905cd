// NaN / ±Inf in a varying (docs/pipeline.md, stage 1): the primitive is rasterised with coverage
// and depth exactly as if its varyings were finite, the non-finite value stands for 0 (NaN) or
// ±FLT_MAX (±Inf), and the primitive is counted in prims_varying_nonfinite. Positions with NaN /
// Inf stay rejected.
//
// Expected values: the same triangles with finite varyings run through the unit (coverage, depth,
// the other varyings: an exact, bit-for-bit comparison), the same triangles with the values the
// rule names written in by this test (std::numeric_limits<float>::max(), 0), and the exact GMP
// geometry reference of tests/model/geom_ref.hpp, which applies the rule on its own.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

#include "geom_ref.hpp"
#include "model/unit/raster_unit.hpp"

using namespace fxr;
using namespace georef;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();
const float kMax = std::numeric_limits<float>::max();

// Non-finite varying inputs: quiet and signalling NaN with payloads and both signs, ±Inf.
const uint32_t kNonFiniteBits[] = {0x7fc00000u, 0xffc00000u, 0x7f800001u, 0xffbfffffu, 0x7fc12345u,
                                   0x7f800000u, 0xff800000u};

// What the rule says a non-finite varying stands for, written independently of the model.
float rule_value(float f) {
  if (std::isnan(f)) return 0.0f;
  if (std::isinf(f)) return f < 0 ? -kMax : kMax;
  return f;
}

struct Scene {
  DrawState st;
  std::vector<ClipTriangle> finite;     // the triangles with finite varyings
  std::vector<ClipTriangle> nonfinite;  // the same with some varyings made NaN / ±Inf
  std::vector<ClipTriangle> ruled;      // nonfinite with the rule's values written in
  std::vector<bool> hit;                // nonfinite[i] differs from finite[i]
};

// Random perspective triangles (w from 0.05 to 8, some crossing the near plane and the guard band),
// a third of them with one to three non-finite varying components.
Scene make_scene(uint64_t seed, int n, int nv) {
  Scene s;
  s.st = state(96, 80, 3, 5, nv);
  s.st.depth_func = DepthFunc::LessEqual;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> pos(-1.6f, 1.6f), zf(-0.2f, 1.1f), wf(0.05f, 8.0f), var(-40.0f, 40.0f);
  for (int t = 0; t < n; ++t) {
    ClipTriangle tri;
    for (auto& v : tri.v) {
      const float w = wf(rng);
      v.pos[0] = pos(rng) * w;
      v.pos[1] = pos(rng) * w;
      v.pos[2] = zf(rng) * w;
      v.pos[3] = w;
      for (int k = 0; k < nv; ++k) v.var[k] = var(rng);
    }
    ClipTriangle bad = tri;
    const bool hit = rng() % 3 == 0;
    if (hit) {
      const int m = 1 + (int)(rng() % 3);
      for (int j = 0; j < m; ++j)
        bad.v[rng() % 3].var[rng() % nv] = f32_from_bits(kNonFiniteBits[rng() % std::size(kNonFiniteBits)]);
    }
    ClipTriangle ruled = bad;
    for (auto& v : ruled.v)
      for (int k = 0; k < nv; ++k) v.var[k] = rule_value(v.var[k]);
    s.finite.push_back(tri);
    s.nonfinite.push_back(bad);
    s.ruled.push_back(ruled);
    s.hit.push_back(hit);
  }
  return s;
}

// Which varyings of primitive p are affected (a non-finite value at any vertex).
uint32_t affected_mask(const ClipTriangle& t, int nv) {
  uint32_t m = 0;
  for (const auto& v : t.v)
    for (int k = 0; k < nv; ++k)
      if (!std::isfinite(v.var[k])) m |= 1u << k;
  return m;
}

bool same_fx(const FxFloat& a, const FxFloat& b) {
  if (a.sig == 0 || b.sig == 0) return a.sig == b.sig;
  return a.neg == b.neg && a.sig == b.sig && a.exp == b.exp;
}

}  // namespace

// The pixel set, the depth codes and the finite varyings of every fragment are those of the same
// triangles with finite varyings, bit for bit; the statistics differ only in the new counter.
TEST(NonFiniteVarying, CoverageDepthAndOtherVaryingsEqualTheFiniteTriangle) {
  const int nv = 3;
  const Scene s = make_scene(81, 400, nv);
  const Config cfg;
  const FrameOutput a = run_raster_unit(cfg, s.st, s.finite);
  const FrameOutput b = run_raster_unit(cfg, s.st, s.nonfinite);
  ASSERT_EQ(a.fragments.size(), b.fragments.size());
  ASSERT_GT(a.fragments.size(), 5000u);  // the scene draws something
  size_t checked_other = 0, affected_frags = 0;
  for (size_t i = 0; i < a.fragments.size(); ++i) {
    const Fragment &fa = a.fragments[i], &fb = b.fragments[i];
    ASSERT_EQ(std::tie(fa.x, fa.y, fa.prim, fa.depth), std::tie(fb.x, fb.y, fb.prim, fb.depth)) << "fragment " << i;
    const uint32_t mask = affected_mask(s.nonfinite[fa.prim], nv);
    affected_frags += mask != 0;
    for (int k = 0; k < nv; ++k) {
      if (mask >> k & 1) continue;
      ++checked_other;
      ASSERT_TRUE(same_fx(fa.var[k], fb.var[k])) << "fragment " << i << " varying " << k;
    }
  }
  EXPECT_GT(affected_frags, 1000u);
  EXPECT_GT(checked_other, 10000u);
  EXPECT_EQ(a.depth, b.depth);
  uint64_t hits_drawn_or_not = 0;
  for (bool h : s.hit) hits_drawn_or_not += h;
  EXPECT_EQ(a.stats.prims_varying_nonfinite, 0u);
  EXPECT_EQ(b.stats.prims_varying_nonfinite, hits_drawn_or_not);
  RasterStats sb = b.stats;
  sb.prims_varying_nonfinite = 0;
  std::vector<uint64_t> va, vb;
  auto collect = [](std::vector<uint64_t>& out) { return [&out](const char*, uint64_t v) { out.push_back(v); }; };
  RasterStats sa = a.stats;
  auto ca = collect(va);
  auto cb = collect(vb);
  sa.visit(ca);
  sb.visit(cb);
  EXPECT_EQ(va, vb);  // every other counter identical: the same dispositions
}

// The replaced varying of every fragment is what the unit gives for the triangle with the rule's
// values (0 / ±FLT_MAX) given as input: the rule is the whole of the behaviour.
TEST(NonFiniteVarying, ReplacedVaryingsEqualTheTriangleWithZeroAndFltMax) {
  const int nv = 3;
  const Scene s = make_scene(82, 300, nv);
  const Config cfg;
  const FrameOutput b = run_raster_unit(cfg, s.st, s.nonfinite);
  const FrameOutput r = run_raster_unit(cfg, s.st, s.ruled);
  ASSERT_EQ(b.fragments.size(), r.fragments.size());
  size_t huge = 0;
  for (size_t i = 0; i < b.fragments.size(); ++i) {
    const Fragment &fb = b.fragments[i], &fr = r.fragments[i];
    ASSERT_EQ(std::tie(fb.x, fb.y, fb.prim, fb.depth), std::tie(fr.x, fr.y, fr.prim, fr.depth));
    for (int k = 0; k < nv; ++k) {
      ASSERT_TRUE(same_fx(fb.var[k], fr.var[k])) << "fragment " << i << " varying " << k;
      huge += fb.var[k].sig != 0 && fb.var[k].lead_exp() > 100;  // an FLT_MAX-sized value arrived
    }
  }
  EXPECT_GT(huge, 100u);
  EXPECT_EQ(r.stats.prims_varying_nonfinite, 0u);  // the ruled input is finite
}

// The exact GMP geometry reference, applying the rule itself, agrees with stages 1–4 on triangles
// with non-finite varyings (snapped positions, depth, 1/w and every v/w).
TEST(NonFiniteVarying, GeometryMatchesTheExactReference) {
  const int nv = 3;
  const Scene s = make_scene(83, 200, nv);
  int hits = 0;
  for (size_t t = 0; t < s.nonfinite.size(); ++t) {
    if (!s.hit[t]) continue;
    ++hits;
    GeomOutcome o;
    EXPECT_EQ(compare_with_reference(Config{}, s.st, s.nonfinite[t], &o), 0) << "triangle " << t;
  }
  EXPECT_GT(hits, 40);
}

// Positions keep the old rule: NaN / Inf there rejects the primitive (NaN first), whatever the
// varyings hold, and the varying counter is not incremented.
TEST(NonFiniteVarying, NonFinitePositionsStayRejected) {
  DrawState st = state(64, 64, 0, 0, 2);
  ClipTriangle t;
  const float p[3][4] = {{-0.5f, -0.5f, 0.5f, 1}, {0.5f, -0.5f, 0.5f, 1}, {0, 0.5f, 0.5f, 1}};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) t.v[i].pos[c] = p[i][c];
  t.v[0].var[1] = kNaN;
  ClipTriangle a = t, b = t, c = t;
  a.v[1].pos[2] = kInf;
  b.v[2].pos[0] = kNaN;
  c.v[1].pos[3] = -kInf;
  c.v[0].pos[1] = kNaN;
  const FrameOutput f = run_raster_unit(Config{}, st, {a, b, c, t});
  EXPECT_EQ(f.stats.prims_rejected_inf, 1u);
  EXPECT_EQ(f.stats.prims_rejected_nan, 2u);
  EXPECT_EQ(f.stats.prims_drawn, 1u);
  EXPECT_EQ(f.stats.prims_varying_nonfinite, 1u);  // only t, the one with finite positions
  for (const Fragment& fr : f.fragments) EXPECT_EQ(fr.prim, 3u);
  EXPECT_GT(f.fragments.size(), 500u);
}

// Inactive varyings are not looked at (not counted), and the rule replaces only the float32
// classes NaN and Inf: ±FLT_MAX, ±0 and denormals given as input are taken as they are.
TEST(NonFiniteVarying, InactiveVaryingsAndFiniteExtremesAreNotReplaced) {
  ClipTriangle t;
  const float p[3][4] = {{-0.5f, -0.5f, 0.5f, 1}, {0.5f, -0.5f, 0.5f, 1}, {0, 0.5f, 0.5f, 1}};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) t.v[i].pos[c] = p[i][c];
  t.v[0].var[0] = kMax;
  t.v[1].var[0] = -0.0f;
  t.v[2].var[0] = std::numeric_limits<float>::denorm_min();
  t.v[1].var[2] = kInf;  // inactive with num_varyings 2
  const FrameOutput f = run_raster_unit(Config{}, state(64, 64, 0, 0, 2), {t});
  EXPECT_EQ(f.stats.prims_varying_nonfinite, 0u);
  EXPECT_EQ(f.stats.prims_drawn, 1u);
  const FrameOutput g = run_raster_unit(Config{}, state(64, 64, 0, 0, 3), {t});
  EXPECT_EQ(g.stats.prims_varying_nonfinite, 1u);
  EXPECT_EQ(g.fragments.size(), f.fragments.size());
}

// Bad input (docs/references.md#spec-bad-input) for the geometry stages (1–4): each case gets defined behaviour — a
// documented discard with a reason (GeomOutcome → RasterStats counter) or exact handling —
// never a crash, and every input primitive is accounted for.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geom_ref.hpp"

using namespace fxr;
using namespace georef;

namespace {

ClipVertex vtx(float x, float y, float z, float w) {
  ClipVertex v;
  v.pos[0] = x;
  v.pos[1] = y;
  v.pos[2] = z;
  v.pos[3] = w;
  return v;
}

ClipTriangle good() {
  ClipTriangle t;
  t.v[0] = vtx(-0.5f, -0.5f, 0.5f, 1);
  t.v[1] = vtx(0.5f, -0.5f, 0.5f, 1);
  t.v[2] = vtx(0, 0.5f, 0.5f, 1);
  return t;
}

GeomOutcome run(const ClipTriangle& t, const DrawState& st, std::vector<SetupTriangle>* out = nullptr,
                const Config& cfg = Config{}) {
  std::vector<SetupTriangle> o;
  RasterStats s;
  const GeomOutcome r = geometry(cfg, st, t, 0, out ? *out : o, s);
  return r;
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

}  // namespace

TEST(BadInput, NaNInAnyPositionComponentIsRejected) {
  const DrawState st = state(64, 64);
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) {
      ClipTriangle t = good();
      t.v[i].pos[c] = kNaN;
      EXPECT_EQ(run(t, st), GeomOutcome::RejectedNaN) << i << " " << c;
      t.v[i].pos[c] = f32_from_bits(0xffc00001u);  // negative NaN with a payload
      EXPECT_EQ(run(t, st), GeomOutcome::RejectedNaN);
      t.v[i].pos[c] = f32_from_bits(0x7f800001u);  // signalling NaN
      EXPECT_EQ(run(t, st), GeomOutcome::RejectedNaN);
    }
}

// A NaN in a varying is replaced (by 0, docs/pipeline.md stage 1), not rejected: the snapped
// triangle is the one without it (tests/model/nonfinite_varying_test.cpp checks the fragments).
TEST(BadInput, NaNInAVaryingIsReplacedNotRejected) {
  ClipTriangle t = good();
  t.v[2].var[3] = kNaN;
  std::vector<SetupTriangle> with_nan, without;
  EXPECT_EQ(run(t, state(64, 64, 0, 0, 4), &with_nan), GeomOutcome::Emitted);
  EXPECT_EQ(run(good(), state(64, 64, 0, 0, 4), &without), GeomOutcome::Emitted);
  ASSERT_EQ(with_nan.size(), 1u);
  ASSERT_EQ(without.size(), 1u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(with_nan[0].v[i].x, without[0].v[i].x);
    EXPECT_EQ(with_nan[0].v[i].y, without[0].v[i].y);
    EXPECT_EQ(with_nan[0].v[i].z, without[0].v[i].z);
  }
  EXPECT_EQ(run(t, state(64, 64, 0, 0, 3)), GeomOutcome::Emitted);
}

TEST(BadInput, InfinitePositionsAreRejectedInfiniteVaryingsReplacedAndNaNTakesPrecedence) {
  const DrawState st = state(64, 64, 0, 0, 1);
  for (float inf : {kInf, -kInf}) {
    ClipTriangle t = good();
    t.v[1].pos[3] = inf;
    EXPECT_EQ(run(t, st), GeomOutcome::RejectedInf);
    t.v[0].var[0] = kNaN;  // a NaN varying does not turn an Inf position into RejectedNaN
    EXPECT_EQ(run(t, st), GeomOutcome::RejectedInf);
    t = good();
    t.v[0].var[0] = inf;
    EXPECT_EQ(run(t, st), GeomOutcome::Emitted);
    t.v[2].pos[0] = kNaN;
    EXPECT_EQ(run(t, st), GeomOutcome::RejectedNaN);
  }
}

// Denormals are exact values (not flushed): a triangle with denormal w / x / z matches the
// exact reference, and w = the smallest denormal is a valid (inside) vertex.
TEST(BadInput, DenormalsAreExactValuesNotFlushed) {
  const DrawState st = state(128, 128, 0, 0, 1);
  const float dmin = std::numeric_limits<float>::denorm_min(), d1 = f32_from_bits(0x00345678u);
  ClipTriangle t;
  t.v[0] = vtx(0, 0, 0, dmin);
  t.v[1] = vtx(d1 * 0.5f, -d1 * 0.25f, d1 * 0.5f, d1);
  t.v[2] = vtx(-d1, d1, 0, d1 * 2);
  t.v[0].var[0] = dmin;
  t.v[1].var[0] = -d1;
  Config cfg;
  GeomOutcome o;
  EXPECT_EQ(compare_with_reference(cfg, st, t, &o), 0);
  EXPECT_EQ(o, GeomOutcome::Emitted);
  std::vector<SetupTriangle> out;
  ASSERT_EQ(run(t, st, &out), GeomOutcome::Emitted);
  // 1/w of the smallest denormal is 2^149, exactly.
  EXPECT_EQ(q_of(out[0].v[0].rw), pow2(149));
  EXPECT_EQ(q_of(out[0].v[0].vw[0]), mpq_class(1));  // v/w = dmin/dmin
}

// Values beyond every format's range (±1e38, FLT_MAX) are exact inputs: they are clipped, never
// overflowed; results match the exact reference.
TEST(BadInput, HugeValuesAreClippedExactlyNotOverflowed) {
  const float big = std::numeric_limits<float>::max();
  const DrawState st = state(200, 100, 0, 0, 1);
  const float vals[] = {1e38f, -1e38f, big, -big, 1e30f};
  int emitted = 0;
  for (float a : vals)
    for (float b : vals) {
      ClipTriangle t = good();
      t.v[0].pos[0] = a;
      t.v[1].pos[1] = b;
      t.v[2].pos[3] = std::fabs(b);
      t.v[2].var[0] = a;
      t.v[1].var[0] = b;
      GeomOutcome o;
      EXPECT_EQ(compare_with_reference(Config{}, st, t, &o), 0) << a << " " << b;
      EXPECT_TRUE(o == GeomOutcome::Emitted || o == GeomOutcome::CulledOutside);
      emitted += o == GeomOutcome::Emitted;
    }
  EXPECT_GT(emitted, 0);
}

// w = 0 and w < 0 for all three vertices: nothing survives (D3D: only w > 0 survives), the
// clip-space origin (0, 0, 0, 0) included.
TEST(BadInput, WZeroOrNegativeForAllVerticesIsCulled) {
  const DrawState st = state(64, 64);
  const float ws[] = {0.0f, -0.0f, -1.0f, -1e-30f, -1e30f};
  for (float w : ws) {
    ClipTriangle t = good();
    for (auto& v : t.v) v.pos[3] = w;
    EXPECT_EQ(run(t, st), GeomOutcome::CulledOutside) << w;
    for (auto& v : t.v) v.pos[0] = v.pos[1] = v.pos[2] = 0;
    EXPECT_EQ(run(t, st), GeomOutcome::CulledOutside) << "origin, w = " << w;
  }
  // Mixed: one vertex at the origin with w = 0, two in front: the w_min plane clips it.
  ClipTriangle t = good();
  t.v[0] = vtx(0, 0, 0, 0);
  std::vector<SetupTriangle> out;
  EXPECT_EQ(run(t, st, &out), GeomOutcome::Emitted);
  EXPECT_EQ(compare_with_reference(Config{}, st, t), 0);
}

TEST(BadInput, EmptySceneProducesNothing) {
  const std::vector<ClipTriangle> none;
  std::vector<SetupTriangle> out;
  RasterStats s;
  for (size_t i = 0; i < none.size(); ++i) geometry(Config{}, state(8, 8), none[i], (uint32_t)i, out, s);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(s.prims_trivial_accept + s.prims_clipped + s.clip_vertices_created, 0u);
}

TEST(BadInput, Viewport1x1) {
  const DrawState st = state(1, 1, 5, 7);
  std::vector<SetupTriangle> out;
  ASSERT_EQ(run(good(), st, &out), GeomOutcome::Emitted);
  EXPECT_EQ(out[0].v[0].x, (5 * 256) + 64);  // x_n = −½ → x_w = 5.25
  EXPECT_EQ(out[0].v[2].y, (7 * 256) + 192);
  EXPECT_EQ(compare_with_reference(Config{}, st, good()), 0);
}

// Maximum viewport: it must lie inside the guard band limit L = 2^(window_int_bits−1) − 1 px,
// so the largest is L × L at the origin (32767² at the default 16 integer bits); one pixel more
// makes every primitive RejectedRange (documented), as do empty viewports.
TEST(BadInput, ViewportOfMaximumSizeAndBeyond) {
  Config cfg;
  const int L = (1 << (cfg.raster.window_int_bits - 1)) - 1;
  std::vector<SetupTriangle> out;
  EXPECT_EQ(run(good(), state(L, L), &out), GeomOutcome::Emitted);
  EXPECT_EQ(compare_with_reference(cfg, state(L, L), good()), 0);
  EXPECT_EQ(run(good(), state(L + 1, L)), GeomOutcome::RejectedRange);
  EXPECT_EQ(run(good(), state(L, L, -1, 0)), GeomOutcome::Emitted);
  EXPECT_EQ(run(good(), state(L, L, 1, 0)), GeomOutcome::RejectedRange);
  EXPECT_EQ(run(good(), state(2 * L, 10, -L, 0)), GeomOutcome::Emitted);
  EXPECT_EQ(run(good(), state(0, 10)), GeomOutcome::RejectedRange);
  EXPECT_EQ(run(good(), state(10, -1)), GeomOutcome::RejectedRange);
  // A triangle much larger than the maximum viewport still fits after clipping.
  ClipTriangle t = good();
  t.v[0].pos[0] = -1e6f;
  t.v[1].pos[1] = 1e6f;
  EXPECT_EQ(compare_with_reference(cfg, state(L, L), t), 0);
  for (int bits : {8, 12, 20}) {
    Config c2;
    c2.raster.window_int_bits = bits;
    const int l2 = (1 << (bits - 1)) - 1;
    EXPECT_EQ(run(good(), state(l2, l2), nullptr, c2), GeomOutcome::Emitted);
    EXPECT_EQ(run(good(), state(l2 + 1, l2), nullptr, c2), GeomOutcome::RejectedRange);
    EXPECT_EQ(compare_with_reference(c2, state(l2, l2), t), 0);
  }
}

TEST(BadInput, NumVaryingsOutOfRangeIsRejected) {
  EXPECT_EQ(run(good(), state(8, 8, 0, 0, kMaxVaryings + 1)), GeomOutcome::RejectedRange);
  EXPECT_EQ(run(good(), state(8, 8, 0, 0, -1)), GeomOutcome::RejectedRange);
  EXPECT_EQ(run(good(), state(8, 8, 0, 0, kMaxVaryings)), GeomOutcome::Emitted);
}

// Every input primitive ends in exactly one outcome, and the geometry counters add up:
// trivial accept + clipped + trivially rejected + rejected before clipping = inputs.
TEST(BadInput, EveryPrimitiveIsAccountedForWithAReason) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<float> u(-3, 3);
  const float specials[] = {kNaN, kInf, -kInf, 0.0f, -0.0f, 1e38f, -1e38f,
                            std::numeric_limits<float>::denorm_min(), -1.0f};
  const DrawState st = state(100, 80, 0, 0, 2);
  RasterStats s;
  uint64_t by[5] = {};
  const int n = 5000;
  for (int i = 0; i < n; ++i) {
    ClipTriangle t;
    for (auto& v : t.v) {
      v = vtx(u(rng), u(rng), u(rng), u(rng));
      v.var[0] = u(rng);
      v.var[1] = u(rng);
      if (rng() % 4 == 0) {
        float* f = (rng() % 3 == 0) ? &v.var[rng() % 2] : &v.pos[rng() % 4];
        *f = specials[rng() % 9];
      }
    }
    std::vector<SetupTriangle> out;
    const uint64_t before = s.prims_trivial_accept + s.prims_clipped;
    const GeomOutcome o = geometry(Config{}, st, t, (uint32_t)i, out, s);
    ++by[(int)o];
    EXPECT_EQ(o == GeomOutcome::Emitted, !out.empty());
    if (o == GeomOutcome::RejectedNaN || o == GeomOutcome::RejectedInf) {
      EXPECT_EQ(s.prims_trivial_accept + s.prims_clipped, before);
    }
  }
  uint64_t sum = 0;
  for (uint64_t b : by) sum += b;
  EXPECT_EQ(sum, (uint64_t)n);
  EXPECT_GT(by[(int)GeomOutcome::RejectedNaN], 0u);
  EXPECT_GT(by[(int)GeomOutcome::RejectedInf], 0u);
  EXPECT_GT(by[(int)GeomOutcome::CulledOutside], 0u);
  EXPECT_GT(by[(int)GeomOutcome::Emitted], 0u);
  // Emitted = trivially accepted + clipped-and-kept; clipped-away ones are CulledOutside.
  EXPECT_LE(by[(int)GeomOutcome::Emitted], s.prims_trivial_accept + s.prims_clipped);
  EXPECT_EQ(by[(int)GeomOutcome::RejectedRange], 0u);  // nothing finite is out of range
}

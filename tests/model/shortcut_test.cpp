// "Model only what a scene needs" (docs/speed.md "Shortcuts"), each shortcut run against the
// full path it replaces on the same scenes:
//   - no sink and the depth test off: nothing reads a depth code nor a varying, so the chain
//     counts each span's pixels and skips stages 7–8 (FragmentChain's count-only path); the full
//     path is forced by a tap (any Taps other than NoTaps observes every stage);
//   - affine mode: D = 2A is constant over the triangle, so DivideStage normalises it once per
//     triangle instead of per pixel; against divide_varying(normalize_den(...)) of every sample;
//   - the vertex cache (model/unit/vertex_cache.hpp): stages 1–4 once per distinct vertex of
//     trivially accepted triangles; GeometryChain<NoTaps> against the full chain (a tap) on
//     meshes with shared vertices, some of them NaN / Inf, with a NaN varying, outside a clip
//     plane or exactly on it, and on the default scene (the bunny) through the whole unit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "frontend/scene.hpp"
#include "geom_ref.hpp"
#include "model/stages/attr.hpp"
#include "model/unit/chain.hpp"
#include "stats_fields.hpp"

using namespace fxr;
using namespace georef;

namespace {

std::vector<ClipTriangle> random_scene(std::mt19937_64& rng, int n, int nv) {
  std::uniform_real_distribution<double> u(-1.3, 1.3), z(0, 1), lw(std::log(0.2), std::log(20.0)), var(-100, 100);
  std::vector<ClipTriangle> tris;
  for (int i = 0; i < n; ++i) {
    ClipTriangle t;
    const double cx = u(rng), cy = u(rng), r = i % 4 == 0 ? 1.0 : 0.05;  // large and small
    for (auto& v : t.v) {
      const double w = std::exp(lw(rng));
      v.pos[0] = (float)((cx + u(rng) * r) * w);
      v.pos[1] = (float)((cy + u(rng) * r) * w);
      v.pos[2] = (float)(z(rng) * w);
      v.pos[3] = (float)w;
      for (int k = 0; k < nv; ++k) v.var[k] = (float)var(rng);
    }
    tris.push_back(t);
  }
  return tris;
}

// Observes nothing, but is not NoTaps: the chain takes its full path.
struct FullPathTap {
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out&) {}
};

// The full geometry chain's answer for one primitive, the reference a vertex-cache shortcut is
// compared with: the triangle must be emitted as exactly one set-up triangle.
::testing::AssertionResult full_chain_setup(GeometryChain<FullPathTap>& full, const InputTriangle& in,
                                            SetupTriangle& out, RasterStats& s) {
  std::vector<SetupTriangle> want;
  if (full.run(in, want, s) != GeomOutcome::Emitted)
    return ::testing::AssertionFailure() << "primitive " << in.prim << " not emitted by the full chain";
  if (want.size() != 1u)
    return ::testing::AssertionFailure() << "primitive " << in.prim << ": " << want.size() << " triangles";
  out = want[0];
  return ::testing::AssertionSuccess();
}
::testing::AssertionResult full_chain_setup(GeometryChain<FullPathTap>& full, const ClipTriangle& tri,
                                            uint32_t prim, SetupTriangle& out) {
  InputTriangle in;
  in.prim = prim;
  in.tri = tri;
  RasterStats s;
  return full_chain_setup(full, in, out, s);
}

// Every sample leaving the depth stage and the fragment divided from it.
struct PairTap {
  std::vector<PlaneSample> samples;
  std::vector<Fragment> frags;
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out& o) {
    if constexpr (std::is_same<S, DepthStage>::value) samples.push_back(o);
    if constexpr (std::is_same<S, DivideStage>::value) frags.push_back(o);
  }
};

struct NullSink : FragmentSink {
  void emit(const Fragment&) override {}
};

}  // namespace

TEST(Shortcut, CountOnlyChainWithTheDepthTestOffEqualsTheFullPath) {
  std::mt19937_64 rng(0x5c01);
  for (const bool attr : {true, false}) {
    Config cfg;
    if (!attr) cfg.raster.attr_subpixel_bits = cfg.raster.subpixel_bits;  // snapped planes
    for (int trial = 0; trial < 4; ++trial) {
      DrawState st = state(256 + 64 * trial, 192, 0, 0, trial % 3);
      st.depth_test = false;
      st.cull = trial % 2 ? CullMode::Back : CullMode::None;
      const std::vector<ClipTriangle> tris = random_scene(rng, 300, st.num_varyings);
      FrameOutput fast, full;
      NoTaps nt;
      FullPathTap ft;
      run_raster_unit_to(cfg, st, tris, fast, nullptr, nt);
      run_raster_unit_to(cfg, st, tris, full, nullptr, ft);
      ASSERT_GT(full.stats.fragments_generated, 1000u);
      EXPECT_EQ(full.stats.fragments_depth_pass, full.stats.fragments_generated);  // test off: all pass
      EXPECT_EQ(stats_fields(fast.stats), stats_fields(full.stats));
      EXPECT_EQ(fast.depth, full.depth);  // never written with the test off
    }
  }
}

TEST(Shortcut, AffineDenominatorNormalisedOncePerTriangleEqualsThePerPixelPath) {
  std::mt19937_64 rng(0x5c02);
  for (const bool attr : {true, false}) {
    Config cfg;
    if (!attr) cfg.raster.attr_subpixel_bits = cfg.raster.subpixel_bits;
    for (const DivAlgorithm alg : {DivAlgorithm::Radix2, DivAlgorithm::SharedRecip}) {
      cfg.div.algorithm = alg;
      DrawState st = state(320, 240, 0, 0, 3);
      st.interp = InterpMode::Affine;
      const std::vector<ClipTriangle> tris = random_scene(rng, 200, st.num_varyings);
      FrameOutput f;
      PairTap tap;
      NullSink sink;
      run_raster_unit_to(cfg, st, tris, f, &sink, tap);
      ASSERT_EQ(tap.samples.size(), tap.frags.size());
      ASSERT_GT(tap.frags.size(), 5000u);
      // Both outcomes of the memo are reached: D repeats (a hit) and changes (a stale D would
      // give wrong quotients on the next triangle).
      size_t repeats = 0, changes = 0;
      for (size_t i = 1; i < tap.samples.size(); ++i) {
        const bool same = tap.samples[i].den == tap.samples[i - 1].den && tap.samples[i].den_exp == tap.samples[i - 1].den_exp;
        (same ? repeats : changes) += 1;
        if (tap.samples[i].prim == tap.samples[i - 1].prim) {
          EXPECT_TRUE(same) << "affine D = 2A varies inside a triangle";
        }
      }
      EXPECT_GT(repeats, tap.samples.size() / 2);
      EXPECT_GT(changes, 50u);
      for (size_t i = 0; i < tap.frags.size(); ++i) {
        const PlaneSample& p = tap.samples[i];
        const DenNorm dn = normalize_den(cfg.div, p.den, p.den_exp);  // per pixel, the reference path
        for (int m = 0; m < st.num_varyings; ++m) {
          const FxFloat want = divide_varying(cfg.div, p.num[m], p.num_exp[m], dn);
          const FxFloat& got = tap.frags[i].var[m];
          ASSERT_TRUE(got.sig == want.sig && got.exp == want.exp && got.neg == want.neg)
              << "fragment " << i << " varying " << m;
        }
      }
    }
  }
}

namespace {

bool same_fx(const FxFloat& a, const FxFloat& b) { return a.sig == b.sig && a.exp == b.exp && a.neg == b.neg; }

// Every field of two snapped triangles (SetupTriangle has padding: no memcmp).
bool same_setup(const SetupTriangle& a, const SetupTriangle& b) {
  if (a.prim != b.prim) return false;
  for (int i = 0; i < 3; ++i) {
    const SetupVertex &u = a.v[i], &w = b.v[i];
    if (u.x != w.x || u.y != w.y || u.ax != w.ax || u.ay != w.ay || u.z != w.z || !same_fx(u.rw, w.rw)) return false;
    for (int k = 0; k < kMaxVaryings; ++k)
      if (!same_fx(u.vw[k], w.vw[k])) return false;
  }
  return true;
}

// A mesh on an n × n grid of shared vertices (two triangles per cell, the cells in a shuffled
// order of row blocks so that the cache both hits and evicts), in clip space around the
// viewport, with hard vertices mixed in: NaN / Inf positions, a NaN or Inf varying, −0,
// vertices outside the guard band, behind the eye, beyond the far plane, exactly on a plane
// (x = w, z = 0, z = w), denormal coordinates.
std::vector<ClipTriangle> grid_mesh(std::mt19937_64& rng, int n, int nv, double span) {
  std::uniform_real_distribution<double> u(-1, 1), wl(std::log(0.3), std::log(8.0)), var(-50, 50), pick(0, 1);
  std::vector<ClipVertex> vs((size_t)n * (size_t)n);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      ClipVertex& v = vs[(size_t)j * n + i];
      const double w = std::exp(wl(rng));
      const double x = (-span + 2 * span * i / (n - 1) + 0.01 * u(rng)), y = (-span + 2 * span * j / (n - 1) + 0.01 * u(rng));
      v.pos[0] = (float)(x * w), v.pos[1] = (float)(y * w), v.pos[2] = (float)((0.5 + 0.4 * u(rng)) * w), v.pos[3] = (float)w;
      for (int k = 0; k < nv; ++k) v.var[k] = (float)var(rng);
      if (j < 2) v.pos[2] = (float)(1.3 * w);  // the first rows beyond the far plane: culled outside
      const double r = pick(rng);
      if (r < 0.005) v.pos[(size_t)(rng() % 4)] = nan;
      else if (r < 0.01) v.pos[(size_t)(rng() % 4)] = (rng() & 1) ? inf : -inf;
      else if (r < 0.015 && nv > 0) v.var[(size_t)(rng() % (uint64_t)nv)] = (rng() & 1) ? nan : inf;
      else if (r < 0.025) v.pos[0] = v.pos[3];            // on the right plane of NDC x = 1 (inside the guard band)
      else if (r < 0.03) v.pos[2] = 0.0f;                 // on the near plane
      else if (r < 0.035) v.pos[2] = v.pos[3];            // on the far plane
      else if (r < 0.04) v.pos[2] = -0.0f;                // −0 on the near plane
      else if (r < 0.045) v.pos[2] = 1.1f * v.pos[3];     // beyond the far plane: clipped
      else if (r < 0.05) v.pos[3] = -v.pos[3];            // behind the eye: clipped
      else if (r < 0.055) v.pos[0] = 5000.0f * v.pos[3];  // outside the guard band
      else if (r < 0.06) v.pos[1] = 1e-40f;               // a denormal
    }
  std::vector<ClipTriangle> tris;
  std::vector<int> rows((size_t)(n - 1));
  for (int j = 0; j < n - 1; ++j) rows[(size_t)j] = j;
  std::shuffle(rows.begin(), rows.end(), rng);
  for (int j : rows)
    for (int i = 0; i < n - 1; ++i) {
      const ClipVertex &a = vs[(size_t)j * n + i], &b = vs[(size_t)j * n + i + 1], &c = vs[(size_t)(j + 1) * n + i],
                       &d = vs[(size_t)(j + 1) * n + i + 1];
      tris.push_back(ClipTriangle{{a, b, d}});
      tris.push_back(ClipTriangle{{a, d, c}});
    }
  return tris;
}

template <class Taps>
GeometryChain<Taps> geometry_run(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                                 Taps& taps, std::vector<SetupTriangle>& out, std::vector<int>& outcomes,
                                 RasterStats& s) {
  GeometryChain<Taps> chain(cfg, st, taps);
  InputTriangle in;
  for (size_t p = 0; p < tris.size(); ++p) {
    in.prim = (uint32_t)p;
    in.tri = tris[p];
    outcomes.push_back((int)chain.run(in, out, s) * 1000 + (int)chain.pieces_rejected());
  }
  return chain;
}

struct KeepSink : FragmentSink {
  std::vector<Fragment> v;
  void emit(const Fragment& f) override { v.push_back(f); }
};

bool same_fragment(const Fragment& a, const Fragment& b, int nv) {
  if (a.prim != b.prim || a.x != b.x || a.y != b.y || a.depth != b.depth) return false;
  for (int k = 0; k < nv; ++k)
    if (!same_fx(a.var[k], b.var[k])) return false;
  return true;
}

}  // namespace

TEST(Shortcut, VertexCacheEqualsTheFullGeometryChainOnMeshesWithHardVertices) {
  std::mt19937_64 rng(0x5c03);
  uint64_t hits = 0, misses = 0;
  for (const bool attr : {true, false}) {
    Config cfg;
    if (!attr) cfg.raster.attr_subpixel_bits = cfg.raster.subpixel_bits;
    for (int trial = 0; trial < 6; ++trial) {
      DrawState st = state(160 + 48 * trial, 120, trial % 2 ? -7 : 0, trial % 3 ? 5 : 0, trial % 4);
      if (trial == 5) st.interp = InterpMode::Affine;
      const std::vector<ClipTriangle> tris = grid_mesh(rng, trial < 3 ? 60 : 90, st.num_varyings, trial % 2 ? 1.05 : 0.7);
      NoTaps nt;
      FullPathTap ft;
      std::vector<SetupTriangle> fast_out, full_out;
      std::vector<int> fast_oc, full_oc;
      RasterStats fast_s, full_s;
      const auto fast = geometry_run(cfg, st, tris, nt, fast_out, fast_oc, fast_s);
      geometry_run(cfg, st, tris, ft, full_out, full_oc, full_s);
      ASSERT_EQ(fast_oc, full_oc);
      EXPECT_EQ(stats_fields(fast_s), stats_fields(full_s));
      ASSERT_EQ(fast_out.size(), full_out.size());
      for (size_t i = 0; i < fast_out.size(); ++i) ASSERT_TRUE(same_setup(fast_out[i], full_out[i])) << "triangle " << i;
      // Every kind of primitive is present: accepted, clipped, culled, NaN, Inf, a varying replaced.
      EXPECT_GT(full_s.prims_trivial_accept, 1000u);
      EXPECT_GT(full_s.prims_clipped, 0u);
      const auto count = [&](GeomOutcome g) {
        return std::count_if(full_oc.begin(), full_oc.end(), [&](int o) { return o / 1000 == (int)g; });
      };
      EXPECT_GT(count(GeomOutcome::RejectedNaN), 0);
      EXPECT_GT(count(GeomOutcome::RejectedInf), 0);
      EXPECT_GT(count(GeomOutcome::CulledOutside), 0);
      if (st.num_varyings > 0) {
        EXPECT_GT(full_s.prims_varying_nonfinite, 0u);
      }
      hits += fast.vertex_cache().hits();
      misses += fast.vertex_cache().misses();
    }
  }
  // Both outcomes of the lookup, many times.
  EXPECT_GT(hits, 2 * misses);
  EXPECT_GT(misses, 10000u);
}

TEST(Shortcut, VertexCacheLeavesTheDefaultSceneUnchangedThroughTheWholeUnit) {
  SceneOptions o;
  o.width = 256, o.height = 192;
  const Scene sc = default_scene(o);
  ASSERT_GT(sc.tris.size(), 10000u);  // the bunny (or its generated stand-in)
  FrameOutput fast, full;
  KeepSink fs, us;
  NoTaps nt;
  FullPathTap ft;
  run_raster_unit_to(sc.config, sc.state, sc.tris, fast, &fs, nt);
  run_raster_unit_to(sc.config, sc.state, sc.tris, full, &us, ft);
  EXPECT_EQ(stats_fields(fast.stats), stats_fields(full.stats));
  EXPECT_EQ(fast.depth, full.depth);
  ASSERT_EQ(fs.v.size(), us.v.size());
  ASSERT_GT(fs.v.size(), 10000u);
  for (size_t i = 0; i < fs.v.size(); ++i)
    ASSERT_TRUE(same_fragment(fs.v[i], us.v[i], sc.state.num_varyings)) << "fragment " << i;
  // The geometry of the same scene hits the cache for most vertices.
  std::vector<SetupTriangle> out;
  std::vector<int> oc;
  RasterStats s;
  const auto g = geometry_run(sc.config, sc.state, sc.tris, nt, out, oc, s);
  EXPECT_GT(g.vertex_cache().hits(), 2 * g.vertex_cache().misses());
}

// A cache of 4 slots, so that every slot is shared by many vertices, fed vertices that differ
// from a base vertex in exactly one 32-bit word (one ulp of a position or a varying, +0 / −0,
// a NaN payload): whenever it answers a triangle, the answer is the full chain's for that
// triangle (a trivial accept of one triangle equal to it). Both answers are reached.
TEST(Shortcut, VertexCacheWithCollidingSlotsAnswersOnlyForTheVertexItKeeps) {
  std::mt19937_64 rng(0x5c04);
  const Config cfg;
  DrawState st = state(200, 150, 0, 0, 3);
  const auto bump = [](float f, int d) {
    uint32_t b;
    std::memcpy(&b, &f, 4);
    b = (uint32_t)((int64_t)b + d);
    std::memcpy(&f, &b, 4);
    return f;
  };
  std::vector<ClipVertex> base(6);
  std::uniform_real_distribution<float> u(-0.8f, 0.8f), var(-5, 5);
  for (ClipVertex& v : base) {
    const float w = 1.5f;
    v.pos[0] = u(rng) * w, v.pos[1] = u(rng) * w, v.pos[2] = 0.5f * w, v.pos[3] = w;
    for (int k = 0; k < st.num_varyings; ++k) v.var[k] = var(rng);
  }
  base[5].var[2] = 0.0f;  // −0 below
  // Families: a base vertex and its one-word siblings.
  std::vector<std::vector<ClipVertex>> family;
  for (const ClipVertex& b : base) {
    family.push_back({b});
    for (int word = 0; word < 4 + st.num_varyings; ++word)
      for (int d : {-1, 1}) {
        ClipVertex v = b;
        float& f = word < 4 ? v.pos[word] : v.var[word - 4];
        f = bump(f, d);
        family.back().push_back(v);
      }
  }
  ClipVertex neg0 = base[5];
  neg0.var[2] = -0.0f;
  family[5].push_back(neg0);
  ClipVertex nan1 = base[1], nan2 = base[1];
  nan1.var[0] = std::numeric_limits<float>::quiet_NaN();
  nan2.var[0] = bump(std::numeric_limits<float>::quiet_NaN(), 1);  // another payload
  family[1].push_back(nan1), family[1].push_back(nan2);
  ClipVertex far = base[2], behind = base[3];  // outside a clip plane
  far.pos[2] = bump(far.pos[3], 1);
  behind.pos[3] = -behind.pos[3];
  family[2].push_back(far), family[3].push_back(behind);
  // One slot: consecutive lookups are the same vertex (a hit) or a sibling (must miss).
  VertexCache cache(cfg, st, 0, 0);
  FullPathTap ft;
  GeometryChain<FullPathTap> full(cfg, st, ft);
  uint64_t answered = 0, declined = 0;
  for (uint32_t p = 0; p < 20000; ++p) {
    InputTriangle in;
    in.prim = p;
    const std::vector<ClipVertex>& fam = family[rng() % family.size()];
    for (auto& v : in.tri.v) v = fam[rng() % (p % 2 ? 3 : fam.size())];
    SetupTriangle got;
    if (!cache.triangle(in, got)) {
      ++declined;
      continue;
    }
    ++answered;
    SetupTriangle want;
    RasterStats s;
    ASSERT_TRUE(full_chain_setup(full, in, want, s));
    ASSERT_EQ(s.prims_trivial_accept, 1u);
    ASSERT_TRUE(same_setup(got, want)) << "primitive " << p;
  }
  EXPECT_GT(answered, 1000u);
  EXPECT_GT(declined, 1000u);
  EXPECT_GT(cache.misses(), 10000u);  // the 4 slots are replaced all the time
  EXPECT_GT(cache.hits(), 1000u);
}

// The slot numbers VertexCache::prefetch keeps for triangle() (docs/speed.md "Session 10: per
// triangle") are hints. Prefetched kVertexCachePrefetchAhead primitives ahead as draw_all does,
// the cache gives every answer and counts every hit and miss as a cache that is never
// prefetched; and when the prefetched triangle object is rewritten before its lookup (the kept
// slots are then another triangle's), every answer is still the full chain's for the triangle
// looked up. Small tables (2^6 slots), so that slots are shared and replaced.
TEST(Shortcut, VertexCachePrefetchedSlotsAreOnlyHints) {
  std::mt19937_64 rng(0x5c05);
  const Config cfg;
  for (int trial = 0; trial < 4; ++trial) {
    const DrawState st = state(200, 150, 0, 0, trial);
    const std::vector<ClipTriangle> tris = grid_mesh(rng, 40, st.num_varyings, 0.8);
    VertexCache plain(cfg, st, 6, 0), ahead(cfg, st, 6, 0), stale(cfg, st, 6, 0);
    FullPathTap ft;
    GeometryChain<FullPathTap> full(cfg, st, ft);
    uint64_t answered = 0, stale_answered = 0;
    ClipTriangle obj;
    for (size_t p = 0; p < tris.size(); ++p) {
      if (p + kVertexCachePrefetchAhead < tris.size()) ahead.prefetch(tris[p + kVertexCachePrefetchAhead]);
      SetupTriangle a, b;
      const bool ra = plain.triangle(tris[p], (uint32_t)p, a), rb = ahead.triangle(tris[p], (uint32_t)p, b);
      ASSERT_EQ(ra, rb) << "primitive " << p;
      if (ra) {
        ++answered;
        ASSERT_TRUE(same_setup(a, b)) << "primitive " << p;
      }
      // The stale ring entry: prefetched as one triangle, looked up as another.
      obj = tris[(p * 7919 + 13) % tris.size()];
      stale.prefetch(obj);
      obj = tris[p];
      SetupTriangle c;
      if (!stale.triangle(obj, (uint32_t)p, c)) continue;
      ++stale_answered;
      SetupTriangle want;
      ASSERT_TRUE(full_chain_setup(full, tris[p], (uint32_t)p, want));
      ASSERT_TRUE(same_setup(c, want)) << "primitive " << p;
    }
    EXPECT_EQ(plain.hits(), ahead.hits());
    EXPECT_EQ(plain.misses(), ahead.misses());
    EXPECT_GT(plain.hits(), 1000u);
    EXPECT_GT(plain.misses(), 1000u);
    EXPECT_GT(answered, 500u);
    EXPECT_GT(stale_answered, 100u);
  }
}

// The table a cache keeps on its thread from draw to draw (KeptVertexTable, docs/speed.md
// "Session 11: per triangle"): a new epoch per draw instead of a zero-filled table. Draw after
// draw on one thread — the viewport moved (the same keys, other answers), the varying count
// changed (another slot layout), the same draw twice (the same keys and answers, an older
// epoch) — a cache on the kept table gives every answer and counts every hit and miss as a cache
// on a table of its own (the second cache alive on the thread gets one), and every triangle it
// answers is the full chain's (a tap). A moved cache keeps the table; the next draw's takes it.
TEST(Shortcut, VertexCacheKeptTableAnswersAsAFreshTable) {
  std::mt19937_64 rng(0x5c06);
  const Config cfg;
  const std::vector<ClipTriangle> tris = grid_mesh(rng, 40, 3, 0.8);
  const DrawState a = state(200, 150, 0, 0, 2), moved = state(200, 150, -37, 11, 2), none = state(200, 150, 0, 0, 0),
                  three = state(200, 150, 0, 0, 3);
  for (const DrawState* st : {&a, &moved, &none, &three, &a, &a}) {
    VertexCache kept(cfg, *st, kVertexCacheMaxSlotBits, 0), own(cfg, *st, kVertexCacheMaxSlotBits, 0);
    FullPathTap ft;
    GeometryChain<FullPathTap> full(cfg, *st, ft);
    uint64_t answered = 0;
    for (size_t p = 0; p < tris.size(); ++p) {
      SetupTriangle x, y;
      const bool rx = kept.triangle(tris[p], (uint32_t)p, x), ry = own.triangle(tris[p], (uint32_t)p, y);
      ASSERT_EQ(rx, ry) << "primitive " << p;
      if (!rx) continue;
      ++answered;
      ASSERT_TRUE(same_setup(x, y)) << "primitive " << p;
      SetupTriangle want;
      ASSERT_TRUE(full_chain_setup(full, tris[p], (uint32_t)p, want));
      ASSERT_TRUE(same_setup(x, want)) << "primitive " << p;
    }
    ASSERT_TRUE(kept.uses_kept_table());
    ASSERT_FALSE(own.uses_kept_table());
    EXPECT_EQ(kept.hits(), own.hits());
    EXPECT_EQ(kept.misses(), own.misses());
    EXPECT_GT(kept.hits(), 1000u);
    EXPECT_GT(kept.misses(), 1000u);
    EXPECT_GT(answered, 1000u);
    // Moved: the table goes with the cache, which answers on.
    VertexCache m(std::move(kept));
    EXPECT_TRUE(m.uses_kept_table());
    for (size_t p = 0; p < tris.size(); p += 7) {
      SetupTriangle x, y;
      ASSERT_EQ(m.triangle(tris[p], (uint32_t)p, x), own.triangle(tris[p], (uint32_t)p, y)) << "primitive " << p;
    }
    EXPECT_EQ(m.hits(), own.hits());
  }
}

namespace {

// What the stages do when nothing needs a varying: setup's planes, the samples' N and D, the
// divider's inputs.
struct WorkTap {
  uint64_t planes = 0, samples = 0, samples_with_nd = 0, divides = 0;
  template <class S>
  void in(const typename S::In&) {
    if constexpr (std::is_same<S, DivideStage>::value) ++divides;
  }
  template <class S>
  void out(const typename S::Out& o) {
    if constexpr (std::is_same<S, SetupStage>::value) planes += (uint64_t)o.interp.n;
    if constexpr (std::is_same<S, InterpStage>::value) {
      ++samples;
      bool nd = o.den != 0;
      for (int m = 0; m < kMaxVaryings; ++m) nd = nd || o.num[m] != 0;
      samples_with_nd += nd;
    }
  }
};

}  // namespace

// "No varyings → no divider work": a draw whose fragments nobody keeps (no sink) builds no
// 1/w or v/w plane, steps no N or D and never reaches the divider, whatever its varying count,
// and counts and depth-tests exactly as the same draw kept by a sink; a draw without varyings
// kept by a sink builds no plane either (the divider gets D = N = 0: nothing to divide). The
// draws with varyings and a sink show that the taps see the work when there is some.
TEST(Shortcut, NoVaryingsMeansNoPlaneNoSumAndNoDivide) {
  std::mt19937_64 rng(0x5c05);
  const Config cfg;
  for (int trial = 0; trial < 3; ++trial) {
    DrawState st = state(200, 150, 0, 0, 2);
    const std::vector<ClipTriangle> tris = random_scene(rng, 300, 2);
    FrameOutput none, kept, novary;
    WorkTap t_none, t_kept, t_novary;
    KeepSink s_kept, s_novary;
    run_raster_unit_to(cfg, st, tris, none, nullptr, t_none);
    run_raster_unit_to(cfg, st, tris, kept, &s_kept, t_kept);
    DrawState st0 = st;
    st0.num_varyings = 0;
    run_raster_unit_to(cfg, st0, tris, novary, &s_novary, t_novary);
    // No sink: nothing of the varyings is computed past geometry.
    EXPECT_EQ(t_none.planes, 0u);
    EXPECT_EQ(t_none.samples_with_nd, 0u);
    EXPECT_EQ(t_none.divides, 0u);
    EXPECT_GT(t_none.samples, 1000u);
    EXPECT_EQ(stats_fields(none.stats), stats_fields(kept.stats));
    EXPECT_EQ(none.depth, kept.depth);
    // Kept with varyings: planes, sums and divides happen (the taps can see them).
    EXPECT_GT(t_kept.planes, 100u);
    EXPECT_GT(t_kept.samples_with_nd, 1000u);
    EXPECT_EQ(t_kept.divides, s_kept.v.size());
    // Kept without varyings: no plane, no sum; the same fragments without their varyings.
    EXPECT_EQ(t_novary.planes, 0u);
    EXPECT_EQ(t_novary.samples_with_nd, 0u);
    ASSERT_EQ(s_novary.v.size(), s_kept.v.size());
    for (size_t i = 0; i < s_kept.v.size(); ++i) ASSERT_TRUE(same_fragment(s_novary.v[i], s_kept.v[i], 0)) << i;
  }
}

// VertexCache::set_rw_unread (docs/speed.md "Session 12: per triangle"): a cache whose caller
// reads no rw answers the same triangles as one that computes it, each equal to the full
// chain's in every field but rw, which is 0 with separate attribute positions (the exact 1/w_c,
// never 0, not computed) and the full chain's without them (rw = r, kept); the same hits and
// misses. Meshes with hard vertices, 0 and 2 varyings, both position paths, small tables; the
// same for caches on shared tables (the threads'), whose flag is the table's (SharedVertexTable::begin).
TEST(Shortcut, VertexCacheWithRwUnreadDiffersFromTheFullChainOnlyInRw) {
  std::mt19937_64 rng(0x5c0c);
  for (const bool attr : {true, false}) {
    Config cfg;
    if (!attr) cfg.raster.attr_subpixel_bits = cfg.raster.subpixel_bits;
    uint64_t answered = 0;
    for (int trial = 0; trial < 4; ++trial) {
      DrawState st = state(200 + 40 * trial, 150, trial % 2 ? -7 : 0, 0, trial);
      st.num_varyings = trial % 2 ? 2 : 0;
      const std::vector<ClipTriangle> tris = grid_mesh(rng, 60, st.num_varyings, trial % 2 ? 1.05 : 0.7);
      VertexCache unread(cfg, st, 8, 0), plain(cfg, st, 8, 0);
      unread.set_rw_unread(true);
      // The same on shared tables (the threads'): the flag is the table's (begin), and a cache's
      // own set_rw_unread is ignored once it shares.
      SharedVertexTable unread_table, plain_table;
      unread_table.begin(st.num_varyings, true);
      plain_table.begin(st.num_varyings, false);
      VertexCache shared_unread(cfg, st, 8, 0), shared_plain(cfg, st, 8, 0);
      shared_unread.share(unread_table);
      shared_plain.set_rw_unread(true);  // before share(): the table's false wins
      shared_plain.share(plain_table);
      shared_unread.set_rw_unread(false);  // after share(): ignored
      FullPathTap ft;
      GeometryChain<FullPathTap> full(cfg, st, ft);
      for (size_t p = 0; p < tris.size(); ++p) {
        SetupTriangle a, b, sa, sb;
        const bool ra = unread.triangle(tris[p], (uint32_t)p, a), rb = plain.triangle(tris[p], (uint32_t)p, b);
        ASSERT_EQ(ra, rb) << "primitive " << p;
        ASSERT_EQ(shared_unread.triangle(tris[p], (uint32_t)p, sa), ra) << "primitive " << p;
        ASSERT_EQ(shared_plain.triangle(tris[p], (uint32_t)p, sb), ra) << "primitive " << p;
        if (!ra) continue;
        ++answered;
        SetupTriangle want;
        ASSERT_TRUE(full_chain_setup(full, tris[p], (uint32_t)p, want));
        ASSERT_TRUE(same_setup(b, want)) << "primitive " << p;
        ASSERT_TRUE(same_setup(sb, want)) << "primitive " << p;
        for (int k = 0; k < 3; ++k) {
          const FxFloat& rw = want.v[k].rw;
          if (attr) {
            ASSERT_TRUE(rw.sig != 0 && same_fx(a.v[k].rw, FxFloat{})) << "primitive " << p << " vertex " << k;
            ASSERT_TRUE(same_fx(sa.v[k].rw, FxFloat{})) << "primitive " << p << " vertex " << k;
            a.v[k].rw = rw;
            sa.v[k].rw = rw;
          }
        }
        ASSERT_TRUE(same_setup(a, want)) << "primitive " << p;
        ASSERT_TRUE(same_setup(sa, want)) << "primitive " << p;
      }
      EXPECT_EQ(unread.hits(), plain.hits());
      EXPECT_EQ(unread.misses(), plain.misses());
      EXPECT_EQ(shared_unread.hits(), plain.hits());
      EXPECT_EQ(shared_plain.misses(), plain.misses());
      EXPECT_GT(unread.hits(), 1000u);
      EXPECT_GT(unread.misses(), 1000u);
    }
    EXPECT_GT(answered, 5000u);
  }
}

// The whole unit without a 1/w plane (no varyings with a sink; varyings without a sink): its
// vertex cache leaves rw uncomputed (UnitChain), and every fragment, the depth buffer and every
// counter are the full chain's.
TEST(Shortcut, UnitChainWithoutA1OverWPlaneEqualsTheFullPath) {
  SceneOptions o;
  o.width = 256, o.height = 192;
  const Scene sc = default_scene(o);
  ASSERT_GT(sc.tris.size(), 10000u);
  for (const bool with_sink : {true, false}) {
    DrawState st = sc.state;
    if (with_sink) st.num_varyings = 0;
    ASSERT_TRUE(!with_sink || attr_separate(sc.config.raster));  // the path that drops rw
    FrameOutput fast, full;
    KeepSink fs, us;
    NoTaps nt;
    FullPathTap ft;
    run_raster_unit_to(sc.config, st, sc.tris, fast, with_sink ? &fs : nullptr, nt);
    run_raster_unit_to(sc.config, st, sc.tris, full, with_sink ? &us : nullptr, ft);
    EXPECT_EQ(stats_fields(fast.stats), stats_fields(full.stats));
    EXPECT_EQ(fast.depth, full.depth);
    EXPECT_GT(fast.stats.fragments_depth_pass, 10000u);
    ASSERT_EQ(fs.v.size(), us.v.size());
    for (size_t i = 0; i < fs.v.size(); ++i) ASSERT_TRUE(same_fragment(fs.v[i], us.v[i], 0)) << "fragment " << i;
  }
}

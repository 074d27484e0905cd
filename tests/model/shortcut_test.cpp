// "Model only what a scene needs" (docs/speed.md "Shortcuts"), each shortcut run against the
// full path it replaces on the same scenes:
//   - no sink and the depth test off: nothing reads a depth code nor a varying, so the chain
//     counts each span's pixels and skips stages 7–8 (FragmentChain's count-only path); the full
//     path is forced by a tap (any Taps other than NoTaps observes every stage);
//   - affine mode: D = 2A is constant over the triangle, so DivideStage normalises it once per
//     triangle instead of per pixel; against divide_varying(normalize_den(...)) of every sample.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "geom_ref.hpp"
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

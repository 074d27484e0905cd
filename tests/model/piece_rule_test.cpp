// The rejected-piece rule and the unit's counters (docs/pipeline.md, "Statistics: primitives,
// pieces, setup triangles"): a clipped piece that fails in stage 3 or 4 is dropped alone, the
// primitive's other pieces are drawn; setup outcomes count once per setup triangle
// (RasterStats::tris, the RTL's tri_* counters) and once per primitive (the dispositions).
// Expected values come from the geometry of the cases (tests/model/piece_cases.hpp) and from the
// same primitive at the default configuration, where no piece fails: not from the rule under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "model/unit/chain.hpp"
#include "piece_cases.hpp"

using namespace fxr;

namespace {

// Records every clipper output and every setup input of a draw.
struct PieceTaps {
  std::vector<ClippedTriangle> clipped;
  std::vector<SetupTriangle> setup;
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out& o) {
    if constexpr (std::is_same_v<S, ClipStage>) clipped.push_back(o);
    if constexpr (std::is_same_v<S, ViewportStage>) setup.push_back(o);
  }
};

struct DrawRun {
  RasterStats stats;
  std::vector<Fragment> fragments;
  PieceTaps taps;
};

DrawRun draw(const Config& cfg, const ClipTriangle& t) {
  DrawRun r;
  const DrawState st = piece_cases::state();
  FrameOutput f;
  frame_begin(cfg, st, f);
  KeepFragments keep(f.fragments);
  {
    UnitChain<PieceTaps> chain(cfg, st, f, &keep, r.taps);
    chain.draw(t, 0);
  }
  r.stats = f.stats;
  r.fragments = f.fragments.to_vector();
  return r;
}

// A vertex on the w_min plane: w = 2^kWMinExp exactly.
bool at_w_min(const ClipVtx& v) {
  const FxFloat& w = v.p[3];
  if (w.neg || w.sig == 0 || (w.sig & (w.sig - 1)) != 0) return false;
  int lead = w.exp;
  for (u128 s = w.sig; s > 1; s >>= 1) ++lead;
  return lead == kWMinExp;
}

bool same_setup(const SetupTriangle& a, const SetupTriangle& b) {
  for (int i = 0; i < 3; ++i)
    if (a.v[i].x != b.v[i].x || a.v[i].y != b.v[i].y || a.v[i].z != b.v[i].z || a.v[i].ax != b.v[i].ax ||
        a.v[i].ay != b.v[i].ay)
      return false;
  return a.prim == b.prim;
}

uint64_t dispositions(const RasterStats& s) {
  return s.prims_drawn + s.prims_culled_outside + s.prims_culled_zero_area + s.prims_culled_backface +
         s.prims_culled_no_samples + s.prims_rejected_nan + s.prims_rejected_inf + s.prims_rejected_range;
}

TEST(PieceRule, APieceFailingInStage3IsDroppedAloneAndTheOthersAreDrawn) {
  const ClipTriangle t = piece_cases::through_the_eye();
  Config narrow;
  narrow.recip.exp_bits = 8;  // 1/w up to 2^127: w = 2^-160 overflows the reciprocal unit
  const DrawRun d = draw(Config{}, t), n = draw(narrow, t);

  // The clipper does not depend on the reciprocal unit: the same pieces, some on the w_min plane.
  ASSERT_EQ(d.taps.clipped.size(), 3u);
  ASSERT_EQ(n.taps.clipped.size(), 3u);
  std::vector<bool> wmin;
  for (const ClippedTriangle& c : d.taps.clipped)
    wmin.push_back(at_w_min(c.v[0]) || at_w_min(c.v[1]) || at_w_min(c.v[2]));
  const size_t failing = (size_t)std::count(wmin.begin(), wmin.end(), true);
  ASSERT_EQ(failing, 2u) << "the case must have pieces with and without a vertex at w = 2^-160";

  // Default: every piece reaches setup. Narrow: exactly those without a w_min vertex, unchanged.
  EXPECT_EQ(d.stats.tris.geom_rejected_range, 0u);
  ASSERT_EQ(d.taps.setup.size(), 3u);
  EXPECT_EQ(n.stats.tris.geom_rejected_range, failing);
  std::vector<SetupTriangle> kept;
  for (size_t i = 0; i < d.taps.setup.size(); ++i)
    if (!wmin[i]) kept.push_back(d.taps.setup[i]);
  ASSERT_EQ(n.taps.setup.size(), kept.size());
  for (size_t i = 0; i < kept.size(); ++i) EXPECT_TRUE(same_setup(n.taps.setup[i], kept[i])) << "piece " << i;

  // The primitive is drawn (not rejected whole); its fragments are the default's that the kept
  // piece covers: a non-empty proper subset.
  EXPECT_EQ(n.stats.prims_drawn, 1u);
  EXPECT_EQ(n.stats.prims_rejected_range, 0u);
  EXPECT_EQ(dispositions(n.stats), n.stats.prims_in);
  EXPECT_EQ(n.stats.tris.in, kept.size());
  ASSERT_GT(n.fragments.size(), 0u);
  EXPECT_LT(n.fragments.size(), d.fragments.size());
  for (const Fragment& f : n.fragments)
    EXPECT_TRUE(std::any_of(d.fragments.begin(), d.fragments.end(), [&](const Fragment& g) {
      return g.x == f.x && g.y == f.y && g.depth == f.depth;
    })) << "fragment (" << f.x << ", " << f.y << ") is not one of the default's";
}

TEST(PieceRule, EveryPieceFailingRejectsThePrimitiveForRange) {
  // The same edge through the eye with the third vertex behind it: every piece has a w_min vertex.
  ClipTriangle t = piece_cases::through_the_eye();
  t.v[2] = piece_cases::vertex(0.0f, 0.0f, -0.25f, -0.5f, 2.0f, -1.0f);
  Config narrow;
  narrow.recip.exp_bits = 8;
  const DrawRun n = draw(narrow, t);
  ASSERT_GT(n.taps.clipped.size(), 0u);
  for (const ClippedTriangle& c : n.taps.clipped)
    ASSERT_TRUE(at_w_min(c.v[0]) || at_w_min(c.v[1]) || at_w_min(c.v[2]));
  EXPECT_EQ(n.stats.tris.geom_rejected_range, n.taps.clipped.size());
  EXPECT_EQ(n.stats.prims_rejected_range, 1u);
  EXPECT_EQ(n.stats.tris.in, 0u);
  EXPECT_TRUE(n.fragments.empty());
}

TEST(PieceRule, PiecesWithDifferentSetupOutcomesCountPerTriangleAndOncePerPrimitive) {
  // Two pieces: (v0, v1, P) over the viewport, drawn; (v0, P, Q) right of it, no samples.
  const DrawRun r = draw(Config{}, piece_cases::near_into_the_band());
  EXPECT_EQ(r.stats.prims_clipped, 1u);
  EXPECT_EQ(r.stats.clip_triangles_out, 2u);
  EXPECT_EQ(r.stats.tris.in, 2u);
  EXPECT_EQ(r.stats.tris.drawn, 1u);
  EXPECT_EQ(r.stats.tris.no_samples, 1u);
  EXPECT_EQ(r.stats.tris.zero_area + r.stats.tris.backface + r.stats.tris.range, 0u);
  EXPECT_EQ(r.stats.prims_drawn, 1u);  // once, as drawn
  EXPECT_EQ(r.stats.prims_culled_no_samples, 0u);
  EXPECT_EQ(dispositions(r.stats), 1u);
  EXPECT_GT(r.fragments.size(), 0u);
  for (const Fragment& f : r.fragments) EXPECT_LT(f.x, 48);
}

}  // namespace

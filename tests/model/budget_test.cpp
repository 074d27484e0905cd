// The error budget (analysis/budget.hpp, analysis/budget_path.hpp; docs/reports.md "Error budget").
// The analysis path is checked against two independent references: with every rounding point
// active it must be the bit-accurate model's fragment (depth code and every varying, as exact
// rationals), and with every point exact it must be IdealJudge's exact value of the unsnapped
// triangle (a separate derivation: the clip-space plane solve of analysis/ideal.cpp), exactly.
// Attribution: triangles and configurations built so that one rounding point dominates by
// design; that point must get the error.
#include <gtest/gtest.h>

#include "analysis/budget.hpp"
#include "analysis/ideal.hpp"
#include "frontend/scene.hpp"

namespace {

using namespace fxr;

Scene scene_of(const IdealScene& s) {
  Scene sc;
  sc.name = s.name;
  sc.state = s.st;
  sc.tris = s.tris;
  sc.u_varying = 0;
  sc.v_varying = 1;
  return sc;
}

void expect_path_is_model_and_ideal(const Scene& sc, int samples) {
  BudgetOptions o;
  o.samples = samples;
  o.threads = 2;
  const BudgetResult r = run_budget(sc, o);
  EXPECT_GT(r.sampled, 100u) << sc.name;
  EXPECT_EQ(r.model_mismatches, 0u) << sc.name;  // every point active: the model's fragment
  EXPECT_EQ(r.exact_nonzero, 0u) << sc.name;     // every point exact: the ideal, exactly
  EXPECT_LT(r.skipped, r.sampled / 10) << sc.name;
}

TEST(Budget, AllActiveIsTheModelAndAllExactIsTheIdealOnTheDefaultScene) {
  expect_path_is_model_and_ideal(default_scene({}), 1500);
}

TEST(Budget, AllActiveIsTheModelAndAllExactIsTheIdealOnClippedAndHardScenes) {
  // Near-plane clipping (new vertices), w ratios to 10^6 (block alignment beyond 2^8), slivers.
  expect_path_is_model_and_ideal(scene_of(ideal_near_clipped(192)), 800);
  expect_path_is_model_and_ideal(scene_of(ideal_w_ratio(192)), 800);
  expect_path_is_model_and_ideal(scene_of(ideal_slivers(192)), 600);
}

TEST(Budget, ResultDoesNotDependOnTheThreadCount) {
  Scene sc = scene_of(ideal_near_clipped(128));
  BudgetOptions a, b;
  a.samples = b.samples = 400;
  a.threads = 1;
  b.threads = 3;
  EXPECT_EQ(budget_json(run_budget(sc, a)).dump(), budget_json(run_budget(sc, b)).dump());
}

// ---- attribution: one point dominates by design ----------------------------------------------

ClipVertex cv(float x, float y, float z, float w, float u, float v) {
  ClipVertex o;
  o.pos[0] = x, o.pos[1] = y, o.pos[2] = z, o.pos[3] = w;
  o.var[0] = u, o.var[1] = v;
  return o;
}

Scene constructed(std::vector<ClipTriangle> tris) {
  Scene sc;
  sc.name = "constructed";
  sc.state.viewport_w = sc.state.viewport_h = 128;
  sc.state.num_varyings = 2;
  sc.state.depth_func = DepthFunc::Always;
  sc.tris = std::move(tris);
  sc.u_varying = 0;
  sc.v_varying = 1;
  return sc;
}

// A perspective triangle over most of the viewport: w 1 … 5, depth steep, u, v 0 … 16.
ClipTriangle persp() {
  ClipTriangle t;
  t.v[0] = cv(-0.9f, -0.9f, 0.05f, 1.0f, 0.0f, 0.0f);
  t.v[1] = cv(4.3f, -4.1f, 4.7f, 5.0f, 16.0f, 1.0f);
  t.v[2] = cv(-0.2f, 2.6f, 2.2f, 3.0f, 3.0f, 16.0f);
  return t;
}

// The share of `p` is the largest (point or residual) on at least `frac` of the fragments of
// output `out`, and the error there is at least `min_err` at its maximum (so the design worked).
void expect_dominates(const Scene& sc, RoundPoint p, const std::string& out, double frac, double min_err) {
  BudgetOptions o;
  o.samples = 600;
  const BudgetResult r = run_budget(sc, o);
  ASSERT_EQ(r.model_mismatches, 0u);
  ASSERT_EQ(r.exact_nonzero, 0u);
  for (const BudgetOutput& b : r.outputs) {
    if (b.name != out) continue;
    ASSERT_GT(b.err.n(), 100u);
    EXPECT_GE(b.err.max(), min_err) << round_point_info(p).name;
    EXPECT_GE((double)b.dominant[(int)p], frac * (double)b.err.n())
        << round_point_info(p).name << " on " << out << ": dominant on " << b.dominant[(int)p] << " of " << b.err.n();
    // Its share carries most of the error on average.
    EXPECT_GE(b.share[(int)p].mean(), 0.8 * b.err.mean()) << round_point_info(p).name;
    return;
  }
  FAIL() << "no output " << out;
}

TEST(BudgetAttribution, DepthCodeDominatesDepthAtTheDefaults) {
  expect_dominates(constructed({persp()}), RoundPoint::DepthCode, "depth", 0.95, 0.45);
}

TEST(BudgetAttribution, DividerDominatesVaryingsAtTheDefaults) {
  expect_dominates(constructed({persp()}), RoundPoint::Divider, "u", 0.9, 0.45);
}

TEST(BudgetAttribution, CoarseAttributePositionsDominateDepth) {
  Scene sc = constructed({persp()});
  sc.config.raster.attr_subpixel_bits = 9;  // one bit beyond the 8-bit snap: ≤ 2^−10 px per vertex
  expect_dominates(sc, RoundPoint::AttrPosition, "depth", 0.8, 20);
}

TEST(BudgetAttribution, NarrowAttributeCoordinatesDominateDepth) {
  Scene sc = constructed({persp()});
  sc.config.raster.attr_coord_bits = sc.config.raster.window_int_bits + 3;  // drops to F = 8 − 2 here
  expect_dominates(sc, RoundPoint::AttrCoord, "depth", 0.8, 20);
}

TEST(BudgetAttribution, NarrowPerVertexReciprocalsAndQuotientsDominateVaryings) {
  Scene sc = constructed({persp()});
  sc.config.raster.attr_sig_bits = 10;  // 1/w and v/w to 10 bits: 2^−11 relative, ~2^13 output ulps
  BudgetOptions o;
  o.samples = 600;
  const BudgetResult r = run_budget(sc, o);
  ASSERT_EQ(r.model_mismatches, 0u);
  const BudgetOutput& u = r.outputs[1];
  EXPECT_GE(u.err.max(), 100.0);
  // The two points of this width together carry the error (each alone: its own half).
  const double both = u.share[(int)RoundPoint::Recip].mean() + u.share[(int)RoundPoint::VaryingW].mean();
  EXPECT_GE(both, 0.7 * u.err.mean());
  EXPECT_GE(u.dominant[(int)RoundPoint::Recip] + u.dominant[(int)RoundPoint::VaryingW] + u.dominant[kNumRoundPoints],
            (uint64_t)(0.9 * (double)u.err.n()));
}

TEST(BudgetAttribution, NarrowBlocksDominateVaryingsAtLargeWRatios) {
  ClipTriangle t = persp();
  t.v[1].pos[0] *= 300, t.v[1].pos[1] *= 300, t.v[1].pos[2] *= 300, t.v[1].pos[3] *= 300;  // w ratio 1500
  Scene sc = constructed({t});
  sc.config.raster.interp_block_bits = 20;  // exact only to w ratios of 2^(20 − 32): never here
  expect_dominates(sc, RoundPoint::BlockAlign, "u", 0.8, 100);
}

TEST(BudgetAttribution, NarrowDividerOperandsDominateVaryings) {
  Scene sc = constructed({persp()});
  sc.config.div.num_bits = sc.config.div.den_bits = 12;
  expect_dominates(sc, RoundPoint::Normalise, "u", 0.8, 100);
}

TEST(BudgetAttribution, NarrowClipperOutputsDominateOnAClippedTriangle) {
  ClipTriangle t = persp();
  t.v[0].pos[2] = -0.6f;  // behind the near plane: two new vertices
  Scene sc = constructed({t});
  sc.config.raster.clip_sig_bits = 16;
  expect_dominates(sc, RoundPoint::Clip, "u", 0.8, 20);
}

TEST(BudgetPath, PointNamesRoundTrip) {
  for (int p = 0; p < kNumRoundPoints; ++p) {
    RoundPoint q;
    ASSERT_TRUE(round_point_from_name(round_point_info((RoundPoint)p).name, &q));
    EXPECT_EQ((int)q, p);
  }
  RoundPoint q;
  EXPECT_FALSE(round_point_from_name("no_such_point", &q));
}

}  // namespace

// ---- scene analysis and planner (analysis/scene_analysis.hpp, analysis/plan.hpp) -------------

#include "analysis/plan.hpp"
#include "analysis/scene_analysis.hpp"
#include "model/stages/clip.hpp"

namespace {

TEST(SceneAnalysis, RangesAndNeverExercisedFeatures) {
  ClipTriangle t = persp();
  t.v[0].pos[2] = -0.6f;  // crosses the near plane
  const SceneAnalysis a = analyze_scene(constructed({t, persp()}));
  EXPECT_EQ(a.prims, 2u);
  EXPECT_EQ(a.prims_clipped, 1u);
  EXPECT_EQ(a.plane_clips[kPlaneNear], 1u);
  EXPECT_EQ(a.plane_clips[kPlaneFar], 0u);
  EXPECT_DOUBLE_EQ(a.w_min, 1.0);
  EXPECT_DOUBLE_EQ(a.w_max, 5.0);
  EXPECT_DOUBLE_EQ(a.w_ratio_max, 5.0);
  EXPECT_EQ(a.overlapping_pixels > 0, true);  // the two triangles overlap
  bool far_unused = false, clipper_unused = false;
  for (const std::string& u : a.unused) far_unused |= u.find("far") != std::string::npos, clipper_unused |= u.find("no primitive is clipped") != std::string::npos;
  EXPECT_TRUE(far_unused);
  EXPECT_FALSE(clipper_unused);
  // The window format: a 128-pixel viewport needs L = 2^(b−1) − 1 ≥ 128, b = 9.
  for (const MinWidth& w : a.widths) {
    if (w.field == "raster.window_int_bits") {
      EXPECT_EQ(w.min, 9);
    }
  }
}

TEST(Plan, TargetParsesAndRejectsNonsense) {
  const auto t = parse_plan_target("u,v <= 1/16 texel; depth <= 1 LSB; image pixels differing from the exact image <= 0");
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0].output, "u");
  EXPECT_EQ(t[1].output, "v");
  EXPECT_DOUBLE_EQ(t[1].max, 1.0 / 16);
  EXPECT_EQ(t[1].unit, "texel");
  EXPECT_EQ(t[2].output, "depth");
  EXPECT_EQ(t[2].unit, "LSB");
  EXPECT_EQ(t[3].output, "pixels");
  EXPECT_THROW(parse_plan_target("u <= x texel"), ConfigError);
  EXPECT_THROW(parse_plan_target("u < 1 texel"), ConfigError);
  EXPECT_THROW(parse_plan_target("depth <= 1 texel"), ConfigError);
  EXPECT_THROW(parse_plan_target("u <= 1 furlong"), ConfigError);
}

TEST(Plan, ChosenIsCheaperMeetsTheTargetIsMinimalAndThreadIndependent) {
  const Scene sc = constructed({persp()});
  PlanOptions o;
  o.target = parse_plan_target("u,v <= 64 ulp; depth <= 1 LSB");
  o.samples = 200;
  o.threads = 1;
  const PlanResult a = run_plan({sc}, o);
  o.threads = 3;
  const PlanResult b = run_plan({sc}, o);
  EXPECT_EQ(plan_json(a, o).dump(), plan_json(b, o).dump());
  EXPECT_TRUE(a.start.meets);
  EXPECT_TRUE(a.chosen.meets);
  EXPECT_LT(a.chosen.cost, a.start.cost);
  for (const MinimalityRow& m : a.minimality) EXPECT_TRUE(m.holds) << m.dimension << ": " << m.verdict;
  // Re-measured by the budget on every fragment (not only the plan's sample).
  Scene again = sc;
  again.config = a.chosen.cfg;
  BudgetOptions bo;
  bo.samples = 0;
  bo.threads = 2;
  const BudgetResult r = run_budget(again, bo);
  EXPECT_EQ(r.model_mismatches, 0u);
  EXPECT_EQ(r.exact_nonzero, 0u);
  EXPECT_LE(r.outputs[0].err.max(), 1.0);
  EXPECT_LE(r.outputs[1].err.max(), 64.0);
  EXPECT_LE(r.outputs[2].err.max(), 64.0);
}

}  // namespace

namespace {

TEST(Plan, AStartThatMissesWidensFirstAndAnUnreachableTargetIsReportedAsMissed) {
  Scene sc = constructed({persp()});
  sc.texture.image = Image(64, 64, 0);  // u, v in texels of a 64 × 64 texture
  PlanOptions o;
  o.samples = 150;
  o.threads = 2;
  // 24-bit u, v near 16 carry ~2^−20 · 16 · 64 ≈ 1e-3 texel; 32-bit ones 256 times less.
  o.target = parse_plan_target("u,v <= 2e-5 texel");
  const PlanResult a = run_plan({sc}, o);
  EXPECT_FALSE(a.start.meets);
  EXPECT_TRUE(a.widened);
  EXPECT_TRUE(a.chosen.meets);
  EXPECT_GT(a.chosen.cfg.raster.varying_out_sig_bits, sc.config.raster.varying_out_sig_bits);
  // No output format makes the depth error against the exact value 0: unreachable, reported.
  o.target = parse_plan_target("depth <= 0 LSB");
  const PlanResult b = run_plan({sc}, o);
  EXPECT_TRUE(b.widened);
  EXPECT_FALSE(b.chosen.meets);
}

}  // namespace

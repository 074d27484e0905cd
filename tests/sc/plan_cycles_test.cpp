// `fxraster plan --cost cycles` (issue 13; docs/reports.md, "Planner"): the cost is the cycle
// model's clocks per frame (sc/cycle_model.hpp), summed over the scenes — recomputed here in
// process with run_unit_cycles, not taken from the planner — and the plan is the same for any
// thread count. unit_frame_clocks (a child process per run) equals the in-process run.
#include <gtest/gtest.h>

#include "analysis/plan.hpp"
#include "frontend/scene.hpp"
#include "model/config/validate.hpp"
#include "sc/cycle_model.hpp"
#include "sc/frame_clocks.hpp"

namespace {

using namespace fxr;

Scene small(int w, int h) {
  SceneOptions so;
  so.no_optional = true;
  so.width = w, so.height = h;
  return default_scene(so);
}

uint64_t in_process_clocks(const Config& c, const Scene& s) {
  FrameOutput f;
  return cyc::run_unit_cycles(c, ArchConfig{}, s.state, s.tris, f, nullptr).clocks;
}

TEST(FrameClocks, TheChildProcessGivesTheInProcessClocks) {
  const Scene s = small(96, 64);
  Config c = s.config;
  const uint64_t a = cyc::unit_frame_clocks(c, ArchConfig{}, s.state, s.tris);
  EXPECT_EQ(a, in_process_clocks(c, s));
  EXPECT_GT(a, 0u);
  c.raster.depth_format = DepthFormat::D16;  // fewer quotient bits in fxr_interp's front: fewer clocks
  EXPECT_LT(cyc::unit_frame_clocks(c, ArchConfig{}, s.state, s.tris), a);
  ArchConfig bad;
  bad.link_depth = 0;
  EXPECT_THROW(cyc::unit_frame_clocks(c, bad, s.state, s.tris), std::exception);
}

TEST(PlanCycles, TheCostIsClocksPerFrameSummedOverTheScenesForAnyThreadCount) {
  std::vector<Scene> scenes = {small(32, 24), small(24, 32)};
  // A narrower start than the default (it meets the target too): shorter ladders, a test of seconds.
  for (Scene& s : scenes) {
    RasterConfig& r = s.config.raster;
    r.attr_subpixel_bits = 20, r.attr_coord_bits = 30, r.attr_sig_bits = 18, r.interp_block_bits = 24;
    r.z_frac_bits = 28, r.varying_out_sig_bits = 18, r.clip_sig_bits = 24;
    s.config.div.num_bits = s.config.div.den_bits = 20;
    derive_widths(s.config);
  }
  PlanOptions o;
  o.target = parse_plan_target("u,v <= 1/16 texel; depth <= 1 LSB");
  o.cost = PlanCost::Cycles;
  o.samples = 60;
  o.frame_clocks = [](const Config& c, const Scene& s) { return cyc::unit_frame_clocks(c, ArchConfig{}, s.state, s.tris); };
  o.threads = 1;
  const PlanResult a = run_plan(scenes, o);
  o.threads = 2;
  const PlanResult b = run_plan(scenes, o);
  EXPECT_EQ(plan_json(a, o).dump(), plan_json(b, o).dump());
  for (const PlanEval* e : {&a.start, &a.chosen}) {
    uint64_t want = 0;
    for (const Scene& s : scenes) want += in_process_clocks(e->cfg, s);
    EXPECT_EQ((uint64_t)e->cost, want) << e->label;
  }
  EXPECT_TRUE(a.start.meets) << a.start.ratio;
  EXPECT_TRUE(a.verified.meets);
  EXPECT_LT(a.chosen.cost, a.start.cost);
  for (const MinimalityRow& m : a.minimality) EXPECT_TRUE(m.holds) << m.dimension << ": " << m.verdict;
  // Without a cycle model the planner refuses the cost instead of guessing.
  o.frame_clocks = nullptr;
  EXPECT_THROW(run_plan(scenes, o), ConfigError);
}

}  // namespace

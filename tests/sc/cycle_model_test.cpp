// The cycle-approximate SystemC model (sc/cycle_model.hpp, docs/cycles.md): the fragment stream
// it carries is the bit-accurate model's (run_raster_unit_to: model/unit/chain.hpp) bit for bit
// and in order, the depth buffer after the draw too; its timing follows the stages' cost() on
// draws whose clocks are known by hand; the architecture knobs are the RTL's parameters.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "frontend/scene.hpp"
#include "model/config/arch_config.hpp"
#include "model/stages/viewport.hpp"
#include "model/unit/chain.hpp"
#include "sc/cycle_model.hpp"

namespace {

struct Collect : fxr::FragmentSink {
  std::vector<fxr::Fragment> v;
  void emit(const fxr::Fragment& f) override { v.push_back(f); }
};

bool same(const fxr::Fragment& a, const fxr::Fragment& b, int nv) {
  if (a.prim != b.prim || a.x != b.x || a.y != b.y || a.depth != b.depth) return false;
  for (int m = 0; m < nv; ++m)
    if (a.var[m].neg != b.var[m].neg || a.var[m].sig != b.var[m].sig || a.var[m].exp != b.var[m].exp) return false;
  return true;
}

// The model's stream and buffer, and the cycle model's on the same draw.
void expect_same_stream(const fxr::Scene& sc, const fxr::ArchConfig& arch, const std::string& what) {
  fxr::FrameOutput want;
  Collect ws;
  fxr::NoTaps taps;
  fxr::run_raster_unit_to(sc.config, sc.state, sc.tris, want, &ws, taps);
  fxr::FrameOutput got;
  Collect gs;
  const fxr::cyc::CycleRun r = fxr::cyc::run_unit_cycles(sc.config, arch, sc.state, sc.tris, got, &gs);
  ASSERT_EQ(gs.v.size(), ws.v.size()) << what;
  size_t bad = 0;
  for (size_t i = 0; i < ws.v.size(); ++i)
    if (!same(gs.v[i], ws.v[i], sc.state.num_varyings) && bad++ < 5)
      ADD_FAILURE() << what << ": fragment " << i << " differs";
  EXPECT_EQ(bad, 0u) << what;
  EXPECT_TRUE(got.depth == want.depth) << what << ": final depth buffer";
  EXPECT_EQ(r.passed, want.stats.fragments_depth_pass) << what;
  EXPECT_EQ(r.samples, want.stats.fragments_generated) << what;
  EXPECT_GT(r.clocks, r.samples / 2) << what;
  std::printf("%s: %llu clocks, %llu fragments, %.3f s\n", what.c_str(), (unsigned long long)r.clocks,
              (unsigned long long)r.passed, r.seconds);
}

TEST(CycleModel, DefaultSceneFragmentStreamIsTheModels) {
  expect_same_stream(fxr::default_scene(), fxr::ArchConfig{}, "default");
}

TEST(CycleModel, KnobsChangeClocksNotValues) {
  fxr::SceneOptions so;
  so.no_optional = true;
  so.width = so.height = 128;
  const fxr::Scene sc = fxr::default_scene(so);
  fxr::ArchConfig a;
  a.tri_fifo_depth = 2;
  a.depth_queue_depth = 2;
  a.depth_write_port = 0;
  a.interp_div_steps = 1;
  a.divide_lanes = 1;
  a.mem_latency = 7;
  a.link_depth = 3;
  expect_same_stream(sc, a, "checkerboard 128, every knob moved");
}

}  // namespace

namespace {

// The knobs' defaults are the parameters rtl/fxr_raster_backend.sv is built from (read from its
// source: the module's `parameter int Name = value` lines).
int rtl_param(const std::string& src, const std::string& name) {
  const std::regex re("parameter\\s+(?:int|bit)\\s+" + name + "\\s*=\\s*(?:1'b)?(\\d+)");
  std::smatch m;
  if (!std::regex_search(src, m, re)) {
    ADD_FAILURE() << "rtl/fxr_raster_backend.sv: no parameter " << name;
    return -1;
  }
  return std::stoi(m[1]);
}

TEST(ArchConfig, DefaultsAreTheBackendRtlParameters) {
  const char* dir = std::getenv("FXR_SOURCE_DIR");  // ctest's environment; the working directory is the source
  std::ifstream in(std::string(dir ? dir : ".") + "/rtl/fxr_raster_backend.sv");
  ASSERT_TRUE(in) << "rtl/fxr_raster_backend.sv";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string src = ss.str();
  const fxr::ArchConfig a;
  EXPECT_EQ(a.tri_fifo_depth, rtl_param(src, "TriFifoDepth"));
  EXPECT_EQ(a.depth_queue_depth, rtl_param(src, "DepthQueueDepth"));
  EXPECT_EQ(a.depth_write_port, rtl_param(src, "DepthWritePort"));
  EXPECT_EQ(a.interp_div_steps, rtl_param(src, "InterpDivSteps"));
  EXPECT_EQ(a.divide_lanes, 0) << "DivideLanes defaults to NumVaryings: lanes 0 means one per varying";
  EXPECT_EQ(fxr::kDepthQueueDepth, a.depth_queue_depth);
  // Stage 4's lanes: fxr_raster_unit's ViewportLanes, emitted from kViewportLanes into fxr_rec_pkg.
  EXPECT_EQ(a.viewport_lanes, fxr::kViewportLanes);
}

TEST(ArchConfig, JsonRoundTripAndErrorsNameTheField) {
  fxr::ArchConfig a;
  a.tri_fifo_depth = 8;
  a.mem_latency = 5;
  const fxr::ArchConfig b = fxr::arch_from_json(fxr::arch_to_json(a), "x.json");
  EXPECT_EQ(b.tri_fifo_depth, 8);
  EXPECT_EQ(b.mem_latency, 5);
  auto err = [](const char* text) {
    try {
      fxr::arch_from_json(nlohmann::json::parse(text), "f.json");
    } catch (const fxr::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(err(R"({"tri_fifo_depth": 3})").find("tri_fifo_depth"), std::string::npos);
  EXPECT_NE(err(R"({"mem_latency": 0})").find("mem_latency"), std::string::npos);
  EXPECT_NE(err(R"({"fifo": 2})").find("fifo"), std::string::npos);
  EXPECT_NE(err(R"({"setup_units": "two"})").find("setup_units"), std::string::npos);
}

// Clocks known by hand: one triangle, no other traffic. The SystemC model's frame is the
// stages' latencies and occupancies added up (docs/cycles.md, "Timing"), and a knob that only
// changes an unloaded stage leaves it.
TEST(CycleModel, OneTriangleTakesTheSumOfTheLatencies) {
  fxr::SceneOptions so;
  so.no_optional = true;
  so.width = so.height = 64;
  fxr::Scene sc = fxr::default_scene(so);
  sc.tris.resize(1);
  fxr::FrameOutput f;
  const fxr::cyc::CycleRun r = fxr::cyc::run_unit_cycles(sc.config, fxr::ArchConfig{}, sc.state, sc.tris, f, nullptr);
  ASSERT_GT(r.passed, 10u);
  ASSERT_EQ(r.drawn, 1u);
  // Geometry latency, setup latency, then the traversal of the first span row, the interpolators'
  // front, one sample per clock, depth and divide latency: the frame is at least that.
  EXPECT_GE(r.clocks, r.samples);
  fxr::ArchConfig slow;
  slow.interp_div_steps = 1;  // the span start: ~25 clocks instead of ~7
  fxr::FrameOutput g;
  const fxr::cyc::CycleRun s = fxr::cyc::run_unit_cycles(sc.config, slow, sc.state, sc.tris, g, nullptr);
  EXPECT_GT(s.clocks, r.clocks);
  EXPECT_EQ(s.passed, r.passed);
}

}  // namespace

// Whole draws through rtl/fxr_raster_backend.sv (Verilator) against the model's chain
// (model/unit/chain.hpp): the setup.in stream of a draw, taken from the chain's taps, is driven
// into the back end, and its fragment stream must equal the model's divide.out stream bit for bit
// and in order (none lost, none duplicated), the final depth buffer behind the memory port the
// model's, and the counter registers the model's statistics. Random input gaps, output
// back-pressure and depth-memory latency / request stalls; the report and waveform of
// tb/txn_harness.hpp on a mismatch. Draws: the default scene, every file of scenes/ (its
// triangles), and 10^5 random triangles with the hard cases mixed in over the eight depth
// functions. The checker can fail: a corrupted, a dropped and a swapped expected fragment are
// each caught. docs/rtl.md, "fxr_raster_backend".
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <type_traits>

#include "Vfxr_raster_backend.h"
#include "backend/backend_draw.hpp"
#include "frontend/scene.hpp"

namespace {

using fxr::SceneStageVectors;
using Dut = Vfxr_raster_backend;

using fxr::tb::Draw;
using fxr::tb::Gen;
using fxr::tb::Handshake;
using fxr::tb::kPerf;
using fxr::tb::kPerfNames;
using fxr::tb::kRtlVaryings;
using fxr::tb::kStatNames;
using fxr::tb::kStats;
using fxr::tb::RtlRun;
using fxr::tb::Stats;
using fxr::tb::stats_text;

// The model's draw (tb/backend/backend_draw.hpp), its passed samples being the divider's outputs.
Draw model_draw(const std::string& name, const fxr::Config& cfg, const fxr::DrawState& st,
                const std::vector<fxr::ClipTriangle>& tris, int64_t clear = -1) {
  Draw d = fxr::tb::model_draw(name, cfg, st, tris, clear);
  EXPECT_EQ(d.want[8], d.fragments) << name << ": depth passes = divide.out rows";
  return d;
}

RtlRun run_rtl(const Draw& d, const SceneStageVectors& v, const Handshake& h, const std::string& run,
               bool write_wave = true, uint64_t time_eval_every = 0) {
  fxr::tb::RtlRunOptions<Dut> o;
  o.run = run;
  o.write_wave = write_wave;
  o.time_eval_every = time_eval_every;
  return fxr::tb::run_rtl<Dut>(d, v, h, o);
}

// Every check of one run: the stream (the harness), the buffer, the counters.
void expect_run_matches(const Draw& d, const RtlRun& k, const std::string& what) {
  EXPECT_TRUE(k.r.passed()) << what;
  EXPECT_EQ(k.r.inputs, d.v.in.rows) << what;
  EXPECT_EQ(k.r.outputs, d.v.out.rows) << what;
  EXPECT_EQ(k.bad_addresses, 0u) << what;
  EXPECT_TRUE(k.depth == d.depth) << what << ": the final depth buffer differs from the model's";
  EXPECT_EQ(k.stats, d.want) << what << "\n  rtl:   " << stats_text(k.stats) << "\n  model: " << stats_text(d.want);
}

// Figures of a run without gaps, stalls or memory latency beyond one clock.
void print_figures(const Draw& d, const RtlRun& k) {
  const uint64_t cyc = k.r.last_out_cycle > k.r.first_in_cycle ? k.r.last_out_cycle - k.r.first_in_cycle + 1 : 0;
  std::printf("FIGURES %s: %llu triangles (%llu drawn), %llu spans, %llu fragments generated, %llu passed; %llu cycles "
              "first input to last output: %.3f fragments/clock (generated), %.4f triangles/clock; "
              "Verilator %.0f cycles/s, %.0f fragments/s; per CPU second %.0f cycles, %.0f fragments%s\n",
              d.name.c_str(), (unsigned long long)d.want[0], (unsigned long long)d.want[1], (unsigned long long)d.want[6],
              (unsigned long long)d.want[7], (unsigned long long)d.want[8], (unsigned long long)cyc,
              cyc ? (double)d.want[7] / (double)cyc : 0.0, cyc ? (double)d.want[0] / (double)cyc : 0.0,
              k.r.seconds > 0 ? (double)k.r.cycles / k.r.seconds : 0.0,
              k.r.seconds > 0 ? (double)d.want[7] / k.r.seconds : 0.0,
              k.r.cpu_seconds > 0 ? (double)k.r.cycles / k.r.cpu_seconds : 0.0,
              k.r.cpu_seconds > 0 ? (double)d.want[7] / k.r.cpu_seconds : 0.0, harness_text(k.r, d.want[7]).c_str());
  std::printf("FIGURES %s: clocks per triangle %.2f, per span %.2f, per generated fragment %.3f; stall clocks:", d.name.c_str(),
              d.want[0] ? (double)cyc / (double)d.want[0] : 0.0, d.want[6] ? (double)cyc / (double)d.want[6] : 0.0,
              d.want[7] ? (double)cyc / (double)d.want[7] : 0.0);
  for (int i = 0; i < kPerf; ++i) std::printf(" %s %llu", kPerfNames[i], (unsigned long long)k.perf[(size_t)i]);
  std::printf("\n");
}

// ---- scenes ------------------------------------------------------------------------------------

Draw scene_draw(const fxr::Scene& sc, const std::string& name) {
  // More varyings than the RTL has (clip_triangles: 3): the draw runs with the first two —
  // fxr_setup_fields has two varying ports (docs/rtl.md, "fxr_raster_backend": open points).
  if (sc.state.num_varyings > kRtlVaryings)
    std::printf("NOTE %s: %d varyings, run with the first %d (the RTL's varyings)\n", name.c_str(), sc.state.num_varyings,
                kRtlVaryings);
  return model_draw(name, sc.config, sc.state, sc.tris);
}

TEST(Backend, DefaultSceneMatchesTheModel) {
  const fxr::Scene sc = fxr::default_scene();
  const Draw d = scene_draw(sc, "default");
  ASSERT_GT(d.fragments, 10000u);
  const RtlRun a = run_rtl(d, d.v, Handshake{1, 0, 0, 1, 1, 0}, "backend_default");
  expect_run_matches(d, a, "default, no gaps");
  print_figures(d, a);
  const RtlRun b = run_rtl(d, d.v, Handshake{2, 25, 25, 1, 12, 15}, "backend_default_random");
  expect_run_matches(d, b, "default, gaps / back-pressure / latency 1..12");
}

// Figures at 1024 x 1024 (docs/rtl.md): the checkerboard face alone (the default scene without
// its optional bunny) and scenes/bunny.json, zero-latency memory (a response the clock after the
// request), no gaps, no back-pressure. Not run in CI (about a minute in all; each scene is its own
// test so that one can be timed alone, docs/rtl.md "Co-simulation speed"):
//   build/tb/rtl_backend_test --gtest_also_run_disabled_tests --gtest_filter='Backend.DISABLED_Figures1024*'
void figures_1024(const fxr::Scene& sc, const std::string& name) {
  const Draw d = scene_draw(sc, name);
  const RtlRun k = run_rtl(d, d.v, Handshake{1, 0, 0, 1, 1, 0}, "backend_" + name, true, fxr::tb::kTimeEvalEvery);
  expect_run_matches(d, k, d.name);
  print_figures(d, k);
}
fxr::SceneOptions options_1024(bool no_optional) {
  fxr::SceneOptions so;
  so.width = so.height = 1024;
  so.no_optional = no_optional;
  return so;
}
TEST(Backend, DISABLED_Figures1024Checkerboard) {
  figures_1024(fxr::default_scene(options_1024(true)), "checkerboard_1024");
}
TEST(Backend, DISABLED_Figures1024Bunny) {
  figures_1024(fxr::load_scene(std::string(FXR_SOURCE_DIR) + "/scenes/bunny.json", options_1024(false)), "bunny_1024");
}
TEST(Backend, DISABLED_Figures1024Default) { figures_1024(fxr::default_scene(options_1024(false)), "default_1024"); }

TEST(Backend, SceneFilesMatchTheModel) {
  int n = 0;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(FXR_SOURCE_DIR) + "/scenes"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& p : files) {
    const fxr::Scene sc = fxr::load_scene(p.string());
    if (sc.tris.empty()) continue;
    const std::string name = p.stem().string();
    const Draw d = scene_draw(sc, name);
    const RtlRun k = run_rtl(d, d.v, Handshake{(uint64_t)(10 + n), 20, 20, 1, 8, 10}, "backend_" + name);
    expect_run_matches(d, k, name);
    std::printf("scene %s: %llu triangles, %llu fragments passed: %s\n", name.c_str(), (unsigned long long)d.want[0],
                (unsigned long long)d.fragments, k.r.passed() ? "equal" : "DIFFERENT");
    ++n;
  }
  EXPECT_GE(n, 7);
}


// ---- random triangles with the hard cases ------------------------------------------------------

// One draw per depth function, the cull mode, winding, write mask and depth test varying with
// it; kCasesPerDraw random cases each (a tie case is two triangles): 8 × 12,500 cases > 10^5 triangles.
constexpr int kDraws = 8;
constexpr int kCasesPerDraw = 12500;
constexpr int kRandomViewport = 64;

Draw random_draw(int d, std::array<uint64_t, 9>& kinds) {
  fxr::Config cfg;
  fxr::DrawState st;
  st.viewport_w = st.viewport_h = kRandomViewport;
  st.depth_func = (fxr::DepthFunc)d;
  st.cull = (fxr::CullMode)(d % 3);
  st.front_ccw = (d & 1) == 0;
  st.depth_write = d != 3;
  st.depth_test = d != 7;  // draw 7 (always): test off (all pass, no memory traffic)
  if (d == 5) {            // a scissor inside the viewport
    st.scissor_x = 5;
    st.scissor_y = 9;
    st.scissor_w = 40;
    st.scissor_h = 30;
  }
  st.interp = d == 4 ? fxr::InterpMode::Affine : fxr::InterpMode::Perspective;
  Gen g(0x5eed0000u + (uint64_t)d, st.viewport_w, st.viewport_h);
  std::vector<fxr::ClipTriangle> tris;
  for (int i = 0; i < kCasesPerDraw; ++i) g.add(tris, kinds);
  int64_t clear = -1;
  if (st.depth_func == fxr::DepthFunc::Equal || st.depth_func == fxr::DepthFunc::NotEqual) {
    // A full-viewport triangle of constant z first, on a buffer holding the code it produces
    // (found by the model drawing it alone with depth func always): equal passes all of it,
    // not equal none of it.
    double p[3][2] = {{-1, -1}, {2.0 * kRandomViewport + 2, -1}, {-1, 2.0 * kRandomViewport + 2}};
    const double w[3] = {1, 1, 1};
    fxr::ClipTriangle t = g.tri(p, w);
    for (auto& v : t.v) v.pos[2] = 0.25f;
    fxr::ClipTriangle u = t;  // both windings: the draw's cull mode removes one of them
    std::swap(u.v[1], u.v[2]);
    tris.insert(tris.begin(), {t, u});
    fxr::DrawState probe = st;
    probe.depth_func = fxr::DepthFunc::Always;
    probe.cull = fxr::CullMode::None;
    probe.scissor_w = probe.scissor_h = -1;
    const Draw pd = model_draw("probe", cfg, probe, {t});
    clear = pd.depth[(size_t)(kRandomViewport / 2) * kRandomViewport + kRandomViewport / 2];
  }
  // greater, greater or equal, and less or equal without writes start from a half-full buffer
  // (the cleared maximum code would pass nothing or everything).
  const bool mid = st.depth_func == fxr::DepthFunc::Greater || st.depth_func == fxr::DepthFunc::GreaterEqual ||
                   !st.depth_write;
  return model_draw("random_draw" + std::to_string(d), cfg, st, tris, mid ? (int64_t)(fxr::depth_max_code(cfg.raster) / 2) : clear);
}

TEST(Backend, RandomTrianglesMatchTheModel) {
  std::array<uint64_t, 9> kinds{};
  uint64_t tris = 0, frags = 0;
  Stats total{};
  for (int d = 0; d < kDraws; ++d) {
    const Draw dr = random_draw(d, kinds);
    const RtlRun k = run_rtl(dr, dr.v, Handshake{(uint64_t)(100 + d), 20, 20, 1, 10, 10}, dr.name);
    expect_run_matches(dr, k, dr.name);
    // Every function decides both ways (never: nothing passes; test off: nothing fails).
    if (d != (int)fxr::DepthFunc::Never) {
      EXPECT_GT(dr.want[8], 0u) << dr.name << ": nothing passed";
    }
    if (dr.st.depth_test) {
      EXPECT_GT(dr.want[9], 0u) << dr.name << ": nothing failed";
    }
    tris += dr.want[0];
    frags += dr.fragments;
    for (int i = 0; i < kStats; ++i) total[(size_t)i] += dr.want[(size_t)i];
    std::printf("%s: depth func %d: %llu setup triangles, %llu fragments passed, %.1f s\n", dr.name.c_str(), d,
                (unsigned long long)dr.want[0], (unsigned long long)dr.fragments, k.r.seconds);
  }
  std::printf("random: %llu setup triangles; totals %s\n", (unsigned long long)tris, stats_text(total).c_str());
  std::printf("random cases: general %llu, tie pairs %llu, (sub)pixel %llu, slivers %llu, full viewport %llu, guard band "
              "%llu, w ratio 1e6 %llu, zero area %llu\n",
              (unsigned long long)kinds[0], (unsigned long long)kinds[1], (unsigned long long)kinds[2],
              (unsigned long long)kinds[3], (unsigned long long)kinds[4], (unsigned long long)kinds[5],
              (unsigned long long)kinds[6], (unsigned long long)kinds[7]);
  EXPECT_GE(tris, 100000u);
  // Every outcome reached (the hard cases do what they are there for).
  for (int i = 1; i <= 3; ++i) EXPECT_GT(total[(size_t)i], 0u) << kStatNames[i];  // zero area, back face, no samples
  EXPECT_GT(total[9], 0u);  // depth fails
}

// ---- the checker can fail ----------------------------------------------------------------------

// A small random draw; its expected stream altered three ways, each must be reported.
TEST(Backend, CheckerCatchesCorruptedDroppedAndSwappedFragments) {
  std::array<uint64_t, 9> kinds{};
  fxr::Config cfg;
  fxr::DrawState st;
  st.viewport_w = st.viewport_h = kRandomViewport;
  Gen g(77, st.viewport_w, st.viewport_h);
  std::vector<fxr::ClipTriangle> tris;
  for (int i = 0; i < 300; ++i) g.add(tris, kinds);
  const Draw d = model_draw("checker", cfg, st, tris);
  ASSERT_GT(d.v.out.rows, 100u);
  const size_t n = d.v.out.lay.size();
  const Handshake h{5, 20, 20, 1, 6, 10};
  {  // as it is: passes
    const RtlRun k = run_rtl(d, d.v, h, "backend_checker_clean");
    expect_run_matches(d, k, "clean");
  }
  {  // one bit of the depth code of fragment 40 flipped: exactly that row and field
    SceneStageVectors v = d.v;
    size_t cd = 0;
    for (size_t f = 0; f < n; ++f)
      if (v.out.lay[f].name == "depth") cd = f;
    ASSERT_GT(cd, 0u);
    v.out.data[40 * n + cd] ^= 1;
    const RtlRun k = run_rtl(d, v, h, "backend_checker_corrupt");
    EXPECT_FALSE(k.r.passed());
    EXPECT_EQ(k.r.errors, 1u);
    ASSERT_EQ(k.r.mismatches.size(), 1u);
    EXPECT_EQ(k.r.mismatches[0].out_row, 40u);
    EXPECT_EQ(k.r.mismatches[0].cls, "depth");
    EXPECT_NE(k.r.mismatches[0].text.find("backend.out:41: field 'depth'"), std::string::npos) << k.r.mismatches[0].text;
    EXPECT_TRUE(std::filesystem::exists(k.r.wave));
  }
  {  // one bit of the second varying's significand of fragment 45 flipped (the divider's output
     // is compared, not only the pixel): exactly that row and field
    SceneStageVectors v = d.v;
    size_t cv = 0;
    for (size_t f = 0; f < n; ++f)
      if (v.out.lay[f].name == "var1_sig") cv = f;
    ASSERT_GT(cv, 0u);
    v.out.data[45 * n + cv] ^= 1;
    const RtlRun k = run_rtl(d, v, h, "backend_checker_varying");
    EXPECT_FALSE(k.r.passed());
    EXPECT_EQ(k.r.errors, 1u);
    ASSERT_EQ(k.r.mismatches.size(), 1u);
    EXPECT_EQ(k.r.mismatches[0].out_row, 45u);
    EXPECT_EQ(k.r.mismatches[0].cls, "var1_sig");
  }
  {  // fragment 50 dropped from the expected stream: the RTL's extra fragment is reported
    SceneStageVectors v = d.v;
    v.out.data.erase(v.out.data.begin() + 50 * (ptrdiff_t)n, v.out.data.begin() + 51 * (ptrdiff_t)n);
    --v.out.rows;
    const RtlRun k = run_rtl(d, v, h, "backend_checker_dropped", false);
    EXPECT_FALSE(k.r.passed());
    EXPECT_GE(k.r.errors, 1u);
    ASSERT_FALSE(k.r.mismatches.empty());
    EXPECT_EQ(k.r.mismatches[0].out_row, 50u);
  }
  {  // fragments 60 and 61 swapped (different pixels): both reported
    SceneStageVectors v = d.v;
    size_t cx = 0;
    for (size_t f = 0; f < n; ++f)
      if (v.out.lay[f].name == "x") cx = f;
    uint64_t a = 60;
    while (a + 1 < v.out.rows && v.out.data[a * n + cx] == v.out.data[(a + 1) * n + cx]) ++a;
    std::swap_ranges(v.out.data.begin() + (ptrdiff_t)(a * n), v.out.data.begin() + (ptrdiff_t)((a + 1) * n),
                     v.out.data.begin() + (ptrdiff_t)((a + 1) * n));
    const RtlRun k = run_rtl(d, v, h, "backend_checker_swapped", false);
    EXPECT_FALSE(k.r.passed());
    ASSERT_EQ(k.r.mismatches.size(), 2u);
    EXPECT_EQ(k.r.mismatches[0].out_row, a);
    EXPECT_EQ(k.r.mismatches[1].out_row, a + 1);
  }
}

}  // namespace

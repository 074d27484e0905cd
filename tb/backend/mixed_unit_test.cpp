// Mixed simulation of the whole unit (issue 12, docs/cycles.md "Mixed simulation"):
// rtl/fxr_raster_unit.sv (stages 1–9) verilated with `--sc` (Vfxr_raster_unit_sc) runs inside a
// SystemC simulation in place of the cycle model's transaction-level unit
// (fxr::cyc::run_unit_cycles): the same scene (the model's convert.in stream, one primitive
// offered per clock after the draw state is written through the register block), the same
// memory (latency 1), the same counters. Checked: the RTL's fragment stream and final depth
// buffer are the model's, its geometry counters the model's RasterStats and its back-end counters
// the model's per setup triangle (tb/backend/backend_draw.hpp), the transaction-level run's
// counts of primitives, triangles, spans and fragments equal, and its clocks (first primitive in
// to last fragment out) within 5 % of the RTL's; the per-stage busy clocks of stages 1–4 at their
// output handshakes compared (printed, with the bound of docs/cycles.md asserted). Labels rtl and
// sc. A small scene here (seconds); `FXR_MIXED_UNIT_SCENES=all` adds the default scene and
// scenes/ (minutes, for the figures of docs/cycles.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "Vfxr_raster_unit_sc.h"
#include "backend/mixed_bench.hpp"
#include "frontend/scene.hpp"
#include "sc/cycle_model.hpp"
#include "unit/unit_run.hpp"

namespace {

using Dut = Vfxr_raster_unit_sc;
using fxr::tb::mixed::PortT;
constexpr double kClockTolerance = 0.05;

struct Pins {
  static constexpr bool kRegs = true;  // the draw state through the register block
  sc_core::sc_signal<bool> rst_ni{"rst_ni"};
#define FXR_PIN(name) sc_core::sc_signal<PortT<decltype(std::declval<Dut&>().name)>> name{#name};
#define FXR_UNIT_PORTS(X)                                                                                          \
  X(reg_we_i) X(reg_addr_i) X(reg_wdata_i) X(in_valid_i) X(in_ready_o) X(in_i) X(out_valid_o) X(out_ready_i)       \
  X(out_o) X(mem_req_valid_o) X(mem_req_ready_i) X(mem_req_write_o) X(mem_req_addr_o) X(mem_req_wdata_o)            \
  X(mem_rsp_valid_i) X(mem_rsp_rdata_i) X(mem_wr_valid_o) X(mem_wr_ready_i) X(mem_wr_addr_o) X(mem_wr_data_o)       \
  X(stat_prims_in_o) X(stat_prims_rejected_nan_o) X(stat_prims_rejected_inf_o) X(stat_prims_varying_nonfinite_o)   \
  X(stat_prims_trivial_accept_o) X(stat_prims_clipped_o) X(stat_clip_vertices_created_o)                           \
  X(stat_clip_triangles_out_o) X(stat_prims_culled_outside_o) X(stat_geom_rejected_range_o) X(stat_tri_in_o)       \
  X(stat_tri_drawn_o) X(stat_tri_zero_area_o) X(stat_tri_backface_o) X(stat_tri_no_samples_o) X(stat_tri_range_o)   \
  X(stat_spans_o) X(stat_frag_generated_o) X(stat_frag_depth_pass_o) X(stat_frag_depth_fail_o) X(perf_busy_o)      \
  X(perf_stalled_o) X(perf_starved_o) X(perf_setup_stall_o) X(perf_fifo_full_o) X(perf_span_stall_o)               \
  X(perf_span_wait_o) X(perf_sample_stall_o) X(perf_pass_stall_o) X(perf_out_stall_o)
  FXR_UNIT_PORTS(FXR_PIN)
#undef FXR_PIN
  void bind(Dut& d, sc_core::sc_clock& clk) {
    d.clk_i(clk);
    d.rst_ni(rst_ni);
#define FXR_BIND(name) d.name(name);
    FXR_UNIT_PORTS(FXR_BIND)
#undef FXR_BIND
  }
};
using Bench = fxr::tb::mixed::Bench<Dut, Pins>;

template <class S>
uint64_t u64(const S& s) {
  return (uint64_t)s.read();
}
// Stage i's StatBits word of a per-stage counter vector.
template <class S>
uint64_t stage_word(const S& s, int i) {
  return (uint64_t)s.read().get_word(i);  // StatBits = 32 (the unit's default)
}

struct MixedUnit {
  uint64_t rtl_clocks = 0, tl_clocks = 0;
  double rtl_s = 0, tl_s = 0;
};

MixedUnit run_mixed_unit(const std::string& name, const fxr::Scene& sc) {
  MixedUnit m;
  const fxr::Config& cfg = sc.config;
  const fxr::tb::Draw d = fxr::tb::model_draw(name, cfg, sc.state, sc.tris);
  std::vector<fxr::VecRow> in_rows;
  for (uint64_t r = 0; r < d.u.in.rows; ++r) in_rows.push_back(d.u.in.row(r));

  // The transaction-level unit on the same primitives.
  fxr::FrameOutput tf;
  fxr::tb::mixed::Collect tl_frags;
  const fxr::cyc::CycleRun tl = fxr::cyc::run_unit_cycles(cfg, fxr::ArchConfig{}, d.st, sc.tris, tf, &tl_frags);

  // The RTL inside SystemC (a fresh kernel, as every cycle-model run).
  fxr::cyc::fresh_sc_kernel();
  fxr::tb::DepthMemOptions mo;
  mo.seed = 1;
  fxr::tb::DepthMem mem((size_t)d.st.viewport_w * (size_t)d.st.viewport_h, d.clear, mo);
  auto* b = new Bench("bench");  // kept with its kernel (sc/cycle_model.cpp: fresh_sc_kernel)
  b->in_rows = &in_rows;
  b->in_b = fxr::tb::RecordBinding(d.u.in.lay, d.u.in.header);
  b->out_b = fxr::tb::RecordBinding(d.u.out.lay, d.u.out.header);
  b->out_lay = d.u.out.lay;
  b->mem = &mem;
  const auto regs = fxr::tb::unit_registers(d.st, d.st.num_varyings);
  b->regs.assign(regs.begin(), regs.end());
  b->reg_mask = (uint64_t(1) << (cfg.raster.window_int_bits + 1)) - 1;
  b->drain = 20000;  // the last primitive may still be in the clipper
  m.rtl_s = fxr::tb::mixed::run_bench();
  m.tl_s = tl.seconds;
  EXPECT_TRUE(b->done) << name;

  // Fragments: the model's, bit for bit and in order; the transaction-level run's the model's too.
  EXPECT_EQ(b->out_rows.size(), d.u.out.rows) << name;
  size_t bad = 0;
  for (uint64_t i = 0; i < std::min<uint64_t>(d.u.out.rows, b->out_rows.size()); ++i) {
    const fxr::VecRow want = d.u.out.row(i);
    bool same = true;
    for (size_t k = d.u.out.header; k < want.size(); ++k) same = same && want[k] == b->out_rows[i][k];
    if (!same && bad++ < 5) ADD_FAILURE() << name << ": fragment " << i << " differs";
  }
  EXPECT_EQ(bad, 0u) << name;
  EXPECT_EQ(tl_frags.v.size(), d.u.out.rows) << name;
  EXPECT_TRUE(mem.words() == d.depth) << name << ": the RTL's final depth buffer";
  EXPECT_TRUE(tf.depth == d.depth) << name << ": the transaction-level run's final depth buffer";
  // Counters: the RTL's registers against the model's; the transaction-level run's counts.
  const Pins& p = b->pins;
  const fxr::tb::GeomStats geom = {u64(p.stat_prims_in_o), u64(p.stat_prims_rejected_nan_o),
                                   u64(p.stat_prims_rejected_inf_o), u64(p.stat_prims_varying_nonfinite_o),
                                   u64(p.stat_prims_trivial_accept_o), u64(p.stat_prims_clipped_o),
                                   u64(p.stat_clip_vertices_created_o), u64(p.stat_clip_triangles_out_o),
                                   u64(p.stat_prims_culled_outside_o), u64(p.stat_geom_rejected_range_o)};
  EXPECT_EQ(geom, fxr::tb::model_geom_stats(d)) << name;
  const fxr::tb::Stats stats = {u64(p.stat_tri_in_o),       u64(p.stat_tri_drawn_o),      u64(p.stat_tri_zero_area_o),
                                u64(p.stat_tri_backface_o), u64(p.stat_tri_no_samples_o), u64(p.stat_tri_range_o),
                                u64(p.stat_spans_o),        u64(p.stat_frag_generated_o), u64(p.stat_frag_depth_pass_o),
                                u64(p.stat_frag_depth_fail_o)};
  EXPECT_EQ(stats, d.want) << name << "\n  rtl:   " << fxr::tb::stats_text(stats)
                           << "\n  model: " << fxr::tb::stats_text(d.want);
  EXPECT_EQ(tl.primitives, geom[0]) << name;
  EXPECT_EQ(tl.triangles, stats[0]) << name;
  EXPECT_EQ(tl.drawn, stats[1]) << name;
  EXPECT_EQ(tl.spans, stats[6]) << name;
  EXPECT_EQ(tl.samples, stats[7]) << name;
  EXPECT_EQ(tl.passed, stats[8]) << name;

  m.rtl_clocks = b->clocks();
  m.tl_clocks = tl.clocks;
  const double dev = m.rtl_clocks ? ((double)m.tl_clocks - (double)m.rtl_clocks) / (double)m.rtl_clocks : 0.0;
  std::printf("MIXED unit %s: RTL in SystemC %llu clocks (%.2f s), transaction-level %llu clocks (%.3f s), deviation "
              "%+.2f %%, speed %.1fx; %llu primitives, %llu triangles, %llu spans, %llu fragments\n",
              name.c_str(), (unsigned long long)m.rtl_clocks, m.rtl_s, (unsigned long long)m.tl_clocks, m.tl_s,
              100.0 * dev, m.tl_s > 0 ? m.rtl_s / m.tl_s : 0.0, (unsigned long long)geom[0],
              (unsigned long long)stats[0], (unsigned long long)stats[6], (unsigned long long)stats[8]);
  // Stages 1–4: busy clocks at the output handshake (the RTL's perf_busy_o: a record leaving)
  // against the transaction-level modules' outputs, and the RTL's stalled clocks.
  static const int kStage[4] = {fxr::cyc::kInput, fxr::cyc::kClip, fxr::cyc::kRecip, fxr::cyc::kViewport};
  for (int i = 0; i < 4; ++i) {
    const fxr::cyc::StageClocks& c = tl.stage[(size_t)kStage[i]];
    std::printf("MIXED unit %s: %-8s RTL out %llu stalled %llu; SystemC out %llu stalled %llu\n", name.c_str(),
                fxr::cyc::stage_name(kStage[i]), (unsigned long long)stage_word(p.perf_busy_o, i),
                (unsigned long long)stage_word(p.perf_stalled_o, i), (unsigned long long)c.out,
                (unsigned long long)c.stalled);
    EXPECT_EQ(c.out, stage_word(p.perf_busy_o, i)) << name << ": records out of " << fxr::cyc::stage_name(kStage[i]);
  }
  EXPECT_LE(std::abs(dev), kClockTolerance) << name;
  return m;
}

std::string source_dir() {
  const char* dir = std::getenv("FXR_SOURCE_DIR");
  return dir ? dir : FXR_SOURCE_DIR;
}

TEST(MixedUnit, RtlUnitInSystemCOnClipTriangles) {
  run_mixed_unit("clip_triangles", fxr::load_scene(source_dir() + "/scenes/clip_triangles.json"));
}

TEST(MixedUnit, RtlUnitInSystemCOnASmallDefaultScene) {
  fxr::SceneOptions so;
  so.width = so.height = 64;
  so.no_optional = true;  // without the bunny: seconds
  run_mixed_unit("default_64", fxr::default_scene(so));
}

// The figures of docs/cycles.md: the default scene and every file of scenes/ (minutes).
TEST(MixedUnit, AllScenesWhenAsked) {
  const char* all = std::getenv("FXR_MIXED_UNIT_SCENES");
  if (!all || std::string(all) != "all") GTEST_SKIP() << "FXR_MIXED_UNIT_SCENES=all runs the default scene and scenes/";
  run_mixed_unit("default", fxr::default_scene());
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(source_dir() + "/scenes"))
    if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  for (const std::string& f : files) run_mixed_unit(std::filesystem::path(f).stem().string(), fxr::load_scene(f));
}

}  // namespace

// libsystemc.so calls sc_main from its main(); GoogleTest's main runs the tests here, each
// starting its own simulation (sc/cycle_model.cpp defines the sc_main the link needs).

// Mixed simulation (issue 12, docs/cycles.md "Mixed simulation"): rtl/fxr_raster_backend.sv
// verilated with `--sc` (an SC_MODULE, Vfxr_raster_backend_sc) runs inside a SystemC simulation
// in place of the cycle model's transaction-level back end: the same setup-input stream (the
// model's stages 1–4 of the scene, fxr::cyc::setup_inputs), one triangle offered per clock, the
// same memory (latency 1), the same counters (clocks from the first triangle in to the last
// fragment out, triangles, spans, fragments generated / passed) — and the same scene run through
// the transaction-level back end (fxr::cyc::run_backend_cycles) in the same process. Checked:
// the RTL's fragments are the model's bit for bit, its counters the model's, and its clocks
// within 5 % of the transaction-level model's. Labels rtl and sc.
#include <gtest/gtest.h>

#include <cstdio>

#include "Vfxr_raster_backend_sc.h"
#include "backend/mixed_bench.hpp"
#include "frontend/scene.hpp"
#include "model/unit/chain.hpp"
#include "model/vectors/codegen.hpp"
#include "model/vectors/scene_dump.hpp"
#include "sc/cycle_model.hpp"

namespace {

using Dut = Vfxr_raster_backend_sc;
constexpr int kRtlVaryings = fxr::kRecordPackageVaryings;
constexpr double kClockTolerance = 0.05;

using fxr::tb::mixed::PortT;

// One signal per DUT port, named as the port: drive_draw_state and DepthMem's drive / observe
// work on it as on the C++ model's ports.
struct Pins {
  static constexpr bool kRegs = false;  // the draw state on ports (drive_draw_state)
  sc_core::sc_signal<bool> rst_ni{"rst_ni"};
#define FXR_PIN(name) sc_core::sc_signal<PortT<decltype(std::declval<Dut&>().name)>> name{#name};
  FXR_PIN(in_valid_i)
  FXR_PIN(in_ready_o)
  FXR_PIN(in_i)
  FXR_PIN(viewport_x_i)
  FXR_PIN(viewport_y_i)
  FXR_PIN(viewport_w_i)
  FXR_PIN(viewport_h_i)
  FXR_PIN(scissor_x_i)
  FXR_PIN(scissor_y_i)
  FXR_PIN(scissor_w_i)
  FXR_PIN(scissor_h_i)
  FXR_PIN(cull_i)
  FXR_PIN(front_ccw_i)
  FXR_PIN(interp_i)
  FXR_PIN(depth_func_i)
  FXR_PIN(depth_test_i)
  FXR_PIN(depth_write_i)
  FXR_PIN(out_valid_o)
  FXR_PIN(out_ready_i)
  FXR_PIN(out_o)
  FXR_PIN(mem_req_valid_o)
  FXR_PIN(mem_req_ready_i)
  FXR_PIN(mem_req_write_o)
  FXR_PIN(mem_req_addr_o)
  FXR_PIN(mem_req_wdata_o)
  FXR_PIN(mem_rsp_valid_i)
  FXR_PIN(mem_rsp_rdata_i)
  FXR_PIN(mem_wr_valid_o)
  FXR_PIN(mem_wr_ready_i)
  FXR_PIN(mem_wr_addr_o)
  FXR_PIN(mem_wr_data_o)
  FXR_PIN(stat_tri_in_o)
  FXR_PIN(stat_tri_drawn_o)
  FXR_PIN(stat_tri_zero_area_o)
  FXR_PIN(stat_tri_backface_o)
  FXR_PIN(stat_tri_no_samples_o)
  FXR_PIN(stat_tri_range_o)
  FXR_PIN(stat_spans_o)
  FXR_PIN(stat_frag_generated_o)
  FXR_PIN(stat_frag_depth_pass_o)
  FXR_PIN(stat_frag_depth_fail_o)
  FXR_PIN(perf_setup_stall_o)
  FXR_PIN(perf_fifo_full_o)
  FXR_PIN(perf_span_stall_o)
  FXR_PIN(perf_span_wait_o)
  FXR_PIN(perf_sample_stall_o)
  FXR_PIN(perf_pass_stall_o)
  FXR_PIN(perf_out_stall_o)
#undef FXR_PIN
  void bind(Dut& d, sc_core::sc_clock& clk) {
    d.clk_i(clk);
    d.rst_ni(rst_ni);
#define FXR_BIND(name) d.name(name);
    FXR_BIND(in_valid_i) FXR_BIND(in_ready_o) FXR_BIND(in_i) FXR_BIND(viewport_x_i) FXR_BIND(viewport_y_i)
    FXR_BIND(viewport_w_i) FXR_BIND(viewport_h_i) FXR_BIND(scissor_x_i) FXR_BIND(scissor_y_i) FXR_BIND(scissor_w_i)
    FXR_BIND(scissor_h_i) FXR_BIND(cull_i) FXR_BIND(front_ccw_i) FXR_BIND(interp_i) FXR_BIND(depth_func_i)
    FXR_BIND(depth_test_i) FXR_BIND(depth_write_i) FXR_BIND(out_valid_o) FXR_BIND(out_ready_i) FXR_BIND(out_o)
    FXR_BIND(mem_req_valid_o) FXR_BIND(mem_req_ready_i) FXR_BIND(mem_req_write_o) FXR_BIND(mem_req_addr_o)
    FXR_BIND(mem_req_wdata_o) FXR_BIND(mem_rsp_valid_i) FXR_BIND(mem_rsp_rdata_i) FXR_BIND(mem_wr_valid_o)
    FXR_BIND(mem_wr_ready_i) FXR_BIND(mem_wr_addr_o) FXR_BIND(mem_wr_data_o) FXR_BIND(stat_tri_in_o)
    FXR_BIND(stat_tri_drawn_o) FXR_BIND(stat_tri_zero_area_o) FXR_BIND(stat_tri_backface_o)
    FXR_BIND(stat_tri_no_samples_o) FXR_BIND(stat_tri_range_o) FXR_BIND(stat_spans_o) FXR_BIND(stat_frag_generated_o)
    FXR_BIND(stat_frag_depth_pass_o) FXR_BIND(stat_frag_depth_fail_o) FXR_BIND(perf_setup_stall_o)
    FXR_BIND(perf_fifo_full_o) FXR_BIND(perf_span_stall_o) FXR_BIND(perf_span_wait_o) FXR_BIND(perf_sample_stall_o)
    FXR_BIND(perf_pass_stall_o) FXR_BIND(perf_out_stall_o)
#undef FXR_BIND
  }
};

using Bench = fxr::tb::mixed::Bench<Dut, Pins>;

void run_mixed(const std::string& name, const fxr::Scene& sc) {
  fxr::DrawState st = sc.state;
  st.num_varyings = kRtlVaryings;
  const fxr::Config& cfg = sc.config;
  const fxr::RecordShape shape{cfg, kRtlVaryings};
  // Setup's inputs packed as the record port wants them; the expected fragments.
  std::vector<fxr::VecField> fi, fo;
  fxr::append_record_fields<fxr::SetupTriangle>(shape, fxr::VecDir::In, fi);
  fxr::append_record_fields<fxr::Fragment>(shape, fxr::VecDir::Out, fo);
  const fxr::VecLayout in_lay(fi), out_lay(fo);
  const std::vector<fxr::SetupTriangle> tris = fxr::cyc::setup_inputs(cfg, st, sc.tris);
  std::vector<fxr::VecRow> in_rows;
  for (const fxr::SetupTriangle& t : tris) {
    fxr::VecRow r(in_lay.size(), 0);
    fxr::pack_record(t, shape, r, 0, name + ":setup.in");
    in_rows.push_back(std::move(r));
  }
  fxr::FrameOutput mf;
  fxr::tb::mixed::Collect model;
  fxr::NoTaps taps;
  fxr::run_raster_unit_to(cfg, st, sc.tris, mf, &model, taps);

  // The transaction-level back end on the same stream.
  fxr::FrameOutput tf;
  fxr::frame_begin(cfg, st, tf);
  const fxr::cyc::CycleRun tl = fxr::cyc::run_backend_cycles(cfg, fxr::ArchConfig{}, st, tris, tf, nullptr);

  // The RTL inside SystemC (a fresh kernel, as every cycle-model run).
  fxr::cyc::fresh_sc_kernel();
  fxr::tb::DepthMemOptions mo;
  mo.seed = 1;
  fxr::tb::DepthMem mem((size_t)st.viewport_w * (size_t)st.viewport_h, (uint32_t)fxr::depth_max_code(cfg.raster), mo);
  auto* b = new Bench("bench");  // kept with its kernel (sc/cycle_model.cpp: fresh_sc_kernel)
  b->in_rows = &in_rows;
  b->in_b = fxr::tb::RecordBinding(in_lay, 0);
  b->out_b = fxr::tb::RecordBinding(out_lay, 0);
  b->out_lay = out_lay;
  b->mem = &mem;
  b->st = st;
  b->wib = cfg.raster.window_int_bits;
  const double secs = fxr::tb::mixed::run_bench();
  ASSERT_TRUE(b->done) << name;

  // Fragments: the model's, bit for bit and in order.
  ASSERT_EQ(b->out_rows.size(), model.v.size()) << name;
  size_t bad = 0;
  for (size_t i = 0; i < model.v.size(); ++i) {
    fxr::VecRow want(out_lay.size(), 0);
    fxr::pack_record(model.v[i], shape, want, 0, name + ":divide.out");
    if (want != b->out_rows[i] && bad++ < 5) ADD_FAILURE() << name << ": fragment " << i << " differs";
  }
  EXPECT_EQ(bad, 0u) << name;
  EXPECT_TRUE(mem.words() == mf.depth) << name << ": final depth buffer";
  // Counters: the RTL's registers against the model's and the transaction-level run's.
  EXPECT_EQ((uint64_t)b->pins.stat_tri_in_o.read(), (uint64_t)tris.size()) << name;
  EXPECT_EQ((uint64_t)b->pins.stat_tri_drawn_o.read(), tl.drawn) << name;
  EXPECT_EQ((uint64_t)b->pins.stat_spans_o.read(), tl.spans) << name;
  EXPECT_EQ((uint64_t)b->pins.stat_frag_generated_o.read(), tl.samples) << name;
  EXPECT_EQ((uint64_t)b->pins.stat_frag_depth_pass_o.read(), tl.passed) << name;
  const uint64_t rtl = b->clocks();
  const double dev = rtl ? ((double)tl.clocks - (double)rtl) / (double)rtl : 0.0;
  std::printf("MIXED %s: RTL in SystemC %llu clocks (%.2f s), transaction-level %llu clocks (%.3f s), deviation %+.2f %%; "
              "%llu triangles, %llu spans, %llu fragments; span_stall %llu, span_wait %llu\n",
              name.c_str(), (unsigned long long)rtl, secs, (unsigned long long)tl.clocks, tl.seconds, 100.0 * dev,
              (unsigned long long)tris.size(), (unsigned long long)tl.spans, (unsigned long long)tl.passed,
              (unsigned long long)b->pins.perf_span_stall_o.read(), (unsigned long long)b->pins.perf_span_wait_o.read());
  EXPECT_LE(std::abs(dev), kClockTolerance) << name;
}

TEST(MixedSim, RtlBackEndInSystemCOnTheDefaultScene) {
  fxr::SceneOptions so;
  so.width = so.height = 128;
  run_mixed("default_128", fxr::default_scene(so));
}

TEST(MixedSim, RtlBackEndInSystemCOnClipTriangles) {
  const char* dir = std::getenv("FXR_SOURCE_DIR");
  run_mixed("clip_triangles", fxr::load_scene(std::string(dir ? dir : FXR_SOURCE_DIR) + "/scenes/clip_triangles.json"));
}

}  // namespace

// libsystemc.so calls sc_main from its main(); GoogleTest's main runs the tests here, each
// starting its own simulation (sc/cycle_model.cpp defines the sc_main the link needs).

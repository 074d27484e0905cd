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

#include <systemc.h>

#include <array>
#include <cstdio>

#include "Vfxr_raster_backend_sc.h"
#include "depth_mem.hpp"
#include "frontend/scene.hpp"
#include "model/unit/chain.hpp"
#include "model/vectors/codegen.hpp"
#include "model/vectors/record_vectors.hpp"
#include "model/vectors/scene_dump.hpp"
#include "sc/cycle_model.hpp"
#include "txn/draw_state_ports.hpp"
#include "txn_harness.hpp"

namespace {

using Dut = Vfxr_raster_backend_sc;
constexpr int kRtlVaryings = fxr::kRecordPackageVaryings;
constexpr double kClockTolerance = 0.05;

template <class P>
using PortT = typename std::remove_reference_t<P>::data_type;

// One signal per DUT port, named as the port: drive_draw_state and DepthMem's drive / observe
// work on it as on the C++ model's ports.
struct Pins {
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

// A packed record as 32-bit words (RecordBinding's port interface), copied to / from sc_bv.
template <int N>
struct Words {
  std::array<uint32_t, (N + 31) / 32> w{};
  uint32_t operator[](size_t i) const { return w[i]; }
  uint32_t& operator[](size_t i) { return w[i]; }
};
template <int N>
void to_bv(const Words<N>& w, sc_dt::sc_bv<N>& bv) {
  for (size_t i = 0; i < w.w.size(); ++i) bv.set_word((int)i, w.w[i]);
}
template <int N>
void from_bv(const sc_dt::sc_bv<N>& bv, Words<N>& w) {
  for (size_t i = 0; i < w.w.size(); ++i) w.w[i] = bv.get_word((int)i);
}
template <class T>
struct BvWidth;
template <int N>
struct BvWidth<sc_dt::sc_bv<N>> {
  static constexpr int value = N;
};

struct Collect : fxr::FragmentSink {
  std::vector<fxr::Fragment> v;
  void emit(const fxr::Fragment& f) override { v.push_back(f); }
};

// The testbench: reset, then a triangle offered per clock; the memory; every fragment taken.
// Drives in the clock's second half, samples the handshakes a quarter clock before the edge.
SC_MODULE(Bench) {
  Pins pins;
  sc_core::sc_clock clk{"clk", 1, sc_core::SC_NS};
  Dut dut{"dut"};
  const std::vector<fxr::VecRow>* in_rows = nullptr;
  fxr::tb::RecordBinding in_b, out_b;
  fxr::VecLayout out_lay;
  std::vector<fxr::VecRow> out_rows;
  fxr::tb::DepthMem* mem = nullptr;
  fxr::DrawState st;
  int wib = 0;
  uint64_t cycle = 0, first_in = 0, last_out = 0, outputs = 0;
  bool done = false;

  SC_CTOR(Bench) {
    pins.bind(dut, clk);
    SC_THREAD(main);
  }
  void main() {
    using InBv = PortT<decltype(dut.in_i)>;
    using OutBv = PortT<decltype(dut.out_o)>;
    constexpr int kIn = BvWidth<InBv>::value, kOut = BvWidth<OutBv>::value;
    fxr::tb::drive_draw_state(pins, st, wib);
    pins.out_ready_i = true;
    pins.in_valid_i = false;
    pins.rst_ni = false;
    mem->reset();
    for (int i = 0; i < 4; ++i) wait(clk.posedge_event());
    wait(clk.negedge_event());
    pins.rst_ni = true;
    size_t next = 0;
    uint64_t idle = 0;
    Words<kIn> wi;
    Words<kOut> wo;
    InBv bv_in;
    OutBv bv_out;
    fxr::VecRow row(out_lay.size(), 0);
    for (;;) {
      // Drive for the coming edge.
      mem->drive(pins);
      const bool have = next < in_rows->size();
      if (have) {
        wi = Words<kIn>{};
        in_b.drive(wi, (*in_rows)[next]);
        to_bv(wi, bv_in);
        pins.in_i = bv_in;
      }
      pins.in_valid_i = have;
      wait(0.25, sc_core::SC_NS);  // combinational outputs settled
      if (have && pins.in_ready_o.read()) {
        if (next == 0) first_in = cycle;
        ++next;
      }
      if (pins.out_valid_o.read()) {
        from_bv(pins.out_o.read(), wo);
        out_b.sample(wo, row);
        out_rows.push_back(row);
        last_out = cycle;
        ++outputs;
        idle = 0;
      } else if (next == in_rows->size() && ++idle > 400) {
        break;  // drained
      }
      mem->observe(pins);
      wait(clk.negedge_event());
      ++cycle;
    }
    done = true;
    sc_core::sc_stop();
  }
};

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
  Collect model;
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
  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
  const uint64_t rtl = b->outputs ? b->last_out - b->first_in + 1 : 0;
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

// Co-simulation of rtl/fxr_depth.sv (Verilator) on transaction dumps (tb/txn_harness.hpp) with the
// depth buffer behind its memory port (tb/depth_mem.hpp): the committed dump of
// scenes/transactions.json and the default scene (each re-stepped from a cleared buffer, as the
// dump's depth.out was made), the passing samples bit-identical and in order with the model's
// depth.out under random input gaps, output back-pressure, memory latency and request stalls
// (fxr_depth as shipped, and with its separate write channel: tb/txn/fxr_depth_wp.sv),
// and the final buffer equal to the model's (fxr::DepthStage run here on depth.in). Directed
// cases: every depth function with the write mask on and off, the test off, and fragments to one
// pixel back to back (the read-after-write hazard), expected values from the functions'
// definitions computed here. docs/rtl.md, "fxr_depth".
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <vector>


#include "Vfxr_depth.h"
#include "Vfxr_depth_wp.h"
#include "depth_mem.hpp"
#include "model/stages/depth.hpp"
#include "model/vectors/scene_dump.hpp"
#include "txn/backend_sets.hpp"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::DepthMem;
using fxr::tb::DepthMemOptions;
using fxr::tb::TxnHook;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kDefault = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";

struct State {
  int func = 1;
  bool test = true, write = true;
  int vx = 0, vy = 0, vw = 0, vh = 0;
};

State read_state(const std::string& dir) {
  const fxr::DrawState st = fxr::load_scene_draw_state(dir);
  State s;
  s.func = (int)st.depth_func;
  s.test = st.depth_test;
  s.write = st.depth_write;
  s.vx = st.viewport_x;
  s.vy = st.viewport_y;
  s.vw = st.viewport_w;
  s.vh = st.viewport_h;
  return s;
}

uint32_t max_code(const fxr::Config& cfg) { return (uint32_t)((1ull << cfg.raster.depth_bits()) - 1); }

// The hook: draw state on the DUT's state inputs, the memory on its port(s).
template <class Dut>
TxnHook<Dut> hook_for(const State& s, DepthMem& mem) {
  TxnHook<Dut> h;
  h.reset = [&mem] { mem.reset(); };
  h.drive = [s, &mem](Dut& d) {
    d.depth_func_i = (uint8_t)s.func;
    d.depth_test_i = s.test;
    d.depth_write_i = s.write;
    d.viewport_x_i = (uint16_t)s.vx;
    d.viewport_y_i = (uint16_t)s.vy;
    d.viewport_w_i = (uint32_t)s.vw;
    mem.drive(d);
  };
  h.observe = [&mem](Dut& d) { mem.observe(d); };
  return h;
}

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("depth", run, seed, gap, stall);
}

size_t col(const fxr::VecLayout& lay, const char* n) {
  for (size_t f = 0; f < lay.size(); ++f)
    if (lay[f].name == n) return f;
  ADD_FAILURE() << "no field " << n;
  return 0;
}

// The model's buffer after depth.in: fxr::DepthStage from a cleared buffer (what the dump's
// depth.out was re-stepped with, docs/vectors.md).
std::vector<uint32_t> model_buffer(const SceneStageVectors& v, const State& s) {
  fxr::DrawState st;
  st.viewport_x = s.vx;
  st.viewport_y = s.vy;
  st.viewport_w = s.vw;
  st.viewport_h = s.vh;
  st.depth_func = (fxr::DepthFunc)s.func;
  st.depth_test = s.test;
  st.depth_write = s.write;
  std::vector<uint32_t> buf((size_t)s.vw * (size_t)s.vh, max_code(v.cfg));
  fxr::DepthStage stage(v.cfg, st, fxr::DepthBufferView{buf.data(), s.vw, s.vx, s.vy});
  const size_t cx = col(v.in.lay, "x"), cy = col(v.in.lay, "y"), cd = col(v.in.lay, "depth");
  for (uint64_t i = 0; i < v.in.rows; ++i) {
    const fxr::VecRow row = v.in.row(i);
    fxr::PlaneSample p;
    p.x = (int32_t)fxr::vec_unpack_signed(row[cx], v.in.lay[cx].width);
    p.y = (int32_t)fxr::vec_unpack_signed(row[cy], v.in.lay[cy].width);
    p.depth = (uint32_t)row[cd];
    stage.step(p, [](const fxr::PlaneSample&) {});
  }
  return buf;
}

template <class Dut>
void run_dump(const std::string& dir, const std::string& name, bool figures) {
  const SceneStageVectors v = fxr::load_scene_stage(dir, "depth");
  const State s = read_state(dir);
  ASSERT_GT(v.in.rows, 10u);
  const std::vector<uint32_t> want = model_buffer(v, s);
  struct Run {
    uint64_t seed;
    unsigned gap, stall, lat_min, lat_max, req_stall;
  };
  for (const Run& k : {Run{1, 0, 0, 1, 1, 0}, Run{2, 0, 0, 1, 8, 0}, Run{3, 25, 25, 1, 8, 20}, Run{4, 60, 70, 1, 20, 50}}) {
    DepthMemOptions mo;
    mo.seed = 100 + k.seed;
    mo.min_latency = k.lat_min;
    mo.max_latency = k.lat_max;
    mo.req_stall_pct = k.req_stall;
    mo.wr_stall_pct = k.req_stall;
    DepthMem mem((size_t)s.vw * (size_t)s.vh, max_code(v.cfg), mo);
    const TxnHook<Dut> h = hook_for<Dut>(s, mem);
    const TxnResult r =
        fxr::tb::run_txn<Dut>(v, nullptr, opts("depth_" + name + "_" + std::to_string(k.seed), k.seed, k.gap, k.stall), &h);
    EXPECT_TRUE(r.passed()) << "seed " << k.seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
    EXPECT_EQ(mem.bad_addresses, 0u);
    EXPECT_TRUE(mem.words() == want) << "final depth buffer differs from the model's (seed " << k.seed << ")";
    if (figures && k.gap == 0 && k.stall == 0)
      std::printf("depth %s: latency %u..%u: %llu samples in, %llu out, %llu clocks (first input to last output): "
                  "%.3f clocks/sample; %llu reads, %llu writes, %.0f cycles/s\n",
                  name.c_str(), k.lat_min, k.lat_max, (unsigned long long)r.inputs, (unsigned long long)r.outputs,
                  (unsigned long long)(r.last_out_cycle - r.first_in_cycle + 1),
                  (double)(r.last_out_cycle - r.first_in_cycle + 1) / (double)r.inputs, (unsigned long long)mem.reads,
                  (unsigned long long)mem.writes, r.seconds > 0 ? (double)r.cycles / r.seconds : 0.0);
  }
}

TEST(DepthTxn, CommittedDumpMatchesTheModel) { run_dump<Vfxr_depth>(kCommitted, "committed", false); }
TEST(DepthTxn, DefaultSceneMatchesTheModel) { run_dump<Vfxr_depth>(kDefault, "default", true); }
// The same with the separate write channel (WritePort = 1).
TEST(DepthTxn, WritePortCommittedDumpMatchesTheModel) { run_dump<Vfxr_depth_wp>(kCommitted, "wp_committed", false); }
TEST(DepthTxn, WritePortDefaultSceneMatchesTheModel) { run_dump<Vfxr_depth_wp>(kDefault, "wp_default", true); }
// The committed back-end vectors: every depth function (vectors/scenes/backend_state/<func>),
// and the directed geometric cases; both memory ports.
TEST(DepthTxn, CommittedBackendSetsMatchTheModel) {
  for (const auto& [dir, name] : fxr::tb::committed_backend_dumps()) {
    SCOPED_TRACE(dir);
    run_dump<Vfxr_depth>(dir, name, false);
    run_dump<Vfxr_depth_wp>(dir, "wp_" + name, false);
  }
}

// ---- directed cases ---------------------------------------------------------------------------

// `incoming func stored` from the definitions (GL): the function's code has one bit per outcome,
// bit 0 less, bit 1 equal, bit 2 greater (never 0, less 1, equal 2, lequal 3, greater 4,
// notequal 5, gequal 6, always 7).
bool passes(int func, uint32_t in, uint32_t stored) {
  const int outcome = in < stored ? 0 : in == stored ? 1 : 2;
  return ((func >> outcome) & 1) != 0;
}

struct Frag {
  int x, y;
  uint32_t depth;
};

// Builds depth.in / depth.out for `frags` with the committed dump's layouts and the expected
// outcome computed here, runs them, and checks the outputs and the final buffer.
template <class Dut>
void run_directed(const std::string& name, const State& s, const std::vector<Frag>& frags, unsigned lat_max,
                  uint64_t* clocks = nullptr) {
  const SceneStageVectors base = fxr::load_scene_stage(kCommitted, "depth");
  const uint32_t clear = max_code(base.cfg);
  SceneStageVectors v = base;
  const size_t ni = v.in.lay.size(), no = v.out.lay.size();
  v.in.data.clear();
  v.out.data.clear();
  v.in.rows = v.out.rows = 0;
  const size_t cprim = col(v.in.lay, "prim"), cx = col(v.in.lay, "x"), cy = col(v.in.lay, "y"),
               cd = col(v.in.lay, "depth"), cden = col(v.in.lay, "den");
  std::vector<uint32_t> buf((size_t)s.vw * (size_t)s.vh, clear);
  for (size_t i = 0; i < frags.size(); ++i) {
    const Frag& f = frags[i];
    fxr::VecRow rec(ni - v.in.header, 0);
    rec[cprim - v.in.header] = i;
    rec[cx - v.in.header] = fxr::vec_pack(f.x, v.in.lay[cx].width);
    rec[cy - v.in.header] = fxr::vec_pack(f.y, v.in.lay[cy].width);
    rec[cd - v.in.header] = f.depth;
    rec[cden - v.in.header] = fxr::vec_pack((fxr::i128)i * 1000003 - 77, v.in.lay[cden].width);  // passes through
    uint32_t& stored = buf[(size_t)(f.y - s.vy) * (size_t)s.vw + (size_t)(f.x - s.vx)];
    const bool pass = !s.test || passes(s.func, f.depth, stored);
    if (pass && s.test && s.write) stored = f.depth;
    v.in.data.push_back(i);
    v.in.data.push_back(pass ? 1 : 0);
    v.in.data.insert(v.in.data.end(), rec.begin(), rec.end());
    ++v.in.rows;
    if (pass) {
      v.out.data.push_back(i);
      v.out.data.push_back(0);
      v.out.data.push_back(1);
      v.out.data.insert(v.out.data.end(), rec.begin(), rec.end());
      ++v.out.rows;
    }
  }
  ASSERT_EQ(v.in.data.size(), v.in.rows * ni);
  ASSERT_EQ(v.out.data.size(), v.out.rows * no);
  for (uint64_t seed : {1u, 2u}) {
    DepthMemOptions mo;
    mo.seed = seed;
    mo.max_latency = lat_max;
    mo.req_stall_pct = seed == 2 ? 30 : 0;
    mo.wr_stall_pct = seed == 2 ? 30 : 0;
    DepthMem mem(buf.size(), clear, mo);
    const TxnHook<Dut> h = hook_for<Dut>(s, mem);
    const TxnResult r = fxr::tb::run_txn<Dut>(v, nullptr, opts("depth_" + name, seed, seed == 2 ? 30 : 0,
                                                                      seed == 2 ? 30 : 0), &h);
    EXPECT_TRUE(r.passed()) << name << " seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows) << name;
    EXPECT_TRUE(mem.words() == buf) << name << ": final buffer";
    if (!s.test) {
      EXPECT_EQ(mem.reads + mem.writes, 0u) << name << ": test off accesses memory";
    }
    if (s.test && !s.write) {
      EXPECT_EQ(mem.writes, 0u) << name << ": mask off writes";
    }
    if (clocks && seed == 1) *clocks = r.last_out_cycle - r.first_in_cycle + 1;
  }
}

// One pixel hit repeatedly (each fragment back to back with the previous one: the hazard), three
// other pixels, depths below, equal to and above the stored code, for all eight functions with
// the mask on and off, and with the test off.
template <class Dut>
void every_function(const std::string& prefix) {
  const uint32_t M = (1u << 24) - 1;  // the clear value at the committed dump's d24 (checked below)
  ASSERT_EQ(max_code(fxr::load_scene_stage(kCommitted, "depth").cfg), M);
  State s;
  s.vx = -3;
  s.vy = 2;
  s.vw = 5;
  s.vh = 4;
  const std::vector<Frag> frags = {
      {0, 3, 500}, {0, 3, 400}, {0, 3, 400}, {0, 3, 600}, {0, 3, 399}, {-3, 2, M}, {-3, 2, M},  {1, 5, 0},
      {1, 5, 0},   {0, 3, 401}, {1, 5, 7},   {0, 3, 398}, {-3, 2, 1},  {0, 3, 398}, {1, 4, 12}, {0, 3, M}};
  for (int func = 0; func < 8; ++func)
    for (bool write : {true, false}) {
      s.func = func;
      s.test = true;
      s.write = write;
      run_directed<Dut>(prefix + "f" + std::to_string(func) + (write ? "_w" : "_nw"), s, frags, 6);
    }
  s.func = 0;  // never — ignored with the test off: everything passes, nothing is read or written
  s.test = false;
  s.write = true;
  run_directed<Dut>(prefix + "test_off", s, frags, 6);
}
TEST(DepthTxn, EveryFunctionMaskAndHazard) { every_function<Vfxr_depth>(""); }
TEST(DepthTxn, WritePortEveryFunctionMaskAndHazard) { every_function<Vfxr_depth_wp>("wp_"); }

// The hazard's cost: 64 fragments on one pixel (each waits for the previous one's write) versus
// 64 on distinct pixels, memory latency 1.
TEST(DepthTxn, SamePixelBackToBackStallsAndStaysExact) {
  State s;
  s.vw = 16;
  s.vh = 8;
  s.func = 3;  // lequal: every second fragment passes
  std::vector<Frag> same, distinct;
  for (int i = 0; i < 64; ++i) {
    same.push_back({3, 2, (uint32_t)(1000 - (i % 2 ? 0 : i))});
    distinct.push_back({i % 16, i / 16, (uint32_t)(1000 - (i % 2 ? 0 : i))});
  }
  uint64_t c_same = 0, c_distinct = 0;
  run_directed<Vfxr_depth>("same_pixel", s, same, 1, &c_same);
  run_directed<Vfxr_depth>("distinct_pixels", s, distinct, 1, &c_distinct);
  std::printf("depth hazard: 64 fragments on one pixel %llu clocks, on 64 pixels %llu clocks (latency 1)\n",
              (unsigned long long)c_same, (unsigned long long)c_distinct);
  EXPECT_GT(c_same, c_distinct);
  uint64_t w_same = 0, w_distinct = 0;
  run_directed<Vfxr_depth_wp>("wp_same_pixel", s, same, 1, &w_same);
  run_directed<Vfxr_depth_wp>("wp_distinct_pixels", s, distinct, 1, &w_distinct);
  std::printf("depth hazard, write channel: 64 fragments on one pixel %llu clocks, on 64 pixels %llu clocks\n",
              (unsigned long long)w_same, (unsigned long long)w_distinct);
  EXPECT_GT(w_same, w_distinct);
}

}  // namespace

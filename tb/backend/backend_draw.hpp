// tb/backend/backend_draw.hpp — a whole draw through rtl/fxr_raster_backend.sv (Verilator) and
// the model's chain (model/unit/chain.hpp), shared by the back-end test (tb/backend/backend_test.cpp)
// and the user's co-simulation (tb/cosim/cosim_main.cpp, `fxraster cosim`; docs/rtl.md, "fxraster
// cosim"):
//   model_draw()  runs the model's chain on a draw's triangles and collects, from its taps, the
//                 stream the back end is driven with (setup.in), every record at the back end's
//                 stage boundaries (setup.out, traverse.out, interp.out, depth.out, divide.out),
//                 the final depth buffer and the statistics the counter registers must hold;
//   Gen           random triangles with the hard cases mixed in (tb/backend/backend_test.cpp,
//                 tb/backend/cycles_test.cpp);
//   run_rtl()     drives that stream into a verilated fxr_raster_backend (any prefix) through the
//                 transaction harness (tb/txn_harness.hpp) with the draw state, the depth memory
//                 (tb/depth_mem.hpp), random gaps, back-pressure and memory latency, and reads the
//                 counter registers.
#pragma once

#include <array>
#include <cmath>
#include <random>
#include <functional>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "depth_mem.hpp"
#include "model/unit/chain.hpp"
#include "model/vectors/codegen.hpp"
#include "model/vectors/record_vectors.hpp"
#include "model/vectors/scene_dump.hpp"
#include "txn/draw_state_ports.hpp"
#include "txn_harness.hpp"

namespace fxr::tb {

// The varyings the RTL was generated for (fxr_rec_pkg::NumVaryings, `fxraster layout
// --emit-records-sv` at its default): a draw with fewer runs with this many (the extra varyings
// are the scene's zeros), so the records fit the ports.
constexpr int kRtlVaryings = fxr::kRecordPackageVaryings;

// ---- the model's streams of one draw -----------------------------------------------------------

// Counters of the back end (rtl/fxr_raster_backend.sv, stat_*_o), in this order.
constexpr int kStats = 10;
inline const char* const kStatNames[kStats] = {"tri_in",    "tri_drawn", "tri_zero_area",  "tri_backface",    "tri_no_samples",
                                               "tri_range", "spans",     "frag_generated", "frag_depth_pass", "frag_depth_fail"};
using Stats = std::array<uint64_t, kStats>;

// The unit's stage boundaries, in pipeline order: the records each stage emits. The back end's
// are kTapSetup on; the geometry's (stages 1–4) are recorded when model_draw is asked to.
constexpr int kTaps = 9;
inline const char* const kTapNames[kTaps] = {"convert", "clip",   "recip", "viewport", "setup",
                                             "traverse", "interp", "depth", "divide"};
constexpr int kTapSetup = 4;

// The rows of one boundary: (seq, record fields), seq the record's index in the stream.
struct TapStream {
  VecLayout lay;
  uint64_t rows = 0;
  std::vector<vec_word> data;
  VecRow row(uint64_t r) const {
    const size_t n = lay.size();
    return VecRow(data.begin() + (ptrdiff_t)(r * n), data.begin() + (ptrdiff_t)((r + 1) * n));
  }
};
constexpr size_t kTapHeaderFields = 1;

// Taps: setup's inputs become the rows of an in-memory "setup.in" (txn, n_out, SetupTriangle),
// the divider's outputs the rows of "backend.out" (txn, seq, last, Fragment) with txn the
// setup input they came from — the transaction-dump rules (model/vectors/scene_dump.hpp); and
// every stage's outputs the rows of its TapStream.
struct BackendTaps {
  RecordShape shape;
  SceneStageVectors v;
  SceneStageVectors u;  // the whole unit: convert.in (InputTriangle) → divide.out, txn = the primitive
  uint64_t u_n_out = 0;
  std::vector<SetupTriangle> tris;
  std::array<TapStream, kTaps> taps;
  uint64_t spans = 0;
  uint64_t n_out = 0;
  VecRow in_row, out_row, tap_row;
  bool out_pending = false;
  bool geometry_taps = false;  // record stages 1–4's outputs too

  template <class R>
  void tap_layout(int k) {
    std::vector<VecField> f = {{"seq", VecDir::Out, kTxnIdBits, false, "index in the boundary's stream"}};
    append_record_fields<R>(shape, VecDir::Out, f);
    taps[(size_t)k].lay = VecLayout(f);
  }
  BackendTaps(const Config& cfg, int varyings, const std::string& name) : shape{cfg, varyings} {
    std::vector<VecField> fi = {{"txn", VecDir::In, kTxnIdBits, false, "transaction id"},
                                {"n_out", VecDir::In, kTxnCountBits, false, "fragments of this triangle"}};
    append_record_fields<SetupTriangle>(shape, VecDir::In, fi);
    std::vector<VecField> fo = {{"txn", VecDir::Out, kTxnIdBits, false, "setup.in txn"},
                                {"seq", VecDir::Out, kTxnCountBits, false, "index among the triangle's"},
                                {"last", VecDir::Out, 1, false, "last of the triangle"}};
    append_record_fields<Fragment>(shape, VecDir::Out, fo);
    v.stage = "backend";
    v.cfg = cfg;
    v.num_varyings = varyings;
    v.in = SceneStageFile{name + ":setup.in", VecLayout(fi), kTxnInHeaderFields, 0, {}};
    v.out = SceneStageFile{name + ":backend.out", VecLayout(fo), kTxnOutHeaderFields, 0, {}};
    in_row.assign(v.in.lay.size(), 0);
    out_row.assign(v.out.lay.size(), 0);
    std::vector<VecField> ui = {{"txn", VecDir::In, kTxnIdBits, false, "transaction id"},
                                {"n_out", VecDir::In, kTxnCountBits, false, "fragments of this primitive"}};
    append_record_fields<InputTriangle>(shape, VecDir::In, ui);
    u.stage = "unit";
    u.cfg = cfg;
    u.num_varyings = varyings;
    u.in = SceneStageFile{name + ":convert.in", VecLayout(ui), kTxnInHeaderFields, 0, {}};
    u.out = SceneStageFile{name + ":unit.out", VecLayout(fo), kTxnOutHeaderFields, 0, {}};
    tap_layout<ExactTriangle>(0);
    tap_layout<ClippedTriangle>(1);
    tap_layout<RecipTriangle>(2);
    tap_layout<SetupTriangle>(3);
    tap_layout<TriangleEquations>(4);
    tap_layout<Span>(5);
    tap_layout<PlaneSample>(6);
    tap_layout<PlaneSample>(7);
    tap_layout<Fragment>(8);
  }
  template <class R>
  void tap(int k, const R& r) {
    TapStream& t = taps[(size_t)k];
    tap_row.assign(t.lay.size(), 0);
    tap_row[0] = t.rows;
    pack_record(r, shape, tap_row, kTapHeaderFields, kTapNames[k]);
    t.data.insert(t.data.end(), tap_row.begin(), tap_row.end());
    ++t.rows;
  }
  void flush_out(bool last) {
    if (!out_pending) return;
    out_row[2] = last;
    v.out.data.insert(v.out.data.end(), out_row.begin(), out_row.end());
    ++v.out.rows;
    out_pending = false;
  }
  void flush_in() {
    if (v.in.rows == 0 && tris.empty()) return;
    v.in.data[(v.in.rows - 1) * v.in.lay.size() + 1] = n_out;
  }
  template <class S>
  void in(const typename S::In& r) {
    if constexpr (std::is_same_v<S, ConvertStage>) {
      if (u.in.rows) u.in.data[(u.in.rows - 1) * u.in.lay.size() + 1] = u_n_out;
      VecRow row(u.in.lay.size(), 0);
      row[0] = u.in.rows;
      pack_record(r, shape, row, kTxnInHeaderFields, u.in.path);
      u.in.data.insert(u.in.data.end(), row.begin(), row.end());
      ++u.in.rows;
      u_n_out = 0;
    }
    if constexpr (std::is_same_v<S, SetupStage>) {
      flush_out(true);
      if (v.in.rows) flush_in();
      in_row[0] = v.in.rows;
      in_row[1] = 0;
      pack_record(r, shape, in_row, kTxnInHeaderFields, v.in.path);
      v.in.data.insert(v.in.data.end(), in_row.begin(), in_row.end());
      ++v.in.rows;
      tris.push_back(r);
      n_out = 0;
    }
  }
  template <class S>
  void out(const typename S::Out& r) {
    if constexpr (std::is_same_v<S, ConvertStage>) {
      if (geometry_taps) tap(0, r);
    }
    if constexpr (std::is_same_v<S, ClipStage>) {
      if (geometry_taps) tap(1, r);
    }
    if constexpr (std::is_same_v<S, RecipStage>) {
      if (geometry_taps) tap(2, r);
    }
    if constexpr (std::is_same_v<S, ViewportStage>) {
      if (geometry_taps) tap(3, r);
    }
    if constexpr (std::is_same_v<S, SetupStage>) tap(4, r);
    if constexpr (std::is_same_v<S, TraverseStage>) {
      ++spans;
      tap(5, r);
    }
    if constexpr (std::is_same_v<S, InterpStage>) tap(6, r);
    if constexpr (std::is_same_v<S, DepthStage>) tap(7, r);
    if constexpr (std::is_same_v<S, DivideStage>) {
      tap(8, r);
      flush_out(false);
      out_row[0] = v.in.rows - 1;
      out_row[1] = n_out++;
      pack_record(r, shape, out_row, kTxnOutHeaderFields, v.out.path);
      out_pending = true;
      VecRow row = out_row;  // `last` is not compared (the unit has no out_last_o)
      row[0] = u.in.rows - 1;
      row[1] = u_n_out++;
      u.out.data.insert(u.out.data.end(), row.begin(), row.end());
      ++u.out.rows;
    }
  }
  void finish() {
    flush_out(true);
    if (v.in.rows) flush_in();
    if (u.in.rows) u.in.data[(u.in.rows - 1) * u.in.lay.size() + 1] = u_n_out;
  }
};

struct NullSink : FragmentSink {
  void emit(const Fragment&) override {}
};

struct Draw {
  std::string name;
  DrawState st;
  SceneStageVectors v;
  SceneStageVectors u;  // the whole unit's streams (BackendTaps::u)
  std::array<TapStream, kTaps> taps;
  std::vector<uint32_t> depth;  // the model's final buffer
  uint32_t clear = 0;           // the buffer's value before the draw (both sides)
  Stats want{};
  uint64_t fragments = 0;  // divide.out rows
  RasterStats stats;       // the model's statistics of the draw
};

// Runs the model's chain on `tris` and collects what the back end must reproduce. The depth
// buffer starts at `clear` (the unit's clear value, the maximum code, when negative): the chain of
// run_raster_unit_to on a buffer filled after frame_begin.
inline Draw model_draw(const std::string& name, const Config& cfg, DrawState st, const std::vector<ClipTriangle>& tris,
                       int64_t clear = -1, bool geometry_taps = false) {
  st.num_varyings = kRtlVaryings;
  BackendTaps taps(cfg, kRtlVaryings, name);
  taps.geometry_taps = geometry_taps;
  FrameOutput f;
  NullSink sink;  // varyings computed (the planes of every varying), fragments not kept
  frame_begin(cfg, st, f);
  const uint32_t clear_code = clear < 0 ? (uint32_t)depth_max_code(cfg.raster) : (uint32_t)clear;
  std::fill(f.depth.begin(), f.depth.end(), clear_code);
  {
    UnitChain<BackendTaps> chain(cfg, st, f, &sink, taps);
    for (size_t p = 0; p < tris.size(); ++p) chain.draw(tris[p], (uint32_t)p);
  }
  taps.finish();
  Draw d;
  d.clear = clear_code;
  d.name = name;
  d.st = st;
  d.v = std::move(taps.v);
  d.u = std::move(taps.u);
  d.taps = std::move(taps.taps);
  d.depth = std::move(f.depth);
  d.fragments = d.v.out.rows;
  d.stats = f.stats;
  // Setup outcomes per setup triangle: the chain's own counters (RasterStats::tris, the unit's
  // tri_* definition; docs/pipeline.md, "Statistics: primitives, pieces, setup triangles").
  const TriStats& ts = f.stats.tris;
  d.want = {ts.in, ts.drawn, ts.zero_area, ts.backface, ts.no_samples, ts.range, taps.spans,
            f.stats.fragments_generated, f.stats.fragments_depth_pass, f.stats.fragments_depth_fail};
  return d;
}

// ---- the RTL run -------------------------------------------------------------------------------

struct Handshake {
  uint64_t seed = 1;
  unsigned gap = 0, stall = 0;                       // input gaps, output back-pressure (%)
  unsigned lat_min = 1, lat_max = 1, req_stall = 0;  // depth memory
};

constexpr int kPerf = 7;
inline const char* const kPerfNames[kPerf] = {"setup_stall", "fifo_full",  "span_stall", "span_wait",
                                              "sample_stall", "pass_stall", "out_stall"};
using Perf = std::array<uint64_t, kPerf>;

struct RtlRun {
  TxnResult r;
  Stats stats{};
  Perf perf{};
  std::vector<uint32_t> depth;
  uint64_t bad_addresses = 0;
};

template <class T>
uint64_t u64(const T& x) {
  return (uint64_t)x;
}

// The options of run_rtl beyond the handshake: the harness's (print, waveform, output folder)
// and an observer of every cycle (the co-simulation's stage taps).
template <class Dut>
struct RtlRunOptions {
  std::string run;
  bool write_wave = true;
  bool print = true;
  std::function<void()> reset;        // before each simulation (a failed run is replayed)
  std::function<void(Dut&)> observe;  // after the cycle's handshakes settled, before the edge
  std::function<TxnResult(const SceneStageVectors&, const TxnOptions&, const TxnHook<Dut>&)> simulate;  // default: run_txn
  uint64_t time_eval_every = 0;  // TxnOptions::time_eval_every (the figures runs: the harness's share)
};

template <class Dut>
RtlRun run_rtl(const Draw& d, const SceneStageVectors& v, const Handshake& h, const RtlRunOptions<Dut>& ro) {
  RtlRun out;
  DepthMemOptions mo;
  mo.seed = 1000 + h.seed;
  mo.min_latency = h.lat_min;
  mo.max_latency = h.lat_max;
  mo.req_stall_pct = h.req_stall;
  mo.wr_stall_pct = h.req_stall;  // the write channel (DepthWritePort)
  DepthMem mem((size_t)d.st.viewport_w * (size_t)d.st.viewport_h, d.clear, mo);
  Stats& s = out.stats;
  TxnHook<Dut> hook;
  Perf& pf = out.perf;
  hook.reset = [&] {
    mem.reset();
    s = Stats{};
    pf = Perf{};
    if (ro.reset) ro.reset();
  };
  const int wib = v.cfg.raster.window_int_bits;
  hook.drive = [&](Dut& dut) {
    drive_draw_state(dut, d.st, wib);
    mem.drive(dut);
  };
  hook.observe = [&](Dut& dut) {
    mem.observe(dut);
    if (ro.observe) ro.observe(dut);
  };
  // The counters once, after the last clock (not read in every clock: harness time).
  hook.finish = [&](Dut& dut) {
    s = {u64(dut.stat_tri_in_o),       u64(dut.stat_tri_drawn_o),      u64(dut.stat_tri_zero_area_o),
         u64(dut.stat_tri_backface_o), u64(dut.stat_tri_no_samples_o), u64(dut.stat_tri_range_o),
         u64(dut.stat_spans_o),        u64(dut.stat_frag_generated_o), u64(dut.stat_frag_depth_pass_o),
         u64(dut.stat_frag_depth_fail_o)};
    pf = {u64(dut.perf_setup_stall_o), u64(dut.perf_fifo_full_o),    u64(dut.perf_span_stall_o),
          u64(dut.perf_span_wait_o),   u64(dut.perf_sample_stall_o), u64(dut.perf_pass_stall_o),
          u64(dut.perf_out_stall_o)};
  };
  TxnOptions o = txn_options("backend", ro.run, h.seed, h.gap, h.stall);
  o.write_wave = ro.write_wave;
  o.print = ro.print;
  o.drain_cycles = 400;  // the depth queue's failed samples and the memory's last responses
  o.time_eval_every = ro.time_eval_every;
  out.r = ro.simulate ? ro.simulate(v, o, hook) : run_txn<Dut>(v, nullptr, o, &hook);
  out.depth = mem.words();
  out.bad_addresses = mem.bad_addresses;
  return out;
}

// The figures runs sample every kTimeEvalEvery-th clock (a prime: no alias with a pipeline's period).
constexpr uint64_t kTimeEvalEvery = 61;

// The figures runs' CPU rate of the simulation loop and the harness's share of it (sampled,
// TxnOptions::time_eval_every): "…; harness 9.1 % of the loop, the model alone 1,080,000 per CPU second".
inline std::string harness_text(const TxnResult& r, uint64_t items) {
  if (r.harness_share < 0 || r.cpu_seconds <= 0) return "";
  char b[200];
  std::snprintf(b, sizeof b, "; harness %.1f %% of the loop (%llu clocks sampled), the model alone %.0f per CPU second",
                100.0 * r.harness_share, (unsigned long long)r.timed_cycles,
                (double)items / (r.cpu_seconds * (1.0 - r.harness_share)));
  return b;
}

inline std::string stats_text(const Stats& s) {
  std::string t;
  for (int i = 0; i < kStats; ++i) t += std::string(i ? ", " : "") + kStatNames[i] + " " + std::to_string(s[(size_t)i]);
  return t;
}

// ---- random triangles with the hard cases (the back-end test's and the cycle model's draws) ----

// Window position (pixels, y up) → clip coordinates at w (viewport transform of stage 4 inverted
// in double; the front end's single float32 rounding applies).
struct Gen {
  std::mt19937_64 rng;
  double W, H;
  explicit Gen(uint64_t seed, int w, int h) : rng(seed), W(w), H(h) {}
  double uni(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  int pick(int n) { return (int)(rng() % (uint64_t)n); }
  fxr::ClipVertex vtx(double x, double y, double w, double z_ndc) {
    fxr::ClipVertex v;
    v.pos[0] = (float)((x / W * 2.0 - 1.0) * w);
    v.pos[1] = (float)((y / H * 2.0 - 1.0) * w);
    v.pos[2] = (float)(z_ndc * w);
    v.pos[3] = (float)w;
    for (int k = 0; k < kRtlVaryings; ++k) v.var[k] = (float)uni(-4.0, 4.0);
    return v;
  }
  fxr::ClipTriangle tri(const double p[3][2], const double w[3]) {
    fxr::ClipTriangle t;
    for (int i = 0; i < 3; ++i) t.v[i] = vtx(p[i][0], p[i][1], w[i], uni(-0.99, 0.99));
    if (rng() & 1) std::swap(t.v[1], t.v[2]);  // both windings
    return t;
  }
  // Appends one case (two triangles for the shared-edge ties). Kinds, with their weights:
  void add(std::vector<fxr::ClipTriangle>& out, std::array<uint64_t, 9>& kinds) {
    const int r = pick(1000);
    double p[3][2], w[3] = {1, 1, 1};
    auto around = [&](double cx, double cy, double s) {
      for (auto& q : p) {
        q[0] = cx + uni(-s, s);
        q[1] = cy + uni(-s, s);
      }
    };
    const double cx = uni(-4, W + 4), cy = uni(-4, H + 4);
    int kind;
    if (r < 450) {  // 0: general small triangles, up to ~12 pixels across
      kind = 0;
      around(cx, cy, uni(1.0, 6.0));
    } else if (r < 600) {  // 1: top-left ties: a quad on pixel centres / edges split along a diagonal
      kind = 1;
      const double x0 = std::floor(uni(0, W - 8)) + (pick(2) ? 0.5 : 0.0), y0 = std::floor(uni(0, H - 8)) + (pick(2) ? 0.5 : 0.0);
      const double sx = 1 + pick(6), sy = 1 + pick(6);
      const double q[4][2] = {{x0, y0}, {x0 + sx, y0}, {x0 + sx, y0 + sy}, {x0, y0 + sy}};
      const int d = pick(2);
      const double a[3][2] = {{q[0][0], q[0][1]}, {q[1 + d][0], q[1 + d][1]}, {q[2 + d][0], q[2 + d][1]}};
      const double b[3][2] = {{q[0][0], q[0][1]}, {q[2 + d][0], q[2 + d][1]}, {q[(3 + d) % 4][0], q[(3 + d) % 4][1]}};
      out.push_back(tri(a, w));
      out.push_back(tri(b, w));
      ++kinds[1];
      return;
    } else if (r < 720) {  // 2: 1-pixel and sub-pixel triangles
      kind = 2;
      around(std::floor(cx) + 0.5, std::floor(cy) + 0.5, uni(0.01, 0.9));
    } else if (r < 800) {  // 3: slivers: long and thin
      kind = 3;
      const double ang = uni(0, 6.283185307179586), len = uni(8, 40), th = uni(0.001, 0.3);
      p[0][0] = cx; p[0][1] = cy;
      p[1][0] = cx + len * std::cos(ang); p[1][1] = cy + len * std::sin(ang);
      p[2][0] = cx + 0.5 * len * std::cos(ang) - th * std::sin(ang);
      p[2][1] = cy + 0.5 * len * std::sin(ang) + th * std::cos(ang);
    } else if (r < 803) {  // 4: full viewport
      kind = 4;
      p[0][0] = -1; p[0][1] = -1; p[1][0] = 2 * W + 2; p[1][1] = -1; p[2][0] = -1; p[2][1] = 2 * H + 2;
    } else if (r < 810) {  // 5: guard-band-sized: vertices far outside, covering a corner
      kind = 5;
      const double big = uni(1e3, 3e4);
      p[0][0] = uni(0, W); p[0][1] = uni(0, H);
      p[1][0] = p[0][0] + uni(2, 6); p[1][1] = -big;
      p[2][0] = p[0][0] + big; p[2][1] = p[0][1] + uni(-3, 3);
    } else if (r < 900) {  // 6: w ratio up to 10^6 inside a triangle (perspective)
      kind = 6;
      around(cx, cy, uni(1.0, 8.0));
      w[0] = uni(0.001, 0.01);
      w[1] = w[0] * uni(1e5, 1e6);
      w[2] = uni(0.5, 2);
    } else {  // 7: zero area: collinear or repeated vertices
      kind = 7;
      around(cx, cy, uni(1.0, 6.0));
      if (pick(2)) {  // a repeated vertex
        p[2][0] = p[0][0];
        p[2][1] = p[0][1];
      } else {  // three collinear points on whole pixels (exact after snapping)
        p[0][0] = std::round(p[0][0]);
        p[0][1] = std::round(p[0][1]);
        p[1][0] = p[0][0] + 1 + pick(4);
        p[1][1] = p[0][1] + pick(4);
        const double t = 2 + pick(2);
        p[2][0] = p[0][0] + t * (p[1][0] - p[0][0]);
        p[2][1] = p[0][1] + t * (p[1][1] - p[0][1]);
      }
    }
    ++kinds[(size_t)kind];
    out.push_back(tri(p, w));
  }
};

}  // namespace fxr::tb

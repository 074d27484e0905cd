// tb/unit/unit_run.hpp — a whole draw through rtl/fxr_raster_unit.sv (Verilator): the model's
// convert.in stream of the draw (tb/backend/backend_draw.hpp, Draw::u) driven into the unit after
// the draw state is written through its register block, the depth buffer behind its memory port
// (tb/depth_mem.hpp), random gaps, back-pressure and memory latency; the fragment stream compared
// in order by the transaction harness; the counter registers read. docs/rtl.md, "fxr_raster_unit".
#pragma once

#include <array>
#include <functional>
#include <string>

#include "backend/backend_draw.hpp"

namespace fxr::tb {

// fxr_raster_unit's register block (rtl/fxr_raster_unit.sv): address → value of a draw state.
constexpr int kUnitRegs = 15;
inline std::array<int64_t, kUnitRegs> unit_registers(const DrawState& st, int num_varyings) {
  return {st.viewport_x, st.viewport_y, st.viewport_w,  st.viewport_h,     st.scissor_x,
          st.scissor_y,  st.scissor_w,  st.scissor_h,   (int64_t)st.cull,  st.front_ccw,
          (int64_t)st.depth_func, st.depth_test, st.depth_write, (int64_t)st.interp, num_varyings};
}

// The geometry counters (stat_*_o of stages 1–4) and their RasterStats values.
constexpr int kGeomStats = 10;
inline const char* const kGeomStatNames[kGeomStats] = {
    "prims_in", "prims_rejected_nan", "prims_rejected_inf", "prims_varying_nonfinite", "prims_trivial_accept",
    "prims_clipped", "clip_vertices_created", "clip_triangles_out", "prims_culled_outside", "geom_rejected_range"};
using GeomStats = std::array<uint64_t, kGeomStats>;
// The model's: RasterStats of the draw; geometry's range rejections per primitive (the clipper)
// and per clipped piece (stages 3 and 4), RasterStats::tris.
inline GeomStats model_geom_stats(const Draw& d) {
  const RasterStats& s = d.stats;
  return {s.prims_in, s.prims_rejected_nan, s.prims_rejected_inf, s.prims_varying_nonfinite, s.prims_trivial_accept,
          s.prims_clipped, s.clip_vertices_created, s.clip_triangles_out, s.prims_culled_outside,
          s.tris.geom_rejected_range};
}

constexpr int kUnitStages = 5;
inline const char* const kUnitStageNames[kUnitStages] = {"input", "clip", "recip", "viewport", "backend"};

struct UnitRun {
  RtlRun k;
  GeomStats geom{};
  std::array<std::array<uint64_t, 3>, kUnitStages> util{};  // busy, stalled, starved (whole run)
  // The same counters over the clocks from the first input transfer to the last output transfer
  // (without the reset, the register writes and the 20,000-clock drain: the cycle figure's window).
  std::array<std::array<uint64_t, 3>, kUnitStages> util_window{};
};

template <class T>
uint64_t flat_word(const T& p, int i, int bits) {
  return (uint64_t)port_field(p, i * bits, bits);
}

template <class Dut>
UnitRun run_unit(const Draw& d, const SceneStageVectors& v, const Handshake& h, const RtlRunOptions<Dut>& ro,
                 int stat_bits = 32) {
  UnitRun out;
  DepthMemOptions mo;
  mo.seed = 1000 + h.seed;
  mo.min_latency = h.lat_min;
  mo.max_latency = h.lat_max;
  mo.req_stall_pct = h.req_stall;
  mo.wr_stall_pct = h.req_stall;
  DepthMem mem((size_t)d.st.viewport_w * (size_t)d.st.viewport_h, d.clear, mo);
  const std::array<int64_t, kUnitRegs> regs = unit_registers(d.st, d.st.num_varyings);
  const uint64_t reg_mask = (uint64_t(1) << (v.cfg.raster.window_int_bits + 1)) - 1;
  uint64_t cycle = 0;
  // Registered counters: read in a clock, they hold the clocks before it.
  bool started = false, prev_out = false;
  uint64_t outputs = 0;
  std::array<std::array<uint64_t, 3>, kUnitStages> util_first{}, util_last{};
  TxnHook<Dut> hook;
  hook.reset = [&] {
    mem.reset();
    out.k.stats = Stats{};
    out.k.perf = Perf{};
    out.geom = GeomStats{};
    cycle = 0;
    started = prev_out = false;
    outputs = 0;
    util_first = util_last = {};
    if (ro.reset) ro.reset();
  };
  hook.drive = [&](Dut& dut) {
    // One register per clock after reset, then none (the harness offers no input meanwhile).
    dut.reg_we_i = dut.rst_ni && cycle < (uint64_t)kUnitRegs;
    dut.reg_addr_i = cycle < (uint64_t)kUnitRegs ? (uint8_t)cycle : 0;
    dut.reg_wdata_i = cycle < (uint64_t)kUnitRegs ? (uint32_t)((uint64_t)regs[cycle] & reg_mask) : 0;
    mem.drive(dut);
  };
  // The counters are registered: read in a clock, they hold the clocks before it. They are read
  // once at the end (finish), the utilisation also in the clocks that open and close the window
  // (the first input transfer, the clock after the last expected output transfer): per-clock reads
  // of every counter were 4 % of the checkerboard's loop (docs/speed.md, "Session 10: co-simulation
  // speed"), and the read after every output transfer was such a per-clock read on a scene of one
  // fragment per clock (session 11).
  auto read_util = [&](Dut& dut) {
    for (int i = 0; i < kUnitStages; ++i)
      out.util[(size_t)i] = {flat_word(dut.perf_busy_o, i, stat_bits), flat_word(dut.perf_stalled_o, i, stat_bits),
                             flat_word(dut.perf_starved_o, i, stat_bits)};
  };
  hook.observe = [&](Dut& dut) {
    ++cycle;
    mem.observe(dut);
    if (!started && dut.in_valid_i && dut.in_ready_o) {
      started = true;
      read_util(dut);
      util_first = out.util;
    }
    if (prev_out) {
      read_util(dut);
      util_last = out.util;
    }
    prev_out = false;
    if (dut.out_valid_o && dut.out_ready_i) prev_out = ++outputs == v.out.rows;
    if (ro.observe) ro.observe(dut);
  };
  auto read_stats = [](Dut& dut) -> Stats {
    return {u64(dut.stat_tri_in_o),       u64(dut.stat_tri_drawn_o),      u64(dut.stat_tri_zero_area_o),
            u64(dut.stat_tri_backface_o), u64(dut.stat_tri_no_samples_o), u64(dut.stat_tri_range_o),
            u64(dut.stat_spans_o),        u64(dut.stat_frag_generated_o), u64(dut.stat_frag_depth_pass_o),
            u64(dut.stat_frag_depth_fail_o)};
  };
  auto read_geom = [](Dut& dut) -> GeomStats {
    return {u64(dut.stat_prims_in_o),          u64(dut.stat_prims_rejected_nan_o),
            u64(dut.stat_prims_rejected_inf_o), u64(dut.stat_prims_varying_nonfinite_o),
            u64(dut.stat_prims_trivial_accept_o), u64(dut.stat_prims_clipped_o),
            u64(dut.stat_clip_vertices_created_o), u64(dut.stat_clip_triangles_out_o),
            u64(dut.stat_prims_culled_outside_o), u64(dut.stat_geom_rejected_range_o)};
  };
  hook.finish = [&](Dut& dut) {
    out.k.stats = read_stats(dut);
    out.k.perf = {u64(dut.perf_setup_stall_o), u64(dut.perf_fifo_full_o),    u64(dut.perf_span_stall_o),
                  u64(dut.perf_span_wait_o),   u64(dut.perf_sample_stall_o), u64(dut.perf_pass_stall_o),
                  u64(dut.perf_out_stall_o)};
    out.geom = read_geom(dut);
    read_util(dut);
  };
  // The last primitive may still be in the clipper (thousands of clocks) when its fragments, or
  // none, are out: the counters are read once the unit has drained. The drain ends 400 clocks
  // (the back end's drain: the depth queue's failed samples, the memory's last responses) after
  // every counter of the unit holds the model's final value — the geometry counters account for
  // every primitive and piece, the back end's for every setup triangle and fragment — or after
  // 20,000 clocks when they never do (then they differ, and expect_match says so). A counter that
  // moves on after that, or an extra output, is caught within those 400 clocks, as it was within
  // the 20,000 (the fixed drain was 8 % of the 1024² checkerboard's clocks: docs/speed.md,
  // "Session 11: co-simulation speed").
  const GeomStats want_geom = model_geom_stats(d);
  hook.settled = [&](Dut& dut) { return read_stats(dut) == d.want && read_geom(dut) == want_geom; };
  TxnOptions o = txn_options("unit", ro.run, h.seed, h.gap, h.stall);
  o.write_wave = ro.write_wave;
  o.print = ro.print;
  o.drain_cycles = 20000;
  o.settled_drain_cycles = 400;
  o.input_delay_cycles = kUnitRegs + 1;
  o.time_eval_every = ro.time_eval_every;
  out.k.r = ro.simulate ? ro.simulate(v, o, hook) : run_txn<Dut>(v, nullptr, o, &hook);
  for (int i = 0; i < kUnitStages; ++i)
    for (int j = 0; j < 3; ++j) out.util_window[(size_t)i][(size_t)j] = util_last[(size_t)i][(size_t)j] - util_first[(size_t)i][(size_t)j];
  out.k.depth = mem.words();
  out.k.bad_addresses = mem.bad_addresses;
  return out;
}

}  // namespace fxr::tb

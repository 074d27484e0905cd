// tb/txn_harness.hpp — Verilator co-simulation of one stage of the raster unit on a transaction
// dump (docs/vectors.md, "Transaction vectors"; docs/rtl.md, "Transaction testbench").
//
// The DUT has the valid / ready handshake of every unit (clk_i, rst_ni, in_valid_i, in_ready_o,
// out_valid_o, out_ready_i) and record ports: in_i (the stage's In record) and out_o (its Out
// record), each a packed struct of the generated package fxr_rec_pkg (`fxraster layout
// --emit-records-sv`, model/vectors/codegen.hpp), whose members are the record's visit() fields,
// first field most significant. The C++ binding is the same rule applied to the dump's layout
// (which load_scene_stage() checks against the records' visit()), so nothing is written by hand:
// field f of a record with fields f_0 … f_m−1 occupies the bits below Σ_{i ≤ f} width_i, counted
// from the struct's top. Optional ports, used when the DUT has them:
//   out_last_o  compared with the dump's `last` (the input's final output);
//   ctx_i       the per-triangle context of interp (the record of setup.out line `ctx`), driven
//               with the same handshake as in_i.
// Other ports (draw-state inputs, a memory port) are served by an optional TxnHook: drive() sets
// the DUT's inputs before each evaluation, observe() sees the settled handshake of the cycle
// before the clock edge (tb/depth_mem.hpp connects fxr_depth's depth-buffer port this way).
//
// The rows of S.in are driven in order with random input gaps; the outputs are taken with random
// back-pressure and compared, in order, with the rows of S.out: the i-th output must equal row i
// (every record field, and `last`), and must not come before the input it belongs to was
// accepted. A mismatch names S.out's file:line and the first differing field; outputs beyond the
// file are "extra", owed outputs that do not come within timeout_cycles are "lost". On failure the
// run is replayed with tracing on and an FST of the window around the first mismatch is written
// (as tb/harness.hpp does).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <verilated.h>
#include <verilated_fst_c.h>

#include <nlohmann/json.hpp>

#include "harness.hpp"  // cpu_seconds_now()
#include "model/vectors/scene_dump.hpp"
#include "model/vectors/vectors.hpp"

namespace fxr::tb {

// ---- record <-> packed struct port ----------------------------------------------------------

// 32-bit word i of a Verilator port (CData / SData / IData / QData or VlWide<N>).
template <class T>
uint32_t port_word(const T& p, int i) {
  if constexpr (std::is_integral_v<T>) return i * 32 < (int)sizeof(T) * 8 ? (uint32_t)((uint64_t)p >> (32 * i)) : 0u;
  else return p[(size_t)i];
}
template <class T>
void set_port_word(T& p, int i, uint32_t w) {
  if constexpr (std::is_integral_v<T>) {
    if (i * 32 >= (int)sizeof(T) * 8) return;
    uint64_t v = (uint64_t)p;
    v &= ~((uint64_t)0xffffffffu << (32 * i));
    v |= (uint64_t)w << (32 * i);
    p = (T)v;
  } else {
    p[(size_t)i] = w;
  }
}
template <class T>
constexpr int port_bits() {
  if constexpr (std::is_integral_v<T>) return (int)sizeof(T) * 8;
  else return (int)(sizeof(T) / sizeof(uint32_t)) * 32;  // VlWide<N>: N words
}

// Bits [lsb, lsb + width) of a port (width ≤ kVecMaxFieldBits), read / OR-ed in by 32-bit word
// pieces: a field costs one to five word accesses, not one per bit (the per-bit loop was 17 % of
// `fxraster cosim`'s time; docs/rtl.md, "Co-simulation speed").
template <class T>
vec_word port_field(const T& p, int lsb, int width) {
  vec_word v = 0;
  for (int got = 0; got < width;) {
    const int at = lsb + got, b = at % 32, take = std::min(32 - b, width - got);
    const uint32_t piece = (port_word(p, at / 32) >> b) & (take == 32 ? 0xffffffffu : ((1u << take) - 1u));
    v |= (vec_word)piece << got;
    got += take;
  }
  return v;
}
template <class T>
void or_port_field(T& p, int lsb, int width, vec_word v) {
  for (int put = 0; put < width;) {
    const int at = lsb + put, b = at % 32, take = std::min(32 - b, width - put);
    const uint32_t piece = (uint32_t)(v >> put) & (take == 32 ? 0xffffffffu : ((1u << take) - 1u));
    if (piece) set_port_word(p, at / 32, port_word(p, at / 32) | (piece << b));
    put += take;
  }
}

// The record part of a layout: fields [first, size), their struct bit positions.
struct RecordBinding {
  std::vector<int> col, lsb, width;
  int bits = 0;
  RecordBinding() = default;
  RecordBinding(const VecLayout& lay, size_t first) {
    for (size_t f = first; f < lay.size(); ++f) bits += lay[f].width;
    int top = bits;
    for (size_t f = first; f < lay.size(); ++f) {
      top -= lay[f].width;
      col.push_back((int)f);
      lsb.push_back(top);
      width.push_back(lay[f].width);
    }
  }
  // `row` points at a row's first column (VecRow::data(), or a row inside a stream's data).
  template <class T>
  void drive(T& port, const vec_word* row) const {
    static_assert(sizeof(vec_word) * 8 >= kVecMaxFieldBits, "fields up to kVecMaxFieldBits");
    for (int i = 0; i < (port_bits<T>() + 31) / 32; ++i) set_port_word(port, i, 0);
    for (size_t k = 0; k < col.size(); ++k) or_port_field(port, lsb[k], width[k], row[(size_t)col[k]]);
  }
  template <class T>
  void drive(T& port, const VecRow& row) const {
    drive(port, row.data());
  }
  template <class T>
  void sample(const T& port, VecRow& row) const {
    for (size_t k = 0; k < col.size(); ++k) row[(size_t)col[k]] = port_field(port, lsb[k], width[k]);
  }
};

// Optional ports.
template <class D, class = void>
struct HasOutLast : std::false_type {};
template <class D>
struct HasOutLast<D, std::void_t<decltype(std::declval<D&>().out_last_o)>> : std::true_type {};
template <class D, class = void>
struct HasCtx : std::false_type {};
template <class D>
struct HasCtx<D, std::void_t<decltype(std::declval<D&>().ctx_i)>> : std::true_type {};

// ---- the run --------------------------------------------------------------------------------

struct TxnOptions {
  std::string unit;      // report lines ("traverse")
  std::string run_name;  // names the waveform / summary files
  uint64_t seed = 1;     // handshake randomness
  unsigned in_gap_pct = 25, out_stall_pct = 25;
  uint64_t timeout_cycles = 200000;  // cycles without an output while one is owed: lost
  uint64_t reset_cycles = 4, drain_cycles = 200;
  // With TxnHook::settled: once it holds after the last output, the drain ends this many clocks
  // later (drain_cycles stays the limit when it never holds).
  uint64_t settled_drain_cycles = 400;
  uint64_t input_delay_cycles = 0;  // no input offered in the first cycles after reset (a register block's writes)
  uint64_t wave_before = 200, wave_after = 20;
  bool write_wave = true, print = true;
  size_t max_print = 20;
  // Every n-th clock (0: none) the loop times its body and the DUT's eval() calls with the steady
  // clock: TxnResult::harness_share, the harness's share of the loop (figures runs only; the
  // sampled clocks cost a few timer reads each).
  uint64_t time_eval_every = 0;
};

// The options of one run: unit, run name, handshake seed and randomness, the rest at defaults.
inline TxnOptions txn_options(const std::string& unit, const std::string& run, uint64_t seed, unsigned gap_pct,
                              unsigned stall_pct) {
  TxnOptions o;
  o.unit = unit;
  o.run_name = run;
  o.seed = seed;
  o.in_gap_pct = gap_pct;
  o.out_stall_pct = stall_pct;
  return o;
}

// Per-cycle access to the DUT's other ports. reset() is called before each simulation (a failed
// run is replayed with tracing: the hook starts again from the same state).
template <class Dut>
struct TxnHook {
  std::function<void()> reset;
  std::function<void(Dut&)> drive;    // before every evaluation of the cycle's inputs (and in reset)
  std::function<void(Dut&)> observe;  // after the cycle's handshakes settled, before the edge
  std::function<void(Dut&)> finish;   // once after the last clock (the final counter values)
  // After the last output, once per clock (the registered outputs after the edge): true when the
  // DUT has accounted for everything it was given (its counters say so); the drain then ends
  // TxnOptions::settled_drain_cycles later instead of after drain_cycles. Empty: the full drain.
  std::function<bool(Dut&)> settled;
};

struct TxnMismatch {
  uint64_t out_row = 0;  // row of S.out (line − 1) the output was compared with
  uint64_t cycle = 0;
  std::string cls;  // first differing field, "extra", "lost" or "early"
  std::string text;
};

struct TxnResult {
  uint64_t inputs = 0, outputs = 0, errors = 0, cycles = 0;
  uint64_t busy_cycles = 0;  // cycles with an input accepted and its outputs not all out
  uint64_t first_in_cycle = 0, last_out_cycle = 0;  // first input transfer, last output transfer
  double seconds = 0;      // wall clock of the simulation loop
  double cpu_seconds = 0;  // CPU time of the process over the loop (cpu_seconds_now(): a shared machine's load aside)
  // TxnOptions::time_eval_every: of the sampled clocks' loop time, the part outside the DUT's
  // eval() (driving, sampling, comparing, the hooks, the handshake RNG), the timer reads' own cost
  // subtracted; −1 when not sampled.
  double harness_share = -1;
  uint64_t timed_cycles = 0;
  bool timeout = false, sim_error = false;
  std::map<std::string, uint64_t> classes;
  std::vector<TxnMismatch> mismatches;
  std::string wave, summary;
  bool passed() const { return errors == 0 && !timeout && !sim_error; }
};

namespace detail {

template <class Dut>
TxnResult txn_simulate(const SceneStageVectors& v, const SceneStageFile* ctx_file, const TxnOptions& o, bool trace,
                       uint64_t trace_first, uint64_t trace_last, const std::string& wave, const TxnHook<Dut>* hook) {
  TxnResult res;
  const RecordBinding in_b(v.in.lay, v.in.header), out_b(v.out.lay, v.out.header);
  RecordBinding ctx_b;
  if (ctx_file) ctx_b = RecordBinding(ctx_file->lay, ctx_file->header);
  using InPort = std::remove_reference_t<decltype(std::declval<Dut&>().in_i)>;
  using OutPort = std::remove_reference_t<decltype(std::declval<Dut&>().out_o)>;
  // The generated struct and the dump must agree: the port holds the record, with < 32 bits spare.
  if (in_b.bits > port_bits<InPort>() || in_b.bits + 32 <= port_bits<InPort>() || out_b.bits > port_bits<OutPort>() ||
      out_b.bits + 32 <= port_bits<OutPort>())
    throw ConfigError(v.in.path + ": the record widths (" + std::to_string(in_b.bits) + " / " +
                      std::to_string(out_b.bits) + " bits) do not fit the DUT's in_i / out_o ports (" +
                      std::to_string(port_bits<InPort>()) + " / " + std::to_string(port_bits<OutPort>()) +
                      " bits): fxr_rec_pkg was generated for another configuration or number of varyings");

  auto ctx = std::make_unique<VerilatedContext>();
  ctx->fatalOnError(false);
  if (trace) ctx->traceEverOn(true);
  auto dut = std::make_unique<Dut>(ctx.get(), "dut");
  std::unique_ptr<VerilatedFstC> tfp;
  if (trace) tfp = open_trace(*dut, wave);
  std::mt19937_64 hs(o.seed);
  // Without gaps and stalls the generator is not drawn at all (every chance is 0): the same
  // handshakes, two fewer draws per clock in the figures runs (docs/speed.md, "Session 11").
  const bool no_chance = o.in_gap_pct == 0 && o.out_stall_pct == 0;
  auto chance = [&hs, no_chance](unsigned pct) { return !no_chance && (hs() % 100) < pct; };
  uint64_t cycle = 0;
  auto dump = [&](uint64_t t) {
    if (tfp && cycle >= trace_first && cycle <= trace_last) tfp->dump(t);
  };
  // The rising edge, then clk low. Two evaluations per clock, not three: in the loop the low half is
  // evaluated together with the next cycle's inputs (nothing in the RTL acts on the falling edge);
  // only between reset clocks, with no inputs in between, is it evaluated on its own (Verilator
  // sees an edge only against the last evaluated value). docs/rtl.md, "Co-simulation speed".
  // The sampled clocks' timing (TxnOptions::time_eval_every): per sampled clock the loop body's
  // time and its eval() calls' time, and the number of timer reads in each.
  using SteadyClock = std::chrono::steady_clock;
  bool timed = false;
  double t_eval = 0;
  int n_evals = 0;
  struct TimedClock {
    double loop, eval;
    int evals;
  };
  std::vector<TimedClock> timed_clocks;
  auto timed_eval = [&] {
    if (!timed) {
      dut->eval();
      return;
    }
    const auto a = SteadyClock::now();
    dut->eval();
    t_eval += std::chrono::duration<double>(SteadyClock::now() - a).count();
    ++n_evals;
  };
  auto tick = [&](bool settle_low) {
    dut->clk_i = 1;
    timed_eval();
    dump(2 * cycle + 1);
    ++cycle;
    dut->clk_i = 0;
    if (settle_low) dut->eval();
  };
  if (hook && hook->reset) hook->reset();
  auto hook_drive = [&] {
    if (hook && hook->drive) hook->drive(*dut);
  };
  dut->clk_i = 0;
  dut->rst_ni = 0;
  dut->in_valid_i = 0;
  dut->out_ready_i = 0;
  hook_drive();
  dut->eval();
  for (uint64_t i = 0; i < o.reset_cycles; ++i) tick(true);
  dut->rst_ni = 1;
  hook_drive();
  dut->eval();

  auto record = [&](TxnMismatch m) {
    ++res.errors;
    ++res.classes[m.cls];
    if (o.print && res.errors <= o.max_print) std::printf("MISMATCH %s %s\n", o.unit.c_str(), m.text.c_str());
    if (res.mismatches.size() < 1000) res.mismatches.push_back(std::move(m));
  };
  auto line_of = [&](uint64_t r) { return v.out.path + ":" + std::to_string(r + 1); };

  uint64_t next_in = 0, next_out = 0, last_progress = 0, idle_after_end = 0;
  uint64_t drain_limit = o.drain_cycles;  // shortened once hook->settled holds
  bool offering = false;
  VecRow got(v.out.lay.size());
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds_now();
  SteadyClock::time_point t_body;
  for (;;) {
    timed = o.time_eval_every && cycle % o.time_eval_every == 0;
    if (timed) {
      t_eval = 0;
      n_evals = 0;
      t_body = SteadyClock::now();
    }
    if (next_in < v.in.rows && !offering && cycle >= o.reset_cycles + o.input_delay_cycles) {
      offering = !chance(o.in_gap_pct);
      if (offering) {
        const vec_word* row = v.in.data.data() + next_in * v.in.lay.size();
        in_b.drive(dut->in_i, row);
        if constexpr (HasCtx<Dut>::value) {
          if (!ctx_file) throw ConfigError(o.unit + ": the DUT has ctx_i but no context file was given");
          const uint64_t c = (uint64_t)row[2];  // in header: txn, n_out, ctx
          if (c >= ctx_file->rows) throw ConfigError(v.in.path + ":" + std::to_string(next_in + 1) + ": field 'ctx': no such line");
          ctx_b.drive(dut->ctx_i, ctx_file->data.data() + c * ctx_file->lay.size());
        }
      }
    }
    dut->in_valid_i = offering;
    dut->out_ready_i = !chance(o.out_stall_pct);
    hook_drive();
    timed_eval();
    dump(2 * cycle);
    const bool in_fire = offering && dut->in_ready_o;
    const bool out_fire = dut->out_valid_o && dut->out_ready_i;
    // Outputs owed: the rows of S.out whose input has been accepted.
    const bool owed = next_out < v.out.rows && (uint64_t)v.out.data[next_out * v.out.lay.size()] < next_in;
    if (owed || in_fire) ++res.busy_cycles;
    if (out_fire) {
      std::fill(got.begin(), got.end(), 0);
      out_b.sample(dut->out_o, got);
      if (next_out >= v.out.rows) {
        record({next_out, cycle, "extra", "output " + std::to_string(next_out + 1) + " beyond the " +
                                              std::to_string(v.out.rows) + " rows of " + v.out.path});
      } else {
        const vec_word* want = v.out.data.data() + next_out * v.out.lay.size();
        std::string cls, text;
        if ((uint64_t)want[0] >= next_in) {
          cls = "early";
          text = line_of(next_out) + ": output before its input (txn " + std::to_string((uint64_t)want[0]) + ") was accepted";
        }
        if constexpr (HasOutLast<Dut>::value) {
          got[2] = dut->out_last_o;
          if (cls.empty() && got[2] != want[2]) {
            cls = "last";
            text = line_of(next_out) + ": field 'last': got " + std::to_string((int)got[2]) + ", exp " +
                   std::to_string((int)want[2]);
          }
        }
        for (size_t k = v.out.header; k < v.out.lay.size() && cls.empty(); ++k)
          if (got[k] != want[k]) {
            cls = v.out.lay[k].name;
            text = line_of(next_out) + ": field '" + cls + "': got " + vec_field_hex(v.out.lay[k], got[k]) + ", exp " +
                   vec_field_hex(v.out.lay[k], want[k]) + " (txn " + std::to_string((uint64_t)want[0]) + ", seq " +
                   std::to_string((uint64_t)want[1]) + ")";
          }
        if (!cls.empty()) record({next_out, cycle, cls, text});
      }
      ++next_out;
      ++res.outputs;
      last_progress = cycle;
      res.last_out_cycle = cycle;
    }
    if (in_fire) {
      if (!owed) last_progress = cycle;
      if (next_in == 0) res.first_in_cycle = cycle;
      ++next_in;
      ++res.inputs;
      offering = false;
    }
    if (hook && hook->observe) hook->observe(*dut);
    tick(false);
    if (ctx->gotError()) {
      res.sim_error = true;
      if (o.print) std::printf("SIMERROR %s: Verilator reported an error at cycle %llu\n", o.unit.c_str(), (unsigned long long)cycle);
      break;
    }
    const bool still_owed = next_out < v.out.rows && (uint64_t)v.out.data[next_out * v.out.lay.size()] < next_in;
    if (still_owed && cycle - last_progress > o.timeout_cycles) {
      res.timeout = true;
      record({next_out, cycle, "lost", line_of(next_out) + ": no output within " + std::to_string(o.timeout_cycles) +
                                           " cycles (" + std::to_string(v.out.rows - next_out) + " rows left)"});
      break;
    }
    if (timed) timed_clocks.push_back({std::chrono::duration<double>(SteadyClock::now() - t_body).count(), t_eval, n_evals});
    if (next_in == v.in.rows && next_out >= v.out.rows) {
      if (++idle_after_end > drain_limit) break;
      if (hook && hook->settled && drain_limit == o.drain_cycles && hook->settled(*dut))
        drain_limit = std::min(o.drain_cycles, idle_after_end + o.settled_drain_cycles);
    }
    if (tfp && cycle > trace_last) break;
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.cpu_seconds = cpu_seconds_now() - c0;
  if (!timed_clocks.empty()) {
    // One timer read's cost, subtracted once per eval() interval and once per read inside the
    // loop body's interval (two per eval() and about one for the body's own pair). Clocks whose
    // body took more than 5× the median (the process preempted on a loaded machine) are left out.
    const int calib = 1000;
    const auto c0t = SteadyClock::now();
    for (int i = 0; i < calib; ++i) (void)SteadyClock::now();
    const double per_read = std::chrono::duration<double>(SteadyClock::now() - c0t).count() / calib;
    std::vector<double> loops;
    for (const TimedClock& c : timed_clocks) loops.push_back(c.loop);
    std::nth_element(loops.begin(), loops.begin() + (long)(loops.size() / 2), loops.end());
    const double limit = 5 * loops[loops.size() / 2];
    double loop = 0, evals = 0;
    for (const TimedClock& c : timed_clocks) {
      if (c.loop > limit) continue;
      ++res.timed_cycles;
      loop += c.loop - per_read * (2 * c.evals + 1);
      evals += c.eval - per_read * c.evals;
    }
    res.harness_share = loop > 0 ? std::max(0.0, (loop - evals) / loop) : -1;
  }
  res.cycles = cycle;
  if (hook && hook->finish) hook->finish(*dut);
  if (tfp) tfp->close();
  dut->final();
  return res;
}

}  // namespace detail

// Runs stage vectors `v` through the DUT; prints the report (first mismatches, counts by class,
// totals, PASSED / FAILED), writes a summary JSON and, on failure, the FST of the window around
// the first mismatch. `ctx_file`: the context records (interp: setup.out), or nullptr.
template <class Dut>
TxnResult run_txn(const SceneStageVectors& v, const SceneStageFile* ctx_file, const TxnOptions& o,
                  const TxnHook<Dut>* hook = nullptr) {
  TxnResult r = detail::txn_simulate<Dut>(v, ctx_file, o, false, 0, 0, "", hook);
  const std::string dir = [] {
#ifdef FXR_TB_OUT_DIR
    std::string d = FXR_TB_OUT_DIR;
#else
    std::string d = "tb_out";
#endif
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string base = dir + "/" + (o.run_name.empty() ? o.unit : o.run_name);
  if (!r.passed() && o.write_wave && HasTrace<Dut>::value) {
    const uint64_t at = r.mismatches.empty() ? r.cycles : r.mismatches.front().cycle;
    TxnOptions quiet = o;
    quiet.print = false;
    r.wave = base + "_first_mismatch.fst";
    detail::txn_simulate<Dut>(v, ctx_file, quiet, true, at > o.wave_before ? at - o.wave_before : 0, at + o.wave_after,
                              r.wave, hook);
  }
  if (o.print) {
    for (auto& [cls, n] : r.classes) std::printf("  class %-24s %llu\n", cls.c_str(), (unsigned long long)n);
    std::printf("%s: inputs=%llu outputs=%llu (file %llu) errors=%llu\n", o.unit.c_str(), (unsigned long long)r.inputs,
                (unsigned long long)r.outputs, (unsigned long long)v.out.rows, (unsigned long long)r.errors);
    std::printf("%s: %llu cycles (%llu busy), %.3f s, %.0f cycles/s; %.3f CPU s, %.0f cycles per CPU second (gaps %u%%, "
                "stalls %u%%)\n",
                o.unit.c_str(), (unsigned long long)r.cycles, (unsigned long long)r.busy_cycles, r.seconds,
                r.seconds > 0 ? (double)r.cycles / r.seconds : 0.0, r.cpu_seconds,
                r.cpu_seconds > 0 ? (double)r.cycles / r.cpu_seconds : 0.0, o.in_gap_pct, o.out_stall_pct);
    if (!r.wave.empty()) std::printf("%s: waveform of the first mismatch: %s\n", o.unit.c_str(), r.wave.c_str());
    std::printf("%s\n", r.passed() ? "PASSED" : "FAILED");
  }
  nlohmann::json j{{"unit", o.unit},           {"run", o.run_name},        {"inputs", r.inputs},
                   {"outputs", r.outputs},     {"expected", v.out.rows},   {"errors", r.errors},
                   {"cycles", r.cycles},       {"busy_cycles", r.busy_cycles}, {"seconds", r.seconds},
                   {"cpu_seconds", r.cpu_seconds}, {"timeout", r.timeout},     {"sim_error", r.sim_error}, {"passed", r.passed()},
                   {"seed", o.seed},           {"in_gap_pct", o.in_gap_pct}, {"out_stall_pct", o.out_stall_pct},
                   {"classes", r.classes},     {"wave", r.wave}};
  r.summary = base + "_summary.json";
  std::ofstream(r.summary) << j.dump(2) << "\n";
  return r;
}

}  // namespace fxr::tb

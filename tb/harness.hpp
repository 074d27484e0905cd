// tb/harness.hpp — generic Verilator co-simulation harness for a unit with the fxraster
// valid / ready handshake (clk_i, rst_ni, in_valid_i, in_ready_o, out_valid_o, out_ready_i).
//
// The DUT is driven from a stream of vectors (a vector file, or the model on fresh random
// inputs), with random input gaps and random output back-pressure; every output is compared
// bit for bit with the expected one, in order: none lost (timeout), none duplicated (an output
// with nothing in flight), none out of order. On a mismatch the run is replayed with tracing on
// and an FST of the window around the first mismatch is written. A unit plugs in with a Ports
// adapter, generated from the unit's vector layout by `fxraster layout --emit-ports`
// (build/gen/ports/<unit>_ports_gen.hpp, model/vectors/codegen.hpp):
//
//   template <class D> struct RecipPortsGen {
//     using Dut = D;
//     static std::vector<std::string> fields();          // vector fields, file order
//     static int latency(const fxr::Config&), ii(...);   // from the unit's cost model
//     static void drive(Dut& d, const fxr::VecRow& r);   // input fields -> ports <field>_i
//     static void sample(Dut& d, fxr::VecRow& r);        // ports <field>_o -> output fields
//   };
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <deque>
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

#include "model/vectors/vectors.hpp"

namespace fxr::tb {

// Folder for waveforms and summaries (the build's tb/ folder; FXR_TB_OUT_DIR is set by CMake).
inline std::string out_dir() {
#ifdef FXR_TB_OUT_DIR
  std::string d = FXR_TB_OUT_DIR;
#else
  std::string d = "tb_out";
#endif
  std::filesystem::create_directories(d);
  return d;
}

// CPU time of the process (every thread, a threaded model's too): the speed figures divide by it as
// well as by the wall clock, which a loaded machine stretches (docs/rtl.md, "Co-simulation speed").
inline double cpu_seconds_now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

// Whether the model was verilated with --trace-fst (its trace() exists): a model without it runs the
// same, and the replay of a failed run writes no waveform (docs/rtl.md, "Co-simulation speed").
template <class D, class = void>
struct HasTrace : std::false_type {};
template <class D>
struct HasTrace<D, std::void_t<decltype(std::declval<D&>().trace((VerilatedFstC*)nullptr, 0))>> : std::true_type {};

// Opens `wave` and attaches it to the model; nullptr when the model has no tracing compiled in.
template <class Dut>
std::unique_ptr<VerilatedFstC> open_trace(Dut& dut, const std::string& wave) {
  if constexpr (HasTrace<Dut>::value) {
    auto tfp = std::make_unique<VerilatedFstC>();
    dut.trace(tfp.get(), 99);
    tfp->open(wave.c_str());
    return tfp;
  } else {
    (void)dut;
    std::fprintf(stderr, "note: %s not written: the model was verilated without --trace-fst\n", wave.c_str());
    return nullptr;
  }
}

struct HarnessOptions {
  std::string unit;                  // for the report lines ("recip")
  std::string run_name;              // names the waveform / summary files ("recip_file")
  uint64_t seed = 1;                 // handshake randomness (gaps, back-pressure)
  unsigned in_gap_pct = 25;          // chance (%) that a new input is held back one more cycle
  unsigned out_stall_pct = 25;       // chance (%) that out_ready_i is low in a cycle
  uint64_t timeout_cycles = 2000;    // cycles without an output while one is owed: lost
  uint64_t reset_cycles = 4;
  uint64_t drain_cycles = 200;       // idle cycles at the end watching for extra outputs
  uint64_t wave_before = 40, wave_after = 8;  // FST window around the first mismatch (cycles)
  bool write_wave = true;
  size_t max_print = 20;             // MISMATCH lines printed
  size_t max_record = 1000;          // mismatches kept for the CSV
  bool print = true;
};

struct Mismatch {
  uint64_t vec = 0;    // index of the vector in the stream (0-based: file line − 1)
  uint64_t cycle = 0;  // clock cycle of the output handshake
  std::string cls;     // differing output fields joined by '+', or "extra" / "lost"
  std::string in, got, exp;
};

struct RunResult {
  uint64_t checked = 0;  // outputs compared
  uint64_t errors = 0;   // mismatching, extra or lost outputs
  uint64_t sent = 0;     // inputs accepted by the DUT
  uint64_t cycles = 0;
  int64_t first_latency = -1;  // cycles from the first input transfer to the first output valid
  double seconds = 0;      // wall clock of the simulation loop
  double cpu_seconds = 0;  // CPU time of the process over the loop
  double vectors_per_s = 0;
  bool timeout = false;
  bool sim_error = false;  // Verilator reported an error ($fatal, assertion)
  std::map<std::string, uint64_t> classes;
  std::vector<Mismatch> mismatches;  // first max_record
  std::string wave, summary, csv;
  bool passed() const { return errors == 0 && !timeout && !sim_error && checked > 0; }
};

// A stream of complete vectors (inputs and expected outputs); returns false at the end.
using Source = std::function<bool(VecRow&)>;
using SourceFactory = std::function<Source()>;

// Vectors of a file, in order.
inline SourceFactory file_source(const VecFile& f) {
  return [&f]() {
    auto i = std::make_shared<size_t>(0);
    return Source([&f, i](VecRow& r) {
      if (*i >= f.rows()) return false;
      r = f.row((*i)++);
      return true;
    });
  };
}

// `count` fresh random inputs from mt19937_64(seed), outputs computed by the model (lock-step).
inline SourceFactory model_source(const VectorModel& m, uint64_t seed, uint64_t count) {
  return [&m, seed, count]() {
    auto rng = std::make_shared<std::mt19937_64>(seed);
    auto n = std::make_shared<uint64_t>(0);
    return Source([&m, rng, n, count](VecRow& r) {
      if (*n >= count) return false;
      ++*n;
      r.assign(m.layout().size(), 0);
      m.random(*rng, r);
      m.compute(r);
      return true;
    });
  };
}

// The unit's exhaustive sweep (VectorModel::exhaustive), outputs computed by the model.
inline SourceFactory exhaustive_source(const VectorModel& m) {
  return [&m]() {
    auto i = std::make_shared<uint64_t>(0);
    return Source([&m, i](VecRow& r) {
      if (*i >= m.exhaustive_count()) return false;
      r.assign(m.layout().size(), 0);
      m.exhaustive((*i)++, r);
      m.compute(r);
      return true;
    });
  };
}

namespace detail {

// One simulation pass. With trace_window = {first, last}, dumps those cycles into `wave`.
template <class P>
RunResult simulate(const VecLayout& lay, const SourceFactory& make_source, const HarnessOptions& o,
                   bool trace, uint64_t trace_first, uint64_t trace_last, const std::string& wave) {
  using Dut = typename P::Dut;
  RunResult res;
  auto ctx = std::make_unique<VerilatedContext>();
  ctx->fatalOnError(false);
  ctx->commandArgs(0, (const char**)nullptr);
  if (trace) ctx->traceEverOn(true);
  auto dut = std::make_unique<Dut>(ctx.get(), "dut");
  std::unique_ptr<VerilatedFstC> tfp;
  if (trace) tfp = open_trace(*dut, wave);
  std::mt19937_64 hs(o.seed);  // handshake randomness only
  auto chance = [&hs](unsigned pct) { return (hs() % 100) < pct; };
  uint64_t cycle = 0;
  auto dump = [&](uint64_t t) {
    if (tfp && cycle >= trace_first && cycle <= trace_last) tfp->dump(t);
  };
  // The rising edge, then clk low: evaluated with the next cycle's inputs in the loop (dumped at
  // 2·cycle), on its own only between reset clocks (as tb/txn_harness.hpp's tick).
  auto tick = [&](bool settle_low) {
    dut->clk_i = 1;
    dut->eval();
    dump(2 * cycle + 1);
    ++cycle;
    dut->clk_i = 0;
    if (settle_low) dut->eval();
  };

  dut->clk_i = 0;
  dut->rst_ni = 0;
  dut->in_valid_i = 0;
  dut->out_ready_i = 0;
  dut->eval();
  for (uint64_t i = 0; i < o.reset_cycles; ++i) tick(true);
  dut->rst_ni = 1;
  dut->eval();

  Source src = make_source();
  VecRow pending(lay.size()), got(lay.size());
  bool have = src(pending);
  bool offering = false;  // valid stays high until accepted (no retraction)
  std::deque<std::pair<uint64_t, VecRow>> inflight;
  uint64_t vec_in = 0, last_progress = 0, idle_after_end = 0;
  int64_t first_in_cycle = -1;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds_now();

  auto record = [&](Mismatch m) {
    ++res.errors;
    ++res.classes[m.cls];
    if (o.print && res.errors <= o.max_print)
      std::printf("MISMATCH %s vec=%llu in=%s got=%s exp=%s%s\n", o.unit.c_str(), (unsigned long long)m.vec,
                  m.in.c_str(), m.got.c_str(), m.exp.c_str(),
                  (m.cls == "extra" || m.cls == "lost") ? (" (" + m.cls + ")").c_str() : "");
    if (res.mismatches.size() < o.max_record) res.mismatches.push_back(std::move(m));
  };

  for (;;) {
    if (have && !offering) offering = !chance(o.in_gap_pct);
    dut->in_valid_i = offering;
    if (offering) P::drive(*dut, pending);
    dut->out_ready_i = !chance(o.out_stall_pct);
    dut->eval();
    dump(2 * cycle);
    const bool in_fire = offering && dut->in_ready_o;
    if (dut->out_valid_o && res.first_latency < 0 && first_in_cycle >= 0)
      res.first_latency = (int64_t)cycle - first_in_cycle;
    const bool out_fire = dut->out_valid_o && dut->out_ready_i;
    if (out_fire) {
      P::sample(*dut, got);
      if (inflight.empty()) {
        record({res.checked, cycle, "extra", "", vec_hex(lay, got, VecDir::Out), ""});
      } else {
        auto& [idx, want] = inflight.front();
        ++res.checked;
        std::string cls;
        for (int f : lay.outputs())
          if (got[(size_t)f] != want[(size_t)f]) cls += (cls.empty() ? "" : "+") + lay[(size_t)f].name;
        if (!cls.empty())
          record({idx, cycle, cls, vec_hex(lay, want, VecDir::In), vec_hex(lay, got, VecDir::Out),
                  vec_hex(lay, want, VecDir::Out)});
        inflight.pop_front();
      }
      last_progress = cycle;
    }
    if (in_fire) {
      if (inflight.empty()) last_progress = cycle;  // the timeout counts from the oldest owed output
      if (first_in_cycle < 0) first_in_cycle = (int64_t)cycle;
      inflight.emplace_back(vec_in++, pending);
      ++res.sent;
      offering = false;
      have = src(pending);
    }
    tick(false);
    if (ctx->gotError()) {
      res.sim_error = true;
      if (o.print) std::printf("SIMERROR %s: Verilator reported an error at cycle %llu\n", o.unit.c_str(),
                               (unsigned long long)cycle);
      break;
    }
    if (!inflight.empty() && cycle - last_progress > o.timeout_cycles) {
      res.timeout = true;
      for (auto& [idx, want] : inflight)
        record({idx, cycle, "lost", vec_hex(lay, want, VecDir::In), "", vec_hex(lay, want, VecDir::Out)});
      break;
    }
    if (!have && inflight.empty() && ++idle_after_end > o.drain_cycles) break;
    if (tfp && cycle > trace_last) break;
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.cpu_seconds = cpu_seconds_now() - c0;
  res.cycles = cycle;
  res.vectors_per_s = res.seconds > 0 ? (double)res.checked / res.seconds : 0;
  if (tfp) tfp->close();
  dut->final();
  return res;
}

}  // namespace detail

// Runs the stream through the DUT; prints the report (first mismatches, counts by class,
// "<unit>: checked=N errors=M", vectors/s, PASSED / FAILED), writes the summary JSON, the
// mismatch CSV and, on failure, the FST of the first mismatch's window.
template <class P>
RunResult run(const VecLayout& lay, const SourceFactory& src, const HarnessOptions& o) {
  RunResult r = detail::simulate<P>(lay, src, o, false, 0, 0, "");
  const std::string base = out_dir() + "/" + (o.run_name.empty() ? o.unit : o.run_name);
  if (!r.passed() && o.write_wave && HasTrace<typename P::Dut>::value) {
    // Replay (the stimulus is deterministic) with tracing on, dumping only the window.
    uint64_t at = r.mismatches.empty() ? r.cycles : r.mismatches.front().cycle;
    const uint64_t first = at > o.wave_before ? at - o.wave_before : 0;
    HarnessOptions quiet = o;
    quiet.print = false;
    r.wave = base + "_first_mismatch.fst";
    detail::simulate<P>(lay, src, quiet, true, first, at + o.wave_after, r.wave);
  }
  if (o.print) {
    for (auto& [cls, n] : r.classes) std::printf("  class %-24s %llu\n", cls.c_str(), (unsigned long long)n);
    std::printf("%s: checked=%llu errors=%llu\n", o.unit.c_str(), (unsigned long long)r.checked,
                (unsigned long long)r.errors);
    std::printf("%s: %llu cycles, %.3f s, %.0f vectors/s; %.3f CPU s, %.0f vectors per CPU second (gaps %u%%, stalls "
                "%u%%)\n",
                o.unit.c_str(), (unsigned long long)r.cycles, r.seconds, r.vectors_per_s, r.cpu_seconds,
                r.cpu_seconds > 0 ? (double)r.checked / r.cpu_seconds : 0.0, o.in_gap_pct, o.out_stall_pct);
    if (r.timeout) std::printf("%s: TIMEOUT after %llu cycles without output\n", o.unit.c_str(),
                               (unsigned long long)o.timeout_cycles);
    if (!r.wave.empty()) std::printf("%s: waveform of the first mismatch: %s\n", o.unit.c_str(), r.wave.c_str());
    std::printf("%s\n", r.passed() ? "PASSED" : "FAILED");
  }
  // Summary JSON and mismatch CSV beside the waveform.
  nlohmann::json j{{"unit", o.unit},       {"run", o.run_name},      {"checked", r.checked},
                   {"errors", r.errors},   {"sent", r.sent},         {"cycles", r.cycles}, {"first_latency", r.first_latency},
                   {"seconds", r.seconds}, {"cpu_seconds", r.cpu_seconds}, {"vectors_per_s", r.vectors_per_s},
                   {"timeout", r.timeout}, {"sim_error", r.sim_error}, {"passed", r.passed()},
                   {"seed", o.seed},       {"in_gap_pct", o.in_gap_pct}, {"out_stall_pct", o.out_stall_pct},
                   {"classes", r.classes}, {"wave", r.wave}};
  r.summary = base + "_summary.json";
  std::ofstream(r.summary) << j.dump(2) << "\n";
  r.csv = base + "_mismatches.csv";
  std::ofstream csv(r.csv);
  csv << "vec,line,cycle,class,in,got,exp\n";
  for (const auto& m : r.mismatches)
    csv << m.vec << "," << m.vec + 1 << "," << m.cycle << "," << m.cls << "," << m.in << "," << m.got << ","
        << m.exp << "\n";
  std::fflush(stdout);
  return r;
}

}  // namespace fxr::tb

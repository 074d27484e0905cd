// The threaded raster unit (model/unit/threads.hpp) against its 1-thread baseline, measured in
// the same run (docs/speed.md, "Deterministic threads"): the bunny (69,666 triangles,
// setup-bound) and the grazing plane (2 triangles, fill-bound) of bench/peer_bench at
// 1024 × 1024 with 0 and 2 varyings, fragments kept (run_raster_unit, a new FrameOutput per
// frame, as peer_bench's model rows).
//
// Three figures per scene and thread count:
//   - wall time per frame (the speed-up: 1 thread / N threads);
//   - process CPU time per frame (the work the threads add: 1.0 = none; the speed-up on an idle
//     machine is at most N · CPU(1) / CPU(N));
//   - where each thread's time goes (ThreadObserver, model/unit/threads.hpp): the clock is read
//     here, in the bench, at every phase change; each thread's own CPU clock
//     (CLOCK_THREAD_CPUTIME_ID) gives the work of the phases without the time a thread of a
//     loaded machine spends descheduled, the steady clock gives the wall time of the serial
//     phases (Frame: the calling thread prepares the frame; Serial: the last thread at a
//     barrier decides the next step; Compact: it closes a gap between a split step's parts)
//     and of the waits.
// Counters per frame: critical_ms (per step the busiest thread's CPU in Setup, Raster, Direct, Clear
// and Output, summed, plus the serial phases: the frame's length on an idle machine, less the time
// waiters take to see a barrier open), cpu_ms (process CPU), work_ms (the threads' CPU in every phase but
// Wait), serial_pct (Frame + Serial + Compact wall time / frame wall time), wait_pct (thread wall time at
// the barriers / threads × frame wall time) and the phases' work in ms. The summary at the end
// prints the ratios. Nothing passes or fails on time.
#include <benchmark/benchmark.h>

#include <time.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "model/unit/threads.hpp"
#include "reference/peer/peer_scenes.hpp"

using namespace fxr;
using namespace fxr::peer;

namespace {

constexpr int kSize = 1024;
const char* const kSceneNames[] = {"bunny", "plane"};
constexpr int kPhases = (int)ThreadPhase::Done + 1;
const char* const kPhaseNames[kPhases] = {"frame", "setup", "raster", "output", "wait", "serial", "direct", "clear", "compact", "done"};

const PeerScene& scene(int id, int nv) {
  static std::map<int, std::unique_ptr<PeerScene>> cache;
  auto& p = cache[id * 64 + nv];
  if (!p) p.reset(new PeerScene(id == 0 ? bunny_scene(kSize, nv) : grazing_plane_scene(kSize, nv)));
  return *p;
}

double thread_cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

// Per thread: the phase it is in, since when, and the totals per phase.
class PhaseClock final : public ThreadObserver {
 public:
  using clk = std::chrono::steady_clock;
  struct alignas(64) Slot {
    int cur = -1;
    clk::time_point wall_since;
    double cpu_since = 0;
    std::array<double, kPhases> wall{}, cpu{};
    double busy = 0;            // CPU in Setup, Raster and Output since the last barrier …
    std::vector<double> steps;  // … per step (all frames, one after the other)
  };
  explicit PhaseClock(int threads) : slots_((size_t)threads) {}
  void phase(int thread, ThreadPhase p) override {
    const clk::time_point now = clk::now();
    const double cpu = thread_cpu_seconds();
    Slot& s = slots_[(size_t)thread];
    if (s.cur >= 0) {
      s.wall[(size_t)s.cur] += std::chrono::duration<double>(now - s.wall_since).count();
      s.cpu[(size_t)s.cur] += cpu - s.cpu_since;
      if (s.cur == (int)ThreadPhase::Setup || s.cur == (int)ThreadPhase::Raster || s.cur == (int)ThreadPhase::Output ||
          s.cur == (int)ThreadPhase::Direct || s.cur == (int)ThreadPhase::Clear)
        s.busy += cpu - s.cpu_since;
    }
    if (p == ThreadPhase::Wait) s.steps.push_back(s.busy), s.busy = 0;
    s.cur = p == ThreadPhase::Done ? -1 : (int)p;
    s.wall_since = now;
    s.cpu_since = cpu;
  }
  double wall(ThreadPhase p) const {
    double t = 0;
    for (const Slot& s : slots_) t += s.wall[(size_t)p];
    return t;
  }
  double cpu(ThreadPhase p) const {
    double t = 0;
    for (const Slot& s : slots_) t += s.cpu[(size_t)p];
    return t;
  }
  // The frames' critical path from the threads' own CPU clocks: per step (the work between two
  // barriers; every thread passes the same barriers) the busiest thread's work, summed, plus the
  // serial phases. On an idle machine the frames take at least this long (more by the time a
  // waiting thread takes to see the barrier open); a loaded machine's descheduling is not in it.
  double critical() const {
    size_t n = slots_.front().steps.size();
    for (const Slot& s : slots_) n = std::min(n, s.steps.size());
    double t = cpu(ThreadPhase::Frame) + cpu(ThreadPhase::Serial) + cpu(ThreadPhase::Compact);
    for (size_t i = 0; i < n; ++i) {
      double m = 0;
      for (const Slot& s : slots_) m = std::max(m, s.steps[i]);
      t += m;
    }
    return t;
  }

 private:
  std::vector<Slot> slots_;
};

void BM_Threads(benchmark::State& state) {
  const PeerScene& s = scene((int)state.range(0), (int)state.range(1));
  const Config cfg;
  const int threads = (int)state.range(2);
  PhaseClock clock(threads);
  ThreadOptions o;
  o.threads = threads;
  o.observer = &clock;
  uint64_t frags = 0;
  for (auto _ : state) {
    const FrameOutput out = run_raster_unit(cfg, s.st, s.tris, o);
    frags = out.stats.fragments_generated;
    benchmark::DoNotOptimize(out.fragments.data());
  }
  const double n = (double)state.iterations();
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)frags);
  state.counters["fragments"] = (double)frags;
  if (threads > 1) {
    double work = 0;
    for (int p = 0; p < kPhases; ++p)
      if (p != (int)ThreadPhase::Wait) work += clock.cpu((ThreadPhase)p);
    state.counters["work_ms"] = 1e3 * work / n;
    for (ThreadPhase p : {ThreadPhase::Frame, ThreadPhase::Setup, ThreadPhase::Raster, ThreadPhase::Output,
                          ThreadPhase::Serial, ThreadPhase::Compact})
      state.counters[std::string(kPhaseNames[(int)p]) + "_ms"] = 1e3 * clock.cpu(p) / n;
    // raster: stages 6–10 wherever their records go (a split step's direct rows included).
    state.counters["raster_ms"] = 1e3 * (clock.cpu(ThreadPhase::Raster) + clock.cpu(ThreadPhase::Direct)) / n;
    state.counters["direct_ms"] = 1e3 * clock.cpu(ThreadPhase::Direct) / n;
    // frame: the calling thread's new depth buffer, whether filled before the steps or in one.
    state.counters["frame_ms"] = 1e3 * (clock.cpu(ThreadPhase::Frame) + clock.cpu(ThreadPhase::Clear)) / n;
    state.counters["serial_wall_s"] =
        clock.wall(ThreadPhase::Frame) + clock.wall(ThreadPhase::Serial) + clock.wall(ThreadPhase::Compact);
    state.counters["wait_wall_s"] = clock.wall(ThreadPhase::Wait);
    state.counters["critical_ms"] = 1e3 * clock.critical() / n;
  }
}

void thread_args(benchmark::internal::Benchmark* b) {
  for (int id : {0, 1})
    for (int nv : {0, 2})
      for (int t : {1, 2}) b->Args({id, nv, t});
  b->ArgNames({"scene", "varyings", "threads"})->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
}
BENCHMARK(BM_Threads)->Apply(thread_args);

// Collects each run's wall and CPU time per frame and the phase counters; prints the ratios.
class ThreadReporter : public benchmark::ConsoleReporter {
 public:
  struct Row {
    double wall = 0, cpu = 0;  // s per frame
    std::map<std::string, double> c;
  };
  std::map<std::string, std::map<int, Row>> rows;  // [scene vN][threads]

  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.error_occurred || r.run_type != Run::RT_Iteration) continue;
      int id = 0, nv = 0, t = 0;
      const std::string name = r.benchmark_name();
      if (std::sscanf(name.c_str(), "BM_Threads/scene:%d/varyings:%d/threads:%d", &id, &nv, &t) != 3) continue;
      Row& row = rows[std::string(kSceneNames[id]) + " v" + std::to_string(nv)][t];
      const double n = (double)r.iterations;
      row.wall = r.real_accumulated_time / n;
      row.cpu = r.cpu_accumulated_time / n;
      for (const auto& [k, v] : r.counters) row.c[k] = v.value;
      row.c["serial_pct"] = 100.0 * row.c["serial_wall_s"] / r.real_accumulated_time;
      row.c["wait_pct"] = 100.0 * row.c["wait_wall_s"] / (t * r.real_accumulated_time);
    }
  }

  void print_summary() const {
    std::printf("\nthreads (run_raster_unit, fragments kept, a new frame each time; ms per frame): speedup = wall(1) / "
                "wall(2); cpu = CPU(2) / CPU(1) in process CPU time (1.0: no work added); work = the threads' CPU "
                "time outside the barriers / CPU(1); serial = wall time of the serial phases / wall(2); wait = "
                "time at the barriers / (2 · wall(2)); idle = CPU(1) / the critical path of the 2-thread frame "
                "(per step the busier thread's CPU, plus the serial phases); phases: the threads' CPU time in each\n");
    std::printf("%-9s %8s %8s %8s %8s %8s %7s %7s %7s %7s %8s %7s | %7s %7s %7s %7s %7s\n", "scene", "wall1", "wall2",
                "speedup", "cpu1", "cpu2", "cpu", "work", "2cpu1/", "idle", "serial%", "wait%", "frame", "setup", "raster",
                "output", "serial");
    for (const auto& [key, m] : rows) {
      auto i1 = m.find(1), i2 = m.find(2);
      if (i1 == m.end() || i2 == m.end()) continue;
      const Row &a = i1->second, &b = i2->second;
      const auto c = [&](const char* k) { auto it = b.c.find(k); return it == b.c.end() ? 0.0 : it->second; };
      std::printf("%-9s %8.2f %8.2f %8.3f %8.2f %8.2f %7.3f %7.3f %7.3f %7.3f %8.2f %7.2f | %7.2f %7.2f %7.2f %7.2f %7.2f\n",
                  key.c_str(), 1e3 * a.wall, 1e3 * b.wall, a.wall / b.wall, 1e3 * a.cpu, 1e3 * b.cpu, b.cpu / a.cpu,
                  c("work_ms") / (1e3 * a.cpu), 2 * a.cpu / b.cpu, 1e3 * a.cpu / c("critical_ms"), c("serial_pct"),
                  c("wait_pct"), c("frame_ms"),
                  c("setup_ms"), c("raster_ms"), c("output_ms"), c("serial_ms"));
    }
    std::printf("(2cpu1/ = 2 · CPU(1) / CPU(2): the most 2 threads could reach on an idle 2-core machine with the "
                "work shared evenly; idle: the most with the work as shared step by step, measured on any load)\n");
  }
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  ThreadReporter rep;
  benchmark::RunSpecifiedBenchmarks(&rep);
  rep.print_summary();
  benchmark::Shutdown();
  return 0;
}

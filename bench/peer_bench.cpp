// Model speed against two baselines measured in the same run (docs/references.md#spec-speed):
//   - float:    the plain float32 rasterizer (fxr_peer, reference/float_raster.hpp), one thread;
//   - llvmpipe: Mesa through OSMesa with LP_NUM_THREADS=0 (rasterises in the calling thread),
//               context creation, shader compilation and vertex upload excluded; each iteration
//               is clear + draw + glFinish;
//   - model:    fxr::run_raster_unit on the default configuration (keeps every fragment as a
//               compact record, model/unit/fragment_store.hpp; a new FrameOutput per frame);
//   - vector:   the same chain keeping a std::vector<Fragment> (272 bytes per fragment: how
//               run_raster_unit kept fragments before the compact records), for before / after;
//   - keep:     the compact records into a FrameOutput reused from frame to frame (a sweep);
//   - stream:   the same stages (run_raster_unit_to: the stage chain of model/unit/chain.hpp)
//               streaming fragments into an image;
//   - threads:  run_raster_unit with ThreadOptions::threads 1 and 2 (model/unit/threads.hpp),
//               fragments kept, measured in wall time and in process CPU time.
// FXR_BENCH_CONFIG=FILE runs the model benchmarks at that configuration (e.g.
// tests/golden/config_attr_equals_subpixel.json, the default before the attribute positions of
// docs/pipeline.md) — to compare a change of the code at a fixed configuration.
// Scenes at 1024 × 1024: the bunny (69,666 triangles, setup-bound) and a grazing textured
// plane (2 triangles, fill-bound), with 0 and 2 varyings, depth test on (less).
// items/s = fragments/s, fragments = covered samples before the depth test, each renderer
// counting its own. Rates use process CPU time (all threads). The summary at the end prints the
// ratios; nothing passes or fails on time.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "reference/float_raster.hpp"
#include "reference/peer/peer_osmesa.hpp"
#include "reference/peer/peer_scenes.hpp"
#include "model/unit/geometry.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/unit/chain.hpp"
#include "model/unit/threads.hpp"

using namespace fxr;
using namespace fxr::peer;

namespace {

constexpr int kSize = 1024;
enum SceneId { kBunny = 0, kPlane = 1 };
const char* const kSceneNames[] = {"bunny", "plane"};

// The model's configuration: the defaults, or FXR_BENCH_CONFIG's file.
const Config& bench_config() {
  static const Config cfg = [] {
    const char* path = std::getenv("FXR_BENCH_CONFIG");
    return path && *path ? load_config(path) : Config{};
  }();
  return cfg;
}

const PeerScene& scene(int id, int nv) {
  static std::map<int, std::unique_ptr<PeerScene>> cache;
  auto& p = cache[id * 64 + nv];
  if (!p) {
    p.reset(new PeerScene(id == kBunny ? bunny_scene(kSize, nv) : grazing_plane_scene(kSize, nv)));
    if (!p->note.empty()) std::fprintf(stderr, "NOTE: %s\n", p->note.c_str());
  }
  return *p;
}

// The peer is created once, before any timing (LP_NUM_THREADS=0 is set by its constructor,
// before the first context of the process).
OsmesaPeer* the_peer() {
  static std::unique_ptr<OsmesaPeer> p;
  static std::string error;
  if (!p && error.empty()) {
    try {
      PeerOptions opt;
      opt.lp_num_threads = 0;
      p.reset(new OsmesaPeer(opt));
    } catch (const PeerError& e) {
      error = e.what();
    }
  }
  return p.get();
}

void BM_Float(benchmark::State& state) {
  const PeerScene& s = scene((int)state.range(0), (int)state.range(1));
  FloatFrame f;
  for (auto _ : state) {
    float_raster(s.st, s.tris, f);
    benchmark::DoNotOptimize(f.depth.data());
  }
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)f.fragments_generated);
  state.counters["fragments"] = (double)f.fragments_generated;
}

void BM_Llvmpipe(benchmark::State& state) {
  OsmesaPeer* p = the_peer();
  if (!p) {
    state.SkipWithError("no OSMesa/llvmpipe context");
    return;
  }
  const PeerScene& s = scene((int)state.range(0), (int)state.range(1));
  // Fragment count: covered samples before the depth test (depth test off, count attachment).
  DrawState count_st = s.st;
  count_st.depth_test = false;
  const uint64_t frags = p->render(count_st, s.tris).fragments();
  p->prepare(s.st, s.tris);
  p->draw();  // warm-up: shader variants are compiled on first use
  for (auto _ : state) p->draw();
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)frags);
  state.counters["fragments"] = (double)frags;
}

void BM_Model(benchmark::State& state) {
  const PeerScene& s = scene((int)state.range(0), (int)state.range(1));
  const Config& cfg = bench_config();
  uint64_t frags = 0;
  for (auto _ : state) {
    const FrameOutput out = run_raster_unit(cfg, s.st, s.tris);
    frags = out.stats.fragments_generated;
    benchmark::DoNotOptimize(out.fragments.data());
  }
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)frags);
  state.counters["fragments"] = (double)frags;
}

// The chain keeping every Fragment in a std::vector (the record before the compact store).
void BM_ModelVector(benchmark::State& state) {
  const PeerScene& s = scene((int)state.range(0), (int)state.range(1));
  const Config& cfg = bench_config();
  struct VectorSink : FragmentSink {
    std::vector<Fragment> v;
    void emit(const Fragment& f) override { v.push_back(f); }
  };
  uint64_t frags = 0;
  for (auto _ : state) {
    FrameOutput f;
    VectorSink sink;
    NoTaps taps;
    run_raster_unit_to(cfg, s.st, s.tris, f, &sink, taps);
    frags = f.stats.fragments_generated;
    benchmark::DoNotOptimize(sink.v.data());
  }
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)frags);
  state.counters["fragments"] = (double)frags;
}

// Compact records into one FrameOutput reused by every frame (its buffers keep their pages).
void BM_ModelKeep(benchmark::State& state) {
  const PeerScene& s = scene((int)state.range(0), (int)state.range(1));
  const Config& cfg = bench_config();
  FrameOutput f;
  ThreadOptions one;
  for (auto _ : state) {
    run_raster_unit_threads(cfg, s.st, s.tris, f, &f.fragments, nullptr, one);
    benchmark::DoNotOptimize(f.fragments.data());
  }
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)f.stats.fragments_generated);
  state.counters["fragments"] = (double)f.stats.fragments_generated;
}

// run_raster_unit on range(2) threads, fragments kept (a new FrameOutput per frame, as BM_Model).
void BM_ModelThreads(benchmark::State& state) {
  const PeerScene& s = scene((int)state.range(0), (int)state.range(1));
  const Config& cfg = bench_config();
  ThreadOptions o;
  o.threads = (int)state.range(2);
  uint64_t frags = 0;
  for (auto _ : state) {
    const FrameOutput out = run_raster_unit(cfg, s.st, s.tris, o);
    frags = out.stats.fragments_generated;
    benchmark::DoNotOptimize(out.fragments.data());
  }
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)frags);
  state.counters["fragments"] = (double)frags;
}

// The model streaming its fragments into an image (FragmentSink), as the float rasterizer and
// llvmpipe write a framebuffer, instead of keeping a std::vector<Fragment> per frame. Each pixel
// holds its varyings as the compact record's 8-byte words (model/unit/fragment_store.hpp: the
// significand and exponent·2 + sign); the fused span path hands it a span's records at once
// (emit_span: a copy of each record's varying words), the staged path one Fragment at a time.
// Each span prefetches the pixels of the two rows above its start for writing: a small
// triangle's next spans start there, and the image (16 MB at 2 varyings) is written in mesh
// order, so without it most spans' writes missed the cache (docs/speed.md "Session 10: the span
// and the sink": bunny v2 streaming +13 %; a tiled image gained less).
struct ImageSink : FragmentSink {
  int width = 0, height = 0, nv = 0;
  std::vector<uint8_t> var;  // nv · kFragmentVaryingBytes per pixel
  uint8_t* pixel(int x, int y) {
    return &var[((size_t)y * (size_t)width + (size_t)x) * (size_t)nv * kFragmentVaryingBytes];
  }
  void emit(const Fragment& f) override {
    if (nv == 0) return;
    uint8_t rec[fragment_record_bytes(kMaxVaryings)];
    for (int k = 0; k < nv; ++k) put_fragment_var(rec, k, f.var[k].sig, f.var[k].exp, f.var[k].neg);
    std::memcpy(pixel(f.x, f.y), rec + kFragmentHeaderBytes, (size_t)nv * kFragmentVaryingBytes);
  }
  void emit_span(const FragmentRecords& b) override {  // b.num_varyings == nv (the draw's)
    switch (nv) {  // the record and pixel sizes as constants for the benchmark's counts
      case 0: return;
      case 1: return copy_span<1>(b);
      case 2: return copy_span<2>(b);
      default: return copy_span<-1>(b);
    }
  }
  // Each record's varying words to its pixel. Everything the loop reads is a local: the image
  // is written through a byte pointer, which may alias the members (GCC reloaded nv from `this`
  // after every store, docs/speed.md "Session 12: the pixel loop").
  template <int NV>
  void copy_span(const FragmentRecords& b) {
    const int n = NV > 0 ? NV : nv;
    const size_t stride = fragment_record_bytes(n), bytes = (size_t)n * kFragmentVaryingBytes;
    const uint8_t* r = b.data + kFragmentHeaderBytes;
    const size_t count = b.count;
    int y = b.y(0);
    uint8_t* row = pixel(0, y);
    for (size_t i = 0; i < count; ++i, r += stride) {
      // A block may hold several rows (the threaded unit's output merge: FragmentSink::emit_span).
      const int yi = b.y(i);
      if (yi != y) y = yi, row = pixel(0, y);
      uint8_t* const px = row + (size_t)fragment_word(r - kFragmentHeaderBytes, 1) * bytes;
      if (NV > 0) std::memcpy(px, r, (size_t)NV * kFragmentVaryingBytes);  // one fixed-size copy
      else
        for (int k = 0; k < n; ++k)
          std::memcpy(px + (size_t)k * kFragmentVaryingBytes, r + (size_t)k * kFragmentVaryingBytes,
                      kFragmentVaryingBytes);
    }
    const size_t x = (size_t)b.x(0), row_bytes = (size_t)width * bytes;
    for (int k = 1; k <= 2; ++k)  // within the image (the address stays inside the buffer)
      if (y + k < height) __builtin_prefetch(row + k * row_bytes + x * bytes, 1);
  }
};

void BM_ModelStream(benchmark::State& state) {
  const PeerScene& s = scene((int)state.range(0), (int)state.range(1));
  const Config& cfg = bench_config();
  ImageSink sink;
  sink.width = s.st.viewport_x + s.st.viewport_w;
  sink.height = s.st.viewport_y + s.st.viewport_h;
  sink.nv = s.st.num_varyings;
  sink.var.assign((size_t)sink.width * (size_t)sink.height * (size_t)sink.nv *
                      kFragmentVaryingBytes, 0);
  FrameOutput f;
  NoTaps taps;
  for (auto _ : state) {
    run_raster_unit_to(cfg, s.st, s.tris, f, &sink, taps);  // the stage chain, no tap attached
    benchmark::DoNotOptimize(sink.var.data());
  }
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)f.stats.fragments_generated);
  state.counters["fragments"] = (double)f.stats.fragments_generated;
}

void scene_args(benchmark::internal::Benchmark* b) {
  for (int id : {kBunny, kPlane})
    for (int nv : {0, 2}) b->Args({id, nv});
  // Process CPU time: any helper thread of llvmpipe would be counted too. The machine is shared,
  // so wall time is noisier than CPU time.
  b->ArgNames({"scene", "varyings"})->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
}

void thread_args(benchmark::internal::Benchmark* b) {
  for (int id : {kBunny, kPlane})
    for (int nv : {0, 2})
      for (int t : {1, 2}) b->Args({id, nv, t});
  // Wall time decides the speed-up; the reporter also reads the process CPU time.
  b->ArgNames({"scene", "varyings", "threads"})->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
}

BENCHMARK(BM_Model)->Apply(scene_args);
BENCHMARK(BM_ModelVector)->Apply(scene_args);
BENCHMARK(BM_ModelKeep)->Apply(scene_args);
BENCHMARK(BM_ModelThreads)->Apply(thread_args);
BENCHMARK(BM_ModelStream)->Apply(scene_args);
BENCHMARK(BM_Float)->Apply(scene_args);
BENCHMARK(BM_Llvmpipe)->Apply(scene_args);

// Collects items/s per (renderer, scene, varyings) and prints the ratios at the end.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, std::map<std::string, double>> rate;  // [scene/varyings][renderer]

  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.error_occurred || r.run_type != Run::RT_Iteration) continue;
      auto it = r.counters.find("items_per_second");
      if (it == r.counters.end()) continue;
      // Name: BM_<renderer>/scene:<id>/varyings:<n>
      const std::string name = r.benchmark_name();
      const size_t slash = name.find('/');
      std::string renderer = name.substr(3, slash - 3);
      int id = 0, nv = 0, threads = 0;
      const int got = std::sscanf(name.c_str() + slash, "/scene:%d/varyings:%d/threads:%d", &id, &nv, &threads);
      const std::string key = std::string(kSceneNames[id]) + " v" + std::to_string(nv);
      if (got == 3) {  // wall-time rate (items_per_second) and CPU-time rate
        renderer += std::to_string(threads);
        const double items = it->second.value * r.real_accumulated_time;
        rate[key][renderer + "cpu"] = r.cpu_accumulated_time > 0 ? items / r.cpu_accumulated_time : 0.0;
      }
      rate[key][renderer] = it->second.value;
    }
  }

  void print_summary() const {
    std::printf("\nfragments/s at %dx%d (Mfrag/s) and ratios, measured in this run "
                "(model = run_raster_unit keeping fragments, stream = fragments into an image):\n", kSize, kSize);
    std::printf("%-9s %7s %7s %7s %8s %9s %9s %11s %12s %10s\n", "scene", "model", "stream", "float", "llvmpipe",
                "model/flt", "model/lp", "stream/flt", "stream/lp", "flt/lp");
    for (const auto& [key, m] : rate) {
      const auto get = [&](const char* k) { auto it = m.find(k); return it == m.end() ? 0.0 : it->second; };
      const double mo = get("Model"), ms = get("ModelStream"), fl = get("Float"), lp = get("Llvmpipe");
      const auto ratio = [](double a, double b) { return b > 0 && a > 0 ? a / b : 0.0; };
      std::printf("%-9s %7.2f %7.2f %7.2f %8.2f %9.4f %9.4f %11.4f %12.4f %10.3f\n", key.c_str(), mo / 1e6, ms / 1e6,
                  fl / 1e6, lp / 1e6, ratio(mo, fl), ratio(mo, lp), ratio(ms, fl), ratio(ms, lp), ratio(fl, lp));
    }
    std::printf("\nkeeping fragments (Mfrag/s, CPU time): vector = std::vector<Fragment>, compact = run_raster_unit, "
                "keep = compact into a reused frame; cost = stream rate / stored rate (goal <= 1.3).\n"
                "threads (fragments kept, run_raster_unit): wall-time rates, speed-up = 2 threads / 1 thread "
                "in wall time, cpu = the same ratio in process CPU time (1.0: no work added by threading):\n");
    std::printf("%-9s %7s %8s %7s %7s %11s %12s %9s %8s %8s %8s %8s\n", "scene", "vector", "compact", "keep", "stream",
                "cost(cmpct)", "cost(keep)", "vec/cmpct", "thr1", "thr2", "speedup", "cpu");
    for (const auto& [key, m] : rate) {
      const auto get = [&](const char* k) { auto it = m.find(k); return it == m.end() ? 0.0 : it->second; };
      const double vec = get("ModelVector"), mo = get("Model"), kp = get("ModelKeep"), ms = get("ModelStream");
      const double t1 = get("ModelThreads1"), t2 = get("ModelThreads2"), c1 = get("ModelThreads1cpu"),
                   c2 = get("ModelThreads2cpu");
      const auto ratio = [](double a, double b) { return b > 0 && a > 0 ? a / b : 0.0; };
      std::printf("%-9s %7.2f %8.2f %7.2f %7.2f %11.3f %12.3f %9.2f %8.2f %8.2f %8.3f %8.3f\n", key.c_str(), vec / 1e6,
                  mo / 1e6, kp / 1e6, ms / 1e6, ratio(ms, mo), ratio(ms, kp), ratio(mo, vec), t1 / 1e6, t2 / 1e6,
                  ratio(t2, t1), ratio(c2, c1));
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  if (const char* c = std::getenv("FXR_BENCH_CONFIG")) std::printf("model configuration: %s\n", c);
  if (!the_peer()) std::fprintf(stderr, "WARNING: no OSMesa/llvmpipe context: llvmpipe rows are skipped\n");
  else std::printf("llvmpipe: %s, LP_NUM_THREADS=%s\n", the_peer()->info().renderer.c_str(), std::getenv("LP_NUM_THREADS"));
  RatioReporter rep;
  benchmark::RunSpecifiedBenchmarks(&rep);
  rep.print_summary();
  benchmark::Shutdown();
  return 0;
}

// The scene-need shortcuts of docs/speed.md "Shortcuts", on the peer_bench scenes (the bunny and
// the grazing plane at 1024 × 1024, reference/peer/peer_scenes.hpp): the stage chain
// (run_raster_unit_to) streaming into a sink that keeps nothing, in the draw states each
// shortcut serves. Variants (the `path` argument):
//   0 perspective, depth test on, 2 varyings (the peer_bench stream row without the image);
//   1 affine mode, depth test on, 2 varyings (the per-triangle D);
//   2 no sink, depth test off (count only: stages 7–9 skipped);
//   3 the same as 2 through the full path (a tap that observes nothing, as shortcut_test.cpp).
// Fragments/s in process CPU time; compare variants 2 and 3 in one run, the others between two
// builds. Nothing passes or fails on time.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "model/unit/chain.hpp"
#include "reference/peer/peer_scenes.hpp"

using namespace fxr;

namespace {

constexpr int kSize = 1024;

const peer::PeerScene& scene(int id) {
  static std::map<int, std::unique_ptr<peer::PeerScene>> cache;
  auto& p = cache[id];
  if (!p) p.reset(new peer::PeerScene(id == 0 ? peer::bunny_scene(kSize, 2) : peer::grazing_plane_scene(kSize, 2)));
  return *p;
}

struct NullSink : FragmentSink {
  uint64_t n = 0;
  void emit(const Fragment&) override { ++n; }
};

// Observes nothing, but is not NoTaps: the chain takes its full path.
struct FullPathTap {
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out&) {}
};

template <class Taps>
void run(benchmark::State& state, const DrawState& st, const std::vector<ClipTriangle>& tris, bool sink_on) {
  const Config cfg;
  FrameOutput f;
  NullSink sink;
  Taps taps;
  for (auto _ : state) {
    run_raster_unit_to(cfg, st, tris, f, sink_on ? &sink : nullptr, taps);
    benchmark::DoNotOptimize(sink.n);
  }
  state.SetItemsProcessed((int64_t)state.iterations() * (int64_t)f.stats.fragments_generated);
  state.counters["fragments"] = (double)f.stats.fragments_generated;
}

void BM_Shortcut(benchmark::State& state) {
  const peer::PeerScene& s = scene((int)state.range(0));
  DrawState st = s.st;
  switch (state.range(1)) {
    case 0: run<NoTaps>(state, st, s.tris, true); break;
    case 1: st.interp = InterpMode::Affine; run<NoTaps>(state, st, s.tris, true); break;
    case 2: st.depth_test = false; run<NoTaps>(state, st, s.tris, false); break;
    default: st.depth_test = false; run<FullPathTap>(state, st, s.tris, false); break;
  }
}

BENCHMARK(BM_Shortcut)
    ->ArgsProduct({{0, 1}, {0, 1, 2, 3}})
    ->ArgNames({"scene", "path"})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();

}  // namespace

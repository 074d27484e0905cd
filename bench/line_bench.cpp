// Line throughput (docs/lines.md, "Speed"): pixels per second of the line traversal alone
// (fxr::line_pixels, both rules) and of the whole line path of the unit (LineChain without taps:
// segment conversion, clipping, 1/w, snap, setup, traversal, interpolators, depth, divider; two
// perspective-correct varyings), with a baseline in the same run: a float DDA (round the minor
// coordinate at every column centre) over the same segments. Report ratios; nothing here passes
// or fails on time.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "model/stages/line.hpp"
#include "model/unit/line_chain.hpp"

using namespace fxr;

namespace {

constexpr int kSide = 256;  // viewport
constexpr int kSegments = 4096;

struct Segments {
  std::vector<ClipLine> clip;  // clip space, w in [1, 3)
  std::vector<LineIn> snapped; // the same segments at w = 1, on the 1/256 px grid
};

const Segments& segments() {
  static const Segments s = [] {
    Segments o;
    std::mt19937_64 g(7);
    std::uniform_real_distribution<double> pos(8.0, kSide - 8.0), len(-48.0, 48.0), w(1.0, 3.0), v(0.0, 16.0);
    for (int i = 0; i < kSegments; ++i) {
      const double x0 = pos(g), y0 = pos(g), x1 = x0 + len(g), y1 = y0 + len(g);
      LineIn li;
      li.x0 = std::lround(x0 * 256), li.y0 = std::lround(y0 * 256), li.x1 = std::lround(x1 * 256), li.y1 = std::lround(y1 * 256);
      o.snapped.push_back(li);
      ClipLine cl;
      const double xs[2] = {x0, x1}, ys[2] = {y0, y1};
      for (int e = 0; e < 2; ++e) {
        const double ww = w(g);
        cl.v[e].pos[0] = (float)((2.0 * xs[e] / kSide - 1.0) * ww);
        cl.v[e].pos[1] = (float)((2.0 * ys[e] / kSide - 1.0) * ww);
        cl.v[e].pos[2] = (float)(0.5 * ww);
        cl.v[e].pos[3] = (float)ww;
        cl.v[e].var[0] = (float)v(g);
        cl.v[e].var[1] = (float)v(g);
      }
      o.clip.push_back(cl);
    }
    return o;
  }();
  return s;
}

// Baseline: float DDA, one pixel per major-axis column centre.
void BM_Baseline_FloatDDA(benchmark::State& st) {
  const Segments& s = segments();
  int64_t pixels = 0;
  for (auto _ : st) {
    for (const LineIn& l : s.snapped) {
      const float x0 = l.x0 / 256.f, y0 = l.y0 / 256.f, x1 = l.x1 / 256.f, y1 = l.y1 / 256.f;
      const bool ym = std::fabs(y1 - y0) > std::fabs(x1 - x0);
      const float a0 = ym ? y0 : x0, a1 = ym ? y1 : x1, b0 = ym ? x0 : y0, b1 = ym ? x1 : y1;
      const float lo = std::fmin(a0, a1), hi = std::fmax(a0, a1), m = a1 != a0 ? (b1 - b0) / (a1 - a0) : 0.f;
      int32_t acc = 0;
      for (int i = (int)std::ceil(lo - 0.5f); i + 0.5f < hi; ++i) {
        acc += (int32_t)std::floor(b0 + (i + 0.5f - a0) * m);
        ++pixels;
      }
      benchmark::DoNotOptimize(acc);
    }
  }
  st.SetItemsProcessed(pixels);
}

void traversal(benchmark::State& st, LineRule rule) {
  Config cfg;
  cfg.line.rule = rule;
  const Segments& s = segments();
  int64_t pixels = 0;
  for (auto _ : st)
    for (const LineIn& l : s.snapped) {
      const auto p = line_pixels(cfg.raster, cfg.line, l);
      pixels += (int64_t)p.size();
      benchmark::DoNotOptimize(p.data());
    }
  st.SetItemsProcessed(pixels);
}
void BM_LineTraversal_Midpoint(benchmark::State& st) { traversal(st, LineRule::Midpoint); }
void BM_LineTraversal_DiamondExit(benchmark::State& st) { traversal(st, LineRule::DiamondExit); }

struct Count final : FragmentSink {
  int64_t n = 0;
  void emit(const Fragment&) override { ++n; }
};

// The whole line path (fragments out; depth test off so every pixel is divided).
void BM_LinePath_TwoVaryings(benchmark::State& st) {
  const Config cfg;
  DrawState ds;
  ds.viewport_w = ds.viewport_h = kSide;
  ds.num_varyings = 2;
  ds.depth_test = false;
  const Segments& s = segments();
  FrameOutput f;
  frame_begin(cfg, ds, f);
  Count sink;
  NoTaps taps;
  LineChain<NoTaps> chain(cfg, ds, f, &sink, taps);
  for (auto _ : st)
    for (size_t k = 0; k < s.clip.size(); ++k) chain.draw(s.clip[k], (uint32_t)k);
  st.SetItemsProcessed(sink.n);
}

}  // namespace

BENCHMARK(BM_Baseline_FloatDDA);
BENCHMARK(BM_LineTraversal_Midpoint);
BENCHMARK(BM_LineTraversal_DiamondExit);
BENCHMARK(BM_LinePath_TwoVaryings);

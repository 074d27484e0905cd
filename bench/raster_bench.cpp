// Model speed of the raster stages 5–10 (setup, traversal, interpolators, depth, divider,
// fragment output) on synthetic 1024² scenes of snapped triangles, in fragments/s, next to a
// plain float rasterizer doing the same job in the same binary (the baseline: report ratios).
//   small_tris: a jittered mesh of ~6 px triangles over the screen (setup-bound, bunny-like)
//   large_tris: two full-screen triangles with a strong w gradient (fill-bound)
// Arguments: number of varyings (0 or 2); for the model, 1 = streaming sink, 0 = stored fragments.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "model/unit/backend.hpp"
#include "model/unit/chain.hpp"

using namespace fxr;

namespace {

constexpr int kSize = 1024;

struct FloatVert {
  float x, y, z, rw, v[2];
};

FxFloat fx_of(double d, int bits) {  // scene-side conversion (double → FxFloat), not timed
  FxFloat f;
  if (d == 0) return f;
  int e;
  const double m = std::frexp(std::fabs(d), &e);  // d = m·2^e, m ∈ [0.5, 1)
  f.neg = d < 0;
  f.sig = (uint64_t)std::llround(std::ldexp(m, bits));
  f.exp = e - bits;
  return normalize_fx(f, bits, Round::HalfEven);
}

struct Scene {
  std::vector<SetupTriangle> tris;
  std::vector<FloatVert> fverts;  // 3 per triangle, same data for the float baseline
};

void add_tri(Scene& s, const double p[3][2], const double w[3], const double v[3][2]) {
  SetupTriangle t;
  for (int k = 0; k < 3; ++k) {
    SetupVertex& sv = t.v[k];
    sv.x = std::llround(p[k][0] * 256);
    sv.y = std::llround(p[k][1] * 256);
    const double z = 0.2 + 0.6 * (p[k][0] + p[k][1]) / (2.0 * kSize);
    sv.z = (uint64_t)std::llround(z * 4294967296.0);
    sv.rw = fx_of(1 / w[k], 24);
    for (int m = 0; m < 2; ++m) sv.vw[m] = fx_of(v[k][m] / w[k], 24);
    s.fverts.push_back({(float)(sv.x / 256.0), (float)(sv.y / 256.0), (float)z, (float)(1 / w[k]),
                        {(float)(v[k][0] / w[k]), (float)(v[k][1] / w[k])}});
  }
  t.prim = (uint32_t)s.tris.size();
  s.tris.push_back(t);
}

Scene small_tris() {
  Scene s;
  std::mt19937_64 g(1);
  const double cell = 3.5;  // two triangles of ~6.1 px each per cell
  const int n = (int)(kSize / cell);
  auto jit = [&] { return ((double)(g() % 1000) / 1000 - 0.5) * 1.2; };
  std::vector<double> px((n + 1) * (n + 1)), py((n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) px[j * (n + 1) + i] = i * cell + jit(), py[j * (n + 1) + i] = j * cell + jit();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      const int tri[2][3] = {{a, b, d}, {a, d, c}};
      for (auto& t : tri) {
        double p[3][2], w[3], v[3][2];
        for (int k = 0; k < 3; ++k) {
          p[k][0] = px[t[k]], p[k][1] = py[t[k]];
          w[k] = 1 + p[k][1] / kSize * 4;
          v[k][0] = p[k][0] / kSize, v[k][1] = p[k][1] / kSize;
        }
        add_tri(s, p, w, v);
      }
    }
  return s;
}

Scene large_tris() {
  Scene s;
  const double P[4][2] = {{0, 0}, {kSize, 0}, {kSize, kSize}, {0, kSize}};
  const double W[4] = {1, 1, 20, 20}, V[4][2] = {{0, 0}, {16, 0}, {16, 16}, {0, 16}};
  const int idx[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (auto& t : idx) {
    double p[3][2], w[3], v[3][2];
    for (int k = 0; k < 3; ++k) {
      p[k][0] = P[t[k]][0], p[k][1] = P[t[k]][1], w[k] = W[t[k]];
      v[k][0] = V[t[k]][0], v[k][1] = V[t[k]][1];
    }
    add_tri(s, p, w, v);
  }
  return s;
}

const Scene& scene(int which) {
  static const Scene a = small_tris(), b = large_tris();
  return which == 0 ? a : b;
}

// Streaming consumer: folds every fragment into a checksum (no frame-sized storage).
struct SumSink final : FragmentSink {
  uint64_t sum = 0;
  void emit(const Fragment& f) override { sum += f.depth + f.var[0].sig + (uint64_t)f.x; }
};

// Model into a streaming sink (arg 1 = 1) or into FrameOutput::fragments (arg 1 = 0).
void run_model(benchmark::State& state, int which) {
  const Scene& sc = scene(which);
  Config cfg;
  DrawState st;
  st.viewport_w = st.viewport_h = kSize;
  st.num_varyings = (int)state.range(0);
  const bool stream = state.range(1) != 0;
  FrameOutput f;
  SumSink sink;
  uint64_t frags = 0;
  for (auto _ : state) {
    frame_begin(cfg, st, f);
    NoTaps taps;
    if (stream) {
      FragmentChain<NoTaps> chain(cfg, st, f, &sink, taps);  // stages 5–10, set up once per frame
      for (const SetupTriangle& t : sc.tris) chain.run(t);
    } else {
      f.fragments.reserve((size_t)kSize * kSize);
      KeepFragments keep(f.fragments);
      FragmentChain<NoTaps> chain(cfg, st, f, &keep, taps);
      for (const SetupTriangle& t : sc.tris) chain.run(t);
    }
    frags += f.stats.fragments_generated;
    benchmark::DoNotOptimize(f.fragments.data());
    benchmark::DoNotOptimize(sink.sum);
  }
  state.counters["fragments/s"] = benchmark::Counter((double)frags, benchmark::Counter::kIsRate);
  state.counters["tris"] = (double)sc.tris.size();
}

// The baseline: a plain float rasterizer (edge functions in float, top-left by >= 0 only,
// perspective-correct varyings with a float divide, float depth compare).
struct FloatFrag {
  int x, y;
  float z, v[2];
};

void run_float(benchmark::State& state, int which) {
  const Scene& sc = scene(which);
  const int nv = (int)state.range(0);
  std::vector<float> depth((size_t)kSize * kSize);
  std::vector<FloatFrag> out;
  out.reserve((size_t)kSize * kSize);
  uint64_t frags = 0;
  for (auto _ : state) {
    std::fill(depth.begin(), depth.end(), 1.0f);
    out.clear();
    for (size_t t = 0; t < sc.tris.size(); ++t) {
      const FloatVert* v = &sc.fverts[3 * t];
      float area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
      if (area == 0) continue;
      const float inv = 1 / area;
      const int x0 = std::max(0, (int)std::floor(std::min({v[0].x, v[1].x, v[2].x})));
      const int x1 = std::min(kSize - 1, (int)std::ceil(std::max({v[0].x, v[1].x, v[2].x})));
      const int y0 = std::max(0, (int)std::floor(std::min({v[0].y, v[1].y, v[2].y})));
      const int y1 = std::min(kSize - 1, (int)std::ceil(std::max({v[0].y, v[1].y, v[2].y})));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const float px = x + 0.5f, py = y + 0.5f;
          float e[3];
          for (int k = 0; k < 3; ++k) {
            const FloatVert &a = v[(k + 1) % 3], &b = v[(k + 2) % 3];
            e[k] = ((b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x)) * inv;
          }
          if (e[0] < 0 || e[1] < 0 || e[2] < 0) continue;
          ++frags;
          const float z = e[0] * v[0].z + e[1] * v[1].z + e[2] * v[2].z;
          float& d = depth[(size_t)y * kSize + x];
          if (!(z < d)) continue;
          d = z;
          FloatFrag fr{x, y, z, {0, 0}};
          if (nv) {
            const float rw = 1 / (e[0] * v[0].rw + e[1] * v[1].rw + e[2] * v[2].rw);
            for (int m = 0; m < 2; ++m) fr.v[m] = (e[0] * v[0].v[m] + e[1] * v[1].v[m] + e[2] * v[2].v[m]) * rw;
          }
          out.push_back(fr);
        }
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["fragments/s"] = benchmark::Counter((double)frags, benchmark::Counter::kIsRate);
}

void BM_Model_SmallTris(benchmark::State& s) { run_model(s, 0); }
void BM_Float_SmallTris(benchmark::State& s) { run_float(s, 0); }
void BM_Model_LargeTris(benchmark::State& s) { run_model(s, 1); }
void BM_Float_LargeTris(benchmark::State& s) { run_float(s, 1); }

}  // namespace

BENCHMARK(BM_Float_SmallTris)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Model_SmallTris)->Args({0, 1})->Args({2, 1})->Args({2, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Float_LargeTris)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Model_LargeTris)->Args({0, 1})->Args({2, 1})->Args({2, 0})->Unit(benchmark::kMillisecond);

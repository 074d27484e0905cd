// Stages 1–4 (fxr::geometry) per triangle, against a plain float baseline doing the float32
// divide, the float viewport formula and a rounding to the subpixel grid in the same run. Read
// the ratios, not the times: the machine is shared.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "model/unit/geometry.hpp"

using namespace fxr;

namespace {

// spread 0.9: every triangle trivially accepted; 3: about 40 % cross a plane.
std::vector<ClipTriangle> scene(double spread, int nv) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1), z(0, 1), w(0.5, 10);
  std::vector<ClipTriangle> tris(4096);
  for (auto& t : tris)
    for (auto& v : t.v) {
      const double ww = w(rng);
      v.pos[0] = (float)(u(rng) * ww * spread);
      v.pos[1] = (float)(u(rng) * ww * spread);
      v.pos[2] = (float)((spread > 1 ? z(rng) * 1.2 - 0.1 : z(rng)) * ww);
      v.pos[3] = (float)ww;
      for (int k = 0; k < nv; ++k) v.var[k] = (float)u(rng);
    }
  return tris;
}

DrawState draw(int nv) {
  DrawState st;
  st.viewport_w = 1024;
  st.viewport_h = 768;
  st.num_varyings = nv;
  return st;
}

void BM_FloatBaseline(benchmark::State& state) {
  const int nv = (int)state.range(0);
  const auto tris = scene(0.9, nv);
  const DrawState st = draw(nv);
  std::vector<float> out(tris.size() * 3 * (3 + nv));
  for (auto _ : state) {
    size_t o = 0;
    for (const auto& t : tris)
      for (const auto& v : t.v) {
        const float r = 1.0f / v.pos[3];
        out[o++] = std::nearbyint(((v.pos[0] * r + 1.0f) * (st.viewport_w * 0.5f)) * 256.0f);
        out[o++] = std::nearbyint(((v.pos[1] * r + 1.0f) * (st.viewport_h * 0.5f)) * 256.0f);
        out[o++] = v.pos[2] * r;
        for (int k = 0; k < nv; ++k) out[o++] = v.var[k] * r;
      }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * (int64_t)tris.size());
}

void BM_Geometry(benchmark::State& state) {
  const int nv = (int)state.range(0);
  const double spread = state.range(1) ? 3.0 : 0.9;
  const auto tris = scene(spread, nv);
  const DrawState st = draw(nv);
  const Config cfg;
  std::vector<SetupTriangle> out;
  out.reserve(tris.size() * 4);
  for (auto _ : state) {
    out.clear();
    RasterStats s;
    for (size_t i = 0; i < tris.size(); ++i) geometry(cfg, st, tris[i], (uint32_t)i, out, s);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * (int64_t)tris.size());
}

}  // namespace

BENCHMARK(BM_FloatBaseline)->Arg(0)->Arg(4);
BENCHMARK(BM_Geometry)->Args({0, 0})->Args({4, 0})->Args({4, 1});

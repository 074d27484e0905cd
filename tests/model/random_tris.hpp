// Random clip-space triangles for the tests of the fused stages (tests/model/interp_span_test.cpp,
// pixel_divide_test.cpp).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "model/unit/io.hpp"

namespace fxr {

// Random triangles, overlapping in depth, some large (long spans), some crossing w = 0 (clipped).
inline std::vector<ClipTriangle> random_tris(uint64_t seed, int n, int nv) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> pos(-1.3f, 1.3f), zf(-0.2f, 1.0f), wf(0.05f, 6.0f), var(-5.0f, 5.0f);
  std::vector<ClipTriangle> v;
  for (int t = 0; t < n; ++t) {
    ClipTriangle tri;
    const float big = t % 5 == 0 ? 4.0f : 1.0f;
    for (auto& x : tri.v) {
      const float w = wf(rng);
      x.pos[0] = pos(rng) * w * big, x.pos[1] = pos(rng) * w * big, x.pos[2] = zf(rng) * w, x.pos[3] = w;
      // Varyings of both signs (N crosses zero inside the triangle), one nearly constant.
      for (int k = 0; k < nv; ++k) x.var[k] = k == 3 ? 1.0f + var(rng) * 1e-6f : var(rng);
    }
    v.push_back(tri);
  }
  return v;
}

}  // namespace fxr

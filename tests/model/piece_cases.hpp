// tests/model/piece_cases.hpp — clipped primitives whose pieces end differently, for the rule
// "a piece rejected in stage 3 or 4 is dropped alone" and the per-piece / per-setup-triangle
// counters (docs/pipeline.md, "Statistics: primitives, pieces, setup triangles"). Shared by the
// model test (tests/model/piece_rule_test.cpp) and the whole-unit co-simulation
// (tb/unit/unit_test.cpp, tb/unit/unit_variant_test.cpp). Viewport 48 × 48 at the origin.
#pragma once

#include "model/unit/io.hpp"
#include "tests/model/clip_vertex.hpp"

namespace fxr::piece_cases {

inline ClipVertex vertex(float x, float y, float z, float w, float v0, float v1) {
  return test::clip_vertex(x, y, z, w, v0, v1);
}

inline DrawState state() {
  DrawState st;
  st.viewport_w = st.viewport_h = 48;
  st.num_varyings = 2;
  return st;
}

// Through the eye. The edge v0 → v1 runs through the clip-space origin (v1 = −v0 exactly, z/w = ½
// and x/w, y/w inside the viewport along it), so the w_min plane cuts it at w = 2^−160 with x, y,
// z on the clip volume's inside. The clipped polygon fans from v0 into three pieces: the first
// two have a vertex at w = 2^−160, the third none. 1/2^−160 = 2^160 needs a reciprocal exponent
// range of ±160 (recip.exp_bits ≥ 9, docs/pipeline.md stage 2): with recip.exp_bits 8 those two
// pieces fail in stage 3 and only the third goes on; at the default configuration all three do.
inline ClipTriangle through_the_eye() {
  ClipTriangle t;
  t.v[0] = vertex(0.25f, -0.5f, 0.5f, 1.0f, 0.0f, 1.0f);
  t.v[1] = vertex(-0.25f, 0.5f, -0.5f, -1.0f, 1.0f, 0.0f);
  t.v[2] = vertex(-0.25f, 0.125f, 0.25f, 0.5f, 2.0f, -1.0f);
  return t;
}

// Across the near plane into the guard band. v2 is behind the near plane (z < 0) and the edges
// v1 → v2, v2 → v0 cross it at their midpoints, P = (1, 0.25, 0, 1) and Q = (2.125, 0.25, 0, 1):
// the quad v0, v1, P, Q fans into (v0, v1, P), which holds v1 = (−1, 0) in NDC and is drawn, and
// (v0, P, Q), all of it at x_n ≥ 1, right of the viewport: no pixel centre (CulledNoSamples).
inline ClipTriangle near_into_the_band() {
  ClipTriangle t;
  t.v[0] = vertex(1.25f, 0.0f, 0.5f, 1.0f, 0.0f, 1.0f);
  t.v[1] = vertex(-1.0f, 0.0f, 0.5f, 1.0f, 1.0f, 0.0f);
  t.v[2] = vertex(3.0f, 0.5f, -0.5f, 1.0f, 2.0f, -1.0f);
  return t;
}

}  // namespace fxr::piece_cases

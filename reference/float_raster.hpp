// reference/float_raster.hpp — the plain float rasterizer: the speed baseline of the model
// (docs/references.md#spec-speed), independent of the model's code and formats.
//
// What a straightforward software rasterizer does in float32: per triangle, 1/w, the divide,
// the viewport transform (no snapping), float32 edge functions stepped along each row of the
// bounding box, the cover test at pixel centres with a top-left tie rule on exact zeros,
// screen-linear depth with a depth test, and perspective-correct varyings
// v = Σ λ_i v_i/w_i / Σ λ_i /w_i written to a float framebuffer. No clipping: a triangle with a
// vertex at w ≤ 0 is skipped (counted), one outside a clip plane on all three vertices is
// trivially rejected. It is a baseline for speed, not a reference for accuracy.
#pragma once

#include <cstdint>
#include <vector>

#include "model/unit/io.hpp"

namespace fxr::peer {

struct FloatFrame {
  int width = 0, height = 0, num_varyings = 0;
  std::vector<float> depth;  // row 0 at the bottom; cleared to 1
  std::vector<float> var;    // num_varyings per pixel; cleared to 0
  std::vector<int32_t> prim; // triangle index written last (−1: none)
  uint64_t fragments_generated = 0;  // covered samples
  uint64_t fragments_passed = 0;     // passed the depth test (or all when depth_test is off)
  uint64_t skipped_w = 0;            // triangles skipped for w ≤ 0 (no clipper)
  uint64_t rejected = 0;             // trivially rejected
};

// Contract: clears `f` to the size (viewport_x + viewport_w) × (viewport_y + viewport_h) and
// draws `tris` in order. Honours viewport, scissor, num_varyings, cull / front_ccw, depth test
// (func, write), interp. float32 throughout; deterministic (one thread).
void float_raster(const DrawState& st, const std::vector<ClipTriangle>& tris, FloatFrame& f);

}  // namespace fxr::peer

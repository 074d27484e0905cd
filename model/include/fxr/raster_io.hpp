// fxr/raster_io.hpp — what enters and leaves the raster unit.
//
// Input: primitives as a vertex stage emits them (float32 clip-space positions and
// varyings), plus the draw state. Output: fragments with integer codes, and statistics that
// account for every input primitive. Internal stage records live in the stage headers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fxr/fxfloat.hpp"

namespace fxr {

// Upper bound on varyings per vertex (SPEC: 0 … at least 16).
inline constexpr int kMaxVaryings = 16;

// One vertex as the vertex stage emits it: raw float32 values (bit patterns are kept, so a
// user can feed exactly what their vertex stage produced, NaN payloads included).
struct ClipVertex {
  float pos[4] = {0, 0, 0, 1};      // x_c, y_c, z_c, w_c
  float var[kMaxVaryings] = {};     // varyings v_0 … v_{N−1}
};

struct ClipTriangle {
  ClipVertex v[3];
};

enum class CullMode : uint8_t { None, Back, Front };
enum class DepthFunc : uint8_t { Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always };
enum class InterpMode : uint8_t { Perspective, Affine };  // Affine: seed 000's wrong image

// Draw state: everything besides the primitives that the unit needs. Window coordinates have
// y up (row 0 at the bottom), pixel centres at (x + ½, y + ½).
struct DrawState {
  int viewport_x = 0, viewport_y = 0, viewport_w = 256, viewport_h = 256;
  int scissor_x = 0, scissor_y = 0, scissor_w = -1, scissor_h = -1;  // −1: same as the viewport
  int num_varyings = 0;
  bool front_ccw = true;  // counter-clockwise (in y-up window space) is front-facing
  CullMode cull = CullMode::None;
  DepthFunc depth_func = DepthFunc::Less;
  bool depth_test = true;
  bool depth_write = true;
  InterpMode interp = InterpMode::Perspective;
};

}  // namespace fxr

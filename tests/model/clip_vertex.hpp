// tests/model/clip_vertex.hpp — a clip-space vertex from its float position and two varyings, for
// the tests that build primitives by hand (tests/model/reference_test.cpp, tests/model/piece_cases.hpp).
#pragma once

#include "model/unit/io.hpp"

namespace fxr::test {

inline ClipVertex clip_vertex(float x, float y, float z, float w, float v0 = 0, float v1 = 0) {
  ClipVertex v;
  v.pos[0] = x;
  v.pos[1] = y;
  v.pos[2] = z;
  v.pos[3] = w;
  v.var[0] = v0;
  v.var[1] = v1;
  return v;
}

}  // namespace fxr::test

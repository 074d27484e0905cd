// Independent exact coverage reference (no GMP, nothing of the model's arithmetic): orientation
// tests in i128 at pixel centres with the top-left rule written from its D3D11 definition (top
// edge: exactly horizontal with the triangle below it — y is up; left edge: not horizontal, the
// triangle to its right). Used by tests/model/coverage_test.cpp and the raster fuzz harness
// (tests/fuzz/raster_fuzz.cpp).
#pragma once

#include <cstdint>

namespace fxr::covref {

using i128 = __int128;

struct P {
  int64_t x, y;  // subpixel units
};

// Twice-scaled coordinates so that pixel centres are integers for every subpixel_bits:
// vertex 2·x, centre of pixel i (2i + 1)·2^s. Coordinates below 2^40 in magnitude keep every
// product below 2^84.
inline i128 orient(i128 ax, i128 ay, i128 bx, i128 by, i128 px, i128 py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// D3D11: "a top edge is an edge that is exactly horizontal and is above the other edges";
// "a left edge is an edge that is not exactly horizontal and is on the left side of the
// triangle". With y up, "above" means greater y: the third vertex c lies below the edge.
// Left side: at the height of c, the edge's line lies left of c.
inline bool ref_top_left(P a, P b, P c) {
  if (a.y == b.y) return c.y < a.y;
  // x of the edge line at height c.y: a.x + (b.x − a.x)(c.y − a.y)/(b.y − a.y); is c.x greater?
  const i128 dy = b.y - a.y;
  const i128 lhs = (i128)(c.x - a.x) * dy, rhs = (i128)(b.x - a.x) * (c.y - a.y);
  return dy > 0 ? lhs > rhs : lhs < rhs;
}

// Whether the centre of pixel (i, j) is covered by the triangle v (either winding; zero area
// covers nothing), s = subpixel_bits.
inline bool ref_covered(const P v[3], int s, int i, int j) {
  const i128 px = (i128)(2 * (int64_t)i + 1) * ((i128)1 << s), py = (i128)(2 * (int64_t)j + 1) * ((i128)1 << s);
  if (orient(v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y) == 0) return false;  // zero area
  for (int k = 0; k < 3; ++k) {
    const P a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
    const i128 sp = orient(2 * (i128)a.x, 2 * (i128)a.y, 2 * (i128)b.x, 2 * (i128)b.y, px, py);
    const i128 sc = orient(a.x, a.y, b.x, b.y, c.x, c.y);
    if (sp == 0) {
      if (!ref_top_left(a, b, c)) return false;
    } else if ((sp > 0) != (sc > 0)) {
      return false;
    }
  }
  return true;
}

}  // namespace fxr::covref

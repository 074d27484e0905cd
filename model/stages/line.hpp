// model/stages/line.hpp — line rasterisation (issue 15): which pixels a snapped segment covers,
// as a stream of pixels, one per major-axis step. docs/lines.md explains both rules.
//
// Input: two snapped window endpoints in the raster's subpixel grid (raster.subpixel_bits
// fraction bits, raster.window_int_bits signed integer bits: |x|, |y| < 2^(window_int_bits−1) px).
// Output: the covered pixels (i, j) (pixel (i, j) has its centre at (i + ½, j + ½)), in the order
// the hardware emits them: along the major axis, increasing coordinate (canonical order, so both
// directions of a segment give the same stream under the midpoint rule).
//
// Rules (LineConfig::rule):
//   midpoint     — the midpoint algorithm (docs/references.md, seed-001-midpoint-line): in every
//                  column (x-major, |dx| ≥ |dy|; rows for y-major) whose centre lies in the
//                  segment's major-axis range, the pixel whose minor-axis interval contains the
//                  line's exact minor coordinate at that centre, i.e. the nearest pixel centre.
//                  Tie (the line passes exactly between two centres): the smaller minor
//                  coordinate. Endpoints (LineConfig::endpoints): half_open = centres c with
//                  min ≤ c < max along the major axis (a polyline drawn monotonically touches a
//                  shared vertex column once); closed = min ≤ c ≤ max. Both rules depend only on
//                  the unordered pair of endpoints: both directions give the same pixels.
//   diamond_exit — OpenGL's non-antialiased line rule (docs/references.md, the GL / D3D rules):
//                  pixel f is produced when the segment from p_a (first vertex) to p_b intersects
//                  the open diamond R_f = {|x − x_f| + |y − y_f| < ½} and p_b ∉ R_f. Direction
//                  matters at the ends by design (the last pixel of a polyline is not repeated
//                  by the next segment). A line through a diamond's corner produces nothing there.
//
// Integer datapath (all exact, no rounding anywhere): coordinates are doubled so that pixel
// centres are integers, u = 2^(subpixel_bits+1) per pixel, centre of i = i·u + u/2. In the
// canonical frame (major coordinate A increasing, minor coordinate B non-decreasing after an
// optional reflection B → −B) the decision variable at column centre A_c and the row boundary
// B_r = (r+1)·u is D = db·(A_c − A0) − da·(B_r − B0) = −f(x+1, y+½) of the seed, stepped by
// +db·u per column and −da·u per row increment (the seed's (y0−y1) and (y0−y1)+(x1−x0), scaled).
// The first column is within one pixel of A0, so D starts from two products of at most one pixel
// of distance each and never leaves (−da·u − u·db, db·u]: line_decision_bits() signed bits.
#pragma once

#include <cstdint>
#include <vector>

#include "model/config/raster_config.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

enum class LineRule : uint8_t { Midpoint, DiamondExit };
enum class LineEndpoints : uint8_t { HalfOpen, Closed };

struct LineConfig {
  LineRule rule = LineRule::Midpoint;
  // Endpoint rule of the midpoint algorithm (diamond_exit has its own, GL's).
  LineEndpoints endpoints = LineEndpoints::HalfOpen;

  template <class V>
  void visit(V& v) {
    v.choice("rule", rule, {"midpoint", "diamond_exit"},
             "line rule: midpoint algorithm or the GL / D3D diamond-exit rule (non-antialiased lines)");
    v.choice("endpoints", endpoints, {"half_open", "closed"},
             "midpoint endpoints: major-axis centres in [min, max) or [min, max]");
  }
};

// A snapped segment: endpoints in subpixel units (raster.subpixel_bits fraction bits).
// p0 is the first vertex (p_a of the diamond-exit rule).
struct LineIn {
  int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct LinePixel {
  int32_t x = 0, y = 0;
  bool operator==(const LinePixel& o) const { return x == o.x && y == o.y; }
  bool operator<(const LinePixel& o) const { return x != o.x ? x < o.x : y < o.y; }
};

// Signed bits of the decision variable D (see above): |D| < 2^(W + 2S + 3),
// W = window_int_bits, S = subpixel_bits (36 bits at the defaults 16, 8).
inline int line_decision_bits(const RasterConfig& r) { return r.window_int_bits + 2 * r.subpixel_bits + 4; }
// Signed bits of a doubled coordinate difference da, db (< 2^(W + S + 1)).
inline int line_delta_bits(const RasterConfig& r) { return r.window_int_bits + r.subpixel_bits + 2; }

// The segment after setup: the canonical frame and the first decision value. This is what the
// RTL rtl/fxr_line.sv computes in its set-up cycle; line_pixels steps it.
struct LineSetup {
  bool y_major = false;   // major axis is y (|dy| > |dx|)
  bool reflect = false;   // minor axis reflected (B = −minor) so that db ≥ 0
  int64_t da = 0, db = 0; // doubled major / minor extents, 0 ≤ db ≤ da
  int64_t first = 0;      // first major-axis pixel index
  int64_t count = 0;      // major-axis steps (pixels before the diamond-exit drops)
  int64_t row = 0;        // minor pixel index in the canonical frame at the first column, before correction
  int64_t d = 0;          // D at the first column and boundary (row + 1)·u
};

// Contract: endpoints within the raster's window range (|x|, |y| < 2^(W−1+S)); otherwise
// undefined (the front end clips to the guard band first). No rounding; every result is exact.
// Returns the covered pixels in emission order (see above). Pure function.
std::vector<LinePixel> line_pixels(const RasterConfig& r, const LineConfig& c, const LineIn& in);

// Set-up only (midpoint rule's canonical frame; the diamond-exit rule uses the same frame).
LineSetup line_setup(const RasterConfig& r, const LineConfig& c, const LineIn& in);

}  // namespace fxr

// model/stages/traverse.hpp — stage 6 (traversal): which pixel centres of the candidate rectangle a
// set-up triangle covers, row by row, as spans. docs/pipeline.md, stage 6.
//
// Exactness. Every edge value is an exact int64 (setup.hpp: edge_value_bits ≤ 63). Row starts
// are stepped incrementally, E(x0, j+1) = E(x0, j) + b·2^g, and within a narrow rectangle
// pixels are stepped too, E(i+1, j) = E(i, j) + a·2^g: every stepped value equals the direct
// evaluation at that pixel centre (tests/model/coverage_test.cpp checks it). In a row the
// covered pixels form one interval (each biased edge value is monotone in i), so a wide
// rectangle finds the interval ends with one exact floor / ceil division per edge instead of
// visiting empty pixels (this is how empty parts of rows and slivers are skipped quickly).
#pragma once

#include <algorithm>
#include <cstdint>

#include "model/stages/setup.hpp"

namespace fxr {

// Candidate rectangles at most this wide are scanned pixel by pixel; wider ones compute each
// row's covered interval by division. Both are exact and give the same pixels.
inline constexpr int kScanMaxWidth = 16;

// Biased edge values E_k + bias_k at pixel centres, stepped incrementally.
struct EdgeStepper {
  int64_t v[3];        // at the current pixel
  int64_t dx[3];       // a_k·2^g: one pixel right
  int64_t dy[3];       // b_k·2^g: one pixel up

  // Starts at pixel (i, j) with a direct evaluation.
  EdgeStepper(const TriSetup& t, int i, int j) {
    const int64_t X = pixel_centre(i, t.g), Y = pixel_centre(j, t.g);
    for (int k = 0; k < 3; ++k) {
      v[k] = edge_eval(t.e[k], X, Y) + t.e[k].bias;
      dx[k] = t.e[k].a * ((int64_t)1 << t.g);
      dy[k] = t.e[k].b * ((int64_t)1 << t.g);
    }
  }
  bool inside() const { return (v[0] | v[1] | v[2]) >= 0; }  // all three ≥ 0 (sign bits clear)
  void step_x() { v[0] += dx[0], v[1] += dx[1], v[2] += dx[2]; }
  void step_y() { v[0] += dy[0], v[1] += dy[1], v[2] += dy[2]; }
};

// floor(a / d) and ceil(a / d) for d > 0 (exact integer division).
inline int64_t floor_div(int64_t a, int64_t d) {
  const int64_t q = a / d;
  return (a % d != 0 && a < 0) ? q - 1 : q;
}
inline int64_t ceil_div(int64_t a, int64_t d) { return -floor_div(-a, d); }

// Contract: calls span(j, xb, xe) for every row j (bottom to top) with covered pixels
// xb ≤ i ≤ xe (inclusive, xb ≤ xe); rows with none are skipped. A pixel (i, j) of the candidate
// rectangle is covered iff E_k + bias_k ≥ 0 at its centre for k = 0, 1, 2 (top-left rule).
template <class SpanFn>
void traverse(const TriSetup& t, SpanFn&& span) {
  EdgeStepper row(t, t.x0, t.y0);  // at (x0, j)
  const int w = t.x1 - t.x0;       // last offset in a row
  if (w < kScanMaxWidth) {
    // Every pixel of the row is tested into a bit mask (no branch per pixel: the loop runs the
    // same w + 1 times on every row, where stopping at the interval's ends mispredicted twice
    // per row — most of the bunny's traversal time, docs/speed.md "Session 9: the span start");
    // the covered pixels are one interval, so its ends are the mask's lowest and highest bits.
    static_assert(kScanMaxWidth <= 32, "the row mask is 32 bits");
    for (int j = t.y0; j <= t.y1; ++j, row.step_y()) {
      int64_t v0 = row.v[0], v1 = row.v[1], v2 = row.v[2];
      uint32_t m = 0;
      for (int i = 0; i <= w; ++i) {
        m |= (uint32_t)((v0 | v1 | v2) >= 0) << i;
        v0 += row.dx[0], v1 += row.dx[1], v2 += row.dx[2];
      }
      if (m == 0) continue;
      span(j, t.x0 + __builtin_ctz(m), t.x0 + 31 - __builtin_clz(m));
    }
    return;
  }
  for (int j = t.y0; j <= t.y1; ++j, row.step_y()) {
    // Offsets o ∈ [lo, hi] with row.v[k] + o·dx[k] ≥ 0 for all k.
    int64_t lo = 0, hi = w;
    for (int k = 0; k < 3; ++k) {
      const int64_t e = row.v[k], d = row.dx[k];
      if (d > 0) {
        if (e < 0) lo = std::max(lo, ceil_div(-e, d));
      } else if (d < 0) {
        if (e < 0) { hi = -1; break; }
        hi = std::min(hi, floor_div(e, -d));
      } else if (e < 0) {
        hi = -1;
        break;
      }
    }
    if (lo <= hi) span(j, t.x0 + (int)lo, t.x0 + (int)hi);
  }
}

// ---- the stage ------------------------------------------------------------------------------

// Stage 6 output: the covered pixels x0 ≤ i ≤ x1 of row y of one triangle (pixel indices are
// signed raster.window_int_bits).
struct Span {
  uint32_t prim = 0;
  int32_t y = 0, x0 = 0, x1 = -1;

  template <class V>
  void visit(V& v, const RecordShape& s) {
    const int b = s.cfg.raster.window_int_bits;
    v("prim", prim, kPrimIdBits, false);
    v("y", y, b, true);
    v("x0", x0, b, true);
    v("x1", x1, b, true);
  }
};

class TraverseStage {
 public:
  static constexpr const char* kName = "traverse";
  using In = TriangleEquations;
  using Out = Span;

  TraverseStage(const Config&, const DrawState&) {}

  // 1 → 0..n spans, rows bottom to top (never drops a triangle: a set-up triangle whose
  // candidate rectangle holds no covered centre simply emits no span).
  template <class Emit>
  void step(const In& in, Emit&& emit) {
    span_.prim = in.prim;
    traverse(in.edges, [&](int j, int xb, int xe) {
      span_.y = j;
      span_.x0 = xb;
      span_.x1 = xe;
      emit(static_cast<const Out&>(span_));
    });
  }

  // rtl/fxr_traverse.sv: a row every n + 1 clocks, n = bits of the candidate rectangle's width
  // (docs/rtl.md, "fxr_traverse"); cost() gives the n = 0 figures.
  static StageCost cost(const Config& cfg);

  // The data-dependent part of that cost for one triangle (the cycle model, docs/cycles.md):
  // rtl/fxr_traverse.sv searches n = bits of w = x1 − x0 offset bits per row (one per clock) and
  // spends one clock on the row's result, so a row takes n + 1 clocks, the row r span is valid
  // (r + 1)·(n + 1) + 1 clocks after the input transfer and the next triangle is accepted in the
  // clock that finishes the last row: the unit is occupied rows·(n + 1) clocks. An empty
  // candidate rectangle (w < 0 or y1 < y0) is accepted and dropped in one clock.
  struct Timing {
    bool empty = true;
    int rows = 0;  // candidate rows y1 − y0 + 1
    int n = 0;     // search bits per row
    int64_t row_clocks() const { return n + 1; }
    int64_t occupancy() const { return empty ? 1 : (int64_t)rows * row_clocks(); }
  };
  static Timing timing(const In& in) {
    Timing t;
    const int64_t w = (int64_t)in.edges.x1 - in.edges.x0;
    t.empty = w < 0 || in.edges.y1 < in.edges.y0;
    if (t.empty) return t;
    t.rows = in.edges.y1 - in.edges.y0 + 1;
    while (t.n < 62 && (w >> t.n) != 0) ++t.n;
    return t;
  }

 private:
  Span span_;
};

}  // namespace fxr

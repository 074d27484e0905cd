// model/stages/setup.hpp — stage 5 (triangle setup): exact integer edge functions, area, culling,
// the top-left fill rule and the bounding box. docs/pipeline.md, stage 5.
//
// Grid. Snapped vertices arrive with raster.subpixel_bits fraction bits. Setup works on the
// "sample grid", which has g = grid_bits(cfg) = max(subpixel_bits, 1) fraction bits so that the
// pixel centre (i + ½, j + ½) is an integer point: X = i·2^g + 2^(g−1). For subpixel_bits ≥ 1 the
// grid is the snap grid itself; for subpixel_bits = 0 vertices are doubled (exact).
//
// Edge functions (seed 001). For the directed edge a → b,
//     E(X, Y) = (y_a − y_b)·X + (x_b − x_a)·Y + (x_a·y_b − x_b·y_a)
// which is cross(b − a, p − a): positive to the left of a → b. Edge k is the edge opposite
// vertex k (from v_{k+1} to v_{k+2}), so E_k(v_k) = 2·area and E_0 + E_1 + E_2 = 2·area at
// every point (an exact integer invariant). After setup the triangle is normalised to
// counter-clockwise winding in y-up window space (all three functions negated for a clockwise
// triangle), so E_k ≥ 0 inside, and E_k / 2A is the barycentric weight of vertex k.
//
// Top-left rule (D3D11 definition, in y-up window coordinates). A pixel centre exactly on an
// edge is inside only if that edge is a top edge (exactly horizontal, with the triangle below
// it: the edge with the greater y) or a left edge (not horizontal, with the triangle to its
// right). On a counter-clockwise triangle with edge coefficients A = y_a − y_b, B = x_b − x_a
// (the gradient (A, B) points inside):  left ⇔ A > 0;  top ⇔ A = 0 and B < 0.
// It is applied as an exact bias on the edge constant: bias = 0 on top / left edges and −1 on
// the others, and a centre is covered iff E_k + bias_k ≥ 0 for k = 0, 1, 2 (E is an integer,
// so E > 0 ⇔ E − 1 ≥ 0). This is D3D's rule read in y-up coordinates; llvmpipe's rule in y-up
// coordinates makes left and bottom edges inclusive instead (ANCHORS): mirror y to compare.
#pragma once

#include <cstdint>

#include "model/config/config.hpp"
#include "model/arith/fixed.hpp"
#include "model/unit/io.hpp"

namespace fxr {

// ---- widths (derived; docs/pipeline.md stage 5 table) --------------------------------------

// Fraction bits of the sample grid: ≥ 1 so the pixel centre offset 2^(g−1) is an integer.
constexpr int grid_bits(const RasterConfig& c) { return c.subpixel_bits > 0 ? c.subpixel_bits : 1; }
// Signed bits of a vertex coordinate on the sample grid: window_int_bits integer bits (guard
// band included) + grid_bits fraction bits. Range [−2^(cb−1), 2^(cb−1)).
constexpr int coord_bits(const RasterConfig& c) { return c.window_int_bits + grid_bits(c); }
// Signed bits of an edge coefficient A or B: a difference of two coordinates, |A| < 2^cb.
constexpr int edge_coef_bits(const RasterConfig& c) { return coord_bits(c) + 1; }
// Signed bits of an edge value (and of 2·area) at any point p of the coordinate range:
// E = cross(b − a, p − a) with each component of magnitude < 2^cb, so |E| < 2·2^(2cb) and
// 2·cb + 2 signed bits hold it (50 bits at 16.8, ANCHORS). Stepping adds no bits (every stepped
// value is the exact value at a sample point); the −1 top-left bias cannot overflow either.
constexpr int edge_value_bits(const RasterConfig& c) { return 2 * coord_bits(c) + 2; }
// Edge values are held in int64_t.
inline constexpr int kEdgeValueMaxBits = 63;

// The rules that keep edge values in int64 and the interpolator / depth sums in i128 are
// checked by validate() (model/config/validate.hpp), which frame_begin calls.

// ---- setup record ------------------------------------------------------------------------

// One edge function on the sample grid: E(X, Y) = a·X + b·Y + c, and its top-left bias.
struct EdgeEq {
  int64_t a = 0, b = 0, c = 0;  // edge_coef_bits, edge_coef_bits, edge_value_bits (signed)
  int64_t bias = 0;             // 0 on a top or left edge, −1 otherwise
};

// Contract: E(X, Y) exactly, X, Y on the sample grid (no bias). |result| < 2^(edge_value_bits−1)
// for X, Y in the coordinate range.
inline int64_t edge_eval(const EdgeEq& e, int64_t X, int64_t Y) { return e.a * X + e.b * Y + e.c; }

// The sample grid coordinate of pixel centre i: i·2^g + 2^(g−1) (exact).
inline int64_t pixel_centre(int i, int g) { return (int64_t)i * ((int64_t)1 << g) + ((int64_t)1 << (g - 1)); }  // i may be < 0

// Setup of one triangle.
struct TriSetup {
  EdgeEq e[3];           // e[k] opposite vertex k, counter-clockwise normalised: E_k ≥ 0 inside
  int64_t area2 = 0;     // 2·area on the sample grid, > 0 (edge_value_bits)
  bool front = true;     // front-facing per DrawState.front_ccw
  int g = 1;             // grid_bits
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;  // candidate pixels, inclusive: bbox ∩ viewport ∩ scissor
};

enum class SetupOutcome : uint8_t { Ok, CulledZeroArea, CulledBackface, CulledNoSamples, RejectedRange };

// The pixel rectangle a draw may touch: viewport ∩ scissor, inclusive bounds (x1 < x0: empty).
struct PixelRect {
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;
};
PixelRect draw_rect(const DrawState& st);

// Contract: stage 5 on one snapped triangle.
//   Input: vertex x, y in subpixel units (raster.subpixel_bits fraction bits, signed, within
//   ±2^(window_int_bits−1) pixels); anything outside → RejectedRange (documented discard; the
//   geometry stage should never produce it); likewise z > 1 (more than 2^z_frac_bits).
//   Zero area (collinear or repeated vertices, after snapping) → CulledZeroArea.
//   Back faces per st.cull and st.front_ccw → CulledBackface (zero area is never "back").
//   No candidate pixel (bbox of the pixel centres inside the vertex bbox ∩ draw_rect) →
//   CulledNoSamples. Otherwise Ok and `out` filled. All arithmetic exact (int64).
SetupOutcome setup_triangle(const Config& cfg, const DrawState& st, const SetupTriangle& tri, TriSetup& out);

}  // namespace fxr

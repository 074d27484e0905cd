// reference/reference.hpp — the references the model's error is measured against.
//
// 1. run_reference(): the same pipeline as the raster unit in double precision, with no
//    quantisation and no snapping: clip in double (0 ≤ z_c ≤ w_c, Sutherland–Hodgman, linear
//    interpolation of position and varyings in clip space), divide, viewport, coverage by double
//    edge functions at pixel centres with the top-left rule, depth linear in window space,
//    perspective-correct varyings (Σ λ_i v_i/w_i / Σ λ_i/w_i) or affine ones, depth test on
//    doubles. Its input is the same float32 clip-space triangles the model gets (widened to
//    double exactly), so the difference is the model's own error. Its coverage is NOT snapped:
//    a few coverage differences along edges are expected (reported, not failures).
// 2. reference_at_pixel(): the ideal value at a pixel centre for one input primitive,
//    independent of clipping: solve Σ b_i (x_i − x_n w_i) = 0, Σ b_i (y_i − y_n w_i) = 0,
//    Σ b_i = 1 for clip-space barycentrics b, then v = Σ b_i v_i, z = Σ b_i z_i / Σ b_i w_i.
// 3. Exact rational helpers (GMP mpq_class) on the model's own snapped vertices, for hard cases
//    and spot checks: the exact depth and perspective-correct varying at a pixel.
#pragma once

#include <cstdint>
#include <vector>

#include <gmpxx.h>

#include "model/config/config.hpp"
#include "model/stages/setup.hpp"
#include "model/unit/io.hpp"

namespace fxr {

struct RefFragment {
  int x = 0, y = 0;
  uint32_t prim = 0;
  double depth = 0;  // window z ∈ [0, 1]
  double var[kMaxVaryings] = {};
};

struct RefStats {
  uint64_t prims_in = 0, prims_drawn = 0, prims_culled_outside = 0, prims_culled_zero_area = 0,
           prims_culled_backface = 0, prims_culled_no_samples = 0, prims_rejected_nonfinite = 0,
           prims_varying_nonfinite = 0, fragments_generated = 0, fragments_depth_pass = 0,
           fragments_depth_fail = 0;
};

// Contract: the value a varying input stands for under the unit's rule for non-finite varyings
// (docs/pipeline.md, stage 1), in double: NaN → 0, ±Inf → ±FLT_MAX, a finite value itself.
// *replaced is set when a value was replaced.
double ref_varying_input(float f, bool* replaced);

struct RefFrame {
  int width = 0, height = 0;
  std::vector<RefFragment> fragments;  // passed the depth test, in draw order (as FrameOutput)
  std::vector<double> depth;           // final depth buffer, row 0 at the bottom, cleared to 1
  RefStats stats;
};

// Contract: double-precision ideal pipeline (see above). Primitives with a NaN or infinity in
// a position are rejected (counted); a NaN / infinity in a used varying is replaced
// (ref_varying_input, counted as prims_varying_nonfinite). Deterministic.
RefFrame run_reference(const DrawState& st, const std::vector<ClipTriangle>& tris);

struct RefSample {
  bool valid = false;  // false: singular system (edge-on triangle) or w ≤ 0 at the pixel
  double depth = 0;    // z_c / w_c at the pixel (window z)
  double w = 0;        // clip w at the pixel
  double var[kMaxVaryings] = {};
};

// Contract: ideal perspective-correct values of `tri` at window point (wx, wy) (pixel centre:
// (x + ½, y + ½)); exact up to double rounding, independent of clipping. Varyings through
// ref_varying_input.
RefSample reference_at_pixel(const DrawState& st, const ClipTriangle& tri, int num_varyings, double wx, double wy);

// Top-left fill rule in y-up window coordinates for a counter-clockwise (positive-area)
// triangle, edge from a to b with d = b − a: a sample exactly on the edge is inside iff the
// edge is a top edge (horizontal, interior below: d.y == 0 and d.x < 0) or a left edge
// (interior to its right: d.y < 0).
template <class T>
inline bool top_left_edge(T dx, T dy) {
  return dy < 0 || (dy == 0 && dx < 0);
}

// ---- exact rational helpers ------------------------------------------------------------------

mpq_class to_mpq(const FxFloat& f);  // exact value of an FxFloat

// An exact vertex: window x, y (pixels), window z ∈ [0, 1], 1/w and v/w (or v when affine).
struct ExactVertex {
  mpq_class x, y, z, rw, vw;
};

struct ExactSample {
  bool inside = false;  // covered under the top-left rule (exact edge functions)
  mpq_class z;          // depth: Σ λ_i z_i (λ normalised screen barycentrics)
  mpq_class v;          // Σ λ_i vw_i / Σ λ_i rw_i (perspective) or Σ λ_i vw_i (affine)
};

// Contract: exact screen barycentrics of the pixel centre (px + ½, py + ½) in the triangle
// (either orientation; zero area → inside = false, z = v = 0), then the exact depth and
// varying. No rounding anywhere.
ExactSample exact_at_pixel(const ExactVertex v[3], int px, int py, bool affine);

// The snapped vertex k of a setup triangle as exact rationals (x, y in pixels from the
// subpixel codes, z from z_frac_bits, rw and vw[var] from their FxFloats).
ExactVertex exact_vertex(const RasterConfig& rc, const SetupVertex& v, int var);

}  // namespace fxr

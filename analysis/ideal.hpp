// analysis/ideal.hpp — the exact judge of the IDEAL image (docs/pipeline.md, "Accuracy against the
// ideal"): for a pixel and an input primitive, the exact depth and perspective-correct varyings
// of the UNSNAPPED float32 clip-space triangle at the pixel centre, in rational arithmetic (GMP).
//
// Definition. The primitive's points are the clip-space affine combinations P = Σ b_i V_i
// (Σ b_i = 1) of its float32 vertices; clipping (exact) keeps a part of the same plane and
// interpolates varyings linearly in clip space, so the ideal value at a pixel does not depend
// on clipping. The pixel centre (px + ½, py + ½) has NDC (x_n, y_n); the point of the plane that
// projects there solves Σ b_i (x_i − x_n w_i) = 0, Σ b_i (y_i − y_n w_i) = 0, Σ b_i = 1, i.e.
// b ∝ n = a × c with a_i = x_i − x_n w_i, c_i = y_i − y_n w_i. Then
//     window depth  z = Σ n_i z_i / Σ n_i w_i,     varying  v = Σ n_i v_i / Σ n_i
// (the perspective-correct value of seeds 000 / 004 in clip-space form). Invalid when Σ n_i = 0
// (edge-on) or Σ n_i w_i / Σ n_i ≤ 0 (the point is behind the eye).
//
// Also here: the model's fragments as an image (streamed, with the primitive written last), the
// exact value on the model's own quantised triangle, error measures in D-bit LSBs and in ulps of
// a p-bit significand, and the scene suite of issue 8.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <gmpxx.h>

#include "model/config/config.hpp"
#include "model/unit/io.hpp"

namespace fxr {

struct IdealValue {
  bool valid = false;
  mpq_class z;                  // window depth z_c / w_c at the point (may leave [0, 1] off the triangle)
  mpq_class v[kMaxVaryings];    // perspective-correct varyings
};

// Exact ideal values of the primitives of one draw. Inputs are widened exactly (every float32
// times 2^149 is an integer), so nothing is rounded. NaN / Inf inputs give invalid values.
class IdealJudge {
 public:
  IdealJudge(const DrawState& st, const std::vector<ClipTriangle>& tris);
  // Contract: the ideal value of primitive `prim` at the centre of pixel (px, py); exact.
  IdealValue at(uint32_t prim, int px, int py) const { return eval(prim, px, py, true); }
  // Contract: |∂z/∂x| + |∂z/∂y| of the ideal window depth of `prim`, in units of the whole depth
  // range per pixel (depth is affine in window x, y: exact differences of three exact values,
  // converted to double). Negative when undefined (edge-on).
  double depth_gradient(uint32_t prim, int px, int py) const;

 private:
  struct V {
    mpz_class p[4];
    mpz_class v[kMaxVaryings];
    bool finite = true;
  };
  DrawState st_;
  std::vector<V> tris_;  // 3 per primitive
  void solve(uint32_t prim, const mpz_class& xnum, const mpz_class& ynum, mpz_class n[3]) const;
  // in_front: require the point to be in front of the eye (the gradient does not: window depth
  // is affine in x, y over the whole plane).
  IdealValue eval(uint32_t prim, int px, int py, bool in_front) const;
};

// The model's fragments as an image (last written per pixel, like the peer's readback):
// row 0 at the bottom, index y·width + x, window coordinates from 0.
struct ModelImage {
  int width = 0, height = 0, num_varyings = 0;
  std::vector<int32_t> prim;   // −1: none
  std::vector<uint32_t> depth; // unorm code
  std::vector<FxFloat> var;    // num_varyings per pixel
  RasterStats stats;
  size_t index(int x, int y) const { return (size_t)y * (size_t)width + (size_t)x; }
};
// Contract: run the raster unit (stages 1–10, streamed) on `tris` with `cfg`.
ModelImage model_image(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris);

// Contract: the exact depth and varyings at pixel (px, py) on the model's own quantised
// triangle of primitive `prim` (geometry() rebuilt with `cfg`; the piece whose exact coverage
// contains the pixel; vertices as the planes see them: window positions at
// raster.attr_subpixel_bits (= the snapped ones when attr_subpixel_bits = subpixel_bits), z at
// z_frac_bits, 1/w and v/w as quantised). valid = false when no piece covers the pixel.
IdealValue snapped_at(const Config& cfg, const DrawState& st, const ClipTriangle& tri, int px, int py);

// Error measures (for reports; the inputs are exact, the result is rounded to double).
double depth_err_lsb(const mpq_class& got_z, const mpq_class& ideal_z, int depth_bits);  // |Δz|·(2^db − 1)
double abs_err(const mpq_class& got, const mpq_class& ideal);
// |got − ideal| in ulps of ideal in a binary format with p significand bits (unbounded exponent);
// ideal = 0: −1 (no ulp).
double ulp_err(const mpq_class& got, const mpq_class& ideal, int p);
mpq_class to_mpq_float(float f);  // exact

// Order statistics of a list of errors (nearest rank; deterministic).
struct ErrSummary {
  uint64_t n = 0;
  double max = 0, p99 = 0, mean = 0;
  std::string str(int prec = 3) const;
};
ErrSummary summarize(std::vector<double> v);

// ---- the scene suite of issue 8 (deterministic; u, v ∈ [0, 16] as varyings 0, 1) -------------

struct IdealScene {
  std::string name;
  DrawState st;
  std::vector<ClipTriangle> tris;
};
// Grazing textured floor plane, fov 60°, near 0.1, square `size`; depth test on.
IdealScene ideal_grazing_plane(int size);
// Thin slivers in perspective (aspect > 100, w from 0.2 to 200); depth func always.
IdealScene ideal_slivers(int size);
// Triangles crossing the near plane (z_c < 0 at one or two vertices); depth func always.
IdealScene ideal_near_clipped(int size);
// w ratios from 10 up to 10^6 inside one triangle (perspective depth z_c = f/(f−n)·(w − n)).
IdealScene ideal_w_ratio(int size);
// Triangles about one pixel across, in perspective; depth func always.
IdealScene ideal_one_pixel(int size);

}  // namespace fxr

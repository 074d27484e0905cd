// model/stages/line_setup.hpp — stages 5L–7L for line segments (issue 15; docs/lines.md, "The line
// path"): line setup, line traversal (model/stages/line.hpp, rtl/fxr_line.sv) and the line
// interpolators, which hand the same PlaneSample record as the triangle interpolators to the
// depth stage (depth.hpp) and the divider (divide.hpp).
//
//   SetupLine → line_setup → LineEquations → line → LineFragment (n) → line_interp → PlaneSample
//
// Parameterisation (GL's, docs/references.md#gl-line-interp): the fragment at pixel centre p
// takes t = ((p − p_a)·(p_b − p_a)) / |p_b − p_a|², the projection of its centre onto the
// segment, clamped to [0, 1]; depth is (1 − t)·z_a + t·z_b and a varying
//   v = ((1 − t)·v_a/w_a + t·v_b/w_b) / ((1 − t)/w_a + t/w_b).
// In integers: E_1(p) = (p − p_a)·(p_b − p_a) and L² = |p_b − p_a|² on a grid with F fraction
// bits are exact; T = clamp(E_1, 0, L²) and the two weights W_0 = L² − T, W_1 = T (≥ 0, sum L²)
// play the role of the triangle's edge functions E_k (sum 2A): Z = Σ W_k·zq_k over
// den = L²·2^zs gives the depth code with ONE rounding, D = Σ W_k·R_k and N_m = Σ W_k·V_{m,k}
// (R, V on one block exponent, align_block) go to the divider. The roundings are the triangle
// path's: the block alignment, the divider's normalisation and quotient.
//
// Positions: the attribute positions ax, ay (raster.attr_subpixel_bits) when the triangle
// planes use them, else the snapped x, y on the sample grid (grid_bits); F = that many fraction
// bits unless line_param_frac_bits() must drop low bits (RNE) to keep every sum in its width.
// Zero length (L² = 0): t = 0, the first vertex's values.
#pragma once

#include <cstdint>
#include <vector>

#include "model/config/config.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/line.hpp"
#include "model/stages/line_geometry.hpp"
#include "model/stages/setup.hpp"
#include "model/unit/record.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// ---- widths (derived) --------------------------------------------------------------------------

// Signed bits of a per-vertex depth value zq (snapped: z·(2^db − 1); attribute path: that at
// z_frac_bits − db fraction bits, attr_depth_q).
inline int line_zq_bits(const RasterConfig& r) {
  return attr_planes(r) ? r.z_frac_bits + 2 : r.z_frac_bits + r.depth_bits() + 1;
}
// Fraction bits of the positions t is computed from: the source positions' (attribute or sample
// grid), limited so that with relative coordinates < 2^(W+F): L² and E_1 < 2^(2(W+F)+1) fit the
// planes' edge width, N = Σ W_k·V_k (|V| ≤ 2^B) and Z = Σ W_k·zq_k fit i128.
// ConfigError when fewer than 1 fraction bit would remain (not reachable within the ranges).
int line_param_frac_bits(const RasterConfig& r);
// Unsigned bits of L² and of the weights W_k: 2(W + F) + 1.
inline int line_weight_bits(const RasterConfig& r) { return 2 * (r.window_int_bits + line_param_frac_bits(r)) + 1; }

// ---- stage 5L: line setup ------------------------------------------------------------------------

// Stage 5L output: everything the line stages need of one segment.
struct LineEquations {
  uint32_t prim = 0;
  LineIn seg;                 // snapped coverage endpoints (subpixel_bits), p_a = (x0, y0)
  PixelRect rect;             // viewport ∩ scissor ∩ the window range: pixels kept
  int F = 1;                  // fraction bits of the parameter grid
  int64_t ox = 0, oy = 0;     // p_a on the parameter grid (absolute)
  int64_t dx = 0, dy = 0;     // p_b − p_a on the parameter grid
  i128 len2 = 1;              // L² = dx² + dy² (1 when zero: t = 0)
  int64_t zq[2] = {0, 0};     // per-vertex depth values (line_zq_bits)
  i128 zden = 1;              // L²·2^zs: code = RNE(Σ W_k·zq_k / zden)
  int64_t rq[2] = {0, 0};     // 1/w on the block exponent den_exp (affine: 1, 1)
  int den_exp = 0;
  int64_t vq[kMaxVaryings][2] = {};  // v/w on the block exponent num_exp[m]
  int num_exp[kMaxVaryings] = {};
  int n = 0;                  // varyings set up (0 when nothing downstream divides); not in visit():
                              // the line interpolators use their own count, as InterpStage does

  template <class V>
  void visit(V& v, const RecordShape& s) {
    const RasterConfig& r = s.cfg.raster;
    const int cb = r.window_int_bits + r.subpixel_bits, pb = r.window_int_bits + line_param_frac_bits(r);
    const int wb = line_weight_bits(r), eb = fx_exp_field_bits(s.cfg), bb = r.interp_block_bits + 1;
    v("prim", prim, kPrimIdBits, false);
    v("x0", seg.x0, cb, true);
    v("y0", seg.y0, cb, true);
    v("x1", seg.x1, cb, true);
    v("y1", seg.y1, cb, true);
    v("rect_x0", rect.x0, r.window_int_bits, true);
    v("rect_x1", rect.x1, r.window_int_bits, true);
    v("rect_y0", rect.y0, r.window_int_bits, true);
    v("rect_y1", rect.y1, r.window_int_bits, true);
    v("ox", ox, pb, true);
    v("oy", oy, pb, true);
    v("dx", dx, pb + 1, true);
    v("dy", dy, pb + 1, true);
    v("len2", len2, wb, false);
    v("zq0", zq[0], line_zq_bits(r), true);
    v("zq1", zq[1], line_zq_bits(r), true);
    v("zden", zden, wb + r.z_frac_bits, false);
    v("rq0", rq[0], bb, true);
    v("rq1", rq[1], bb, true);
    v("den_exp", den_exp, eb, true);
    for (int m = 0; m < s.num_varyings; ++m) {
      const std::string p = "vq" + std::to_string(m);
      v(p + "_0", vq[m][0], bb, true);
      v(p + "_1", vq[m][1], bb, true);
      v(p + "_exp", num_exp[m], eb, true);
    }
  }
  // The members that are configuration constants, not wires (model/vectors/record_vectors.hpp):
  // F is line_param_frac_bits of the configuration, n the number of varyings.
  void restore(const RecordShape& s) {
    F = line_param_frac_bits(s.cfg.raster);
    n = s.num_varyings;
  }
};

enum class LineSetupOutcome : uint8_t {
  Ok,
  RejectedRange,  // an endpoint outside the window format or z > 1 (the geometry stages never make one)
};

// Contract: stage 5L on one snapped segment (exact apart from align_block and the documented
// drop to F bits). `varyings` false: no 1/w, v/w values (n = 0).
LineSetupOutcome line_setup_equations(const Config& cfg, const DrawState& st, const SetupLine& in, bool varyings,
                                      LineEquations& out);

class LineSetupStage {
 public:
  static constexpr const char* kName = "line_setup";
  using In = SetupLine;
  using Out = LineEquations;

  LineSetupStage(const Config& cfg, const DrawState& st, bool with_varyings = true)
      : cfg_(cfg), st_(st), varyings_(with_varyings && st.num_varyings > 0) {
    (void)line_param_frac_bits(cfg.raster);  // ConfigError early
  }

  template <class Emit>
  LineSetupOutcome step(const In& in, Emit&& emit) {
    const LineSetupOutcome o = line_setup_equations(cfg_, st_, in, varyings_, out_);
    if (o == LineSetupOutcome::Ok) emit(static_cast<const Out&>(out_));
    return o;
  }

  // Planned RTL: the frame of fxr_line's set-up cycle, 3 products of the parameter grid (dx², dy²
  // and the first E_1), per vertex value the block alignment (shared with the triangle setup).
  static StageCost cost(const Config& cfg);

 private:
  const Config& cfg_;
  const DrawState& st_;
  bool varyings_;
  LineEquations out_;
};

// ---- stage 6L: line traversal ------------------------------------------------------------------

// Stage 6L output: one covered pixel of the segment, inside the draw rectangle.
struct LineFragment {
  uint32_t prim = 0;
  int32_t x = 0, y = 0;

  template <class V>
  void visit(V& v, const RecordShape& s) {
    v("prim", prim, kPrimIdBits, false);
    v("x", x, s.cfg.raster.window_int_bits, true);
    v("y", y, s.cfg.raster.window_int_bits, true);
  }
};

class LineTraverseStage {
 public:
  // The stage of rtl/fxr_line.sv and tb/line/ (one name, three places).
  static constexpr const char* kName = "line";
  using In = LineEquations;
  using Out = LineFragment;

  LineTraverseStage(const Config& cfg, const DrawState&) : rc_(cfg.raster), lc_(cfg.line) {}

  // 1 → n: the pixels of line_pixels (the configured rule, canonical order) that lie inside
  // in.rect; pixels outside are discarded here (the walk covers the whole snapped segment, as
  // fxr_line does). Returns the number emitted.
  template <class Emit>
  uint64_t step(const In& in, Emit&& emit) {
    uint64_t n = 0;
    out_.prim = in.prim;
    for (const LinePixel& p : line_pixels(rc_, lc_, in.seg)) {
      if (p.x < in.rect.x0 || p.x > in.rect.x1 || p.y < in.rect.y0 || p.y > in.rect.y1) continue;
      out_.x = p.x;
      out_.y = p.y;
      ++n;
      emit(static_cast<const Out&>(out_));
    }
    return n;
  }

  // rtl/fxr_line.sv (docs/lines.md: one set-up cycle, then one pixel per clock).
  static StageCost cost(const Config& cfg);

 private:
  RasterConfig rc_;
  LineConfig lc_;
  LineFragment out_;
};

// ---- stage 7L: line interpolators --------------------------------------------------------------

// Contract: the weight W_1 = clamp(E_1(centre(x, y)), 0, L²) of a pixel (exact).
i128 line_weight(const LineEquations& e, int32_t x, int32_t y);

class LineInterpStage {
 public:
  static constexpr const char* kName = "line_interp";
  using Context = LineEquations;
  using In = LineFragment;
  using Out = PlaneSample;

  LineInterpStage(const Config& cfg, const DrawState& st, bool with_varyings = true)
      : nv_(with_varyings ? st.num_varyings : 0), max_code_(depth_max_code(cfg.raster)) {}

  // 1 → 1: the depth code (one RNE of Σ W_k·zq_k / zden, clamped to the code range) and the exact
  // sums D = Σ W_k·R_k, N_m = Σ W_k·V_{m,k}.
  template <class Emit>
  void step(const Context& e, const In& in, Emit&& emit) {
    const i128 w1 = line_weight(e, in.x, in.y), w0 = e.len2 - w1;
    s_.prim = e.prim;
    s_.x = in.x;
    s_.y = in.y;
    i128 q, r;
    floor_divmod(w0 * (i128)e.zq[0] + w1 * (i128)e.zq[1], e.zden, q, r);
    const i128 c = rne_round_up<i128>(q, r, e.zden) ? q + 1 : q;
    s_.depth = (uint32_t)(c < 0 ? 0 : c > max_code_ ? max_code_ : c);
    const int nv = nv_;  // as InterpStage: the stage's own count (e.n is not part of the record)
    if (nv > 0) {
      s_.den = w0 * (i128)e.rq[0] + w1 * (i128)e.rq[1];
      s_.den_exp = e.den_exp;
      for (int m = 0; m < nv; ++m) {
        s_.num[m] = w0 * (i128)e.vq[m][0] + w1 * (i128)e.vq[m][1];
        s_.num_exp[m] = e.num_exp[m];
      }
    }
    emit(static_cast<const Out&>(s_));
  }

  // Planned RTL: E_1 stepped along the walk (adds of dx, dy·2^F per major / minor step), a clamp,
  // then per plane two products of the weights by the vertex values (W_0 = L² − W_1).
  static StageCost cost(const Config& cfg);

 private:
  int nv_;
  i128 max_code_;
  PlaneSample s_;
};

// ---- stages 8L, 9L: the depth test and the divider of the line path ------------------------------

// The triangles' depth stage and divider (the same hardware), named apart because segments are
// drawn with their own draw state (a scene's line_state: depth function, test, write): the
// transaction vectors (model/vectors/scene_dump.hpp) dump and re-step the line samples in files of
// their own, line_depth.* and line_divide.*, the depth test on the buffer the triangles left.
class LineDepthStage : public DepthStage {
 public:
  static constexpr const char* kName = "line_depth";
  using DepthStage::DepthStage;
};
class LineDivideStage : public DivideStage {
 public:
  static constexpr const char* kName = "line_divide";
  using DivideStage::DivideStage;
};

}  // namespace fxr

// model/stages/clip.hpp — stage 2: the clipper (trivial accept / reject, Sutherland–Hodgman in
// homogeneous clip space, exact intersections rounded once per component).
//
// Clip volume (D3D11 / Vulkan): w ≥ 2^kWMinExp (the "w > 0" plane), 0 ≤ z ≤ w, and a guard
// band for x and y: the region whose window coordinates still fit the snapped format
// (RasterConfig.window_int_bits signed integer bits, minus kGuardMarginPx). Every plane test is
// exact (integer arithmetic on the dyadic values); every new vertex component is the exact
// rational (c_E·d_S − c_S·d_E)/(d_S − d_E) rounded once, to nearest even, to a normalised
// significand of a named width. That value does not depend on the direction of the edge, so a
// shared edge of two triangles is clipped identically in both. docs/pipeline.md, stage 2.
#pragma once

#include <cstdint>

#include "model/config/config.hpp"
#include "model/stages/input.hpp"
#include "model/unit/io.hpp"

namespace fxr {

// Planes in the order Sutherland–Hodgman applies them. Inside means d ≥ 0.
enum ClipPlane : uint8_t { kPlaneWMin, kPlaneNear, kPlaneFar, kPlaneLeft, kPlaneRight,
                           kPlaneBottom, kPlaneTop, kNumClipPlanes };
const char* to_string(ClipPlane p);

// The "w > 0" plane is w ≥ 2^kWMinExp: below the smallest float32 denormal (2^−149), so no
// input vertex with w > 0 is ever clipped by it, yet every vertex that survives has a
// non-zero w for the reciprocal unit (D3D11: only w > 0 survives clipping).
inline constexpr int kWMinExp = -160;
// Clipper outputs whose leading one lies below 2^kClipFlushLeadExp are flushed to (signed)
// zero: the only precision lost besides the per-component rounding. Below every float32 value
// and below 2^kWMinExp, so w is never flushed.
inline constexpr int kClipFlushLeadExp = -192;
// Pixels kept between the guard band and the end of the window format. Covers the error of
// x_c·rcp(w_c) against x_c / w_c: |Δx_w| ≤ 2^window_int_bits · 2^−(recip.out_sig_bits−1) px,
// ≤ 2^−3 px for window_int_bits ≤ 20 and out_sig_bits ≥ 24, plus ½ subpixel of snapping.
inline constexpr int kGuardMarginPx = 1;
// A triangle clipped by all planes has at most 3 + kNumClipPlanes = 10 vertices when convex;
// rounded new vertices can make the polygon very slightly non-convex (a plane may then cross
// it more than twice), so the buffer has room to spare; exceeding it sets `overflow`.
inline constexpr int kClipMaxPolyVerts = 16;

// Guard band of a viewport, as exact integer plane coefficients:
//   x_w = (x_n + 1)·W/2 + X0 ∈ [−L, L] with L = 2^(window_int_bits−1) − kGuardMarginPx px
//   ⇔ n_left·w_c ≤ W·x_c ≤ n_right·w_c with n_left = 2(−L − X0) − W, n_right = 2(L − X0) − W
//   (likewise y with H, Y0). The band's NDC extent is the exact rational n/W.
// valid is false when the viewport is empty or does not lie inside [−L, L] (then the unit
// rejects every primitive with RejectedRange: no window coordinate could be represented).
struct GuardBand {
  bool valid = false;
  int64_t w = 0, h = 0;                  // viewport size in pixels
  int64_t n_left = 0, n_right = 0;       // x: n_left·w_c ≤ W·x_c ≤ n_right·w_c
  int64_t n_bottom = 0, n_top = 0;       // y: n_bottom·w_c ≤ H·y_c ≤ n_top·w_c
};

// Largest |window coordinate| in whole pixels the guard band admits: 2^(window_int_bits−1) − margin.
inline int64_t guard_limit_px(const RasterConfig& rc) {
  return (int64_t(1) << (rc.window_int_bits - 1)) - kGuardMarginPx;
}
// Contract: derives the guard band from the viewport and the window format (exact integers).
GuardBand guard_band(const RasterConfig& rc, const DrawState& st);

// Plane distance d = a·p[comp] + b·w_c − (wmin ? 2^kWMinExp : 0); inside when d ≥ 0.
struct PlaneEq {
  int comp = -1;  // 0 x, 1 y, 2 z, −1 none
  int64_t a = 0, b = 0;
  bool wmin = false;
};
PlaneEq plane_eq(const GuardBand& gb, ClipPlane p);

// Contract: exact sign (−1, 0, +1) of the plane distance of v. No rounding. In 64-bit words
// when both products fit (float32 inputs always), else plane_side_u128.
int plane_side(const PlaneEq& pl, const ClipVtx& v);
// The u128 path alone (not for the wmin plane): the reference of the 64-bit one.
int plane_side_u128(const PlaneEq& pl, const ClipVtx& v);
// Bit p set when v is strictly outside plane p (d < 0).
uint32_t outcode(const GuardBand& gb, const ClipVtx& v);

// Widths of the clipper's outputs (normalised significands, rounded to nearest even).
struct ClipWidths {
  int pos_sig_bits = 32;  // x_c, y_c, z_c and the varyings: RasterConfig.clip_sig_bits
  int w_sig_bits = 24;    // w_c: recip.in_sig_bits, so the reciprocal unit sees it unrounded
  int num_varyings = 0;
  // The RTL's cycle count (ClipPolygon::rtl_cycles): the record's significand width, which its
  // shift-and-add walks, and whether the record has the attribute w (only then is it made).
  int rtl_record_sig_bits = 32;
  bool rtl_with_wa = true;
};
ClipWidths clip_widths(const Config& cfg, int num_varyings);

// Contract: the point where edge s–e crosses plane pl (d_s and d_e of strictly opposite signs).
// Each component c = (c_e·d_s − c_s·d_e)/(d_s − d_e), computed exactly (multi-word integers),
// rounded once to nearest even to its width (precision is lost here, ≤ ½ ulp per component),
// flushed to zero below 2^kClipFlushLeadExp. Symmetric in s and e. *overflow is set if an
// internal bound was exceeded (cannot happen for float32 inputs; then the result is unusable).
ClipVtx clip_intersect(const ClipWidths& cw, const PlaneEq& pl, const ClipVtx& s, const ClipVtx& e,
                       bool* overflow, int64_t* rtl_cycles = nullptr);

// rtl/fxr_clip.sv's clocks per new vertex before its components: d_s, d_e (two terms each) and
// |d_s − d_e| normalised (docs/rtl.md, "fxr_clip"; the clock count of a clipped triangle is
// ClipPolygon::rtl_cycles).
inline constexpr int kClipRtlDistClocks = 5;

struct ClipPolygon {
  int n = 0;                       // number of vertices (0: clipped away)
  ClipVtx v[kClipMaxPolyVerts];
  int created = 0;                 // intersection vertices made (counted once per creation)
  bool overflow = false;
  int64_t rtl_cycles = 0;          // rtl/fxr_clip.sv's clocks from the input transfer to done
};

// Contract: Sutherland–Hodgman of triangle `in` against every plane that some current vertex
// is strictly outside of, in ClipPlane order. A vertex on a plane (d = 0) is inside and makes
// no new vertex. The output polygon is convex, in the input's winding; vertices are either
// input vertices or outputs of clip_intersect on an edge of the current polygon.
ClipPolygon clip_triangle(const GuardBand& gb, const ClipWidths& cw, const ClipVtx in[3]);

// ---- the stage ------------------------------------------------------------------------------

// Stage 2 output: one triangle inside the clip volume (an input triangle accepted whole, or one
// triangle of the fan of a clipped polygon). Only the active varyings are set.
using ClippedTriangle = ClipSpaceTriangle;

enum class ClipOutcome : uint8_t {
  Accepted,          // trivial accept: the input triangle, unchanged (1 output)
  Clipped,           // went through Sutherland–Hodgman: n − 2 ≥ 1 fan triangles
  CulledOutside,     // trivial reject: all three vertices outside one plane (0 outputs)
  ClippedAway,       // went through the clipper, nothing left (0 outputs)
  RejectedViewport,  // invalid viewport: no window coordinate is representable (0 outputs)
  RejectedOverflow,  // the clipper's internal bound (not reachable from float32 inputs)
};
struct ClipReport {
  ClipOutcome outcome = ClipOutcome::Accepted;
  int vertices_created = 0;  // intersections made (also when the result is rejected)
};

class ClipStage {
 public:
  static constexpr const char* kName = "clip";
  using In = ExactTriangle;
  using Out = ClippedTriangle;

  ClipStage(const Config& cfg, const DrawState& st)
      : gb_(guard_band(cfg.raster, st)), cw_(clip_widths(cfg, st.num_varyings)), nv_(st.num_varyings) {}

  // 1 → 0..n triangles. The fan (v0, v_i, v_i+1) of the clipped polygon keeps the input's
  // winding.
  template <class Emit>
  ClipReport step(const In& in, Emit&& emit) {
    ClipReport r;
    rtl_cycles_ = 1;  // the trivial cases: one clock (the RTL's fast path)
    if (!gb_.valid) return r.outcome = ClipOutcome::RejectedViewport, r;
    const uint32_t oc0 = outcode(gb_, in.v[0]), oc1 = outcode(gb_, in.v[1]), oc2 = outcode(gb_, in.v[2]);
    if (oc0 & oc1 & oc2) return r.outcome = ClipOutcome::CulledOutside, r;  // all outside one plane
    out_.prim = in.prim;
    if ((oc0 | oc1 | oc2) == 0) {  // trivial accept: all inside every plane, no clipper
      for (int i = 0; i < 3; ++i) copy_clip_vertex(in.v[i], out_.v[i], nv_);
      emit(static_cast<const Out&>(out_));
      return r;
    }
    const ClipPolygon poly = clip_triangle(gb_, cw_, in.v);
    r.vertices_created = poly.created;
    rtl_cycles_ = poly.rtl_cycles;
    if (poly.overflow) return r.outcome = ClipOutcome::RejectedOverflow, r;
    if (poly.n < 3) return r.outcome = ClipOutcome::ClippedAway, r;  // clip_triangle gives 0 or ≥ 3
    r.outcome = ClipOutcome::Clipped;
    for (int i = 1; i + 1 < poly.n; ++i) {
      copy_clip_vertex(poly.v[0], out_.v[0], nv_);
      copy_clip_vertex(poly.v[i], out_.v[1], nv_);
      copy_clip_vertex(poly.v[i + 1], out_.v[2], nv_);
      emit(static_cast<const Out&>(out_));
    }
    return r;
  }

  // RTL (rtl/fxr_clip.sv): 21 exact plane-side units (2 multipliers each) for the one-clock
  // trivial accept / reject (latency 1, II 1), and one iterative clipper: a side unit, a
  // sequential exact-distance term (one multiplier), an MSB-first shift-and-add numerator and a
  // restoring divider. A clipped triangle occupies the stage rtl_cycles() clocks.
  static StageCost cost(const Config& cfg);
  // Clocks the last step()'s input occupied rtl/fxr_clip.sv (input transfer to done, without
  // output back-pressure): 1 for the trivial cases, ClipPolygon::rtl_cycles for a clipped one.
  int64_t rtl_cycles() const { return rtl_cycles_; }

 private:
  GuardBand gb_;
  ClipWidths cw_;
  int nv_;
  int64_t rtl_cycles_ = 0;
  ClippedTriangle out_;
};

}  // namespace fxr

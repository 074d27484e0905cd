// model/stages/viewport.hpp — stage 4: perspective divide (exact products with stage 3's 1/w),
// viewport transform and snapping. From a clipped vertex (exact dyadic x_c, y_c, z_c, w_c,
// varyings) and its 1/w to a SetupVertex. (project_vertex: stages 3 + 4 for one vertex.)
//
// Which snapping the model is (docs/references.md#snapping: float32 divide + float32 viewport formula differs from
// exact rounding for ~3 % of vertices at 4096 px): the model snaps the EXACT value of
// ((x_c·r + 1)·W/2 + X0)·2^subpixel_bits, r = recip(w_c) the reciprocal unit's output, with ONE
// round to nearest even. x_c·r is an exact product: no rounding happens between the
// reciprocal unit and the snap. docs/pipeline.md, stages 3 and 4.
#pragma once

#include <algorithm>
#include <cstdint>

#include "model/config/config.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/recip_stage.hpp"
#include "model/stages/setup.hpp"
#include "model/unit/io.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// An exact product of two FxFloats: (−1)^neg · sig · 2^exp with a 128-bit significand.
struct FxProd {
  bool neg = false;
  u128 sig = 0;
  int exp = 0;
};

// Significand bits an FxProd may carry into the snap arithmetic: the snap multiplies it by the
// viewport size (< 2^(window_int_bits+1) ≤ 2^21) inside an i128 (127 value bits), so ≤ 100.
inline constexpr int kSnapProdMaxBits = 100;

// Contract: exact a·b. Requires msb(a.sig) + msb(b.sig) < 127 (≤ 64 + 62 bits: always true for
// FxFloat significands ≤ 63 bits). No rounding.
FxProd mul_exact(const FxFloat& a, const FxFloat& b);

// Contract: RNE((m·2^e + c) · 2^−sh), exact (a guard bit and a sticky bit stand for the bits
// of m·2^e below the integer point). m: |m| < 2^122; c: |c| < 2^100; sh ≥ 0.
// *range is set (result unusable) when m·2^e does not fit 2^120.
i128 round_scaled_sum(i128 m, int e, i128 c, int sh, bool* range);

// Contract: snapped window coordinate in subpixel units:
//   RNE(((n + 1)·size/2 + origin) · 2^subpixel_bits), one rounding from the exact n.
// Range: the result must fit a signed (window_int_bits + subpixel_bits)-bit code; otherwise
// *range is set (cannot happen inside the guard band; see kGuardMarginPx).
int64_t snap_window(const FxProd& n, int64_t size, int64_t origin, const RasterConfig& rc, bool* range);

// The i128 reference of snap_window, which takes round_scaled_sum64 when its range test passes
// (docs/speed.md "Session 9: per triangle"; tests/model/attr_fast64_test.cpp runs both).
int64_t snap_window_wide(const FxProd& n, int64_t size, int64_t origin, const RasterConfig& rc, bool* range);

// The 64-bit path's bound on |m| (round_scaled_sum64).
inline constexpr int kSnapFast64Bits = 60;
// Contract: true when |m| < 2^kSnapFast64Bits, |c| < 2^(kSnapFast64Bits − 1), 0 ≤ sh ≤ 60 and
// |m·2^e| < 2^(kSnapFast64Bits − 1) (e ≥ 0) or −e ≤ kSnapFast64Bits (e < 0); *out is then
// round_scaled_sum(m, e, c, sh) (never out of range). false: nothing written.
bool round_scaled_sum64(int64_t m, int e, int64_t c, int sh, int64_t* out);

// Contract: depth code RNE(z_n · 2^z_frac_bits), saturated to [0, 2^z_frac_bits] (z_n can leave
// [0, 1] by the reciprocal's rounding and the clipper's rounding of z and w separately).
uint64_t snap_depth(const FxProd& zn, const RasterConfig& rc);

// Contract: RNE of p to a normalised `bits`-bit significand FxFloat (precision lost: ½ ulp).
FxFloat round_prod(const FxProd& p, int bits);

enum class ProjectStatus : uint8_t { Ok, RecipError, Range };

// Contract: stages 3 + 4 for one vertex inside the clip volume (w_c ≥ 2^kWMinExp).
//   r = recip(cfg.recip, w_c normalised to recip.in_sig_bits) (exact for float32 and clipper
//   outputs); x, y: snap_window(x_c·r); z: snap_depth(z_c·r); rw = r;
//   vw_k = RNE(v_k·r) to raster.varying_sig_bits (Affine: RNE(v_k) to the same width).
//   RecipError: the unit flagged a zero divisor or an exponent overflow. Range: a snapped
//   coordinate outside the window format. `out` is complete only for Ok.
ProjectStatus project_vertex(const Config& cfg, const DrawState& st, const ClipVtx& v, SetupVertex& out);

// Contract: stage 4 for one vertex with r = 1/w_c from the reciprocal unit (the part of
// project_vertex after the reciprocal): Ok or Range. `out` is complete only for Ok.
ProjectStatus snap_vertex(const Config& cfg, const DrawState& st, const ClipVtx& v, const FxFloat& r,
                          SetupVertex& out);
// Contract: snap_vertex without its zero fill of the varyings past st.num_varyings: out.vw[k],
// k ≥ num_varyings, are left as they are (the vertex cache, whose triangle keeps them zero from
// its construction: model/unit/vertex_cache.hpp; the fill was 336 bytes per computed vertex at
// 2 varyings, docs/speed.md "Session 11: per triangle"). Otherwise snap_vertex's.
// rw_unread: a consumer that reads no rw (a chain whose draw has no varyings: setup builds no
// 1/w plane then) — with separate attribute positions out.rw is then 0 instead of the exact
// quotient 1/w_c, a division per vertex saved (docs/speed.md "Session 12: per triangle"); the
// other fields are snap_vertex's. Without attribute positions rw = r costs nothing and is kept.
ProjectStatus snap_vertex_active(const Config& cfg, const DrawState& st, const ClipVtx& v, const FxFloat& r,
                                 SetupVertex& out, bool rw_unread = false);

// ---- the stage ------------------------------------------------------------------------------

// Divider lanes of stage 4 in the RTL (fxr_viewport's Lanes, fxr_raster_unit's ViewportLanes):
// emitted into fxr_rec_pkg as ViewportLanes, the RTL's default (one source).
inline constexpr int kViewportLanes = 3;

// Quotient bits of the stage-4 dividers (rtl/fxr_viewport_core.sv QuotBits): the widest of
// ax / ay (window_int_bits + attr_subpixel_bits + 5: two fraction bits, guard, range), z
// (z_frac_bits + 4) and the floats rw, vw_k (attr_sig_bits + 2: guard and sticky).
inline int viewport_quot_bits(const RasterConfig& r) {
  const int qxy = r.window_int_bits + r.attr_subpixel_bits + 5, qz = r.z_frac_bits + 4, qf = r.attr_sig_bits + 2;
  return std::max(qxy, std::max(qz, qf));
}

enum class ViewportOutcome : uint8_t {
  Emitted,
  RejectedRange,  // a snapped coordinate outside the window format (not reachable inside the
                  // guard band, see kGuardMarginPx)
};

class ViewportStage {
 public:
  static constexpr const char* kName = "viewport";
  using In = RecipTriangle;
  using Out = SetupTriangle;

  ViewportStage(const Config& cfg, const DrawState& st) : cfg_(cfg), st_(st) {}

  // 1 → 0..1: the snapped triangle.
  template <class Emit>
  ViewportOutcome step(const In& in, Emit&& emit) {
    out_.prim = in.prim;
    for (int i = 0; i < 3; ++i)
      if (snap_vertex(cfg_, st_, in.v[i], in.r[i], out_.v[i]) != ProjectStatus::Ok) return ViewportOutcome::RejectedRange;
    emit(static_cast<const Out&>(out_));
    return ViewportOutcome::Emitted;
  }

  // The RTL's cost (rtl/fxr_viewport_core.sv; docs/rtl.md, "fxr_viewport"): with the attribute
  // path (attr_separate, the default) a triangle's J = 3·(4 + num_varyings) correctly rounded
  // quotients run on `lanes` pipelined restoring dividers of viewport_quot_bits(cfg) stages:
  // ii = ⌈J / lanes⌉ clocks per triangle, latency = ii + viewport_quot_bits(cfg) + 3 clocks.
  // Without it (not built in RTL): the planned products (latency 3, ii 1). num_varyings: the
  // record package's (the RTL's NumVaryings); lanes: fxr_raster_unit's ViewportLanes.
  static StageCost cost(const Config& cfg, int num_varyings = kRecordPackageVaryings, int lanes = kViewportLanes);

 private:
  const Config& cfg_;
  const DrawState& st_;
  SetupTriangle out_;
};

}  // namespace fxr

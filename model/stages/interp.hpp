// model/stages/interp.hpp — stage 7 (interpolators): z, 1/w and every v/w at the pixel centre.
// The planes are built in setup (model/stages/setup.hpp), the divide is stage 9
// (model/stages/divide.hpp). docs/pipeline.md, stages 7 and 9.
//
// Everything the unit interpolates is an affine function of the pixel (i, j) with exact
// integer coefficients: for per-vertex integers Q_k,
//     P(i, j) = Σ_k E_k(centre(i, j)) · Q_k = c + i·dx + j·dy           (a "plane", i128)
// where E_k are the unbiased edge functions of setup (E_k / 2A is the barycentric weight of
// vertex k). The perspective-correct varying is (docs/references.md#seed-000-rational, #seed-004; the 2A cancels)
//     v = Σ E_k·vw_k / Σ E_k·rw_k = N / D,
// with vw_k = v_k/w_k and rw_k = 1/w_k. N and D are exact integer planes once the three vw_k
// (and the three rw_k) are put on one block exponent: the only roundings are
//   (1) block alignment (align_block): RNE to raster.interp_block_bits, exact while the lead
//       exponents of the three values differ by ≤ interp_block_bits − significand bits;
//   (2) normalising |N| and D to the divider's num_bits / den_bits significands (RNE);
//   (3) the divider itself (model/arith/div.hpp: RNE of its quotient to quot_bits).
// Affine mode (InterpMode::Affine, the wrong image of docs/references.md#seed-000-wrong-image): vw_k holds v_k itself and D = 2A.
#pragma once

#include <algorithm>
#include <cstdint>

#include "model/config/config.hpp"
#include "model/arith/div.hpp"
#include "model/arith/fxfloat.hpp"
#include "model/arith/round.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/unit/record.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// div.quot_bits is derived from raster.varying_out_sig_bits (model/config/validate.hpp:
// derive_widths; validate() rejects a configuration where they differ).

// ---- z: exact stepping of the depth code (derivation in model/stages/depth.hpp) -------------

// floor(a / d) with remainder in [0, d): floor_divmod (model/arith/fixed.hpp).

// Exact stepping of RNE(Z / den) along +x, in the integer type T (i128: the reference; int64_t:
// the fast path, used only where depth_step_fits64 proves every value of the span fits).
template <class T>
struct DepthStepperT {
  T q = 0, r = 0, dq = 0, dr = 0, den = 1, max_code = 0;
  DepthStepperT() = default;
  void step_x() {
    q += dq;
    r += dr;
    if (r >= den) r -= den, q += 1;
  }
  // Round to nearest, ties to even.
  // Clamped to [0, max_code] (acts only on attribute planes, see DepthSetup).
  uint32_t code() const {
    const T c = rne_round_up<T>(q, r, den) ? q + 1 : q;
    return (uint32_t)(c < 0 ? 0 : c > max_code ? max_code : c);
  }
};
struct DepthStepper : DepthStepperT<i128> {
  DepthStepper(const DepthSetup& s, int i, int j) {
    den = s.den;
    max_code = s.max_code;
    floor_divmod(s.z.at(i, j), den, q, r);
    floor_divmod(s.z.dx, den, dq, dr);
  }
};

// Wide-to-narrow test (docs/speed.md "Depth stepper"): true when `steps` calls of step_x from
// dz keep every value of DepthStepperT<int64_t> exact: den, max_code < 2^61 (so r, r + dr < 2den
// and 2r < 2^62), |q| + steps·(|dq| + 1) < 2^61 (q moves by dq or dq + 1 per step; c ≤ q + 1).
inline bool depth_step_fits64(const DepthStepperT<i128>& dz, int64_t steps) {
  const i128 lim = (i128)1 << 61;
  if (steps < 0 || dz.den >= lim || dz.max_code >= lim || dz.dr < 0 || dz.r < 0) return false;
  const i128 aq = dz.q < 0 ? -dz.q : dz.q, adq = dz.dq < 0 ? -dz.dq : dz.dq;
  if (aq >= lim || adq >= lim) return false;
  return aq + (i128)steps * (adq + 1) < lim;
}
inline DepthStepperT<int64_t> narrow64(const DepthStepperT<i128>& w) {
  DepthStepperT<int64_t> n;
  n.q = (int64_t)w.q, n.r = (int64_t)w.r, n.dq = (int64_t)w.dq, n.dr = (int64_t)w.dr;
  n.den = (int64_t)w.den, n.max_code = (int64_t)w.max_code;
  return n;
}

// ---- the stage ------------------------------------------------------------------------------

// Quotient bits per clock of the span-start divisions in rtl/fxr_interp.sv (its parameter
// DivStepsPerClock; a micro-architecture choice, not a configuration field: docs/rtl.md).
inline constexpr int kInterpDivStepsPerClock = 8;

// Stage 7 output: the planes at one pixel centre — the depth code (raster.depth_bits(), rounded
// once, RNE), the 1/w sum D = den·2^den_exp and the v/w sums N_m = num[m]·2^num_exp[m] (exact,
// signed interp_plane_bits), the exponents being the triangle's block exponents.
struct PlaneSample {
  uint32_t prim = 0;
  int32_t x = 0, y = 0;
  uint32_t depth = 0;
  i128 den = 0;
  int den_exp = 0;
  i128 num[kMaxVaryings] = {};
  int num_exp[kMaxVaryings] = {};

  template <class V>
  void visit(V& v, const RecordShape& s) {
    const RasterConfig& r = s.cfg.raster;
    visit_pixel_fields(v, s, prim, x, y, depth);
    v("den", den, interp_plane_bits(r), true);
    v("den_exp", den_exp, fx_exp_field_bits(s.cfg), true);
    for (int m = 0; m < s.num_varyings; ++m) {
      const std::string p = "num" + std::to_string(m);
      v(p, num[m], interp_plane_bits(r), true);
      v(p + "_exp", num_exp[m], fx_exp_field_bits(s.cfg), true);
    }
  }
};

class InterpStage {
 public:
  static constexpr const char* kName = "interp";
  using Context = TriangleEquations;  // the triangle's planes, latched once per triangle
  using In = Span;
  using Out = PlaneSample;

  // with_varyings false: only the depth code (D and N are left 0).
  InterpStage(const Config&, const DrawState& st, bool with_varyings = true)
      : nv_(with_varyings ? st.num_varyings : 0) {}

  // 1 → n: one sample per pixel of the span, left to right. The planes are evaluated directly
  // at the span start and stepped exactly along x (every stepped value is the direct value).
  template <class Emit>
  void step(const Context& t, const In& in, Emit&& emit) {
    const int nv = nv_;
    DepthStepper dz(t.depth, in.x0, in.y);
    s_.prim = t.prim;
    s_.y = in.y;
    if (nv > 0) {
      s_.den = t.interp.den.at(in.x0, in.y);
      s_.den_exp = t.interp.den_exp;
      for (int m = 0; m < nv; ++m) {
        s_.num[m] = t.interp.num[m].at(in.x0, in.y);
        s_.num_exp[m] = t.interp.num_exp[m];
      }
    }
    // The depth code stepped in int64_t where the span provably fits (depth_step_fits64),
    // else in i128: the same codes (DepthStep64.* in tests/model/interp_test.cpp).
    const auto run = [&](auto& z) {
      for (int i = in.x0; i <= in.x1; ++i) {
        s_.x = i;
        s_.depth = z.code();
        emit(static_cast<const Out&>(s_));
        z.step_x();
        if (nv > 0) {
          s_.den += t.interp.den.dx;
          for (int m = 0; m < nv; ++m) s_.num[m] += t.interp.num[m].dx;
        }
      }
    };
    if (depth_step_fits64(dz, (int64_t)in.x1 - in.x0 + 1)) {
      DepthStepperT<int64_t> z = narrow64(dz);
      run(z);
    } else {
      run(dz);
    }
  }

  // rtl/fxr_interp.sv: the planes evaluated at the span start, the depth quotient / remainder
  // by a sequential divider, then one pixel per clock (interp.cpp; docs/rtl.md, "fxr_interp").
  static StageCost cost(const Config& cfg) { return cost(cfg, kInterpDivStepsPerClock); }
  // With `div_steps_per_clock` quotient bits per clock (fxr_interp's DivStepsPerClock as an
  // instance sets it: the back end's InterpDivSteps, ArchConfig::interp_div_steps).
  static StageCost cost(const Config& cfg, int div_steps_per_clock);

  // The data-dependent part for one span (the cycle model, docs/cycles.md): rtl/fxr_interp.sv's
  // restoring divider iterates only the quotient's own bits, msb(|dividend|) − msb(den) + 1 (0
  // when |dividend| < 2^msb(den)), for Z at the span start and for z_dx side by side; the front
  // spends max(1, ⌈longer / div_steps_per_clock⌉) clocks dividing, so a span occupies it
  // 2 + that (accept / normalise, divide, hand over in the clock the next span is accepted).
  static int span_div_clocks(const Context& t, const In& in, int div_steps_per_clock) {
    auto msb = [](i128 v) {
      unsigned __int128 u = v < 0 ? (unsigned __int128)(-v) : (unsigned __int128)v;
      int b = -1;
      while (u != 0) u >>= 1, ++b;
      return b;  // −1 for 0
    };
    const int md = msb(t.depth.den);
    int bits = 0;
    for (const i128 v : {t.depth.z.at(in.x0, in.y), t.depth.z.dx}) {
      const int mv = msb(v);
      if (mv >= 0 && mv >= md) bits = std::max(bits, mv - md + 1);
    }
    return std::max(1, (bits + div_steps_per_clock - 1) / div_steps_per_clock);
  }
  static int span_front_clocks(const Context& t, const In& in, int div_steps_per_clock) {
    return 2 + span_div_clocks(t, in, div_steps_per_clock);
  }

 private:
  int nv_;
  PlaneSample s_;
};

}  // namespace fxr

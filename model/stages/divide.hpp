// model/stages/divide.hpp — stage 9 (divider): per pixel and varying v = (v/w) / (1/w) = N / D,
// from the plane sums of stage 7 (model/stages/interp.hpp) to the output varyings. The
// quotient is the divider of model/arith/div.hpp (rtl/fxr_div.sv). docs/pipeline.md, stage 9.
#pragma once

#include <cstdint>

#include "model/arith/div.hpp"
#include "model/arith/fxfloat.hpp"
#include "model/config/config.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/recip_stage.hpp"
#include "model/unit/io.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// Contract (stage 9): the varying N·2^en / (D·2^ed) as a normalised FxFloat with
// div.quot_bits (= raster.varying_out_sig_bits) significand bits.
//   D > 0 (always inside a triangle with all rw_k > 0); D ≤ 0 or N == 0 → zero (sig 0).
//   |N| is rounded (RNE) to div.num_bits and D to div.den_bits significant bits — PRECISION
//   IS LOST HERE when they have more bits — then div_sig rounds the quotient (RNE).
//   Sign-magnitude: the divider sees magnitudes, the sign of N is the result's sign.
struct DenNorm {
  uint64_t d = 0;  // D's significand, msb at den_bits − 1
  int e = 0;       // msb index of D (after rounding carry) + ed
};
inline DenNorm normalize_den(const DivConfig& dc, i128 D, int ed) {
  DenNorm r;
  if (D <= 0) return r;
  const Normalized nd = normalize((u128)D, dc.den_bits, Round::HalfEven);
  r.d = nd.sig;
  r.e = nd.exp + ed;
  return r;
}
inline FxFloat divide_varying(const DivConfig& dc, i128 N, int en, const DenNorm& dn) {
  FxFloat out;
  if (N == 0 || dn.d == 0) return out;
  out.neg = N < 0;
  const u128 mag = N < 0 ? (u128)0 - (u128)N : (u128)N;
  const Normalized nn = normalize(mag, dc.num_bits, Round::HalfEven);
  const DivSig q = div_sig(dc, nn.sig, dn.d);
  // value = sig·2^−(qb−1)·2^exp_adj · 2^(msb N + en) / 2^(msb D + ed)
  out.sig = q.sig;
  out.exp = q.exp_adj + (nn.exp + en) - dn.e - (dc.quot_bits - 1);
  return out;
}

// ---- the stage ------------------------------------------------------------------------------

class DivideStage {
 public:
  static constexpr const char* kName = "divide";
  using In = PlaneSample;
  using Out = Fragment;

  // with_varyings false: fragments without varyings (nothing is divided).
  DivideStage(const Config& cfg, const DrawState& st, bool with_varyings = true)
      : dc_(cfg.div), nv_(with_varyings ? st.num_varyings : 0) {}

  // 1 → 1: the fragment (position, depth code, varyings var[0 … num_varyings−1]).
  template <class Emit>
  void step(const In& in, Emit&& emit) {
    f_.x = in.x;
    f_.y = in.y;
    f_.depth = in.depth;
    f_.prim = in.prim;
    if (nv_ > 0) {
      const DenNorm dn = normalize_den(dc_, in.den, in.den_exp);
      for (int m = 0; m < nv_; ++m) f_.var[m] = divide_varying(dc_, in.num[m], in.num_exp[m], dn);
    }
    emit(static_cast<const Out&>(f_));
  }

  // The divider's own cost (div_cost, rtl/fxr_div.sv) for one varying lane.
  static StageCost cost(const Config& cfg) { return as_stage_cost(div_cost(cfg.div)); }

 private:
  DivConfig dc_;
  int nv_;
  Fragment f_;
};

}  // namespace fxr

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
//   div.algorithm = shared_recip: the reciprocal of D's significand is computed once per pixel
//   (normalize_den, div_recip) and every varying is one multiply rounded once (div_mul_round):
//   the same values as div_sig per varying, within div_bound() of the exact quotient of the
//   rounded operands, not correctly rounded (docs/arith.md "shared_recip").
struct DenNorm {
  uint64_t d = 0;  // D's significand, msb at den_bits − 1
  int e = 0;       // msb index of D (after rounding carry) + ed
  uint64_t y = 0;  // shared_recip: div_recip(d), once per pixel (else 0)
};
inline DenNorm normalize_den(const DivConfig& dc, i128 D, int ed) {
  DenNorm r;
  if (D <= 0) return r;
  const Normalized nd = normalize((u128)D, dc.den_bits, Round::HalfEven);
  r.d = nd.sig;
  r.e = nd.exp + ed;
  if (dc.algorithm == DivAlgorithm::SharedRecip) r.y = div_recip(dc, r.d);
  return r;
}
inline FxFloat divide_varying(const DivConfig& dc, i128 N, int en, const DenNorm& dn) {
  FxFloat out;
  if (N == 0 || dn.d == 0) return out;
  out.neg = N < 0;
  const u128 mag = N < 0 ? (u128)0 - (u128)N : (u128)N;
  const Normalized nn = normalize(mag, dc.num_bits, Round::HalfEven);
  // div_sig_fast64 is div_sig for radix2 at W + qb ≤ 63 (the defaults), inline (docs/speed.md).
  const DivSig q = dc.algorithm == DivAlgorithm::SharedRecip ? div_mul_round(dc, nn.sig, dn.d, dn.y)
                   : div_fast64_ok(dc)                       ? div_sig_fast64(dc, nn.sig, dn.d)
                                                             : div_sig(dc, nn.sig, dn.d);
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
      : dc_(cfg.div), nv_(with_varyings ? st.num_varyings : 0), memo_(st.interp == InterpMode::Affine) {}

  // 1 → 1: the fragment (position, depth code, varyings var[0 … num_varyings−1]).
  template <class Emit>
  void step(const In& in, Emit&& emit) {
    f_.x = in.x;
    f_.y = in.y;
    f_.depth = in.depth;
    f_.prim = in.prim;
    if (nv_ > 0) {
      // Affine mode: D = 2A is one value per triangle; its normalisation (and shared_recip's
      // reciprocal) is kept while D and its exponent repeat (docs/speed.md "Shortcuts").
      if (!memo_ || in.den != memo_den_ || in.den_exp != memo_exp_ || !memo_valid_) {
        dn_ = normalize_den(dc_, in.den, in.den_exp);
        memo_den_ = in.den, memo_exp_ = in.den_exp, memo_valid_ = true;
      }
      for (int m = 0; m < nv_; ++m) f_.var[m] = divide_varying(dc_, in.num[m], in.num_exp[m], dn_);
    }
    emit(static_cast<const Out&>(f_));
  }

  // The divider's own cost (div_cost, rtl/fxr_div.sv) for one varying lane; the whole stage
  // (rtl/fxr_divide.sv) at a number of varyings and lanes: divide_cost below.
  static StageCost cost(const Config& cfg) { return as_stage_cost(div_cost(cfg.div)); }

 private:
  DivConfig dc_;
  int nv_;
  bool memo_;  // affine mode
  bool memo_valid_ = false;
  i128 memo_den_ = 0;
  int memo_exp_ = 0;
  DenNorm dn_;
  Fragment f_;
};

// Cost of rtl/fxr_divide.sv (stage 9) with `lanes` divider lanes for `num_varyings` varyings
// (lanes ≤ num_varyings; the RTL's default is lanes = num_varyings):
//   latency = lane latency + 3 (the sample register, the normalised group register, the lanes,
//   the output register; the lane latency is div_cost's) + (groups − 1) (the fragment's last
//   group is issued that much later), ii = groups = ⌈num_varyings / lanes⌉ (pipelined lanes);
//   per_varying (radix2, recip_mul): `lanes` dividers (div_cost each);
//   shared_recip: one reciprocal core (seed ROM, NR multipliers) and per lane one (W+1) × F
//   product, compare, increment and clamps (div_cost's shared_recip figures are one lane).
//   Plus (1 + lanes) normalisers of a plane sum (leading-one search, shift, RNE increment).
// ff_bits estimates the registers: the lanes', the sample, the normalised group, the sideband
// FIFO (2^⌈log2(lane latency + 2)⌉ entries), the fragment accumulator and the output.
inline StageCost divide_cost(const Config& cfg, int num_varyings, int lanes) {
  const DivConfig& c = cfg.div;
  const StageCost lane = div_cost(c);
  StageCost k;
  const int groups = (num_varyings + lanes - 1) / lanes;
  k.latency = lane.latency + 3 + (groups - 1) * lane.ii;  // the last group issues groups − 1 later
  k.ii = lane.ii * groups;
  const int w = div_align_bits(c);
  if (c.algorithm == DivAlgorithm::SharedRecip) {
    k.table_bits = lane.table_bits;
    for (const auto& m : recip_core_multipliers(div_recip_core_shape(c))) k.add_mult(m.first, m.second);
    for (int l = 0; l < lanes; ++l) k.add_mult(w + 1, c.nr_frac_bits);
    k.adder_bits = lanes * lane.adder_bits;
    k.ff_bits = lane.ff_bits + (lanes - 1) * (lane.latency * (w + 1 + 2) + c.quot_bits + 2);
  } else {
    k.table_bits = (int64_t)lanes * lane.table_bits;
    for (int l = 0; l < lanes; ++l)
      for (const auto& m : lane.multipliers) k.add_mult(m.first, m.second);
    k.adder_bits = lanes * lane.adder_bits;
    k.ff_bits = lanes * lane.ff_bits;
  }
  const int ipb = interp_plane_bits(cfg.raster), eb = fx_exp_field_bits(cfg);
  k.adder_bits += (1 + lanes) * (ipb + c.num_bits + 1) + lanes * 3 * (eb + 4);  // negate, RNE, exponents
  int fifo = 1;
  while (fifo < lane.latency + 2) fifo *= 2;
  const int64_t pix = record_bits<Fragment>(cfg, 0);
  const int64_t sideband = pix + lanes * (2 + eb + 4) + 2;
  k.ff_bits += record_bits<PlaneSample>(cfg, num_varyings) + lanes * c.num_bits + c.den_bits + sideband +
               fifo * sideband + 2 * record_bits<Fragment>(cfg, num_varyings);
  return k;
}

}  // namespace fxr

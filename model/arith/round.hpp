// model/arith/round.hpp — the model's one round-to-nearest-even decision and the one
// "increment and renormalise" step of a rounded significand (docs/arith.md "# Shared arithmetic").
//
// Every RNE in the model goes through rne_round_up: fixed.hpp's shift_round (Round::HalfEven),
// the divider's quotient rounding (div.cpp), the reciprocal's remainder correction (recip.cpp),
// the depth code (stages/depth.hpp). The RTL twin is rtl/fxr_round.sv, which takes the same
// three-way comparison as two flags (t_neg_i, t_zero_i).
#pragma once

#include <cstdint>

namespace fxr {

// Contract: a value v = q + φ with q an integer and the fraction φ compared with ½:
//   frac_vs_half < 0 (φ < ½), == 0 (φ = ½, a tie), > 0 (φ > ½).
//   Returns true when round-to-nearest, ties to even, gives q + 1 (else q). No overflow: a
//   decision only. Valid for any φ ∈ [−½, 1) (a candidate q one above the floor, φ < 0, rounds
//   to q unless φ = −½, which a caller must not pass).
constexpr bool rne_round_up(int frac_vs_half, bool q_odd) {
  return frac_vs_half > 0 || (frac_vs_half == 0 && q_odd);
}

// Contract: the same decision for v = q + r/den, 0 ≤ r < den, den > 0, in any integer type T
//   (uint64_t, u128, i128) where 2r does not overflow: up when 2r > den, or 2r = den and q odd.
template <class T>
constexpr bool rne_round_up(T q, T r, T den) {
  const T two_r = r + r;
  return rne_round_up(two_r > den ? 1 : (two_r == den ? 0 : -1), (q & 1) != 0);
}

// A significand with an exponent adjustment: value = sig · 2^−(bits−1) · 2^exp_adj.
struct RoundedSig {
  uint64_t sig = 0;
  int exp_adj = 0;
  bool operator==(const RoundedSig& o) const { return sig == o.sig && exp_adj == o.exp_adj; }
  bool operator!=(const RoundedSig& o) const { return !(*this == o); }
};

// Contract: q ∈ [2^(bits−1), 2^bits) a significand of `bits` bits (1 ≤ bits ≤ 63) with
//   exponent adjustment exp_adj; up = the rounding decision. Returns q + up; when that carries
//   out (q + 1 = 2^bits) it renormalises to sig = 2^(bits−1), exp_adj + 1. Exact.
constexpr RoundedSig round_increment(uint64_t q, bool up, int bits, int exp_adj) {
  const uint64_t s = q + (up ? 1 : 0);
  if (s == (uint64_t{1} << bits)) return {uint64_t{1} << (bits - 1), exp_adj + 1};
  return {s, exp_adj};
}

}  // namespace fxr

// model/arith/round_flat.hpp — round.hpp's round-to-nearest-even decision and fixed.hpp's RNE
// right shift formed without a conditional branch, for callers whose rounded fraction is
// data-dependent: the per-vertex quotients and snaps (model/stages/attr.cpp, viewport.cpp), where
// the compiler's branch on 2r > den was mispredicted about once a call (docs/speed.md "Session
// 13: per vertex and per triangle"). The same decisions and values as rne_round_up and
// shift_round_right(…, Round::HalfEven): tests/model/fixed_test.cpp runs both on exhaustive small
// operands, the int64 ends and random ones; tests/model/fixed_slow_test.cpp on 10^8.
#pragma once

#include "model/arith/fixed.hpp"
#include "model/arith/round.hpp"

namespace fxr {

// Contract: rne_round_up(q, r, den) — the same decision on the same domain (0 ≤ r < den, 2r
//   does not overflow T) — from the comparison flags, without a conditional branch.
template <class T>
constexpr bool rne_round_up_flat(T q, T r, T den) {
  const T two_r = r + r;
  return (two_r > den) | ((two_r == den) & ((q & 1) != 0));
}

namespace detail {

// Contract: shift_round_right<S, U>(x, shift, Round::HalfEven) — the same value for the same
//   arguments (1 ≤ shift ≤ bits(S) − 2) — without a conditional branch.
template <class S, class U>
inline S shift_round_right_rne_flat(S x, int shift) {
  const S floor_q = x >> shift;                   // arithmetic shift: floor
  const U rem = (U)x & ((((U)1) << shift) - 1);   // [0, 2^shift)
  const U half = ((U)1) << (shift - 1);
  return floor_q + (S)rne_round_up_flat<U>((U)floor_q, rem, half << 1);  // + 1 fits: |floor_q| ≤ |x| / 2
}

}  // namespace detail
}  // namespace fxr

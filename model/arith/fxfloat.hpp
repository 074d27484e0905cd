// model/arith/fxfloat.hpp — stage 1 (input conversion): float32 bits → exact integer values.
//
// An FxFloat is the exact dyadic number (−1)^neg · sig · 2^exp with an integer significand
// (sig == 0 means zero; exp is then irrelevant). Every finite float32 is exactly an FxFloat
// with sig < 2^24, so input conversion loses nothing: the first rounding of the model happens
// in a later stage and is documented there. Infinities and NaN are classified, never converted.
#pragma once

#include <cstdint>
#include <cstring>

#include "model/arith/fixed.hpp"

namespace fxr {

struct FxFloat {
  bool neg = false;
  uint64_t sig = 0;  // magnitude significand (integer)
  int exp = 0;       // value = (−1)^neg · sig · 2^exp

  bool is_zero() const { return sig == 0; }
  // Exponent of the leading one (IEEE-style unbiased exponent): value ∈ [2^e, 2^(e+1)).
  int lead_exp() const { return exp + msb_index(sig); }
};

// float32 layout, named once.
inline constexpr int kF32FracBits = 23;                    // stored fraction bits
inline constexpr int kF32SigBits = kF32FracBits + 1;       // significand with the hidden one
inline constexpr int kF32ExpBits = 8;
inline constexpr int kF32ExpBias = 127;
inline constexpr int kF32ExpMax = (1 << kF32ExpBits) - 1;  // all-ones exponent: Inf / NaN

enum class F32Class : uint8_t { Zero, Denormal, Normal, Inf, NaN };

struct F32Decoded {
  F32Class cls = F32Class::Zero;
  FxFloat value;  // exact for Zero / Denormal / Normal; sign only for Inf / NaN
};

inline uint32_t f32_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}
inline float f32_from_bits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

// Contract: decodes IEEE-754 binary32 bits exactly.
//   Normal: sig = 2^23 | frac (24 bits), exp = E − 127 − 23.
//   Denormal: sig = frac (< 2^23, not normalised), exp = −126 − 23 (exact, nothing flushed).
//   Zero: sig = 0, neg = sign bit (−0 keeps its sign). Inf / NaN: cls says so, sig = 0.
inline F32Class decode_f32_to(uint32_t bits, FxFloat& v);
inline F32Decoded decode_f32(uint32_t bits) {
  F32Decoded d;
  d.cls = decode_f32_to(bits, d.value);
  return d;
}
// The same, the value written into `v` (every member: the class returned). For a caller that
// keeps the value in place (convert_vertex: a returned F32Decoded copied into the vertex stalled
// on store forwarding, docs/speed.md "Session 10: per triangle").
inline F32Class decode_f32_to(uint32_t bits, FxFloat& v) {
  const bool neg = bits >> 31;
  const int e = (int)((bits >> kF32FracBits) & kF32ExpMax);
  const uint32_t frac = bits & ((1u << kF32FracBits) - 1);
  v.neg = neg;
  if (e == kF32ExpMax) {
    v.sig = 0;
    v.exp = 0;
    return frac ? F32Class::NaN : F32Class::Inf;
  }
  if (e == 0) {
    v.sig = frac;
    v.exp = 1 - kF32ExpBias - kF32FracBits;
    return frac ? F32Class::Denormal : F32Class::Zero;
  }
  v.sig = (1u << kF32FracBits) | frac;
  v.exp = e - kF32ExpBias - kF32FracBits;
  return F32Class::Normal;
}

// Contract: rescales x to a significand of exactly `bits` bits with its msb set
// (sig ∈ [2^(bits−1), 2^bits)), rounding by r when bits are dropped (a carry-out renormalises).
// Zero stays zero. Exact when x has at most `bits` significant bits.
inline FxFloat normalize_fx(FxFloat x, int bits, Round r) {
  if (x.sig == 0) return x;
  const Normalized n = normalize(x.sig, bits, r);
  FxFloat y;
  y.neg = x.neg;
  y.sig = n.sig;
  y.exp = x.exp + n.exp - (bits - 1);
  return y;
}

}  // namespace fxr

// model/stages/texaddr.hpp — the texture address unit (issue 15, docs/texaddr.md): a fragment's
// texture coordinates (u, v as FxFloat codes) and the texture size → texel addresses, nearest
// or bilinear, with the wrap modes of docs/references.md#seed-002-wrap plus mirrored repeat and
// clamp to border (the seed's constant background colour, docs/references.md#seed-002-lookup).
//
// Per axis (u with size W; v with size H alike), exactly, in integers:
//   nearest:  i0 = floor(u·W)                         (texel k covers [k/W, (k+1)/W): the
//             seed's round(u·W − ½) except at exact ties, docs/references.md#seed-002-lookup)
//   bilinear: T  = RNE((u·W − ½) · 2^F)               F = weight_frac_bits; the one rounding
//             i0 = floor(T / 2^F), i1 = i0 + 1, weight = T mod 2^F ∈ [0, 2^F)
//             The weight of texel i1 is weight / 2^F, of texel i0 (2^F − weight) / 2^F: the
//             fraction of u·W − ½ correctly rounded (nearest, ties to even). A fraction that
//             rounds up to 1 carries into i0 (weight 0, same blend), so weight < 2^F always.
// Wrap, applied to each of i0, i1 (any integer, mathematical modulo):
//   repeat:           i mod W
//   mirrored_repeat:  m = i mod 2W; m < W ? m : 2W − 1 − m     (OpenGL MIRRORED_REPEAT)
//   clamp_to_edge:    clamp(i, 0, W − 1)                         (the seed's clamp)
//   clamp_to_border:  border = (i < 0 or i ≥ W); index = clamp(i, 0, W − 1) (a defined value;
//                     the caller uses the background colour for a border texel)
// For nearest, i1 = i0, border1 = border0 and weight = 0.
//
// Special cases (no overflow for any exponent):
//   zero (either sign): u = 0 → nearest texel 0; bilinear i0 = −1, weight = 2^(F−1).
//   negative u: the same formulas (floor toward −∞, mathematical modulo).
//   huge |u| (exp ≥ 1): u·W is changed by a multiple of 2W when exp is replaced by 1 (sig·W·2^exp
//     − sig·W·2 = sig·W·2·(2^(exp−1) − 1)), which no wrap mode sees (repeat has period W,
//     mirrored repeat 2W; clamping sees only the sign since |u| ≥ 2 either way): the unit
//     computes with min(exp, 1), exactly.
//   tiny |u| (exp ≪ 0): the right shift of sig·W is capped at sig_bits + size_bits + 2 bits,
//     where δ = |sig·W·2^−shift| < ¼ already: floor(±δ − o) and RNE(±δ − o) for the integer
//     offset o (0, or 2^(F−1) for bilinear) depend only on the sign of δ, before and after the cap.
// Formats: sig < 2^sig_bits (normalised: msb set, or zero), size ∈ [1, 2^size_bits]; the RTL
// reads exp as a signed exp_bits field (value = sig · 2^exp). The widest product,
// sig · W · 2^(1+F), has sig_bits + size_bits + F + 1 ≤ 65 bits (i128 here).
#pragma once

#include <cstdint>

#include "model/arith/fxfloat.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

enum class TexFilter : uint8_t { Nearest, Bilinear };
enum class TexWrap : uint8_t { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder };

struct TexAddrConfig {
  int sig_bits = 24;         // significand of u, v incl. the leading one (derived: = raster.varying_out_sig_bits)
  int exp_bits = 10;         // signed exponent of the significand's lsb (value = sig · 2^exp)
  int size_bits = 12;        // texture width / height ≤ 2^size_bits (4096)
  int weight_frac_bits = 8;  // bilinear weight fraction bits F (8: an RGBA8 blend step)
  TexFilter filter = TexFilter::Nearest;
  TexWrap wrap = TexWrap::Repeat;

  template <class V>
  void visit(V& v) {
    v.integer("sig_bits", sig_bits, 8, 32, "significand bits of u, v incl. the leading one");
    v.integer("exp_bits", exp_bits, 6, 16, "signed exponent bits of u, v (exponent of the significand's lsb)");
    v.integer("size_bits", size_bits, 1, 16, "texture width and height are at most 2^size_bits");
    v.integer("weight_frac_bits", weight_frac_bits, 1, 16, "fraction bits of the bilinear weights (correctly rounded)");
    v.choice("filter", filter, {"nearest", "bilinear"},
             "texture filter: one texel, or four texels and two weights (render's shaded image; render --filter)");
    v.choice("wrap", wrap, {"repeat", "mirrored_repeat", "clamp_to_edge", "clamp_to_border"},
             "wrap mode outside [0, 1): modulo, mirrored modulo, edge texel, border (background) colour");
  }
};

bool operator==(const TexAddrConfig& a, const TexAddrConfig& b);
inline bool operator!=(const TexAddrConfig& a, const TexAddrConfig& b) { return !(a == b); }

// One axis of the result.
struct TexAxis {
  uint32_t i0 = 0, i1 = 0;       // texel indices in [0, size)
  bool border0 = false, border1 = false;  // clamp_to_border: the texel lies outside the texture
  uint32_t weight = 0;           // weight of i1, F fraction bits, in [0, 2^F); 0 for nearest
  bool operator==(const TexAxis& o) const {
    return i0 == o.i0 && i1 == o.i1 && border0 == o.border0 && border1 == o.border1 && weight == o.weight;
  }
};

struct TexAddrIn {
  FxFloat u, v;
  uint32_t width = 1, height = 1;
};

struct TexAddrOut {
  TexAxis s, t;  // s: along u (width), t: along v (height)
};

// Contract: see the file comment. size outside [1, 2^size_bits] or sig ≥ 2^sig_bits: throws
// std::invalid_argument (the caller's texture and varying formats are configured to fit).
TexAxis texaddr_axis(const TexAddrConfig& cfg, const FxFloat& u, uint32_t size);
TexAddrOut texaddr(const TexAddrConfig& cfg, const TexAddrIn& in);

// Validates cfg alone (validate(cfg, "tex_addr"), model/config/validate.hpp); throws ConfigError.
void texaddr_validate(const TexAddrConfig& cfg);

// Cost of the RTL rtl/fxr_texaddr.sv (docs/texaddr.md): one cycle per fragment.
StageCost texaddr_cost(const TexAddrConfig& cfg);

}  // namespace fxr

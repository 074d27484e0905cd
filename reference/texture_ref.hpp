// reference/texture_ref.hpp — the references of texture addressing and filtering (docs/texaddr.md):
// the exact address of a rational coordinate (GMP: what the texture address unit must give, and
// the unrounded weight it approximates), the double texture sample of the reference image, and
// the unrounded colour blend both are judged with.
//
// The rules (docs/texaddr.md), per axis of `size` texels, without any rounding:
//   nearest:  i0 = floor(u·size), weight 0
//   bilinear: i0 = floor(u·size − ½), frac = (u·size − ½) − i0 ∈ [0, 1) is the weight of i0 + 1
//   wrap of every index: repeat, mirrored repeat, clamp to edge, clamp to border (flag).
#pragma once

#include <array>
#include <cstdint>

#include <gmpxx.h>

#include "frontend/texture.hpp"
#include "model/stages/texaddr.hpp"

namespace fxr {

// One axis of a reference address: wrapped indices, border flags, the weight of i1 as a double.
struct RefTexAxis {
  uint32_t i0 = 0, i1 = 0;
  bool border0 = false, border1 = false;
  double weight = 0;
};

// ---- exact (GMP) -------------------------------------------------------------------------------

// The exact address of u along an axis of `size` texels: the unwrapped i0 and the exact fraction
// (0 for nearest).
struct ExactTexAxis {
  mpz_class i0;
  mpq_class frac;
};
ExactTexAxis exact_tex_axis(TexFilter filter, const mpq_class& u, uint32_t size);

// The wrap mode on an unwrapped index (mathematical modulo on mpz).
void exact_wrap(TexWrap wrap, const mpz_class& i, uint32_t size, uint32_t* idx, bool* border);

// Contract: the correctly rounded result the unit must produce for the exact coordinate u:
// bilinear weight RNE(frac · 2^F) (a fraction that rounds to 2^F carries into i0, weight 0),
// indices wrapped. *i0_unwrapped (optional) receives the unwrapped i0 after the carry.
TexAxis exact_tex_axis_rounded(const TexAddrConfig& cfg, const mpq_class& u, uint32_t size,
                               mpz_class* i0_unwrapped = nullptr);

// Contract: the exact (unrounded) reference address of u: wrapped indices of the exact i0, i0 + 1
// (nearest: i1 = i0) and frac as a double.
RefTexAxis exact_ref_axis(TexFilter filter, TexWrap wrap, const mpq_class& u, uint32_t size);

// ---- double (the reference image) --------------------------------------------------------------

// Contract: the rules above on a double coordinate (floor and fraction in double; the modulo by
// fmod, exact on integers). NaN, ±Inf or u·size beyond double: index 0, weight 0 (the reference
// image's choice).
RefTexAxis ref_tex_axis(TexFilter filter, TexWrap wrap, double u, uint32_t size);

// Contract: the correctly rounded address on a double coordinate, as exact_tex_axis_rounded:
// bilinear weight = round-half-even(frac · 2^F) with the carry into i0 + 1 at 2^F. *x_out
// (optional) receives the double u·size (− ½ for bilinear), *i0_out the unwrapped i0 after the
// carry. Non-finite u·size: as ref_tex_axis (x = 0).
TexAxis ref_tex_axis_rounded(const TexAddrConfig& cfg, double u, uint32_t size, double* x_out = nullptr,
                             double* i0_out = nullptr);

// ---- the colour -------------------------------------------------------------------------------

// Contract: the unrounded blend per channel (R, G, B, A in 8-bit levels) of the four texels
// (s.i_a, t.i_b) with weights (1 − s.weight, s.weight) × (1 − t.weight, t.weight); a texel with a
// border flag along either axis is `border`. Nearest addresses (i1 = i0, weight 0) give the texel.
std::array<double, 4> blend_ref(const Image& tex, uint32_t border, const RefTexAxis& s, const RefTexAxis& t);

// The blend rounded to 8 bits per channel (nearest, ties away from zero) and packed: the pixel of
// the double reference image.
uint32_t pack_blend(const std::array<double, 4>& c);

}  // namespace fxr

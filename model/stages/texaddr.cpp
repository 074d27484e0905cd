// Texture address unit (issue 15): FxFloat u, v and the texture size → texel indices, border
// flags and bilinear weights, exactly in integers. Contract and rules: model/stages/texaddr.hpp,
// docs/texaddr.md.
#include "model/stages/texaddr.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "model/arith/fixed.hpp"
#include "model/config/param.hpp"
#include "model/config/validate.hpp"

namespace fxr {

namespace {

// Exponents ≥ kExpReduced are replaced by kExpReduced: u·W then changes by a multiple of 2W,
// the period of mirrored repeat (and a multiple of W, the period of repeat); clamping sees the
// same sign and |u| ≥ 2 (texaddr.hpp, "huge |u|").
constexpr int kExpReduced = 1;
// Extra right-shift bits beyond the widest magnitude sig·W (< 2^(sig_bits+size_bits)) at which
// δ = |sig·W·2^−shift| < ¼: floor(±δ − offset) and RNE(±δ − offset) (offset an integer, or the
// bilinear −½ of F = 1 scaled to an integer) depend only on the sign of δ, as for any larger shift.
constexpr int kShiftCapMargin = 2;

// Pipeline registers of rtl/fxr_texaddr.sv: the output register.
constexpr int kOutputStages = 1;

// Mathematical modulo of x into [0, m).
i128 mod_floor(i128 x, i128 m) {
  const i128 r = x % m;
  return r < 0 ? r + m : r;
}

// One index through the wrap mode (texaddr.hpp, "Wrap").
void wrap_index(TexWrap wrap, i128 i, uint32_t size, uint32_t* idx, bool* border) {
  const i128 w = size;
  *border = false;
  switch (wrap) {
    case TexWrap::Repeat: *idx = (uint32_t)mod_floor(i, w); return;
    case TexWrap::MirroredRepeat: {
      const i128 m = mod_floor(i, 2 * w);
      *idx = (uint32_t)(m < w ? m : 2 * w - 1 - m);
      return;
    }
    case TexWrap::ClampToBorder: *border = i < 0 || i >= w; [[fallthrough]];
    case TexWrap::ClampToEdge: *idx = (uint32_t)(i < 0 ? 0 : (i >= w ? w - 1 : i)); return;
  }
}

// ±sig·size·2^(min(exp, 1) + extra) − offset rounded to an integer with r (Trunc = floor, or
// HalfEven); offset is an integer, subtracted exactly before the rounding.
i128 scale_round(const TexAddrConfig& c, const FxFloat& u, uint32_t size, int extra, i128 offset, Round r) {
  const int e = std::min(u.exp, kExpReduced) + extra;
  const i128 mag = (i128)u.sig * size;  // < 2^(sig_bits + size_bits), exact
  const i128 x = u.neg ? -mag : mag;
  if (e >= 0) return x * ((i128)1 << e) - offset;  // |x·2^e| < 2^(sig_bits + size_bits + 1 + F) ≤ 2^65 (no shift of a negative)
  const int s = std::min(-e, c.sig_bits + c.size_bits + kShiftCapMargin);
  // offset·2^s < 2^(F − 1 + sig_bits + size_bits + 2) ≤ 2^65: exact in i128.
  return shift_round(x - (offset << s), s, r);  // the unit's one rounding (floor or RNE)
}

}  // namespace

bool operator==(const TexAddrConfig& a, const TexAddrConfig& b) { return params_equal(a, b); }

void texaddr_validate(const TexAddrConfig& c) { validate(c, "tex_addr"); }

TexAxis texaddr_axis(const TexAddrConfig& c, const FxFloat& u, uint32_t size) {
  if (size < 1 || (uint64_t)size > (uint64_t{1} << c.size_bits))
    throw std::invalid_argument("texaddr: texture size " + std::to_string(size) + " outside [1, 2^" +
                                std::to_string(c.size_bits) + "]");
  if (u.sig >> c.sig_bits)
    throw std::invalid_argument("texaddr: significand wider than sig_bits " + std::to_string(c.sig_bits));
  TexAxis a;
  if (c.filter == TexFilter::Nearest) {
    const i128 i = scale_round(c, u, size, 0, 0, Round::Trunc);  // floor(u·W)
    wrap_index(c.wrap, i, size, &a.i0, &a.border0);
    a.i1 = a.i0;
    a.border1 = a.border0;
    return a;
  }
  const int f = c.weight_frac_bits;
  // T = RNE(u·W·2^F − 2^(F−1)): the offset is subtracted before rounding (for F = 1 it is odd
  // and would flip the tie parity if subtracted after). Precision is lost here only.
  const i128 t = scale_round(c, u, size, f, (i128)1 << (f - 1), Round::HalfEven);
  const i128 i0 = t >> f;  // arithmetic shift: floor
  a.weight = (uint32_t)(t & (((i128)1 << f) - 1));
  wrap_index(c.wrap, i0, size, &a.i0, &a.border0);
  wrap_index(c.wrap, i0 + 1, size, &a.i1, &a.border1);
  return a;
}

TexAddrOut texaddr(const TexAddrConfig& c, const TexAddrIn& in) {
  return {texaddr_axis(c, in.u, in.width), texaddr_axis(c, in.v, in.height)};
}

StageCost texaddr_cost(const TexAddrConfig& c) {
  texaddr_validate(c);
  StageCost r;
  r.latency = kOutputStages;
  r.ii = 1;
  const int prod = c.sig_bits + c.size_bits;  // sig · W
  r.multipliers = {{c.sig_bits, c.size_bits + 1}, {c.sig_bits, c.size_bits + 1}};
  for (const auto& [x, y] : r.multipliers) r.mult_bits += (int64_t)x * y;
  // Per axis: the shifter to F fraction bits, the rounding increment, the two modulo
  // reductions / clamps of i0 and i1 (size_bits + 1 wide each).
  r.adder_bits = 2 * ((prod + c.weight_frac_bits) + 4 * (c.size_bits + 1));
  r.ff_bits = 2 * (2 * c.size_bits + 2 + c.weight_frac_bits);
  return r;
}

}  // namespace fxr

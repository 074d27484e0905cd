// model/stages/texfilter.hpp — texel fetch and filter (issue 15, docs/texaddr.md, "Texel fetch
// and filter"): the texel addresses of the texture address unit (model/stages/texaddr.hpp) and
// an RGBA8 texture → the fragment's colour, in integer arithmetic.
//
// Per 8-bit channel c, with F = tex_addr.weight_frac_bits, the weights of the texture address
// unit ws = s.weight, wt = t.weight (weight of i1 along each axis, F fraction bits) and the four
// texels c_ab = texel(s.i_a, t.i_b) (a, b ∈ {0, 1}):
//     c = RNE( ((2^F − ws)(2^F − wt)·c_00 + ws(2^F − wt)·c_10 + (2^F − ws)·wt·c_01 + ws·wt·c_11) / 2^(2F) )
// one rounding (to nearest, ties to even); the four weights sum to 2^(2F), so c ∈ [0, 255].
// A texel whose border flag is set along either axis (clamp_to_border) is the border colour
// (the seed's constant colour outside the unit square, docs/references.md#seed-002-lookup).
// Nearest is the same formula: the unit gives i1 = i0 and weight 0, so c = c_00 exactly.
// Widths: the sum has 2F + kTexChannelBits bits (≤ 40 at F = 16): uint64.
#pragma once

#include <cstdint>

#include "model/stages/texaddr.hpp"

namespace fxr {

// RGBA8 texel layout: 0xAABBGGRR, channel k in bits [8k, 8k + 8).
inline constexpr int kTexChannelBits = 8;
inline constexpr int kTexChannels = 4;

// A texture's texels, row-major, row 0 at v = 0: texel (x, y) is rgba[y · width + x].
struct TexelView {
  const uint32_t* rgba = nullptr;
  uint32_t width = 0, height = 0;
};

// Contract: the filtered colour of one fragment (formula above). addr must come from texaddr()
// with the same cfg on a texture of tex.width × tex.height (its indices are then in range and are
// read unchecked). Exact except the one RNE per channel.
uint32_t texfilter(const TexAddrConfig& cfg, const TexAddrOut& addr, const TexelView& tex, uint32_t border_rgba);

}  // namespace fxr

// Texel fetch and filter (model/stages/texfilter.hpp, docs/texaddr.md).
#include "model/stages/texfilter.hpp"

#include "model/arith/fixed.hpp"

namespace fxr {

uint32_t texfilter(const TexAddrConfig& cfg, const TexAddrOut& a, const TexelView& tex, uint32_t border) {
  const int f = cfg.weight_frac_bits;
  const uint64_t one = uint64_t{1} << f;
  const uint64_t ws[2] = {one - a.s.weight, a.s.weight}, wt[2] = {one - a.t.weight, a.t.weight};
  const uint32_t si[2] = {a.s.i0, a.s.i1}, ti[2] = {a.t.i0, a.t.i1};
  const bool sb[2] = {a.s.border0, a.s.border1}, tb[2] = {a.t.border0, a.t.border1};
  uint32_t texel[2][2];
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      texel[j][i] = sb[i] || tb[j] ? border : tex.rgba[(size_t)ti[j] * tex.width + si[i]];
  constexpr uint32_t kMask = (1u << kTexChannelBits) - 1;
  uint32_t out = 0;
  for (int k = 0; k < kTexChannels; ++k) {
    uint64_t sum = 0;  // < 2^(2F + kTexChannelBits)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) sum += ws[i] * wt[j] * ((texel[j][i] >> (kTexChannelBits * k)) & kMask);
    const uint32_t c = (uint32_t)shift_round((i128)sum, 2 * f, Round::HalfEven);  // the one rounding
    out |= c << (kTexChannelBits * k);
  }
  return out;
}

}  // namespace fxr

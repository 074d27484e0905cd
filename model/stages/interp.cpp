// Stage 7 (interpolators). Contracts in model/stages/interp.hpp; the planes are set up in
// model/stages/setup.cpp.
#include <string>

#include "model/stages/interp.hpp"

namespace fxr {

StageCost InterpStage::cost(const Config& cfg, int div_steps_per_clock) {
  // rtl/fxr_interp.sv (docs/rtl.md, "fxr_interp"), per plane of the record (1/w and kMaxVaryings
  // v/w; the RTL has the generated record's number) and the depth code. Front: the planes at the
  // span start, c + (x0 − i0)·dx + (y − j0)·dy, in the accepting clock ((window_int_bits + 1) ×
  // plane-width products); then the two floor divisions Z / den and z_dx / den in a restoring
  // divider, div_steps_per_clock quotient bits per clock after one normalising clock, over
  // the quotient's own bits only (about depth_bits + 1 for Z, the depth code); one clock hands
  // the span start to the back and accepts the next span. Back: one sample per clock (plane +=
  // dx; the depth quotient / remainder DDA; RNE and clamp of the code). Latency 3 + n, n =
  // ceil((depth_bits + 1) / div_steps_per_clock); a span occupies the front 2 + n clocks
  // (ii) and the back one clock per pixel (the two overlap).
  const RasterConfig& r = cfg.raster;
  const int ipb = interp_plane_bits(r), zpb = depth_plane_bits(r), zdb = depth_den_bits(r);
  const int pb = r.window_int_bits, np = kMaxVaryings + 1;
  const int n = (r.depth_bits() + 1 + div_steps_per_clock - 1) / div_steps_per_clock;
  StageCost c;
  c.latency = 3 + n;
  c.ii = 2 + n;
  for (int p = 0; p < np; ++p) {
    c.add_mult(pb + 1, ipb);  // (x0 − i0)·dx
    c.add_mult(pb + 1, ipb);  // (y − j0)·dy
  }
  c.add_mult(pb + 1, zpb);
  c.add_mult(pb + 1, zpb);
  // Start sums and offsets, the divider lanes (subtract + compare per step), the sign fix, the
  // steps along x, the remainder DDA and the code's rounding / clamp.
  c.adder_bits = (int64_t)np * (2 * ipb + 2 * (pb + 1)) + 2 * zpb + 2 * (pb + 1) +
                 2 * (int64_t)div_steps_per_clock * zpb + 2 * (zpb + zdb) + (int64_t)np * ipb +
                 zpb + 2 * (zdb + 1) + 2 * (zdb + 1) + zpb + 2 * (zpb + 1);
  // Front: planes and dx, the lanes' remainder / shifted divisor / quotient; back: planes and dx,
  // q, dq, r, dr, den, the pixel fields.
  c.ff_bits = 2 * (int64_t)np * ipb + 6 * (int64_t)zpb + zdb + 2 * (int64_t)np * ipb + 2 * zpb + 3 * zdb +
              record_bits<Span>(cfg, 0) + kPrimIdBits + 2 * pb;
  return c;
}

}  // namespace fxr

// model/stages/depth.hpp — stage 8 (depth): the depth code of a pixel and the depth test.
// docs/pipeline.md, stage 8.
//
// z is affine in window space (D3D, Vulkan): z = Σ E_k·z_k / 2A with z_k the per-vertex
// z_c/w_c (raster.z_frac_bits fraction bits). The unorm code is ONE rounding of the exact
// rational value: code = RNE(z · (2^depth_bits − 1)) = RNE(Z / Qd) with the integer plane
// Z = Σ E_k·(z_k·(2^depth_bits − 1)) and Qd = 2A·2^z_frac_bits. The quotient and remainder are
// stepped exactly along a span (a Bresenham-style DDA), so the per-pixel cost is two adds and
// a compare. Inside a triangle z is a convex combination of z_k ∈ [0, 1], so the code is in
// [0, 2^depth_bits − 1] without clamping.
#pragma once

#include <cstdint>

#include "model/arith/round.hpp"
#include "model/stages/interp.hpp"

namespace fxr {

// The maximum depth code (buffer clear value): 2^depth_bits − 1.
inline uint32_t depth_max_code(const RasterConfig& c) { return (uint32_t)((1u << c.depth_bits()) - 1); }

struct DepthSetup {
  Plane z;     // Σ E_k·z_k·(2^depth_bits − 1)
  i128 den = 0;  // 2A · 2^z_frac_bits (> 0)
};
// Contract: exact; needs z_k ≤ 2^z_frac_bits (setup rejects larger as RejectedRange).
DepthSetup depth_setup(const Config& cfg, const SetupTriangle& tri, const TriSetup& t);

// floor(a / d) with remainder in [0, d), d > 0.
inline void floor_divmod(i128 a, i128 d, i128& q, i128& r) {
  q = a / d;
  r = a % d;
  if (r < 0) r += d, q -= 1;
}

// Exact stepping of RNE(Z / den) along +x.
struct DepthStepper {
  i128 q = 0, r = 0, dq = 0, dr = 0, den = 1;
  DepthStepper(const DepthSetup& s, int i, int j) : den(s.den) {
    floor_divmod(s.z.at(i, j), den, q, r);
    floor_divmod(s.z.dx, den, dq, dr);
  }
  void step_x() {
    q += dq;
    r += dr;
    if (r >= den) r -= den, q += 1;
  }
  // Round to nearest, ties to even.
  uint32_t code() const { return (uint32_t)(rne_round_up<i128>(q, r, den) ? q + 1 : q); }
};

// Contract: the depth comparison `incoming func stored` (GL / D3D semantics).
inline bool depth_compare(DepthFunc f, uint32_t incoming, uint32_t stored) {
  switch (f) {
    case DepthFunc::Never: return false;
    case DepthFunc::Less: return incoming < stored;
    case DepthFunc::Equal: return incoming == stored;
    case DepthFunc::LessEqual: return incoming <= stored;
    case DepthFunc::Greater: return incoming > stored;
    case DepthFunc::NotEqual: return incoming != stored;
    case DepthFunc::GreaterEqual: return incoming >= stored;
    case DepthFunc::Always: return true;
  }
  return false;
}

}  // namespace fxr

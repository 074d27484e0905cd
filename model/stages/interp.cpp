// Stages 7 and 8 setup: planes, block alignment, depth planes. Contracts in model/stages/interp.hpp and
// model/stages/depth.hpp.
#include <algorithm>
#include <climits>
#include <string>

#include "model/stages/depth.hpp"
#include "model/stages/interp.hpp"

namespace fxr {

Plane make_plane(const TriSetup& t, const int64_t q[3]) {
  // P(i, j) = Σ_k (a_k·(i·2^g + h) + b_k·(j·2^g + h) + c_k)·q_k, h = 2^(g−1): exact in i128.
  const int64_t h = (int64_t)1 << (t.g - 1);
  Plane p;
  for (int k = 0; k < 3; ++k) {
    const EdgeEq& e = t.e[k];
    p.dx += (i128)e.a * q[k] * ((i128)1 << t.g);  // signed: a multiply, not a negative <<
    p.dy += (i128)e.b * q[k] * ((i128)1 << t.g);
    p.c += (i128)(e.a * h + e.b * h + e.c) * q[k];
  }
  return p;
}

Block3 align_block(const FxFloat v[3], int bits) {
  Block3 b;
  int lead = INT_MIN;
  for (int k = 0; k < 3; ++k)
    if (!v[k].is_zero()) lead = std::max(lead, v[k].lead_exp());
  if (lead == INT_MIN) return b;
  b.exp = lead - (bits - 1);
  for (int k = 0; k < 3; ++k) {
    if (v[k].is_zero()) continue;
    // sig·2^exp / 2^b.exp = sig·2^−(b.exp − exp): a right shift with RNE (precision lost when
    // > 0), or an exact left shift that keeps the value below 2^bits.
    const i128 m = shift_round((i128)v[k].sig, b.exp - v[k].exp, Round::HalfEven);
    b.q[k] = v[k].neg ? -(int64_t)m : (int64_t)m;
  }
  return b;
}

void interp_setup(const Config& cfg, const DrawState& st, const SetupTriangle& tri, const TriSetup& t,
                  InterpSetup& out) {
  const int bits = cfg.raster.interp_block_bits;
  out.n = st.num_varyings;
  if (st.interp == InterpMode::Affine) {
    const int64_t one[3] = {1, 1, 1};  // R_k = 1: D = 2A
    out.den = make_plane(t, one);
    out.den_exp = 0;
  } else {
    const FxFloat rw[3] = {tri.v[0].rw, tri.v[1].rw, tri.v[2].rw};
    const Block3 r = align_block(rw, bits);
    out.den = make_plane(t, r.q);
    out.den_exp = r.exp;
  }
  for (int m = 0; m < out.n; ++m) {
    const FxFloat vw[3] = {tri.v[0].vw[m], tri.v[1].vw[m], tri.v[2].vw[m]};
    const Block3 b = align_block(vw, bits);
    out.num[m] = make_plane(t, b.q);
    out.num_exp[m] = b.exp;
  }
}

DepthSetup depth_setup(const Config& cfg, const SetupTriangle& tri, const TriSetup& t) {
  const int64_t M = (int64_t)depth_max_code(cfg.raster);
  int64_t q[3];
  for (int k = 0; k < 3; ++k) q[k] = (int64_t)tri.v[k].z * M;  // ≤ 2^(z_frac_bits + depth_bits) < 2^63
  DepthSetup d;
  d.z = make_plane(t, q);
  d.den = (i128)t.area2 << cfg.raster.z_frac_bits;
  return d;
}

}  // namespace fxr

// Stages 5L–7L for line segments (line_setup.hpp). Integer arithmetic only.
#include "model/stages/line_setup.hpp"

#include <algorithm>
#include <string>

#include "model/arith/round.hpp"
#include "model/stages/attr.hpp"

namespace fxr {

int line_param_frac_bits(const RasterConfig& r) {
  const int src = attr_planes(r) ? r.attr_subpixel_bits : grid_bits(r);
  const int W = r.window_int_bits;
  // 2(W + F) + 1 ≤ plane_edge_bits − 1 (the record widths of the triangle planes);
  // 2(W + F) + 1 + (B + 1) ≤ 127 (N, D with |V| ≤ 2^B); 2(W + F) + 1 + zq ≤ 127 (Z).
  const int by_edge = (plane_edge_bits(r) - 2) / 2 - W;
  const int by_sums = (125 - std::max(r.interp_block_bits, line_zq_bits(r))) / 2 - W;
  const int F = std::min({src, by_edge, by_sums});
  if (F < 1)
    throw ConfigError("configuration: raster: the line parameter grid would have " + std::to_string(F) +
                      " fraction bits (window_int_bits " + std::to_string(W) + ", interp_block_bits " +
                      std::to_string(r.interp_block_bits) + ", z_frac_bits " + std::to_string(r.z_frac_bits) +
                      "): at least 1 is needed (docs/lines.md)");
  return F;
}

namespace {
// RNE(v / 2^s), s ≥ 0.
int64_t drop_bits(int64_t v, int s) { return s == 0 ? v : (int64_t)shift_round((i128)v, s, Round::HalfEven); }
}  // namespace

LineSetupOutcome line_setup_equations(const Config& cfg, const DrawState& st, const SetupLine& in, bool varyings,
                                      LineEquations& out) {
  const RasterConfig& rc = cfg.raster;
  const int64_t lim = (int64_t)1 << (rc.window_int_bits - 1 + rc.subpixel_bits);
  for (const SetupVertex& v : in.v) {
    if (v.x <= -lim || v.x >= lim || v.y <= -lim || v.y >= lim) return LineSetupOutcome::RejectedRange;
    if (v.z > ((uint64_t)1 << rc.z_frac_bits)) return LineSetupOutcome::RejectedRange;
  }
  out.prim = in.prim;
  out.seg = LineIn{in.v[0].x, in.v[0].y, in.v[1].x, in.v[1].y};
  PixelRect dr = draw_rect(st);
  const int wlim = 1 << (rc.window_int_bits - 1);
  dr.x0 = std::max(dr.x0, -wlim), dr.y0 = std::max(dr.y0, -wlim);
  dr.x1 = std::min(dr.x1, wlim - 1), dr.y1 = std::min(dr.y1, wlim - 1);
  out.rect = dr;

  // The parameter grid.
  const bool attr = attr_planes(rc);
  const int src = attr ? rc.attr_subpixel_bits : grid_bits(rc);
  const int F = line_param_frac_bits(rc);
  int64_t px[2], py[2];
  for (int i = 0; i < 2; ++i) {
    const SetupVertex& v = in.v[i];
    const int up = attr ? 0 : grid_bits(rc) - rc.subpixel_bits;  // snapped: to the sample grid (exact)
    px[i] = drop_bits((attr ? v.ax : v.x) * ((int64_t)1 << up), src - F);
    py[i] = drop_bits((attr ? v.ay : v.y) * ((int64_t)1 << up), src - F);
  }
  out.F = F;
  out.ox = px[0], out.oy = py[0];
  out.dx = px[1] - px[0], out.dy = py[1] - py[0];
  const i128 l2 = (i128)out.dx * out.dx + (i128)out.dy * out.dy;
  out.len2 = l2 > 0 ? l2 : 1;  // zero length: dx = dy = 0, so W_1 = 0 and t = 0

  // Depth: as depth_setup / attr_depth_setup with L² for 2A.
  const int64_t M = (int64_t)depth_max_code(rc);
  for (int i = 0; i < 2; ++i) out.zq[i] = attr ? attr_depth_q(rc, in.v[i].z) : (int64_t)in.v[i].z * M;
  out.zden = out.len2 << (attr ? rc.z_frac_bits - rc.depth_bits() : rc.z_frac_bits);

  // 1/w and v/w on one block exponent per plane (align_block with a zero third value).
  out.n = varyings ? st.num_varyings : 0;
  const int bits = rc.interp_block_bits;
  if (st.interp == InterpMode::Affine) {
    out.rq[0] = out.rq[1] = 1;  // D = L²
    out.den_exp = 0;
  } else {
    const FxFloat rw[3] = {in.v[0].rw, in.v[1].rw, FxFloat{}};
    const Block3 b = align_block(rw, bits);
    out.rq[0] = b.q[0], out.rq[1] = b.q[1];
    out.den_exp = b.exp;
  }
  for (int m = 0; m < out.n; ++m) {
    const FxFloat vw[3] = {in.v[0].vw[m], in.v[1].vw[m], FxFloat{}};
    const Block3 b = align_block(vw, bits);
    out.vq[m][0] = b.q[0], out.vq[m][1] = b.q[1];
    out.num_exp[m] = b.exp;
  }
  return LineSetupOutcome::Ok;
}

i128 line_weight(const LineEquations& e, int32_t x, int32_t y) {
  const int64_t one = (int64_t)1 << e.F, half = (int64_t)1 << (e.F - 1);
  const i128 X = (i128)x * one + half - e.ox, Y = (i128)y * one + half - e.oy;
  const i128 w = X * e.dx + Y * e.dy;
  return w < 0 ? 0 : w > e.len2 ? e.len2 : w;
}

StageCost LineSetupStage::cost(const Config& cfg) {
  const RasterConfig& r = cfg.raster;
  const int pb = r.window_int_bits + line_param_frac_bits(r) + 1;
  StageCost c;
  for (int k = 0; k < 3; ++k) c.add_mult(pb, pb);                     // dx², dy², first E_1
  c.add_mult(line_weight_bits(r), r.z_frac_bits);                     // zden shift is free; zq: z·M
  c.latency = 2;
  c.ii = 1;
  c.adder_bits = 4 * (int64_t)pb + (int64_t)(kMaxVaryings + 1) * 2 * (r.interp_block_bits + 1);
  c.ff_bits = record_bits<LineEquations>(cfg, kMaxVaryings);
  return c;
}

StageCost LineTraverseStage::cost(const Config& cfg) {
  const RasterConfig& r = cfg.raster;
  StageCost c;
  c.latency = 1;  // the set-up cycle (docs/lines.md, RTL)
  c.ii = 1;       // one major-axis step per clock
  c.add_mult(line_delta_bits(r), r.subpixel_bits + 2);  // the two one-pixel products of the set-up cycle
  c.add_mult(line_delta_bits(r), r.subpixel_bits + 2);
  c.adder_bits = 3 * (int64_t)line_decision_bits(r) + 4 * (int64_t)r.window_int_bits;
  c.ff_bits = record_bits<LineEquations>(cfg, 0);  // the latched segment (Yosys: docs/lines.md)
  return c;
}

StageCost LineInterpStage::cost(const Config& cfg) {
  const RasterConfig& r = cfg.raster;
  const int wb = line_weight_bits(r);
  StageCost c;
  for (int p = 0; p < kMaxVaryings + 1; ++p) c.add_mult(wb, r.interp_block_bits + 1), c.add_mult(wb, r.interp_block_bits + 1);
  c.add_mult(wb, line_zq_bits(r)), c.add_mult(wb, line_zq_bits(r));
  c.latency = 2;
  c.ii = 1;
  c.adder_bits = 2 * (int64_t)wb + (int64_t)(kMaxVaryings + 2) * (wb + r.interp_block_bits + 1);
  // The depth code RNE(Z / zden): a restoring divider, depth_bits quotient bits.
  c.adder_bits += (int64_t)r.depth_bits() * (wb + r.z_frac_bits);
  c.ff_bits = c.latency * record_bits<PlaneSample>(cfg, kMaxVaryings);
  return c;
}

}  // namespace fxr

// Stage 5: triangle setup. Contracts in model/stages/setup.hpp; derivations in docs/pipeline.md.
#include "model/stages/setup.hpp"

#include <algorithm>
#include <climits>
#include <string>

namespace fxr {

PixelRect draw_rect(const DrawState& st) {
  PixelRect r;
  r.x0 = st.viewport_x;
  r.y0 = st.viewport_y;
  r.x1 = st.viewport_x + st.viewport_w - 1;
  r.y1 = st.viewport_y + st.viewport_h - 1;
  if (st.scissor_w >= 0 && st.scissor_h >= 0) {
    r.x0 = std::max(r.x0, st.scissor_x);
    r.y0 = std::max(r.y0, st.scissor_y);
    r.x1 = std::min(r.x1, st.scissor_x + st.scissor_w - 1);
    r.y1 = std::min(r.y1, st.scissor_y + st.scissor_h - 1);
  }
  return r;
}

// The least and the greatest of three, each as two selects the compiler makes conditional moves.
static inline int64_t min3_flat(int64_t a, int64_t b, int64_t c) {
  const int64_t m = b < a ? b : a;
  return c < m ? c : m;
}
static inline int64_t max3_flat(int64_t a, int64_t b, int64_t c) {
  const int64_t m = b > a ? b : a;
  return c > m ? c : m;
}

// floor(a / 2^s) and ceil(a / 2^s) for signed a (arithmetic shift is floor).
static int64_t floor_shift(int64_t a, int s) { return a >> s; }
static int64_t ceil_shift(int64_t a, int s) { return -((-a) >> s); }

PixelRect setup_rect(const Config& cfg, const DrawState& st) {
  PixelRect dr = draw_rect(st);
  const int wlim = 1 << (cfg.raster.window_int_bits - 1);
  dr.x0 = std::max(dr.x0, -wlim);
  dr.y0 = std::max(dr.y0, -wlim);
  dr.x1 = std::min(dr.x1, wlim - 1);
  dr.y1 = std::min(dr.y1, wlim - 1);
  return dr;
}

SetupOutcome setup_triangle(const Config& cfg, const DrawState& st, const SetupTriangle& tri, TriSetup& out) {
  return setup_triangle(cfg, st, setup_rect(cfg, st), tri, out);
}

SetupOutcome setup_triangle(const Config& cfg, const DrawState& st, const PixelRect& dr, const SetupTriangle& tri,
                            TriSetup& out) {
  const RasterConfig& rc = cfg.raster;
  const int g = grid_bits(rc);
  const int up = g - rc.subpixel_bits;  // 1 when subpixel_bits == 0 (exact doubling), else 0
  // Vertex range: ±2^(window_int_bits−1) pixels in subpixel units.
  const int64_t lim = (int64_t)1 << (rc.window_int_bits - 1 + rc.subpixel_bits);
  int64_t x[3], y[3];
  for (int k = 0; k < 3; ++k) {
    const SetupVertex& v = tri.v[k];
    if (v.x < -lim || v.x >= lim || v.y < -lim || v.y >= lim) return SetupOutcome::RejectedRange;
    if (v.z > ((uint64_t)1 << rc.z_frac_bits)) return SetupOutcome::RejectedRange;  // z/w > 1
    x[k] = v.x * ((int64_t)1 << up);
    y[k] = v.y * ((int64_t)1 << up);
  }
  // Edge k from v_{k+1} to v_{k+2}. Exact: coefficients < 2^cb, products < 2^(2cb) (int64).
  // Formed in locals and written to `out` once, with the winding's sign (a local array copied
  // into `out` at the end, and later the negation of `out.e` read back by 16-byte loads from
  // 8-byte stores, stalled on store forwarding: a fifth and a tenth of this function's samples,
  // docs/speed.md "Session 10: per triangle", "Session 12: per triangle"); nothing reads `out`
  // when the outcome is not Ok.
  int64_t ea[3], eb[3], ec[3];
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    ea[k] = y[a] - y[b];
    eb[k] = x[b] - x[a];
    ec[k] = x[a] * y[b] - x[b] * y[a];
  }
  // 2·area = E_0(v_0) (signed; > 0 for counter-clockwise in y-up window space).
  int64_t area2 = ea[0] * x[0] + eb[0] * y[0] + ec[0];
  if (area2 == 0) return SetupOutcome::CulledZeroArea;
  const bool ccw = area2 > 0;
  const bool front = (ccw == st.front_ccw);
  if ((st.cull == CullMode::Back && !front) || (st.cull == CullMode::Front && front))
    return SetupOutcome::CulledBackface;
  EdgeEq* const e = out.e;
  // Normalise the winding: −E of a → b is E of b → a (exact: |values| < 2^(2cb) ≤ 2^62). By a
  // mask (x ^ m) − m, m = −1 for clockwise: a branch on the winding (half of a mesh's triangles
  // with the culling off) was mispredicted (docs/speed.md "Session 13: per vertex and per
  // triangle").
  const int64_t m = -(int64_t)!ccw;
  const auto wind = [m](int64_t v) { return (v ^ m) - m; };
  for (int k = 0; k < 3; ++k) e[k].a = wind(ea[k]), e[k].b = wind(eb[k]), e[k].c = wind(ec[k]);
  area2 = wind(area2);
  // Top-left rule (see the header): the gradient (a, b) points inside.
  for (int k = 0; k < 3; ++k) {
    EdgeEq& q = e[k];
    const bool left = q.a > 0;
    const bool top = q.a == 0 && q.b < 0;
    q.bias = (left || top) ? 0 : -1;
  }
  // Candidate pixels: centres X = i·2^g + 2^(g−1) within [min x, max x], likewise y.
  const int64_t h = (int64_t)1 << (g - 1);
  // Without branches (which vertex is the least is data-dependent: std::min's compare-and-jump
  // was mispredicted about once a triangle per coordinate, docs/speed.md "Session 13: per vertex
  // and per triangle"); conditional moves.
  const int64_t xmin = min3_flat(x[0], x[1], x[2]), xmax = max3_flat(x[0], x[1], x[2]);
  const int64_t ymin = min3_flat(y[0], y[1], y[2]), ymax = max3_flat(y[0], y[1], y[2]);
  // dr = setup_rect: the draw rectangle within the window coordinate range.
  const int64_t bx0 = std::max<int64_t>(ceil_shift(xmin - h, g), dr.x0);
  const int64_t bx1 = std::min<int64_t>(floor_shift(xmax - h, g), dr.x1);
  const int64_t by0 = std::max<int64_t>(ceil_shift(ymin - h, g), dr.y0);
  const int64_t by1 = std::min<int64_t>(floor_shift(ymax - h, g), dr.y1);
  if (bx0 > bx1 || by0 > by1) return SetupOutcome::CulledNoSamples;
  out.area2 = area2;
  out.front = front;
  out.g = g;
  out.x0 = (int)bx0;
  out.x1 = (int)bx1;
  out.y0 = (int)by0;
  out.y1 = (int)by1;
  return SetupOutcome::Ok;
}

// ---- planes (stages 7 and 8 read them) ------------------------------------------------------

void make_plane_to(const TriSetup& t, const int64_t q[3], Plane& out) {
  // P(i, j) = Σ_k (a_k·(i·2^g + h) + b_k·(j·2^g + h) + c_k)·q_k, h = 2^(g−1): exact in i128.
  // Summed in locals and stored once (as attr_plane_to).
  const int64_t h = (int64_t)1 << (t.g - 1);
  i128 c = 0, dx = 0, dy = 0;
  for (int k = 0; k < 3; ++k) {
    const EdgeEq& e = t.e[k];
    dx += (i128)e.a * q[k] * ((i128)1 << t.g);  // signed: a multiply, not a negative <<
    dy += (i128)e.b * q[k] * ((i128)1 << t.g);
    c += (i128)(e.a * h + e.b * h + e.c) * q[k];
  }
  out.c = c;
  out.dx = dx;
  out.dy = dy;
  out.i0 = 0;
  out.j0 = 0;
}

Plane make_plane(const TriSetup& t, const int64_t q[3]) {
  Plane p;
  make_plane_to(t, q, p);
  return p;
}

Block3 align_block(const FxFloat v[3], int bits) {
  // align_block_wide in int64 (docs/speed.md "Session 9: per triangle"): every significand
  // below 2^63 and every right shift ≤ 62 (shift_round_right's int64 range); a left shift keeps
  // the value below 2^bits ≤ 2^62. Otherwise (a value below ¼ block ulp, or wider) the i128 path.
  // One return of `b` (a copy of a Block3 written word by word and read back by 16-byte loads
  // stalled on store forwarding: half of align_block's samples).
  Block3 b;
  int lead = INT_MIN;
  for (int k = 0; k < 3; ++k)
    if (!v[k].is_zero()) lead = std::max(lead, v[k].lead_exp());
  if (lead != INT_MIN) {
    b.exp = lead - (bits - 1);
    for (int k = 0; k < 3; ++k) {
      if (v[k].is_zero()) continue;
      const int sh = b.exp - v[k].exp;
      if (sh > detail::kFastMaxShift || (v[k].sig >> 63) != 0) {
        b = align_block_wide(v, bits);
        break;
      }
      const int64_t x = (int64_t)v[k].sig;
      const int64_t m = sh <= 0 ? x << -sh : detail::shift_round_right<int64_t, uint64_t>(x, sh, Round::HalfEven);
      b.q[k] = v[k].neg ? -m : m;
    }
  }
  return b;
}

Block3 align_block_wide(const FxFloat v[3], int bits) {
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
  build_interp_planes(cfg, st, tri, out, [&](const int64_t q[3], Plane& p) { make_plane_to(t, q, p); });
}

DepthSetup depth_setup(const Config& cfg, const SetupTriangle& tri, const TriSetup& t) {
  const int64_t M = (int64_t)depth_max_code(cfg.raster);
  int64_t q[3];
  for (int k = 0; k < 3; ++k) q[k] = (int64_t)tri.v[k].z * M;  // ≤ 2^(z_frac_bits + depth_bits) < 2^63
  DepthSetup d;
  d.z = make_plane(t, q);
  d.den = (i128)t.area2 << cfg.raster.z_frac_bits;
  d.max_code = depth_max_code(cfg.raster);
  return d;
}

StageCost SetupStage::cost(const Config& cfg) {
  // rtl/fxr_setup.sv at this configuration (docs/pipeline.md, stage 5 "RTL").
  const RasterConfig& r = cfg.raster;
  StageCost c;
  const int cb = coord_bits(r);
  // Coverage: the 6 coordinate products of the edge constants (2A is c_0 + c_1 + c_2).
  for (int k = 0; k < 6; ++k) c.add_mult(cb, cb);
  // The planes' edge functions (fxr_setup_attr): on the attribute triangle c_0 = x_1·y_2 − x_2·y_1
  // (vertex 0 is the origin) and the edge values at the anchor a_k·X0 + b_k·Y0.
  const int W = r.attr_coord_bits;
  const int ab = std::max(W + 2, edge_coef_bits(r)), cwb = std::max(2 * W + 2, edge_value_bits(r));
  if (attr_planes(r)) {
    for (int k = 0; k < 2; ++k) c.add_mult(W + 1, W + 1);
    for (int k = 0; k < 6; ++k) c.add_mult(ab, W + 2);
  }
  // Planes (fxr_setup_plane): a_k·q_k, b_k·q_k, C_k·q_k per plane; 1/w and every v/w (sized for
  // kMaxVaryings: the RTL instance has kSetupVecVaryings, each more is one more plane) with
  // block-aligned values (interp_block_bits + 2 signed), depth with z (z_frac_bits + 2 signed).
  const int qb = r.interp_block_bits + 2, zqb = r.z_frac_bits + 2;
  for (int p = 0; p < kMaxVaryings + 1; ++p) {
    for (int k = 0; k < 6; ++k) c.add_mult(ab, qb);
    for (int k = 0; k < 3; ++k) c.add_mult(cwb, qb);
  }
  for (int k = 0; k < 6; ++k) c.add_mult(ab, zqb);
  for (int k = 0; k < 3; ++k) c.add_mult(cwb, zqb);
  // Adders: edge coefficients, 2A, the rectangle (16 compares); the attribute triangle's
  // relative positions and RNE drops; per plane the three-term sums of c, dx, dy.
  c.adder_bits = 6 * (int64_t)edge_coef_bits(r) + 3 * (int64_t)edge_value_bits(r) + 16 * (int64_t)(r.window_int_bits + 3);
  if (attr_planes(r)) c.adder_bits += 18 * (int64_t)(r.window_int_bits + r.attr_subpixel_bits + 2);
  c.adder_bits += (int64_t)(kMaxVaryings + 2) * 3 * 2 * interp_plane_bits(r);
  c.latency = kSetupEdgeStages + kSetupAttrStages + kSetupPlaneStages;
  c.ii = 1;
  c.ff_bits = c.latency * record_bits<TriangleEquations>(cfg, kMaxVaryings);
  return c;
}

}  // namespace fxr

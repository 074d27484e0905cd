// Stage 5: triangle setup. Contracts in model/stages/setup.hpp; derivations in docs/pipeline.md.
#include "model/stages/setup.hpp"

#include <algorithm>
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

// floor(a / 2^s) and ceil(a / 2^s) for signed a (arithmetic shift is floor).
static int64_t floor_shift(int64_t a, int s) { return a >> s; }
static int64_t ceil_shift(int64_t a, int s) { return -((-a) >> s); }

SetupOutcome setup_triangle(const Config& cfg, const DrawState& st, const SetupTriangle& tri, TriSetup& out) {
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
  EdgeEq e[3];
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    e[k].a = y[a] - y[b];
    e[k].b = x[b] - x[a];
    e[k].c = x[a] * y[b] - x[b] * y[a];
  }
  // 2·area = E_0(v_0) (signed; > 0 for counter-clockwise in y-up window space).
  int64_t area2 = edge_eval(e[0], x[0], y[0]);
  if (area2 == 0) return SetupOutcome::CulledZeroArea;
  const bool ccw = area2 > 0;
  const bool front = (ccw == st.front_ccw);
  if ((st.cull == CullMode::Back && !front) || (st.cull == CullMode::Front && front))
    return SetupOutcome::CulledBackface;
  if (!ccw) {  // normalise the winding: −E of a → b is E of b → a (exact)
    for (EdgeEq& q : e) q = EdgeEq{-q.a, -q.b, -q.c, 0};
    area2 = -area2;
  }
  // Top-left rule (see the header): the gradient (a, b) points inside.
  for (EdgeEq& q : e) {
    const bool left = q.a > 0;
    const bool top = q.a == 0 && q.b < 0;
    q.bias = (left || top) ? 0 : -1;
  }
  // Candidate pixels: centres X = i·2^g + 2^(g−1) within [min x, max x], likewise y.
  const int64_t h = (int64_t)1 << (g - 1);
  const int64_t xmin = std::min({x[0], x[1], x[2]}), xmax = std::max({x[0], x[1], x[2]});
  const int64_t ymin = std::min({y[0], y[1], y[2]}), ymax = std::max({y[0], y[1], y[2]});
  PixelRect dr = draw_rect(st);
  // Pixels outside the window coordinate range are never candidates (keeps every evaluated
  // edge value within edge_value_bits).
  const int wlim = 1 << (rc.window_int_bits - 1);
  dr.x0 = std::max(dr.x0, -wlim);
  dr.y0 = std::max(dr.y0, -wlim);
  dr.x1 = std::min(dr.x1, wlim - 1);
  dr.y1 = std::min(dr.y1, wlim - 1);
  const int64_t bx0 = std::max<int64_t>(ceil_shift(xmin - h, g), dr.x0);
  const int64_t bx1 = std::min<int64_t>(floor_shift(xmax - h, g), dr.x1);
  const int64_t by0 = std::max<int64_t>(ceil_shift(ymin - h, g), dr.y0);
  const int64_t by1 = std::min<int64_t>(floor_shift(ymax - h, g), dr.y1);
  if (bx0 > bx1 || by0 > by1) return SetupOutcome::CulledNoSamples;
  for (int k = 0; k < 3; ++k) out.e[k] = e[k];
  out.area2 = area2;
  out.front = front;
  out.g = g;
  out.x0 = (int)bx0;
  out.x1 = (int)bx1;
  out.y0 = (int)by0;
  out.y1 = (int)by1;
  return SetupOutcome::Ok;
}

}  // namespace fxr

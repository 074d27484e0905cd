// model/stages/line.cpp — line rasterisation, midpoint and diamond-exit rules (line.hpp).
#include "model/stages/line.hpp"

#include <cstddef>
#include <utility>

namespace fxr {

namespace {

int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}
int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }
int64_t abs64(int64_t v) { return v < 0 ? -v : v; }

struct Frame {
  LineSetup s;
  int64_t u = 0, h = 0;          // one pixel and half a pixel, doubled subpixel units
  int64_t a0 = 0, b0 = 0, a1 = 0, b1 = 0;  // canonical endpoints (a0 ≤ a1, b0 ≤ b1)
  int64_t pa_a = 0, pa_b = 0, pb_a = 0, pb_b = 0;  // first / last vertex in the canonical frame
};

Frame make_frame(const RasterConfig& r, const LineConfig& c, const LineIn& in) {
  Frame f;
  const int S = r.subpixel_bits;
  f.u = (int64_t)1 << (S + 1);
  f.h = (int64_t)1 << S;
  // Doubled coordinates: pixel centres become integers (i·u + h).
  const int64_t X0 = 2 * in.x0, Y0 = 2 * in.y0, X1 = 2 * in.x1, Y1 = 2 * in.y1;
  LineSetup& s = f.s;
  s.y_major = abs64(Y1 - Y0) > abs64(X1 - X0);
  int64_t A0 = s.y_major ? Y0 : X0, B0 = s.y_major ? X0 : Y0;
  int64_t A1 = s.y_major ? Y1 : X1, B1 = s.y_major ? X1 : Y1;
  const bool swapped = A1 < A0;
  if (swapped) std::swap(A0, A1), std::swap(B0, B1);
  s.reflect = B1 < B0;
  if (s.reflect) B0 = -B0, B1 = -B1;
  f.a0 = A0, f.b0 = B0, f.a1 = A1, f.b1 = B1;
  // p_a is the first input vertex, wherever canonicalisation put it.
  f.pa_a = swapped ? A1 : A0, f.pa_b = swapped ? B1 : B0;
  f.pb_a = swapped ? A0 : A1, f.pb_b = swapped ? B0 : B1;
  s.da = A1 - A0;
  s.db = B1 - B0;
  const bool midpoint = c.rule == LineRule::Midpoint;
  // Major-axis pixels whose centre i·u + h lies in [A0, A1) (half_open) or [A0, A1].
  s.first = ceil_div(A0 - f.h, f.u);
  const int64_t last = (midpoint && c.endpoints == LineEndpoints::HalfOpen) ? ceil_div(A1 - f.h, f.u) - 1
                                                                            : floor_div(A1 - f.h, f.u);
  s.count = last >= s.first ? last - s.first + 1 : 0;
  // Ties go to the smaller original minor coordinate: in a reflected frame, to the larger row.
  // The diamond-exit rule skips ties, so it needs no bias.
  const int64_t bias = (midpoint && s.reflect) ? 1 : 0;
  // Row whose interval holds B0: (r·u, (r+1)·u] without bias, [r·u, (r+1)·u) with it.
  s.row = floor_div(B0 - 1 + bias, f.u);
  const int64_t ac = s.first * f.u + f.h;
  // Both factors of each product are at most one pixel (u) apart: no overflow (line.hpp).
  s.d = s.db * (ac - A0) - s.da * ((s.row + 1) * f.u - B0);
  return f;
}

LinePixel to_pixel(const LineSetup& s, int64_t major, int64_t row) {
  const int64_t minor = s.reflect ? -1 - row : row;
  return s.y_major ? LinePixel{(int32_t)minor, (int32_t)major} : LinePixel{(int32_t)major, (int32_t)minor};
}

// |a − centre_a| + |b − centre_b| < h: the point lies in the open diamond of that pixel.
bool in_diamond(const Frame& f, int64_t a, int64_t b, int64_t i, int64_t row) {
  return abs64(a - (i * f.u + f.h)) + abs64(b - (row * f.u + f.h)) < f.h;
}

}  // namespace

LineSetup line_setup(const RasterConfig& r, const LineConfig& c, const LineIn& in) {
  return make_frame(r, c, in).s;
}

std::vector<LinePixel> line_pixels(const RasterConfig& r, const LineConfig& c, const LineIn& in) {
  const Frame f = make_frame(r, c, in);
  const LineSetup& s = f.s;
  std::vector<LinePixel> out;
  out.reserve((size_t)s.count + 1);
  const bool diamond = c.rule == LineRule::DiamondExit;
  const int64_t bias = (!diamond && s.reflect) ? 1 : 0;
  const int64_t row_step = s.da * f.u, col_step = s.db * f.u;

  // Diamond exit: p_a inside a diamond whose centre lies outside [A0, A1] along the major axis
  // (the segment starts inside it and leaves it without crossing its centre line).
  bool extra = false, extra_before = false;
  int64_t extra_i = 0, extra_row = 0;
  if (diamond) {
    extra_i = floor_div(f.pa_a, f.u);
    extra_row = floor_div(f.pa_b, f.u);
    const int64_t centre = extra_i * f.u + f.h;
    extra = (centre < f.a0 || centre > f.a1) && in_diamond(f, f.pa_a, f.pa_b, extra_i, extra_row) &&
            !in_diamond(f, f.pb_a, f.pb_b, extra_i, extra_row);
    extra_before = centre < f.a0;
  }
  if (extra && extra_before) out.push_back(to_pixel(s, extra_i, extra_row));

  int64_t d = s.d, row = s.row;
  for (int64_t k = 0; k < s.count; ++k) {
    const int64_t i = s.first + k;
    if (d + bias > 0) ++row, d -= row_step;  // at most once per column: db ≤ da
    if (!diamond) {
      out.push_back(to_pixel(s, i, row));
    } else if (d != 0 && !in_diamond(f, f.pb_a, f.pb_b, i, row)) {
      // d == 0: the line crosses this column's centre line exactly between two pixels, on the
      // corners of both diamonds (open): no pixel in this column.
      out.push_back(to_pixel(s, i, row));
    }
    d += col_step;
  }
  if (extra && !extra_before) out.push_back(to_pixel(s, extra_i, extra_row));
  return out;
}

}  // namespace fxr

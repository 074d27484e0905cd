// tests/model/line_ref.hpp — exact references of the two line rules (docs/lines.md), written
// from the rules' definitions, not from model/stages/line.cpp: no decision variable, no
// stepping, no canonical frame. Every pixel is decided by a direct exact evaluation in 128-bit
// integers at doubled coordinates (pixel centres (2i+1)·2^S are integers).
//   midpoint:     per major-axis centre c in the endpoint range, the row j with
//                 j·u < b*(c) ≤ (j+1)·u, b*(c) the exact rational minor coordinate of the line.
//   diamond exit: min over t ∈ [0, 1] of the L1 distance from P(t) to the pixel centre < ½ px
//                 (convex piecewise linear: its minimum is at t = 0, 1 or where x(t) or y(t)
//                 equals the centre's), and the last vertex not in the open diamond.
// Also the segment generator of the line tests (classes of issue 15).
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "model/stages/line.hpp"

namespace fxr::line_ref {

using i128 = __int128;

inline i128 fdiv(i128 a, i128 b) {  // floor, b > 0
  i128 q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}
inline i128 iabs(i128 v) { return v < 0 ? -v : v; }

inline std::vector<LinePixel> midpoint(int S, bool closed, const LineIn& in) {
  const i128 u = (i128)2 << S, h = (i128)1 << S;
  const i128 X0 = 2 * (i128)in.x0, Y0 = 2 * (i128)in.y0, X1 = 2 * (i128)in.x1, Y1 = 2 * (i128)in.y1;
  const bool y_major = iabs(Y1 - Y0) > iabs(X1 - X0);
  const i128 A0 = y_major ? Y0 : X0, B0 = y_major ? X0 : Y0, A1 = y_major ? Y1 : X1, B1 = y_major ? X1 : Y1;
  const i128 lo = std::min(A0, A1), hi = std::max(A0, A1);
  std::vector<LinePixel> out;
  for (i128 i = fdiv(lo, u) - 1; i <= fdiv(hi, u) + 1; ++i) {
    const i128 c = i * u + h;
    if (c < lo || c > hi || (c == hi && !closed)) continue;
    // b*(c) = N / Q exactly, Q > 0.
    i128 N, Q;
    if (A1 == A0) {
      N = B0, Q = 1;
    } else {
      Q = A1 - A0, N = B0 * Q + (c - A0) * (B1 - B0);
      if (Q < 0) Q = -Q, N = -N;
    }
    // j·u < N/Q ≤ (j+1)·u  ⇔  j = ceil(N / (u·Q)) − 1.
    const i128 j = -fdiv(-N, u * Q) - 1;
    out.push_back(y_major ? LinePixel{(int32_t)j, (int32_t)i} : LinePixel{(int32_t)i, (int32_t)j});
  }
  std::sort(out.begin(), out.end());
  return out;
}

// q · L1(P(p/q), C) < h · q for the segment P(t) = Pa + t·(Pb − Pa).
inline bool diamond_hit(i128 h, i128 Xa, i128 Ya, i128 dX, i128 dY, i128 cx, i128 cy) {
  auto below = [&](i128 p, i128 q) {  // q > 0, 0 ≤ p ≤ q
    return iabs(q * (Xa - cx) + p * dX) + iabs(q * (Ya - cy) + p * dY) < h * q;
  };
  if (below(0, 1) || below(1, 1)) return true;
  if (dX != 0) {  // x(t) = cx at t = (cx − Xa) / dX
    i128 p = cx - Xa, q = dX;
    if (q < 0) p = -p, q = -q;
    if (p >= 0 && p <= q && below(p, q)) return true;
  }
  if (dY != 0) {
    i128 p = cy - Ya, q = dY;
    if (q < 0) p = -p, q = -q;
    if (p >= 0 && p <= q && below(p, q)) return true;
  }
  return false;
}

inline std::vector<LinePixel> diamond_exit(int S, const LineIn& in) {
  const i128 u = (i128)2 << S, h = (i128)1 << S;
  const i128 X0 = 2 * (i128)in.x0, Y0 = 2 * (i128)in.y0, X1 = 2 * (i128)in.x1, Y1 = 2 * (i128)in.y1;
  const i128 dX = X1 - X0, dY = Y1 - Y0;
  auto produced = [&](i128 i, i128 j) {
    const i128 cx = i * u + h, cy = j * u + h;
    return diamond_hit(h, X0, Y0, dX, dY, cx, cy) && iabs(X1 - cx) + iabs(Y1 - cy) >= h;
  };
  std::vector<LinePixel> out;
  const i128 ix0 = fdiv(std::min(X0, X1), u) - 1, ix1 = fdiv(std::max(X0, X1), u) + 1;
  const i128 iy0 = fdiv(std::min(Y0, Y1), u) - 1, iy1 = fdiv(std::max(Y0, Y1), u) + 1;
  if ((ix1 - ix0 + 1) * (iy1 - iy0 + 1) <= 40000) {
    for (i128 i = ix0; i <= ix1; ++i)
      for (i128 j = iy0; j <= iy1; ++j)
        if (produced(i, j)) out.push_back({(int32_t)i, (int32_t)j});
  } else {
    // Long segments: every pixel whose diamond the segment can reach lies within ±2 pixels of the
    // segment along the minor axis at its centre (the diamond has radius ½ px).
    const bool y_major = iabs(dY) > iabs(dX);
    const i128 a_lo = y_major ? iy0 : ix0, a_hi = y_major ? iy1 : ix1;
    const i128 A0 = y_major ? Y0 : X0, B0 = y_major ? X0 : Y0, dA = y_major ? dY : dX, dB = y_major ? dX : dY;
    for (i128 i = a_lo; i <= a_hi; ++i) {
      const i128 c = std::clamp(i * u + h, std::min(A0, A0 + dA), std::max(A0, A0 + dA));
      const i128 b = B0 + fdiv((c - A0) * dB * (dA < 0 ? -1 : 1), iabs(dA));
      for (i128 j = fdiv(b, u) - 2; j <= fdiv(b, u) + 2; ++j) {
        const i128 px = y_major ? j : i, py = y_major ? i : j;
        if (produced(px, py)) out.push_back({(int32_t)px, (int32_t)py});
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

inline std::vector<LinePixel> reference(const RasterConfig& r, const LineConfig& c, const LineIn& in) {
  return c.rule == LineRule::Midpoint ? midpoint(r.subpixel_bits, c.endpoints == LineEndpoints::Closed, in)
                                      : diamond_exit(r.subpixel_bits, in);
}

// Segments of every class issue 15 lists, drawn with raw mt19937_64 words.
enum class SegClass { Random, AxisAligned, Diagonal45, SubPixel, OnCentres, OnTies, GuardBandLong, kCount };

class SegmentGen {
 public:
  SegmentGen(const RasterConfig& r, uint64_t seed) : S_(r.subpixel_bits), W_(r.window_int_bits), rng_(seed) {}
  // |coordinate| < 2^(W−1+S), the raster's window range.
  LineIn next(SegClass k) {
    const int64_t lim = ((int64_t)1 << (W_ - 1 + S_)) - 1;
    const int64_t one = (int64_t)1 << S_;
    auto clampc = [&](int64_t v) { return std::clamp<int64_t>(v, -lim, lim); };
    auto small = [&](int bits_px) { return sgn_mag((S_ + bits_px)); };
    LineIn s;
    s.x0 = small(6), s.y0 = small(6);
    switch (k) {
      case SegClass::Random: s.x1 = s.x0 + small(5), s.y1 = s.y0 + small(5); break;
      case SegClass::AxisAligned:
        if (rng_() & 1) s.x1 = s.x0 + small(5), s.y1 = s.y0;
        else s.x1 = s.x0, s.y1 = s.y0 + small(5);
        break;
      case SegClass::Diagonal45: {
        const int64_t d = small(5);
        s.x1 = s.x0 + d, s.y1 = s.y0 + ((rng_() & 1) ? d : -d);
        break;
      }
      case SegClass::SubPixel: s.x1 = s.x0 + sgn_mag(S_ > 0 ? S_ : 1), s.y1 = s.y0 + sgn_mag(S_ > 0 ? S_ : 1); break;
      case SegClass::OnCentres:
      case SegClass::OnTies: {
        // Centres: i + ½ on both axes. Ties: one axis on a pixel edge, the other on a centre
        // (diamond corners, midpoint ties) or both on edges (pixel corners).
        auto snap = [&](int64_t v, bool centre) {
          const int64_t i = v >> S_;
          return i * one + (centre ? one / 2 : 0);
        };
        const uint64_t m = rng_();
        const bool ties = k == SegClass::OnTies;
        s.x0 = snap(s.x0, !ties || (m & 1)), s.y0 = snap(s.y0, !ties || (m & 2));
        s.x1 = snap(s.x0 + small(4), !ties || (m & 4)), s.y1 = snap(s.y0 + small(4), !ties || (m & 8));
        if (m & 16) s.y1 = s.y0 + ((m & 32) ? 1 : -1) * (s.x1 - s.x0);  // a 45° one through them
        break;
      }
      case SegClass::GuardBandLong:
        s.x0 = sgn_mag(W_ - 1 + S_), s.y0 = sgn_mag(W_ - 1 + S_);
        s.x1 = sgn_mag(W_ - 1 + S_), s.y1 = sgn_mag(W_ - 1 + S_);
        break;
      default: break;
    }
    s.x0 = clampc(s.x0), s.y0 = clampc(s.y0), s.x1 = clampc(s.x1), s.y1 = clampc(s.y1);
    return s;
  }

 private:
  int64_t sgn_mag(int bits) {  // uniform in (−2^bits, 2^bits)
    const uint64_t w = rng_();
    const int64_t m = (int64_t)((w >> 1) & (((uint64_t)1 << bits) - 1));
    return (w & 1) ? -m : m;
  }
  int S_, W_;
  std::mt19937_64 rng_;
};

}  // namespace fxr::line_ref

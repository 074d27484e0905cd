// Random cases of DepthCursor (model/stages/depth.hpp: the depth quotient / remainder moved from
// one span start to the next without a division), shared by depth_cursor_test.cpp (10^6 cases,
// model label) and depth_cursor_slow_test.cpp (10^8, slow label). Each case is a depth plane,
// a candidate rectangle and a start pixel; then several moves (most to the next row with x0
// moved by −1, 0 or +1, as traversal's spans go; some anywhere in the rectangle) and after each
// the span's int64_t stepper over a few pixels. The reference is the definition: Z(i, j) by i128
// products and floor(Z / den) by the compiler's i128 `/` and `%` (not floor_divmod), the code
// RNE and clamped by comparisons of 2r with den written out here.
#pragma once

#include <cstdint>
#include <random>

#include "model/stages/depth.hpp"

namespace fxr::cursor_cases {

struct Tally {
  uint64_t cases = 0, started = 0, refused = 0, moves = 0, divided = 0, lost = 0, codes = 0, bad = 0;
};

// floor(a / d), a mod d (d > 0) from i128's truncating division.
inline void ref_divmod(i128 a, i128 d, i128& q, i128& r) {
  q = a / d;
  r = a % d;
  if (r < 0) r += d, q -= 1;
}
inline uint32_t ref_code(i128 q, i128 r, i128 den, i128 max_code) {
  i128 c = q;
  if (2 * r > den || (2 * r == den && (q & 1) != 0)) c += 1;
  return (uint32_t)(c < 0 ? 0 : c > max_code ? max_code : c);
}
inline i128 ref_z(const DepthSetup& s, int64_t i, int64_t j) { return s.z.c + (i - s.z.i0) * s.z.dx + (j - s.z.j0) * s.z.dy; }

inline int bits_of(uint64_t v) { return v == 0 ? 0 : 64 - __builtin_clzll(v); }

// A random magnitude below 2^bits (bits ≤ 62), often near its top.
inline int64_t rand_mag(std::mt19937_64& g, int bits) {
  if (bits <= 0) return 0;
  const uint64_t top = (uint64_t)1 << (bits - 1);
  switch (g() % 4) {
    case 0: return (int64_t)(top + (g() % top));              // in the top binade
    case 1: return (int64_t)((top << 1) - 1 - g() % 4);        // at the very top
    default: return (int64_t)(g() % (top << 1));
  }
}

// One case: returns false on a mismatch (counted in t.bad).
inline bool run_case(std::mt19937_64& g, Tally& t) {
  ++t.cases;
  const i128 lim = (i128)1 << DepthCursor::kLimitBits;
  DepthSetup s;
  // den: 1 to 62 bits (2^61 and above must be refused).
  const int db = 1 + (int)(g() % 62);
  const int64_t den = std::max<int64_t>(1, rand_mag(g, db));
  s.den = den;
  s.max_code = g() % 8 == 0 ? (i128)rand_mag(g, 62) : (i128)((1 << 24) - 1);
  // The rectangle: mostly small (the bunny), sometimes wide.
  const int W = g() % 8 == 0 ? (int)(g() % 4096) : (int)(g() % 24), H = g() % 8 == 0 ? (int)(g() % 4096) : (int)(g() % 24);
  const int x0 = (int)(g() % 4000) - 2000, y0 = (int)(g() % 4000) - 2000, x1 = x0 + W, y1 = y0 + H;
  const int a = x0 + (int)(g() % (uint64_t)(W + 1)), b = y0 + (int)(g() % (uint64_t)(H + 1));
  // Quotients qx, qy, q0 of magnitudes up to the bound's limit and past it, kept small enough
  // that every Z of the rectangle fits i128 (|q|·den·(extent + 2) < 2^125).
  const int room = 124 - db - bits_of((uint64_t)std::max(W, H) + 2);
  auto quot = [&]() {
    const int qbits = std::min(62, std::max(0, std::min(room, (int)(g() % 64))));
    const int64_t m = rand_mag(g, qbits);
    return g() % 2 ? -m : m;
  };
  const int64_t qx = quot(), qy = quot(), q0 = quot();
  auto rem = [&]() { return (int64_t)(g() % (uint64_t)den); };
  s.z.dx = (i128)qx * den + rem();
  s.z.dy = (i128)qy * den + rem();
  s.z.i0 = a, s.z.j0 = b;
  s.z.c = (i128)q0 * den + rem();
  DepthStepper dz(s, a, b);
  DepthCursor c;
  const bool ok = c.start(dz, a, b, x0, x1, y0, y1);
  // Sound: accepted ⇒ den, max_code < 2^61 and |q| < 2^61 at the four corners (x1 + 1: the
  // stepper's last step; q is monotone in i and in j, so the corners bound the rectangle) —
  // the y corners only once a move to another row has accepted the y part.
  auto corner_ok = [&](bool with_y) {
    for (int64_t i : {(int64_t)x0, (int64_t)x1 + 1})
      for (int64_t j : {(int64_t)(with_y ? y0 : b), (int64_t)(with_y ? y1 : b)}) {
        i128 q, r;
        ref_divmod(ref_z(s, i, j), s.den, q, r);
        if (q >= lim || -q >= lim) return false;
      }
    return s.den < lim && s.max_code < lim;
  };
  if (!ok) {
    ++t.refused;
    return true;
  }
  ++t.started;
  if (!corner_ok(false)) return ++t.bad, false;
  int i = a, j = b;
  for (int k = 0; k < 8; ++k) {
    int i2 = i, j2 = j;
    if (g() % 4 != 0) {  // the next row, x0 moved by −1, 0 or +1 (or the same row)
      j2 = j + (g() % 8 == 0 ? 0 : 1);
      i2 = i + (int)(g() % 3) - 1;
    } else {
      i2 = x0 + (int)(g() % (uint64_t)(W + 1));
      j2 = y0 + (int)(g() % (uint64_t)(H + 1));
    }
    if (i2 < x0 || i2 > x1 || j2 < y0 || j2 > y1) break;  // traversal's spans stay inside
    const int m = c.move(s, i2, j2);
    if (m == DepthCursor::kLost) {  // only when the y part of the bound fails
      ++t.lost;
      if (!c.have_y && j2 != j) return true;
      return ++t.bad, false;
    }
    ++t.moves;
    t.divided += m == DepthCursor::kMovedDivided ? 1 : 0;
    if (c.have_y && !corner_ok(true)) return ++t.bad, false;
    i = i2, j = j2;
    i128 q, r;
    ref_divmod(ref_z(s, i, j), s.den, q, r);
    if ((i128)c.q != q || (i128)c.r != r) return ++t.bad, false;
    // The span's stepper from here: every code to the rectangle's end.
    DepthStepperT<int64_t> z = c.stepper();
    const int n = std::min(x1 - i + 1, 6);
    for (int p = 0; p < n; ++p, z.step_x()) {
      ref_divmod(ref_z(s, i + p, j), s.den, q, r);
      ++t.codes;
      if (z.code() != ref_code(q, r, s.den, s.max_code)) return ++t.bad, false;
    }
  }
  return true;
}

}  // namespace fxr::cursor_cases

// Independent exact references for the raster stages' tests (GMP rationals): barycentric edge
// values at pixel centres from orientation tests, FxFloat ↔ rational, rational rounding.
// Nothing here calls the model's arithmetic.
#pragma once

#include <gmpxx.h>

#include <cmath>
#include <vector>

#include "model/arith/fxfloat.hpp"
#include "model/unit/backend.hpp"

namespace fxr::ref {

// (unsigned long is 64 bits on the LP64 targets this project builds for.)
static_assert(sizeof(unsigned long) == 8, "LP64 expected");
inline mpz_class to_mpz_u(uint64_t v) { return mpz_class((unsigned long)v); }
inline mpz_class to_mpz(int64_t v) {
  const uint64_t m = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
  return v < 0 ? mpz_class(-to_mpz_u(m)) : to_mpz_u(m);
}

inline mpz_class to_mpz(i128 v) {
  const u128 m = v < 0 ? (u128)0 - (u128)v : (u128)v;
  return (v < 0 ? -1 : 1) * ((to_mpz_u((uint64_t)(m >> 64)) << 64) + to_mpz_u((uint64_t)m));
}

// sig · 2^exp exactly.
inline mpq_class to_mpq(const FxFloat& f) {
  mpq_class q(to_mpz_u(f.sig));
  if (f.exp >= 0) q *= mpq_class(mpz_class(1) << f.exp);
  else q /= mpq_class(mpz_class(1) << -f.exp);
  q.canonicalize();
  return f.neg ? mpq_class(-q) : q;
}
inline mpq_class to_mpq(double d) {
  mpq_class q(d);  // exact
  return q;
}

// floor(log2 |x|), x ≠ 0.
inline int ilog2(const mpq_class& x) {
  mpq_class a = abs(x);
  int e = (int)mpz_sizeinbase(a.get_num_mpz_t(), 2) - (int)mpz_sizeinbase(a.get_den_mpz_t(), 2);
  // adjust so that 2^e ≤ a < 2^(e+1)
  auto pow2 = [](int k) { return k >= 0 ? mpq_class(mpz_class(1) << k) : mpq_class(1, mpz_class(1) << -k); };
  while (a < pow2(e)) --e;
  while (a >= pow2(e + 1)) ++e;
  return e;
}
inline mpq_class pow2(int k) { return k >= 0 ? mpq_class(mpz_class(1) << k) : mpq_class(mpz_class(1), mpz_class(1) << -k); }

// Round-to-nearest-even of a rational to an integer.
inline mpz_class rne(const mpq_class& x) {
  mpz_class q, r;
  mpz_fdiv_qr(q.get_mpz_t(), r.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
  const int c = cmp(2 * r, x.get_den());
  if (c > 0 || (c == 0 && mpz_odd_p(q.get_mpz_t()))) q += 1;
  return q;
}

// x rounded (RNE) to a `bits`-bit significand, as an FxFloat (the test's stand-in for an
// upstream unit that delivers correctly rounded values).
inline FxFloat fx_round(const mpq_class& x, int bits) {
  FxFloat f;
  if (x == 0) return f;
  int e = ilog2(x);
  mpz_class s = rne(abs(x) * pow2(bits - 1 - e));
  if (s == (mpz_class(1) << bits)) s >>= 1, ++e;
  f.neg = x < 0;
  f.sig = s.get_ui();
  f.exp = e - (bits - 1);
  return f;
}

// Barycentric edge values at the centre of pixel (i, j) for vertices in subpixel units
// (s fraction bits), scaled by 2^(s+1)·2: E_k = orient(v_{k+1}, v_{k+2}, p) with the sign of the
// triangle's orientation removed, so E_k ≥ 0 inside and Σ E_k = 2A (same scale).
struct Bary {
  mpz_class e[3];
  mpz_class sum;
};
inline Bary bary(const SetupTriangle& t, int s, int i, int j) {
  auto X = [&](int k) { return mpz_class(to_mpz(t.v[k].x) * 2); };
  auto Y = [&](int k) { return mpz_class(to_mpz(t.v[k].y) * 2); };
  const mpz_class px = mpz_class(2 * i + 1) << s, py = mpz_class(2 * j + 1) << s;
  Bary b;
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, c = (k + 2) % 3;
    b.e[k] = (X(c) - X(a)) * (py - Y(a)) - (Y(c) - Y(a)) * (px - X(a));
  }
  b.sum = b.e[0] + b.e[1] + b.e[2];
  if (b.sum < 0) {
    for (auto& e : b.e) e = -e;
    b.sum = -b.sum;
  }
  return b;
}

// All covered fragments of one triangle (depth test off, nothing kept from earlier draws).
inline std::vector<Fragment> all_fragments(const Config& cfg, DrawState st, const SetupTriangle& t,
                                           SetupOutcome* o = nullptr) {
  st.depth_test = false;
  FrameOutput f;
  frame_begin(cfg, st, f);
  const SetupOutcome r = raster_triangle(cfg, st, t, f);
  if (o) *o = r;
  return f.fragments.to_vector();
}

}  // namespace fxr::ref

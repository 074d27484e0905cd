// Cases of the attribute planes' per-triangle fast path (attr_edge_terms / attr_plane,
// model/stages/attr.hpp) against the reference make_attr_plane: attr_plane_test.cpp (directed and
// 10^6 random) and attr_plane_slow_test.cpp (10^8 random, slow label).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "model/config/config.hpp"
#include "model/stages/attr.hpp"

namespace fxr::attr_cases {

inline i128 p2(int b) { return (i128)1 << b; }

// A random value of a random bit length 0 … max_bits (signed), so that both sides of every
// 64-bit boundary are drawn.
inline i128 rand_bits(std::mt19937_64& rng, int max_bits) {
  const int b = (int)(rng() % (uint64_t)(max_bits + 1));
  if (b == 0) return 0;
  u128 m = ((u128)rng() << 64) | rng();
  m &= ((u128)1 << b) - 1;
  m |= (u128)1 << (b - 1);  // exactly b bits
  const i128 v = (i128)m;
  return (rng() & 1) ? -v : v;
}

// A random AttrSetup within the widths the configuration allows and attr_setup produces:
// attr_coord_bits = acb ∈ [16, 40], relative coordinates (the anchor's centre X0, Y0 relative to
// vertex 0) and coefficients a, b below 2^acb, edge constants c below 2^(2·acb + 1), F ∈ [1, 40],
// anchors of window_int_bits ≤ 20; plane values q below 2^(123 − 2·acb − 2) (at most
// interp_block_bits = 62 bits), so that no i128 sum of the reference overflows. Every value is
// drawn with a random bit length, so both outcomes of the 64-bit test are frequent.
struct PlaneCase {
  AttrSetup s;
  int64_t q[3];
};
inline PlaneCase random_case(std::mt19937_64& rng) {
  PlaneCase c;
  AttrSetup& s = c.s;
  const int acb = 16 + (int)(rng() % 25);  // 16 … 40
  s.F = 1 + (int)(rng() % 40);
  const int ib = std::max(0, std::min(19, acb - 2 - s.F));
  for (int axis = 0; axis < 2; ++axis) {
    const i128 X0 = rand_bits(rng, acb - 1), i0 = rand_bits(rng, ib);
    const int64_t o = (int64_t)(i0 * p2(s.F) + p2(s.F - 1) - X0);  // X0 = i0·2^F + 2^(F−1) − o
    (axis ? s.j0 : s.i0) = (int)i0;
    (axis ? s.oy : s.ox) = o;
  }
  const int qb = std::min(62, 123 - 2 * acb - 2);
  for (int k = 0; k < 3; ++k) {
    s.a[k] = rand_bits(rng, acb);
    s.b[k] = rand_bits(rng, acb);
    s.c[k] = rand_bits(rng, 2 * acb + 1);
    c.q[k] = (int64_t)rand_bits(rng, qb);
  }
  s.ok = true;
  return c;
}

// Every field of the fast plane equal to the reference's; `what` names the case.
inline void expect_same_plane(const PlaneCase& c, const char* what, uint64_t i) {
  const Plane want = make_attr_plane(c.s, c.q);
  const Plane got = attr_plane(attr_edge_terms(c.s), c.q);
  ASSERT_TRUE(want.c == got.c && want.dx == got.dx && want.dy == got.dy && want.i0 == got.i0 && want.j0 == got.j0)
      << what << " case " << i;
}

// n random cases (random_case from `seed`) through expect_same_plane, `extra` called on each;
// both outcomes of the 64-bit test must be frequent (each > n / 10). Returns the fast ones.
template <class Extra>
uint64_t check_random(uint64_t seed, uint64_t n, Extra&& extra) {
  std::mt19937_64 rng(seed);
  uint64_t fits = 0;
  for (uint64_t i = 0; i < n; ++i) {
    const PlaneCase c = random_case(rng);
    fits += attr_edge_terms(c.s).fits64;
    expect_same_plane(c, "random", i);
    extra(c, i);
  }
  EXPECT_GT(fits, n / 10);
  EXPECT_LT(fits, n - n / 10);
  return fits;
}

// ---- attr_edge_terms64 (the vertices to the edge terms in 64-bit words) --------------------

// A configuration of the attribute path: the default, or (variant > 0) other widths within
// check_attr_widths — the narrowest coordinates (attr_coord_bits 16 … 40), A up to 40 with
// window_int_bits + A ≤ 62.
inline Config terms_config(int variant) {
  Config cfg;
  RasterConfig& r = cfg.raster;
  switch (variant % 4) {
    case 0: break;  // 16 integer bits, A = 24, attr_coord_bits = 40
    case 1: r.attr_coord_bits = 20, r.window_int_bits = 12, r.attr_subpixel_bits = 12; break;
    case 2: r.window_int_bits = 20, r.attr_subpixel_bits = 40, r.attr_coord_bits = 40; break;
    case 3: r.window_int_bits = 13, r.attr_subpixel_bits = 30, r.attr_coord_bits = 16; break;
  }
  return cfg;
}

// A set-up triangle for the attribute path: vertex 0 anywhere in the window range, the other two
// at offsets of random bit length (so that triangles of every extent, 2^−A px to the whole
// window, and so both outcomes of every int64 check, are drawn), and a candidate rectangle
// around the vertices, clamped to the window range, sometimes widened by the anchor far away.
struct TermsCase {
  SetupTriangle tri;
  TriSetup t;
};
inline TermsCase random_terms_case(std::mt19937_64& rng, const RasterConfig& r) {
  TermsCase c;
  const int A = r.attr_subpixel_bits;
  const int pb = r.window_int_bits + A;  // signed position bits
  const int64_t lim = (int64_t)1 << (pb - 1);
  const auto clampp = [lim](i128 v) { return (int64_t)std::max<i128>(-lim, std::min<i128>(lim - 1, v)); };
  const int64_t ax0 = clampp(rand_bits(rng, pb - 1)), ay0 = clampp(rand_bits(rng, pb - 1));
  const int ob = (int)(rng() % (uint64_t)pb);  // offsets of at most ob bits
  c.tri.v[0].ax = ax0, c.tri.v[0].ay = ay0;
  for (int k = 1; k < 3; ++k) {
    c.tri.v[k].ax = clampp((i128)ax0 + rand_bits(rng, ob));
    c.tri.v[k].ay = clampp((i128)ay0 + rand_bits(rng, ob));
  }
  if (rng() % 16 == 0) c.tri.v[2] = c.tri.v[1];  // zero area
  if (rng() % 16 == 0) {                          // collinear: v2 = 2·v1 − v0
    c.tri.v[2].ax = clampp(2 * (i128)c.tri.v[1].ax - ax0);
    c.tri.v[2].ay = clampp(2 * (i128)c.tri.v[1].ay - ay0);
  }
  const int wlim = 1 << (r.window_int_bits - 1);
  const auto pix = [&](int64_t v) { return (int)std::max<int64_t>(-wlim, std::min<int64_t>(wlim - 1, v >> A)); };
  int lo[2] = {wlim, wlim}, hi[2] = {-wlim, -wlim};
  for (const SetupVertex& v : c.tri.v) {
    lo[0] = std::min(lo[0], pix(v.ax)), hi[0] = std::max(hi[0], pix(v.ax));
    lo[1] = std::min(lo[1], pix(v.ay)), hi[1] = std::max(hi[1], pix(v.ay));
  }
  if (rng() % 8 == 0) lo[rng() % 2] = -wlim;  // a far anchor
  if (rng() % 8 == 0) hi[rng() % 2] = wlim - 1;
  c.t.x0 = lo[0], c.t.x1 = hi[0], c.t.y0 = lo[1], c.t.y1 = hi[1];
  return c;
}

// When attr_edge_terms64 must answer Done: every intermediate value of its formulas fits int64,
// evaluated here in i128 from the reference attribute triangle `a` (a.ok): the cross products
// x_i·y_j, x_j·y_i, their difference, its negation (clockwise), a·2^F, b·2^F, a·X0, b·Y0,
// a·X0 + b·Y0 and + c at the anchor.
inline bool terms_fit64(const AttrSetup& a) {
  const auto in64 = [](i128 v) { return v >= (i128)INT64_MIN && v <= (i128)INT64_MAX; };
  bool ok = true;
  bool cw = false;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const i128 p = (i128)a.x[i] * a.y[j], q = (i128)a.x[j] * a.y[i];
    ok = ok && in64(p) && in64(q) && in64(p - q);
    if (k == 0) cw = p - q < 0;
  }
  if (!ok) return false;
  for (int k = 0; k < 3; ++k)
    if (cw && !in64(a.c[k])) return false;  // the negated constant (a.c is after the negation)
  const i128 unit = p2(a.F), h = p2(a.F - 1);
  const i128 X0 = (i128)a.i0 * unit + h - a.ox, Y0 = (i128)a.j0 * unit + h - a.oy;
  for (int k = 0; k < 3; ++k) {
    const i128 ax = a.a[k] * X0, by = a.b[k] * Y0;
    ok = ok && in64(a.a[k] * unit) && in64(a.b[k] * unit) && in64(ax) && in64(by) && in64(ax + by) &&
         in64(ax + by + a.c[k]);
  }
  return ok;
}

// The outcome of attr_edge_terms64 on `c`, checked against the reference attr_setup +
// attr_edge_terms: Done → every member and 2·area' equal; ZeroArea → the reference's ok = false.
inline AttrTerms64 expect_same_terms(const Config& cfg, const TermsCase& c, const char* what, uint64_t i) {
  AttrEdgeTerms got;
  i128 area2 = -1;
  const AttrTerms64 o = attr_edge_terms64(cfg, c.tri, c.t, got, &area2);
  const AttrSetup a = attr_setup(cfg, c.tri, c.t);
  if (o == AttrTerms64::ZeroArea) {
    EXPECT_FALSE(a.ok) << what << " case " << i;
  }
  if (a.ok) {
    EXPECT_EQ(o == AttrTerms64::Done, terms_fit64(a)) << what << " case " << i;  // Wide only when needed
  }
  if (o != AttrTerms64::Done) return o;
  EXPECT_TRUE(a.ok) << what << " case " << i;
  const AttrEdgeTerms want = attr_edge_terms(a);
  bool same = want.fits64 && got.fits64 && area2 == a.area2 && got.i0 == want.i0 && got.j0 == want.j0;
  for (int k = 0; k < 3; ++k)
    same = same && got.dx[k] == want.dx[k] && got.dy[k] == want.dy[k] && got.e0[k] == want.e0[k] &&
           got.dx64[k] == want.dx64[k] && got.dy64[k] == want.dy64[k] && got.e064[k] == want.e064[k];
  EXPECT_TRUE(same) << what << " case " << i;
  return o;
}

// n random cases over the four configurations; every outcome must be reached (Done and Wide
// each in > 5 % of the cases, ZeroArea > 0.5 %). Returns the Done count.
inline uint64_t check_random_terms(uint64_t seed, uint64_t n) {
  std::mt19937_64 rng(seed);
  uint64_t count[3] = {};
  const Config cfgs[4] = {terms_config(0), terms_config(1), terms_config(2), terms_config(3)};
  for (uint64_t i = 0; i < n; ++i) {
    const Config& cfg = cfgs[i % 4];
    const TermsCase c = random_terms_case(rng, cfg.raster);
    ++count[(int)expect_same_terms(cfg, c, "random", i)];
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_GT(count[(int)AttrTerms64::Done], n / 20);
  EXPECT_GT(count[(int)AttrTerms64::Wide], n / 20);
  EXPECT_GT(count[(int)AttrTerms64::ZeroArea], n / 200);
  return count[(int)AttrTerms64::Done];
}

}  // namespace fxr::attr_cases

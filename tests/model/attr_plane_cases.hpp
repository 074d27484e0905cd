// Cases of the attribute planes' per-triangle fast path (attr_edge_terms / attr_plane,
// model/stages/attr.hpp) against the reference make_attr_plane: attr_plane_test.cpp (directed and
// 10^6 random) and attr_plane_slow_test.cpp (10^8 random, slow label).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

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

}  // namespace fxr::attr_cases

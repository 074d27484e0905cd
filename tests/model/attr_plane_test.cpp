// The attribute planes' per-triangle fast path (attr_edge_terms / attr_plane, model/stages/attr.hpp;
// docs/speed.md "Shortcuts"): the edge terms formed once per triangle and, when all nine fit
// int64_t, each plane term one widening int64 × int64 multiply — against the reference
// make_attr_plane (the i128 formula per plane) and, on the directed cases, against the plane's
// definition evaluated with GMP. Directed: every term at the int64 boundary (2^63 − 1, −2^63
// in, 2^63 and −2^63 − 1 out), the largest F and q, zeros; random: 10^6 cases with both outcomes
// of the 64-bit test (10^8 in attr_plane_slow_test.cpp).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <random>

#include "attr_plane_cases.hpp"
#include "raster_ref.hpp"

using namespace fxr;
using namespace fxr::attr_cases;
using fxr::ref::to_mpz;

namespace {

// The plane from its definition: P(i, j) = Σ_k E'_k(centre(i, j))·q_k with
// E'_k(X, Y) = a_k·X + b_k·Y + c_k, X = (2i + 1)·2^(F−1) − ox (GMP).
mpz_class plane_at(const AttrSetup& s, const int64_t q[3], int i, int j) {
  mpz_class sum = 0;
  for (int k = 0; k < 3; ++k) {
    const mpz_class X = mpz_class(2 * i + 1) * (mpz_class(1) << (s.F - 1)) - to_mpz(s.ox);
    const mpz_class Y = mpz_class(2 * j + 1) * (mpz_class(1) << (s.F - 1)) - to_mpz(s.oy);
    sum += (to_mpz(s.a[k]) * X + to_mpz(s.b[k]) * Y + to_mpz(s.c[k])) * to_mpz(q[k]);
  }
  return sum;
}

void expect_definition(const PlaneCase& c, const char* what) {
  const Plane p = attr_plane(attr_edge_terms(c.s), c.q);
  const int i = p.i0, j = p.j0;
  EXPECT_EQ(to_mpz(p.c), plane_at(c.s, c.q, i, j)) << what;
  EXPECT_EQ(to_mpz(p.dx), plane_at(c.s, c.q, i + 1, j) - plane_at(c.s, c.q, i, j)) << what;
  EXPECT_EQ(to_mpz(p.dy), plane_at(c.s, c.q, i, j + 1) - plane_at(c.s, c.q, i, j)) << what;
}

}  // namespace

TEST(AttrPlane, TermsAtTheInt64BoundaryEqualTheReferenceAndTheDefinition) {
  const i128 max64 = (i128)INT64_MAX, min64 = (i128)INT64_MIN;
  int in = 0, out = 0;
  for (const i128 e : {max64, min64, max64 + 1, min64 - 1, (i128)0, (i128)1, (i128)-1}) {
    for (int which = 0; which < 3; ++which) {  // the boundary value in e0, dx or dy of edge 1
      for (const int F : {1, 20, 40}) {
        PlaneCase c{};
        AttrSetup& s = c.s;
        s.F = F, s.ok = true;
        // Anchor centre X0 = Y0 = 0: i0 = j0 = 0, ox = oy = 2^(F−1); then e0 = c, dx = a·2^F.
        s.ox = s.oy = (int64_t)1 << (F - 1);
        for (int k = 0; k < 3; ++k) s.a[k] = 3 - k, s.b[k] = -(i128)k, s.c[k] = 5 * k;
        if (which == 0) s.c[1] = e;
        // a·2^F at the boundary: ±2^63 needs a = ±2^(63 − F) (2^63 − 1 is odd: not a multiple).
        if (which == 1) s.a[1] = e == max64 + 1 ? p2(63 - F) : e == min64 ? -p2(63 - F) : e == min64 - 1 ? -p2(63 - F) - 1 : e;
        if (which == 2) s.b[1] = e == max64 + 1 ? p2(63 - F) : e == min64 ? -p2(63 - F) : e == min64 - 1 ? -p2(63 - F) - 1 : e;
        for (const int64_t qv : {(int64_t)1, (int64_t)-1, (int64_t)((1ll << 40) - 1), -(int64_t)(1ll << 40)}) {
          c.q[0] = qv, c.q[1] = -qv, c.q[2] = qv / 2;
          if ((which == 0 && (e > max64 || e < min64)) || F == 40) c.q[0] = c.q[1] = c.q[2] = qv % (1 << 20);  // i128 room
          const AttrEdgeTerms t = attr_edge_terms(c.s);
          (t.fits64 ? in : out) += 1;
          expect_same_plane(c, "directed", (uint64_t)(which * 100 + F));
          expect_definition(c, "directed");
        }
      }
    }
  }
  EXPECT_GT(in, 50);  // both outcomes of the 64-bit test
  EXPECT_GT(out, 20);
}

TEST(AttrPlane, RandomCasesEqualTheReference) {
  check_random(0xa77e, 1000000, [](const PlaneCase& c, uint64_t i) {
    if (i % 1000 == 0) expect_definition(c, "random");
  });
}

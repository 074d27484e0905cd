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

// attr_edge_terms64 (the vertices to the edge terms in 64-bit words) at its int64 boundaries,
// default configuration (A = 24, attr_coord_bits = 40: no bit dropped below 2^37): vertex 0 at
// the origin, v1 = (2^32, 0), v2 = (x2, y2), so that 2·area' = 2^32·y2 − x2·0 … — the cross
// product at 2^63 − 2^32 (in), 2^63 (out), −2^63 (in, but its negation for the clockwise
// triangle is out), and the difference of two in-range products leaving int64; then, from
// random triangles, the two sides of the first int64 overflow found by bisection on one vertex
// offset. Every case against the reference attr_setup + attr_edge_terms and the i128 oracle
// terms_fit64 (Done exactly when every intermediate fits).
TEST(AttrTerms64, DirectedInt64BoundariesEqualTheReference) {
  const Config cfg;
  const int A = cfg.raster.attr_subpixel_bits;
  int count[3] = {};
  const auto run = [&](int64_t x1, int64_t y1, int64_t x2, int64_t y2, const char* what) {
    TermsCase c;
    c.tri.v[0].ax = c.tri.v[0].ay = 0;
    c.tri.v[1].ax = x1, c.tri.v[1].ay = y1, c.tri.v[2].ax = x2, c.tri.v[2].ay = y2;
    int lo[2] = {0, 0}, hi[2] = {0, 0};
    for (const SetupVertex& v : c.tri.v) {
      lo[0] = std::min(lo[0], (int)(v.ax >> A)), hi[0] = std::max(hi[0], (int)(v.ax >> A));
      lo[1] = std::min(lo[1], (int)(v.ay >> A)), hi[1] = std::max(hi[1], (int)(v.ay >> A));
    }
    c.t.x0 = lo[0], c.t.x1 = hi[0], c.t.y0 = lo[1], c.t.y1 = hi[1];
    ++count[(int)expect_same_terms(cfg, c, what, 0)];
  };
  const int64_t X = (int64_t)1 << 32, Y = (int64_t)1 << 31;
  run(X, 0, 0, Y - 1, "c = 2^63 - 2^32");
  run(X, 0, 0, Y, "c = 2^63");
  run(X, 0, 0, -Y, "c = -2^63, negated");
  run(X, 0, 0, -Y - 1, "c < -2^63");
  run(X, -Y, Y, Y - 1, "difference 2^63 - 2^32 + 2^62");
  run(X / 2, -Y, Y, Y, "difference of two 2^62 products = 2^63");
  run(1 << 20, 0, 0, 1 << 20, "small");
  run(0, 0, 0, 1 << 20, "zero area");
  EXPECT_GE(count[(int)AttrTerms64::Done], 2);
  EXPECT_GE(count[(int)AttrTerms64::Wide], 4);
  EXPECT_EQ(count[(int)AttrTerms64::ZeroArea], 1);
  // Bisection: a triangle that answers Done, v2 moved along a random direction until Wide; the
  // adjacent offsets on both sides of the flip.
  std::mt19937_64 rng(0x7e64);
  int flips = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Config c2 = terms_config(trial % 2 ? 2 : 0);  // (the narrow ones never leave int64)
    const int pb = c2.raster.window_int_bits + c2.raster.attr_subpixel_bits;
    TermsCase c = random_terms_case(rng, c2.raster);
    AttrEdgeTerms t;
    i128 ar;
    if (attr_edge_terms64(c2, c.tri, c.t, t, &ar) != AttrTerms64::Done) continue;
    const int64_t dx = (int64_t)(rng() % 7) - 3, dy = (int64_t)(rng() % 7) - 3;
    if (dx == 0 && dy == 0) continue;
    const int64_t lim = (int64_t)1 << (pb - 1);
    const auto moved = [&](int64_t s) {
      TermsCase m = c;
      m.tri.v[2].ax = std::max(-lim, std::min(lim - 1, c.tri.v[2].ax + s * dx));
      m.tri.v[2].ay = std::max(-lim, std::min(lim - 1, c.tri.v[2].ay + s * dy));
      return m;
    };
    const auto wide = [&](int64_t s) {
      const TermsCase m = moved(s);
      return attr_edge_terms64(c2, m.tri, m.t, t, &ar) == AttrTerms64::Wide;
    };
    int64_t lo = 0, hi = lim / 2;
    if (!wide(hi)) continue;
    while (hi - lo > 1) {
      const int64_t mid = lo + (hi - lo) / 2;
      (wide(mid) ? hi : lo) = mid;
    }
    // lo: not Wide, hi: Wide — both against the reference and the oracle.
    const TermsCase a = moved(lo), b = moved(hi);
    expect_same_terms(c2, a, "below the flip", (uint64_t)trial);
    EXPECT_EQ(expect_same_terms(c2, b, "at the flip", (uint64_t)trial), AttrTerms64::Wide);
    ++flips;
  }
  EXPECT_GT(flips, 100);
}

TEST(AttrTerms64, RandomTrianglesEqualTheReference) { check_random_terms(0x7e640, 1000000); }

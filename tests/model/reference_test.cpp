// The double reference pipeline and the exact GMP helpers, against hand-checked cases.
#include <cmath>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "reference/reference.hpp"
#include "tests/model/clip_vertex.hpp"

using namespace fxr;

namespace {

ClipVertex cv(float x, float y, float z, float w, float v0 = 0, float v1 = 0) { return test::clip_vertex(x, y, z, w, v0, v1); }

DrawState state(int w, int h, int nv = 2) {
  DrawState st;
  st.viewport_w = w;
  st.viewport_h = h;
  st.num_varyings = nv;
  return st;
}

std::set<std::pair<int, int>> pixels(const RefFrame& f) {
  std::set<std::pair<int, int>> s;
  for (const auto& fr : f.fragments) s.insert({fr.x, fr.y});
  return s;
}

}  // namespace

TEST(Reference, OrthographicQuadCoversExactlyItsPixels) {
  // Viewport 8×8, w = 1: NDC [−0.5, 0.5]² is window [2, 6]²: pixel centres 2.5 … 5.5 → 4 × 4.
  // The shared diagonal passes through pixel centres: the top-left rule gives each to exactly one.
  const DrawState st = state(8, 8);
  std::vector<ClipTriangle> t(2);
  t[0].v[0] = cv(-0.5f, -0.5f, 0.5f, 1);
  t[0].v[1] = cv(0.5f, -0.5f, 0.5f, 1);
  t[0].v[2] = cv(0.5f, 0.5f, 0.5f, 1);
  t[1].v[0] = cv(-0.5f, -0.5f, 0.5f, 1);
  t[1].v[1] = cv(0.5f, 0.5f, 0.5f, 1);
  t[1].v[2] = cv(-0.5f, 0.5f, 0.5f, 1);
  DrawState nodepth = st;
  nodepth.depth_test = false;  // count every fragment
  const RefFrame f = run_reference(nodepth, t);
  std::set<std::pair<int, int>> want;
  for (int y = 2; y < 6; ++y)
    for (int x = 2; x < 6; ++x) want.insert({x, y});
  EXPECT_EQ(pixels(f), want);
  EXPECT_EQ(f.fragments.size(), 16u);  // no pixel twice
  EXPECT_EQ(f.stats.prims_drawn, 2u);
}

TEST(Reference, TopLeftRuleOnEdgesThroughPixelCentres) {
  // Window square [2.5, 5.5]²: every edge runs through pixel centres. Left edge (x = 2.5) and
  // top edge (y = 5.5) are inclusive, right and bottom exclusive: x ∈ {2, 3, 4}, y ∈ {3, 4, 5}.
  const DrawState st = state(8, 8);
  const float a = 2.5f / 4 - 1, b = 5.5f / 4 - 1;  // window → NDC for 8 px
  std::vector<ClipTriangle> t(2);
  t[0].v[0] = cv(a, a, 0.5f, 1);
  t[0].v[1] = cv(b, a, 0.5f, 1);
  t[0].v[2] = cv(b, b, 0.5f, 1);
  t[1].v[0] = cv(a, a, 0.5f, 1);
  t[1].v[1] = cv(b, b, 0.5f, 1);
  t[1].v[2] = cv(a, b, 0.5f, 1);
  DrawState s2 = st;
  s2.depth_test = false;
  const RefFrame f = run_reference(s2, t);
  std::set<std::pair<int, int>> want;
  for (int y = 3; y <= 5; ++y)
    for (int x = 2; x <= 4; ++x) want.insert({x, y});
  EXPECT_EQ(pixels(f), want);
  EXPECT_EQ(f.fragments.size(), 9u);
}

TEST(Reference, PerspectiveCorrectVaryingAndDepthMatchHandSolution) {
  // A = (−1, −1, 0, 1) v 0; B = (2, −2, 1, 2) v 1 (NDC (1, −1)); C = (−1, 1, 0.5, 1) v 0.
  // Pixel (2, 0) of a 4 × 4 viewport, centre NDC (0.25, −0.75). With P = A + s(B − A) + t(C − A):
  // x: (−1 + 3s)/(1 + s) = 1/4 → s = 5/11; y: (−1 − s + 2t)/(1 + s) = −3/4 → t = 2/11.
  // v = s = 5/11; z_c = s + t/2 = 6/11, w = 16/11 → depth 3/8.
  const DrawState st = state(4, 4);
  std::vector<ClipTriangle> t(1);
  t[0].v[0] = cv(-1, -1, 0, 1, 0);
  t[0].v[1] = cv(2, -2, 1, 2, 1);
  t[0].v[2] = cv(-1, 1, 0.5f, 1, 0);
  const RefFrame f = run_reference(st, t);
  bool found = false;
  for (const auto& fr : f.fragments)
    if (fr.x == 2 && fr.y == 0) {
      found = true;
      EXPECT_NEAR(fr.var[0], 5.0 / 11.0, 1e-15);
      EXPECT_NEAR(fr.depth, 3.0 / 8.0, 1e-15);
    }
  EXPECT_TRUE(found);
  const RefSample r = reference_at_pixel(st, t[0], 2, 2.5, 0.5);
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.var[0], 5.0 / 11.0, 1e-15);
  EXPECT_NEAR(r.depth, 3.0 / 8.0, 1e-15);
  EXPECT_NEAR(r.w, 16.0 / 11.0, 1e-15);
  DrawState aff = st;
  aff.interp = InterpMode::Affine;
  const RefFrame g = run_reference(aff, t);
  // Affine: screen barycentric of B. NDC A(−1,−1), B(1,−1), C(−1,1): x = −1 + 2α = 1/4 → α = 5/8.
  bool found_affine = false;
  for (const auto& fr : g.fragments) {
    if (fr.x == 2 && fr.y == 0) {
      found_affine = true;
      EXPECT_NEAR(fr.var[0], 5.0 / 8.0, 1e-15);
    }
  }
  EXPECT_TRUE(found_affine);
}

TEST(Reference, ClippedTriangleValuesMatchTheClipIndependentSolve) {
  // A triangle crossing the near plane z_c = 0 (and w = 0): clipping must not change values.
  const DrawState st = state(32, 32);
  std::vector<ClipTriangle> t(1);
  t[0].v[0] = cv(-0.5f, -0.8f, 0.9f, 1.0f, 0, 1);
  t[0].v[1] = cv(0.9f, -0.6f, 2.5f, 3.0f, 1, 0);
  t[0].v[2] = cv(0.1f, 0.7f, -0.6f, -0.2f, 3, 2);
  const RefFrame f = run_reference(st, t);
  ASSERT_GT(f.fragments.size(), 20u);
  EXPECT_EQ(f.stats.prims_drawn, 1u);
  for (const auto& fr : f.fragments) {
    EXPECT_GE(fr.depth, 0.0);
    EXPECT_LE(fr.depth, 1.0);
    const RefSample r = reference_at_pixel(st, t[0], 2, fr.x + 0.5, fr.y + 0.5);
    ASSERT_TRUE(r.valid);
    EXPECT_NEAR(fr.var[0], r.var[0], 1e-12);
    EXPECT_NEAR(fr.var[1], r.var[1], 1e-12);
    EXPECT_NEAR(fr.depth, r.depth, 1e-12);
  }
}

TEST(Reference, AccountsForEveryPrimitive) {
  const DrawState st = state(16, 16);
  std::vector<ClipTriangle> t(4);
  t[0].v[0] = cv(-1, -1, 0.5f, 1), t[0].v[1] = cv(1, -1, 0.5f, 1), t[0].v[2] = cv(0, 1, 0.5f, 1);  // drawn
  t[1].v[0] = cv(-1, -1, 2, 1), t[1].v[1] = cv(1, -1, 2, 1), t[1].v[2] = cv(0, 1, 2, 1);           // beyond far
  t[2].v[0] = cv(-1, -1, 0.5f, 1), t[2].v[1] = cv(0, 0, 0.5f, 1), t[2].v[2] = cv(1, 1, 0.5f, 1);   // zero area
  t[3].v[0] = cv(NAN, -1, 0.5f, 1), t[3].v[1] = cv(0, 0, 0.5f, 1), t[3].v[2] = cv(1, 1, 0.5f, 1);  // NaN
  const RefFrame f = run_reference(st, t);
  EXPECT_EQ(f.stats.prims_in, 4u);
  EXPECT_EQ(f.stats.prims_drawn, 1u);
  EXPECT_EQ(f.stats.prims_culled_outside, 1u);
  EXPECT_EQ(f.stats.prims_culled_zero_area, 1u);
  EXPECT_EQ(f.stats.prims_rejected_nonfinite, 1u);
}

TEST(Exact, ToMpqIsExact) {
  FxFloat a{false, 3, -2};
  EXPECT_EQ(to_mpq(a), mpq_class(3, 4));
  FxFloat b{true, 5, 3};
  EXPECT_EQ(to_mpq(b), mpq_class(-40));
  FxFloat c{false, (1ull << 40) + 1, -40};
  EXPECT_EQ(to_mpq(c), mpq_class(1) + mpq_class(1) / mpq_class(mpz_class("1099511627776")));
}

TEST(Exact, PerspectiveCorrectValueByHand) {
  // Window triangle (0,0), (4,0), (0,4); at the centre (1.5, 1.5) of pixel (1, 1) the screen
  // barycentrics are (1/4, 3/8, 3/8). With 1/w = (1, 1/2, 1) and v/w = (0, 1/2, 0) (v_B = 1,
  // w_B = 2): v = (3/8 · 1/2) / (1/4 + 3/16 + 3/8) = (3/16) / (13/16) = 3/13. Affine: 3/16.
  ExactVertex v[3];
  v[0] = {0, 0, 0, 1, 0};
  v[1] = {4, 0, mpq_class(1, 2), mpq_class(1, 2), mpq_class(1, 2)};
  v[2] = {0, 4, 1, 1, 0};
  const ExactSample s = exact_at_pixel(v, 1, 1, false);
  EXPECT_TRUE(s.inside);
  EXPECT_EQ(s.v, mpq_class(3, 13));
  EXPECT_EQ(s.z, mpq_class(3, 16) + mpq_class(3, 8));  // 3/8 · 1/2 + 3/8 · 1
  EXPECT_EQ(exact_at_pixel(v, 1, 1, true).v, mpq_class(3, 16));
  // Outside: pixel (3, 3) centre (3.5, 3.5) has x + y > 4.
  EXPECT_FALSE(exact_at_pixel(v, 3, 3, false).inside);
  // Clockwise order covers the same pixels.
  ExactVertex w[3] = {v[0], v[2], v[1]};
  EXPECT_TRUE(exact_at_pixel(w, 1, 1, false).inside);
  EXPECT_EQ(exact_at_pixel(w, 1, 1, false).v, mpq_class(3, 13));
}

TEST(Exact, SharedDiagonalThroughCentresIsCoveredOnce) {
  // Square [0, 4]² split along y = x, which passes through the centres (i + ½, i + ½).
  ExactVertex a{0, 0, 0, 1, 0}, b{4, 0, 0, 1, 0}, c{4, 4, 0, 1, 0}, d{0, 4, 0, 1, 0};
  ExactVertex t1[3] = {a, b, c}, t2[3] = {a, c, d};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      EXPECT_EQ((int)exact_at_pixel(t1, x, y, false).inside + (int)exact_at_pixel(t2, x, y, false).inside, 1)
          << x << "," << y;
}

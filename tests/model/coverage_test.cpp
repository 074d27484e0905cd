// Coverage (stages 5–6) against an independent exact reference: orientation tests in i128 at
// pixel centres with the top-left rule written from its D3D11 definition (top edge: exactly
// horizontal with the triangle below it — y is up; left edge: not horizontal, the triangle to
// its right), plus watertightness of fans and meshes and the exact edge-function identities.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "tests/model/coverage_ref.hpp"

using namespace fxr;

namespace {

using covref::P;
using covref::orient;
using covref::ref_covered;
using covref::ref_top_left;

// ---- model under test -----------------------------------------------------------------------

Config make_cfg(int sub = 8, int wib = 16) {
  Config c;
  c.raster.subpixel_bits = sub;
  c.raster.window_int_bits = wib;
  return c;
}

DrawState make_state(int w, int h, int ox = 0, int oy = 0) {
  DrawState st;
  st.viewport_x = ox;
  st.viewport_y = oy;
  st.viewport_w = w;
  st.viewport_h = h;
  return st;
}

SetupTriangle make_tri(const P v[3]) {
  SetupTriangle t;
  for (int k = 0; k < 3; ++k) {
    t.v[k].x = v[k].x;
    t.v[k].y = v[k].y;
  }
  return t;
}

// Covered pixels as (i, j) pairs, via setup + traversal. Checks spans are well formed.
std::vector<std::pair<int, int>> model_cover(const Config& cfg, const DrawState& st, const P v[3],
                                             SetupOutcome* outcome = nullptr) {
  std::vector<std::pair<int, int>> px;
  TriSetup t;
  const SetupOutcome o = setup_triangle(cfg, st, make_tri(v), t);
  if (outcome) *outcome = o;
  if (o != SetupOutcome::Ok) return px;
  int last_row = INT32_MIN;
  traverse(t, [&](int j, int xb, int xe) {
    EXPECT_GT(j, last_row);
    EXPECT_LE(xb, xe);
    last_row = j;
    for (int i = xb; i <= xe; ++i) px.emplace_back(i, j);
  });
  return px;
}

// Compares model coverage with the reference over the draw rectangle ∩ a loose vertex box.
// Returns the number of differing pixels (and prints the first few).
int compare_coverage(const Config& cfg, const DrawState& st, const P v[3], long* covered = nullptr) {
  const int s = cfg.raster.subpixel_bits;
  const PixelRect dr = draw_rect(st);
  int64_t xmin = std::min({v[0].x, v[1].x, v[2].x}) >> s, xmax = std::max({v[0].x, v[1].x, v[2].x}) >> s;
  int64_t ymin = std::min({v[0].y, v[1].y, v[2].y}) >> s, ymax = std::max({v[0].y, v[1].y, v[2].y}) >> s;
  const int x0 = (int)std::max<int64_t>(dr.x0, xmin - 1), x1 = (int)std::min<int64_t>(dr.x1, xmax + 1);
  const int y0 = (int)std::max<int64_t>(dr.y0, ymin - 1), y1 = (int)std::min<int64_t>(dr.y1, ymax + 1);
  auto m = model_cover(cfg, st, v);
  int diff = 0;
  std::vector<uint8_t> mask;
  const int W = std::max(0, x1 - x0 + 1), H = std::max(0, y1 - y0 + 1);
  mask.assign((size_t)W * H, 0);
  for (auto [i, j] : m) {
    if (i < x0 || i > x1 || j < y0 || j > y1) {
      if (++diff <= 5) ADD_FAILURE() << "model covers (" << i << "," << j << ") outside the candidate area";
      continue;
    }
    mask[(size_t)(j - y0) * W + (i - x0)]++;
  }
  long cov = 0;
  for (int j = y0; j <= y1; ++j)
    for (int i = x0; i <= x1; ++i) {
      const bool r = ref_covered(v, s, i, j);
      cov += r;
      const int got = mask[(size_t)(j - y0) * W + (i - x0)];
      if (got != (int)r) {
        if (++diff <= 5)
          ADD_FAILURE() << "pixel (" << i << "," << j << ") model " << got << " ref " << r << " tri (" << v[0].x
                        << "," << v[0].y << ") (" << v[1].x << "," << v[1].y << ") (" << v[2].x << "," << v[2].y
                        << ") sub=" << s;
      }
    }
  if (covered) *covered += cov;
  return diff;
}

int64_t rnd(std::mt19937_64& g, int64_t lo, int64_t hi) {
  return lo + (int64_t)(g() % (uint64_t)(hi - lo + 1));
}

}  // namespace

// ---- exact identities ---------------------------------------------------------------------

TEST(EdgeFunction, SumOfEdgeValuesIsTwiceTheAreaEverywhere) {
  std::mt19937_64 g(11);
  const Config cfg = make_cfg();
  const DrawState st = make_state(4096, 4096, -2048, -2048);
  const int64_t R = (int64_t)1 << 23;  // full 16.8 range
  int checked = 0;
  for (int n = 0; n < 20000; ++n) {
    P v[3];
    for (auto& p : v) p = {rnd(g, -R, R - 1), rnd(g, -R, R - 1)};
    TriSetup t;
    if (setup_triangle(cfg, st, make_tri(v), t) != SetupOutcome::Ok) continue;
    // 2A independently: the shoelace formula on the input vertices (absolute value).
    i128 a2 = orient(v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y);
    ASSERT_EQ((i128)t.area2, a2 < 0 ? -a2 : a2);
    for (int q = 0; q < 8; ++q) {
      const int64_t X = rnd(g, -R, R - 1), Y = rnd(g, -R, R - 1);
      ASSERT_EQ(edge_eval(t.e[0], X, Y) + edge_eval(t.e[1], X, Y) + edge_eval(t.e[2], X, Y), t.area2);
      ++checked;
    }
    ASSERT_LT(std::max({std::abs(t.e[0].a), std::abs(t.e[0].b)}), (int64_t)1 << (edge_coef_bits(cfg.raster) - 1));
  }
  EXPECT_GT(checked, 100000);
}

TEST(EdgeFunction, SteppingEqualsDirectEvaluation) {
  std::mt19937_64 g(12);
  const Config cfg = make_cfg();
  const DrawState st = make_state(512, 512);
  long checked = 0;
  for (int n = 0; n < 300; ++n) {
    P v[3];
    for (auto& p : v) p = {rnd(g, -100 * 256, 600 * 256), rnd(g, -100 * 256, 600 * 256)};
    TriSetup t;
    if (setup_triangle(cfg, st, make_tri(v), t) != SetupOutcome::Ok) continue;
    EdgeStepper row(t, t.x0, t.y0);
    for (int j = t.y0; j <= t.y1; ++j, row.step_y()) {
      EdgeStepper p = row;
      for (int i = t.x0; i <= t.x1; ++i, p.step_x()) {
        for (int k = 0; k < 3; ++k) {
          const int64_t direct =
              edge_eval(t.e[k], pixel_centre(i, t.g), pixel_centre(j, t.g)) + t.e[k].bias;
          ASSERT_EQ(p.v[k], direct) << "edge " << k << " at (" << i << "," << j << ")";
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000000);
}

TEST(EdgeFunction, TopLeftRuleExcludesSharedEdge) {
  // Two triangles sharing the vertical edge x = 10.5 px and the diagonal through centres.
  const Config cfg = make_cfg();
  const DrawState st = make_state(32, 32);
  const int64_t S = 256, H = 128;
  const P left[3] = {{2 * S + H, 2 * S + H}, {10 * S + H, 2 * S + H}, {10 * S + H, 20 * S + H}};
  const P right[3] = {{10 * S + H, 2 * S + H}, {20 * S + H, 2 * S + H}, {10 * S + H, 20 * S + H}};
  auto a = model_cover(cfg, st, left), b = model_cover(cfg, st, right);
  std::map<std::pair<int, int>, int> cnt;
  for (auto& p : a) cnt[p]++;
  for (auto& p : b) cnt[p]++;
  for (auto& [p, c] : cnt) EXPECT_EQ(c, 1) << p.first << "," << p.second;
  // Column 10 (centre exactly on the shared vertical edge) belongs to the right triangle,
  // for which it is a left edge.
  EXPECT_TRUE(std::count(b.begin(), b.end(), std::make_pair(10, 5)));
  EXPECT_FALSE(std::count(a.begin(), a.end(), std::make_pair(10, 5)));
  // Row 2 (centres on the bottom edge, which is not top): excluded from both.
  EXPECT_FALSE(std::count(a.begin(), a.end(), std::make_pair(5, 2)));
  EXPECT_FALSE(std::count(b.begin(), b.end(), std::make_pair(12, 2)));
  EXPECT_EQ(compare_coverage(cfg, st, left), 0);
  EXPECT_EQ(compare_coverage(cfg, st, right), 0);
}

TEST(EdgeFunction, TopEdgeIsTheOneWithGreaterY) {
  // A horizontal edge through pixel centres at y = 8.5: inclusive when the triangle is below.
  const Config cfg = make_cfg();
  const DrawState st = make_state(32, 32);
  const int64_t S = 256, H = 128;
  const P below[3] = {{2 * S + H, 8 * S + H}, {12 * S, 1 * S}, {20 * S + H, 8 * S + H}};
  const P above[3] = {{2 * S + H, 8 * S + H}, {20 * S + H, 8 * S + H}, {12 * S, 16 * S}};
  auto a = model_cover(cfg, st, below), b = model_cover(cfg, st, above);
  EXPECT_TRUE(std::count(a.begin(), a.end(), std::make_pair(10, 8)));   // top edge: in
  EXPECT_FALSE(std::count(b.begin(), b.end(), std::make_pair(10, 8)));  // bottom edge: out
  EXPECT_EQ(compare_coverage(cfg, st, below), 0);
  EXPECT_EQ(compare_coverage(cfg, st, above), 0);
}

// ---- random coverage against the reference --------------------------------------------------

namespace {

enum class Shape { General, Small, SubPixel, Sliver, Huge, OnCentres, AxisAligned, FullScreen };

void random_tri(std::mt19937_64& g, Shape sh, int s, int W, int H, P v[3]) {
  const int64_t S = (int64_t)1 << s;
  const int64_t half = s > 0 ? S / 2 : 0;
  auto pt = [&](int64_t x0, int64_t x1, int64_t y0, int64_t y1) { return P{rnd(g, x0, x1), rnd(g, y0, y1)}; };
  switch (sh) {
    case Shape::General:
      for (int k = 0; k < 3; ++k) v[k] = pt(-8 * S, (W + 8) * S, -8 * S, (H + 8) * S);
      break;
    case Shape::Small: {
      v[0] = pt(0, W * S, 0, H * S);
      for (int k = 1; k < 3; ++k) v[k] = {v[0].x + rnd(g, -4 * S, 4 * S), v[0].y + rnd(g, -4 * S, 4 * S)};
      break;
    }
    case Shape::SubPixel: {
      v[0] = pt(0, W * S, 0, H * S);
      for (int k = 1; k < 3; ++k) v[k] = {v[0].x + rnd(g, -S, S), v[0].y + rnd(g, -S, S)};
      break;
    }
    case Shape::Sliver: {
      // Long edge across the viewport and the third vertex within a few subpixels of it:
      // aspect ratios up to ~10^4.
      v[0] = pt(-4 * S, (W + 4) * S, -4 * S, (H + 4) * S);
      v[1] = pt(-4 * S, (W + 4) * S, -4 * S, (H + 4) * S);
      const int64_t num = rnd(g, 0, 1000), den = 1000;
      v[2] = {v[0].x + (v[1].x - v[0].x) * num / den + rnd(g, -3, 3),
              v[0].y + (v[1].y - v[0].y) * num / den + rnd(g, -3, 3)};
      break;
    }
    case Shape::Huge: {
      const int64_t R = ((int64_t)1 << 15) * S;
      for (int k = 0; k < 3; ++k) v[k] = pt(-R, R - 1, -R, R - 1);
      break;
    }
    case Shape::OnCentres:  // vertices exactly on pixel centres: ties everywhere
      for (int k = 0; k < 3; ++k) v[k] = {rnd(g, -2, W + 2) * S + half, rnd(g, -2, H + 2) * S + half};
      break;
    case Shape::AxisAligned: {  // right triangles with horizontal and vertical edges through centres
      const int64_t x0 = rnd(g, -2, W + 2) * S + half, y0 = rnd(g, -2, H + 2) * S + half;
      const int64_t x1 = rnd(g, -2, W + 2) * S + half, y1 = rnd(g, -2, H + 2) * S + half;
      v[0] = {x0, y0};
      v[1] = {x1, y0};
      v[2] = (g() & 1) ? P{x0, y1} : P{x1, y1};
      break;
    }
    case Shape::FullScreen: {
      const int64_t R = ((int64_t)1 << 15) * S;
      v[0] = {-rnd(g, W * S, R / 2), -rnd(g, H * S, R / 2)};
      v[1] = {rnd(g, 3 * W * S, R - 1), v[0].y + rnd(g, -S, S)};
      v[2] = {v[0].x + rnd(g, -S, S), rnd(g, 3 * H * S, R - 1)};
      break;
    }
  }
  if (g() & 1) std::swap(v[1], v[2]);  // both windings
}

}  // namespace

TEST(Coverage, EqualsExactReferenceOnRandomTriangles) {
  std::mt19937_64 g(2024);
  struct Mode {
    Shape sh;
    int count;
  };
  const Mode modes[] = {{Shape::General, 20000}, {Shape::Small, 30000}, {Shape::SubPixel, 20000},
                        {Shape::Sliver, 15000},  {Shape::Huge, 3000},   {Shape::OnCentres, 10000},
                        {Shape::AxisAligned, 5000}, {Shape::FullScreen, 1000}};
  long total = 0, covered = 0, culled = 0;
  int diffs = 0;
  for (int sub : {8, 4, 0}) {
    const Config cfg = make_cfg(sub);
    for (const Mode& m : modes) {
      const int n = sub == 8 ? m.count : m.count / 10;
      for (int it = 0; it < n; ++it) {
        // Viewports of varied size and offset, with and without a scissor.
        const int W = 16 + (int)(g() % 48), H = 16 + (int)(g() % 48);
        DrawState st = make_state(W, H, (int)(g() % 5) - 2, (int)(g() % 5) - 2);
        if (g() % 4 == 0) {
          st.scissor_x = (int)(g() % 8);
          st.scissor_y = (int)(g() % 8);
          st.scissor_w = (int)(g() % W);
          st.scissor_h = (int)(g() % H);
        }
        P v[3];
        random_tri(g, m.sh, sub, W, H, v);
        SetupOutcome o;
        model_cover(cfg, st, v, &o);
        culled += o != SetupOutcome::Ok;
        diffs += compare_coverage(cfg, st, v, &covered);
        ++total;
        ASSERT_EQ(diffs, 0) << "shape " << (int)m.sh << " sub " << sub;
      }
    }
  }
  std::printf("coverage: %ld triangles, %ld covered pixels, %ld culled, %d differences\n", total, covered, culled,
              diffs);
  EXPECT_GE(total, 100000);
  EXPECT_EQ(diffs, 0);
}

TEST(Coverage, DegenerateTrianglesAreCulledAsZeroArea) {
  const Config cfg = make_cfg();
  const DrawState st = make_state(64, 64);
  const P collinear[3] = {{100, 100}, {2000, 2000}, {5000, 5000}};
  const P repeated[3] = {{100, 100}, {100, 100}, {5000, 300}};
  const P all_same[3] = {{640, 640}, {640, 640}, {640, 640}};
  const P horizontal[3] = {{0, 1280}, {8000, 1280}, {16000, 1280}};
  for (const P* v : {collinear, repeated, all_same, horizontal}) {
    SetupOutcome o;
    EXPECT_TRUE(model_cover(cfg, st, v, &o).empty());
    EXPECT_EQ(o, SetupOutcome::CulledZeroArea);
  }
}

TEST(Coverage, BackFacesCulledBySignOfArea) {
  const Config cfg = make_cfg();
  DrawState st = make_state(64, 64);
  const P ccw[3] = {{256, 256}, {5000, 256}, {256, 5000}};
  const P cw[3] = {{256, 256}, {256, 5000}, {5000, 256}};
  SetupOutcome o;
  st.cull = CullMode::Back;
  EXPECT_FALSE(model_cover(cfg, st, ccw, &o).empty());
  model_cover(cfg, st, cw, &o);
  EXPECT_EQ(o, SetupOutcome::CulledBackface);
  st.front_ccw = false;
  model_cover(cfg, st, ccw, &o);
  EXPECT_EQ(o, SetupOutcome::CulledBackface);
  st.cull = CullMode::Front;
  EXPECT_FALSE(model_cover(cfg, st, ccw, &o).empty());
  st.cull = CullMode::None;
  EXPECT_EQ(model_cover(cfg, st, ccw).size(), model_cover(cfg, st, cw).size());
}

TEST(Coverage, OutsideScissorIsCulledNoSamples) {
  const Config cfg = make_cfg();
  DrawState st = make_state(64, 64);
  st.scissor_x = 40;
  st.scissor_y = 40;
  st.scissor_w = 10;
  st.scissor_h = 10;
  const P v[3] = {{256, 256}, {5000, 256}, {256, 5000}};
  SetupOutcome o;
  model_cover(cfg, st, v, &o);
  EXPECT_EQ(o, SetupOutcome::CulledNoSamples);
  // A sub-pixel triangle between pixel centres has no candidate pixel at all.
  const P tiny[3] = {{10 * 256 + 10, 10 * 256 + 10}, {10 * 256 + 100, 10 * 256 + 10}, {10 * 256 + 10, 10 * 256 + 100}};
  model_cover(cfg, make_state(64, 64), tiny, &o);
  EXPECT_EQ(o, SetupOutcome::CulledNoSamples);
}

TEST(Coverage, OnePixelTriangleCoversExactlyItsCentre) {
  const Config cfg = make_cfg();
  const DrawState st = make_state(64, 64);
  // Around the centre of pixel (7, 9), half a pixel each way.
  const P v[3] = {{7 * 256, 9 * 256}, {8 * 256, 9 * 256}, {7 * 256 + 128, 10 * 256}};
  auto px = model_cover(cfg, st, v);
  ASSERT_EQ(px.size(), 1u);
  EXPECT_EQ(px[0], std::make_pair(7, 9));
  EXPECT_EQ(compare_coverage(cfg, st, v), 0);
}

// ---- watertightness -----------------------------------------------------------------------

namespace {

// Counts per pixel over the draw rectangle.
struct CountImage {
  int W, H;
  std::vector<int> c;
  CountImage(int w, int h) : W(w), H(h), c((size_t)w * h, 0) {}
  void add(const Config& cfg, const DrawState& st, const P v[3]) {
    for (auto [i, j] : model_cover(cfg, st, v)) c[(size_t)j * W + i]++;
  }
};

// Exact point-in-polygon for a simple polygon (vertices in subpixel units) at the centre of
// pixel (i, j): +1 strictly inside, 0 on the boundary, −1 outside (crossing number, i128).
int ref_in_polygon(const std::vector<P>& poly, int s, int i, int j) {
  const i128 px = (i128)(2 * i + 1) << s, py = (i128)(2 * j + 1) << s;
  bool in = false;
  for (size_t k = 0; k < poly.size(); ++k) {
    const P a = poly[k], b = poly[(k + 1) % poly.size()];
    const i128 ax = 2 * (i128)a.x, ay = 2 * (i128)a.y, bx = 2 * (i128)b.x, by = 2 * (i128)b.y;
    const i128 o = orient(ax, ay, bx, by, px, py);
    if (o == 0 && std::min(ax, bx) <= px && px <= std::max(ax, bx) && std::min(ay, by) <= py && py <= std::max(ay, by))
      return 0;
    if ((ay > py) != (by > py)) {
      // crossing of the ray to +x: x at py > px ⇔ sign(o) matches the edge's upward direction
      if ((by > ay) ? o > 0 : o < 0) in = !in;
    }
  }
  return in ? 1 : -1;
}

struct WaterStats {
  long inside = 0, twice = 0, missed = 0, outside_hits = 0;
};

WaterStats check_union(const CountImage& img, const std::vector<P>& boundary, int s) {
  WaterStats w;
  for (int j = 0; j < img.H; ++j)
    for (int i = 0; i < img.W; ++i) {
      const int c = img.c[(size_t)j * img.W + i];
      const int r = ref_in_polygon(boundary, s, i, j);
      if (c > 1) w.twice++;
      if (r > 0) {
        w.inside++;
        if (c == 0) w.missed++;
      } else if (r < 0 && c > 0) {
        w.outside_hits++;
      }
    }
  return w;
}

}  // namespace

TEST(Watertight, FanOf257TrianglesAroundOneVertex) {
  for (int variant = 0; variant < 4; ++variant) {
    const Config cfg = make_cfg();
    const int W = 128, H = 128;
    const DrawState st = make_state(W, H);
    const int n = 257 + variant * 100;
    // Centre on a pixel centre (variant 0, 2) or off-grid; rim snapped to the subpixel grid.
    const P c = (variant % 2 == 0) ? P{64 * 256 + 128, 64 * 256 + 128} : P{64 * 256 + 37, 63 * 256 + 201};
    std::vector<P> rim;
    for (int k = 0; k < n; ++k) {
      const double a = 2 * 3.14159265358979323846 * k / n;
      // The test's fan geometry is generated in double; the rasterised data are integers.
      rim.push_back({(int64_t)std::llround(c.x + 60 * 256 * std::cos(a)), (int64_t)std::llround(c.y + 60 * 256 * std::sin(a))});
    }
    CountImage img(W, H);
    for (int k = 0; k < n; ++k) {
      P v[3] = {c, rim[k], rim[(k + 1) % n]};
      if (variant >= 2 && (k & 1)) std::swap(v[1], v[2]);  // mixed windings
      img.add(cfg, st, v);
    }
    const WaterStats w = check_union(img, rim, 8);
    std::printf("fan %d triangles: %ld pixels inside, %ld twice, %ld missed, %ld outside\n", n, w.inside, w.twice,
                w.missed, w.outside_hits);
    EXPECT_GT(w.inside, 10000);
    EXPECT_EQ(w.twice, 0);
    EXPECT_EQ(w.missed, 0);
    EXPECT_EQ(w.outside_hits, 0);
  }
}

TEST(Watertight, JitteredGridsAndRandomDiagonals) {
  std::mt19937_64 g(77);
  long total_inside = 0, total_twice = 0, total_missed = 0, total_outside = 0, tris = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int sub = trial % 3 == 0 ? 4 : 8;
    const Config cfg = make_cfg(sub);
    const int64_t S = (int64_t)1 << sub;
    const int W = 96, H = 80;
    const DrawState st = make_state(W, H);
    const int nx = 4 + (int)(g() % 20), ny = 4 + (int)(g() % 20);
    // Grid over [x0, x1] × [y0, y1] (subpixel units), partly outside the viewport; on pixel
    // centres (no jitter) for some trials, jittered interior vertices otherwise.
    const bool centres = trial % 4 == 1;
    const int64_t x0 = (int64_t)((int)(g() % 20) - 10) * S + (centres ? S / 2 : rnd(g, 0, S - 1));
    const int64_t y0 = (int64_t)((int)(g() % 20) - 10) * S + (centres ? S / 2 : rnd(g, 0, S - 1));
    const int64_t cw = (centres ? S * (1 + (int64_t)(g() % 8)) : rnd(g, S / 2, 8 * S));
    const int64_t ch = (centres ? S * (1 + (int64_t)(g() % 8)) : rnd(g, S / 2, 8 * S));
    std::vector<P> pts((size_t)(nx + 1) * (ny + 1));
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        P p{x0 + i * cw, y0 + j * ch};
        if (!centres && i > 0 && i < nx && j > 0 && j < ny) {
          // ≤ 1/5 of a cell per coordinate keeps every quad convex (each vertex stays more
          // than 1/√2 − 2·(√2/5) > 0 cell diagonals from the opposite diagonal), so both
          // diagonal choices tile the cell.
          p.x += rnd(g, -cw / 5, cw / 5);
          p.y += rnd(g, -ch / 5, ch / 5);
        }
        pts[(size_t)j * (nx + 1) + i] = p;
      }
    CountImage img(W, H);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const P a = pts[(size_t)j * (nx + 1) + i], b = pts[(size_t)j * (nx + 1) + i + 1];
        const P c = pts[(size_t)(j + 1) * (nx + 1) + i], d = pts[(size_t)(j + 1) * (nx + 1) + i + 1];
        P t1[3], t2[3];
        if (g() & 1) {
          t1[0] = a, t1[1] = b, t1[2] = d, t2[0] = a, t2[1] = d, t2[2] = c;
        } else {
          t1[0] = a, t1[1] = b, t1[2] = c, t2[0] = b, t2[1] = d, t2[2] = c;
        }
        if (g() & 1) std::swap(t1[1], t1[2]);
        if (g() & 1) std::swap(t2[1], t2[2]);
        img.add(cfg, st, t1);
        img.add(cfg, st, t2);
        tris += 2;
      }
    const std::vector<P> boundary = {pts[0], pts[(size_t)nx], pts[(size_t)ny * (nx + 1) + nx],
                                     pts[(size_t)ny * (nx + 1)]};
    const WaterStats w = check_union(img, boundary, sub);
    total_inside += w.inside, total_twice += w.twice, total_missed += w.missed, total_outside += w.outside_hits;
  }
  std::printf("grids: %ld triangles, %ld pixels inside, %ld twice, %ld missed, %ld outside\n", tris, total_inside,
              total_twice, total_missed, total_outside);
  EXPECT_GT(total_inside, 50000);
  EXPECT_EQ(total_twice, 0);
  EXPECT_EQ(total_missed, 0);
  EXPECT_EQ(total_outside, 0);
}

// Line rasterisation (issue 15, docs/lines.md): the model's pixels against the exact references
// of both rules (tests/model/line_ref.hpp), every pixel of every segment, a few thousand
// segments per run (the 10^5-segment run is line_slow_test.cpp), plus hand-worked examples.
#include <gtest/gtest.h>

#include "line_check.hpp"

using namespace fxr;

namespace {

RasterConfig raster(int S, int W) {
  RasterConfig r;
  r.subpixel_bits = S;
  r.window_int_bits = W;
  return r;
}
LineConfig line(LineRule rule, LineEndpoints e = LineEndpoints::HalfOpen) {
  LineConfig c;
  c.rule = rule;
  c.endpoints = e;
  return c;
}
std::vector<LinePixel> px(std::initializer_list<LinePixel> l) { return l; }

}  // namespace

// Hand-worked (S = 8, one pixel = 256): a horizontal segment on the row boundary y = 1 from
// x = 0.5 to x = 3.5: centres 0.5, 1.5, 2.5 (3.5 excluded, half-open), tie → the smaller row 0.
TEST(Line, MidpointTieOnRowBoundaryGoesToSmallerRowAndHalfOpenDropsLastCentre) {
  const RasterConfig r = raster(8, 16);
  const LineIn s{128, 256, 3 * 256 + 128, 256};
  EXPECT_EQ(line_pixels(r, line(LineRule::Midpoint), s), px({{0, 0}, {1, 0}, {2, 0}}));
  EXPECT_EQ(line_pixels(r, line(LineRule::Midpoint, LineEndpoints::Closed), s), px({{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  // The same segment drawn the other way round: the same pixels in the same order.
  EXPECT_EQ(line_pixels(r, line(LineRule::Midpoint), LineIn{s.x1, s.y1, s.x0, s.y0}),
            px({{0, 0}, {1, 0}, {2, 0}}));
}

// Diamond exit: on the row boundary the line passes through the diamonds' corners (open): nothing.
TEST(Line, DiamondExitLineThroughDiamondCornersProducesNothing) {
  EXPECT_TRUE(line_pixels(raster(8, 16), line(LineRule::DiamondExit), LineIn{128, 256, 3 * 256 + 128, 256}).empty());
}

// Diamond exit from centre (0.5, 0.5) to centre (3.5, 0.5): the last diamond contains p_b, so
// pixels 0, 1, 2; drawn backwards, pixels 3, 2, 1 (direction matters by design).
TEST(Line, DiamondExitDropsTheLastPixelOfEachDirection) {
  const RasterConfig r = raster(8, 16);
  const LineIn s{128, 128, 3 * 256 + 128, 128};
  EXPECT_EQ(line_pixels(r, line(LineRule::DiamondExit), s), px({{0, 0}, {1, 0}, {2, 0}}));
  EXPECT_EQ(line_pixels(r, line(LineRule::DiamondExit), LineIn{s.x1, s.y1, s.x0, s.y0}), px({{1, 0}, {2, 0}, {3, 0}}));
}

// A steep segment in the third octant backwards: y-major, one pixel per row, 8-connected.
TEST(Line, MidpointStreamsOnePixelPerMajorStepEightConnected) {
  const RasterConfig r = raster(8, 16);
  line_ref::SegmentGen gen(r, 7);
  for (int t = 0; t < 2000; ++t) {
    const LineIn s = gen.next(line_ref::SegClass::Random);
    const auto p = line_pixels(r, line(LineRule::Midpoint), s);
    const LineSetup st = line_setup(r, line(LineRule::Midpoint), s);
    ASSERT_EQ((int64_t)p.size(), st.count);
    for (size_t k = 1; k < p.size(); ++k) {
      const int32_t dmaj = st.y_major ? p[k].y - p[k - 1].y : p[k].x - p[k - 1].x;
      const int32_t dmin = st.y_major ? p[k].x - p[k - 1].x : p[k].y - p[k - 1].y;
      ASSERT_EQ(dmaj, 1);
      ASSERT_LE(std::abs(dmin), 1);
    }
  }
}

// Every pixel of 7 classes × 1000 segments (100 guard-band-long) against the exact references,
// at the default grid and at coarse / no subpixel grids.
TEST(Line, MatchesExactReferenceOfBothRulesForEverySegmentClass) {
  for (const RasterConfig& r : {raster(8, 16), raster(4, 12), raster(0, 10)})
    for (const LineConfig& c : {line(LineRule::Midpoint), line(LineRule::Midpoint, LineEndpoints::Closed),
                                line(LineRule::DiamondExit)}) {
      const line_check::Counts k = line_check::check(r, c, 1, 1000);
      EXPECT_EQ(k.mismatched_segments, 0u) << "S=" << r.subpixel_bits << " rule=" << (int)c.rule
                                           << " endpoints=" << (int)c.endpoints << " first: " << k.first;
      EXPECT_EQ(k.reverse_mismatches, 0u);
      EXPECT_GT(k.pixels, k.segments);
    }
}

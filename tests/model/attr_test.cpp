// The attribute path (issue 8; model/stages/attr.hpp, docs/pipeline.md "Attribute positions"):
// per-vertex attribute positions, depth, 1/w and v/w are the exact quotients rounded once (checked
// against the GMP geometry reference of geom_ref.hpp for many widths, clipped triangles included),
// and the attribute planes are exact on the model's own attribute triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geom_ref.hpp"
#include "model/stages/attr.hpp"

using namespace fxr;
using namespace georef;

namespace {

ClipTriangle random_tri(std::mt19937_64& rng, int nv, bool clipped) {
  std::uniform_real_distribution<double> u(-1.2, 1.2), z(0, 1), lw(std::log(1e-3), std::log(1e3)), var(-1000, 1000);
  ClipTriangle t;
  for (auto& v : t.v) {
    const double w = std::exp(lw(rng));
    v.pos[0] = (float)(u(rng) * w * (clipped ? 20 : 0.8));
    v.pos[1] = (float)(u(rng) * w * (clipped ? 20 : 0.8));
    v.pos[2] = (float)((clipped ? z(rng) * 1.4 - 0.2 : z(rng)) * w);
    v.pos[3] = (float)w;
    if (!clipped) v.pos[2] = std::min(v.pos[2], v.pos[3]);
    for (int k = 0; k < nv; ++k) v.var[k] = (float)var(rng);
  }
  return t;
}

}  // namespace

TEST(Attr, PerVertexValuesAreExactQuotientsRoundedOnce) {
  std::mt19937_64 rng(0xa77a0001);
  const DrawState st = state(1024, 768, 0, 0, 3);
  const int attr_bits[] = {9, 16, 24, 30, 40}, sig_bits[] = {24, 32, 40};
  int diffs = 0, checked = 0;
  for (int a : attr_bits)
    for (int s : sig_bits) {
      Config cfg;
      cfg.raster.attr_subpixel_bits = a;
      cfg.raster.attr_sig_bits = s;
      for (int i = 0; i < 200; ++i) {
        diffs += compare_with_reference(cfg, st, random_tri(rng, 3, i % 2 == 1));
        ++checked;
      }
    }
  EXPECT_EQ(diffs, 0) << "of " << checked << " triangles";
}

TEST(Attr, QuotientRoundsToNearestEven) {
  const FxFloat one{false, 1, 0}, three{false, 3, 0};
  // 1/3 = 1.0101 0101…b·2^-2: 4 significant bits 1010, the rest 1010… > ½ ulp → 1011·2^-5.
  const FxFloat q = attr_quotient(one, three, 4);
  EXPECT_EQ(q.sig, 0b1011u);
  EXPECT_EQ(q.exp, -5);
  // Exact quotients are exact: 3/4 at 2 bits.
  const FxFloat four{false, 4, 0};
  const FxFloat r = attr_quotient(three, four, 2);
  EXPECT_EQ(r.sig, 3u);
  EXPECT_EQ(r.exp, -2);
  // Ties to even: 5/4 = 1.01b to 2 bits → 1.0b (even), 7/4 = 1.11b → 10.0b (carry).
  const FxFloat five{false, 5, 0}, seven{false, 7, 0};
  EXPECT_EQ(attr_quotient(five, four, 2).sig, 2u);
  const FxFloat c = attr_quotient(seven, four, 2);
  EXPECT_EQ(c.sig, 2u);
  EXPECT_EQ(c.exp, 0);
}

TEST(Attr, AtMostSubpixelBitsIsTheSnappedPath) {
  std::mt19937_64 rng(0xa77a0002);
  const DrawState st = state(256, 256, 0, 0, 2);
  for (int a : {0, 4, 8}) {
    Config cfg;
    cfg.raster.attr_subpixel_bits = a;
    EXPECT_FALSE(attr_separate(cfg.raster));
    std::vector<SetupTriangle> out;
    RasterStats s;
    const ClipTriangle t = random_tri(rng, 2, false);
    ASSERT_EQ(geometry(cfg, st, t, 0, out, s), GeomOutcome::Emitted);
    for (const SetupVertex& v : out[0].v) {
      EXPECT_EQ(v.ax, v.x);
      EXPECT_EQ(v.ay, v.y);
    }
    EXPECT_EQ(compare_with_reference(cfg, st, t), 0);
  }
}

// The setup vector unit (model/vectors/setup_vectors.hpp): its fields are the records' visit()
// lists, and its directed and random cases reach every outcome and both plane paths, so the
// co-simulation of rtl/fxr_setup.sv (tb/setup_test.cpp) exercises all of them.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "model/stages/setup.hpp"
#include "model/vectors/setup_vectors.hpp"
#include "model/vectors/vectors.hpp"

namespace fxr {
namespace {

TEST(SetupVectors, FieldsAreTheRecordsInVisitOrder) {
  const auto m = make_vector_model("setup", Config{});
  const VecLayout& l = m->layout();
  // Inputs: SetupTriangle (prim, v0_x, v0_y, …), then the draw state; outputs: outcome, then
  // TriangleEquations with prim renamed (it is also an input).
  EXPECT_EQ(l[0].name, "prim");
  EXPECT_EQ(l[1].name, "v0_x");
  EXPECT_EQ(l[(size_t)l.index("viewport_x") - 1].name, "v2_vw" + std::to_string(kSetupVecVaryings - 1) + "_exp");
  const size_t o = (size_t)l.index("outcome");
  ASSERT_EQ(l.outputs().front(), (int)o);
  EXPECT_EQ(l[o + 1].name, "out_prim");
  EXPECT_EQ(l[o + 2].name, "e0_a");
  EXPECT_EQ(l[l.size() - 1].name, "num" + std::to_string(kSetupVecVaryings - 1) + "_exp");
  // Widths from the configuration (docs/pipeline.md, stage 5 and "Attribute positions").
  const RasterConfig r;
  EXPECT_EQ(l[(size_t)l.index("e0_c")].width, edge_value_bits(r));
  EXPECT_EQ(l[(size_t)l.index("z_c")].width, depth_plane_bits(r));
  EXPECT_EQ(l[(size_t)l.index("num0_c")].width, interp_plane_bits(r));
  EXPECT_GT(interp_plane_bits(r), 64);  // the wide-field path of the vectors and the ports
}

TEST(SetupVectors, CasesReachEveryOutcomeAndBothPlanePaths) {
  const auto m = make_vector_model("setup", Config{});
  const VecLayout& l = m->layout();
  const size_t oc = (size_t)l.index("outcome"), x0 = (size_t)l.index("x0"), y0 = (size_t)l.index("y0");
  const size_t zi = (size_t)l.index("z_i0"), zj = (size_t)l.index("z_j0");
  const size_t nd = m->directed().size();
  std::map<int, int> dir, rnd;
  int fallback = 0, anchored = 0;
  size_t n = 0;
  const uint64_t count = 2000;
  generate_vectors(*m, 1, count, false, [&](const VecRow& r) {
    const int o = (int)r[oc];
    (n++ < nd ? dir : rnd)[o]++;
    if (o != (int)SetupOutcome::Ok) return;
    // Planes anchored at the candidate rectangle's corner (attribute triangle) or at pixel
    // (0, 0) (the snapped triangle, when the attribute triangle has zero area).
    if (r[zi] == r[x0] && r[zj] == r[y0]) ++anchored;
    if (r[zi] == 0 && r[zj] == 0 && (r[x0] != 0 || r[y0] != 0)) ++fallback;
  });
  for (int o = 0; o <= (int)SetupOutcome::RejectedRange; ++o) {
    EXPECT_GT(dir[o], 0) << "directed, outcome " << o;
    EXPECT_GT(rnd[o], 0) << "random, outcome " << o;
  }
  EXPECT_GT(rnd[(int)SetupOutcome::Ok], (int)count / 4);  // most triangles reach the planes
  EXPECT_GT(fallback, 0);
  EXPECT_GT(anchored, (int)count / 4);
}

}  // namespace
}  // namespace fxr

// Co-simulation of the line stage, rtl/fxr_line_rec.sv (rtl/fxr_line.sv's walk with record ports and
// the draw rectangle's discard), under Verilator on transaction dumps (tb/txn_harness.hpp): the
// committed dump of scenes/transactions.json (9 segments reaching every line outcome) and the
// default scene's wireframe variant dumped at build time (3,298 segments), every pixel
// bit-identical and in order with the model's line.out, under random input gaps and output
// back-pressure; and the harness catching a corrupted expected pixel. docs/lines.md, "RTL".
#include <gtest/gtest.h>

#include <cstdio>
#include <tuple>

#include "Vfxr_line_rec.h"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kWireframe = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("line", run, seed, gap, stall);
}

TEST(LineTxn, CommittedDumpMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kCommitted, "line");
  ASSERT_GT(v.in.rows, 5u);
  ASSERT_GT(v.out.rows, 50u);
  for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
    const TxnResult r =
        fxr::tb::run_txn<Vfxr_line_rec>(v, nullptr, opts("line_committed_" + std::to_string(seed), seed, gap, stall));
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
  }
}

// The wireframe of the default scene (the face's edges and the bunny's silhouette): the unit's own
// rate without gaps or stalls (busy cycles per segment and per pixel), then the same stream under
// gaps and back-pressure.
TEST(LineTxn, WireframeSceneMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kWireframe, "line");
  ASSERT_GT(v.in.rows, 1000u);
  ASSERT_GT(v.out.rows, 1000u);
  const TxnResult r = fxr::tb::run_txn<Vfxr_line_rec>(v, nullptr, opts("line_wireframe", 1, 0, 0));
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.outputs, v.out.rows);
  EXPECT_EQ(r.inputs, v.in.rows);
  std::printf("line wireframe scene: %llu segments, %llu pixels, %llu busy cycles: %.3f cycles/segment, "
              "%.3f cycles/pixel\n",
              (unsigned long long)v.in.rows, (unsigned long long)v.out.rows, (unsigned long long)r.busy_cycles,
              (double)r.busy_cycles / (double)v.in.rows, (double)r.busy_cycles / (double)v.out.rows);
  const TxnResult s = fxr::tb::run_txn<Vfxr_line_rec>(v, nullptr, opts("line_wireframe_stalls", 7, 25, 25));
  EXPECT_TRUE(s.passed());
  EXPECT_EQ(s.outputs, v.out.rows);
}

// The checker can fail: one bit of x in row 6 of the expected pixels flipped -> exactly that row
// and field are reported (and the waveform written).
TEST(LineTxn, CorruptedExpectedPixelIsReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "line");
  size_t cx = 0;
  for (size_t f = 0; f < v.out.lay.size(); ++f)
    if (v.out.lay[f].name == "x") cx = f;
  ASSERT_GT(cx, 0u);
  v.out.data[5 * v.out.lay.size() + cx] ^= 1;
  const TxnResult r = fxr::tb::run_txn<Vfxr_line_rec>(v, nullptr, opts("line_corrupt", 2, 25, 25));
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].out_row, 5u);
  EXPECT_EQ(r.mismatches[0].cls, "x");
  EXPECT_NE(r.mismatches[0].text.find("line.out.hex:6: field 'x'"), std::string::npos) << r.mismatches[0].text;
  EXPECT_TRUE(std::filesystem::exists(r.wave));
}

}  // namespace

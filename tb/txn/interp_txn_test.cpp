// Co-simulation of rtl/fxr_interp.sv (Verilator) on transaction dumps (tb/txn_harness.hpp): the
// committed dump of scenes/transactions.json and the default scene dumped at build time, every
// plane sample (depth code, 1/w and v/w sums) bit-identical and in order with the model's
// interp.out, the triangle's equations of setup.out on ctx_i, under random input gaps and output
// back-pressure; and the harness catching a corrupted expected sample. docs/rtl.md, "fxr_interp".
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "Vfxr_interp.h"
#include "txn/backend_sets.hpp"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kDefault = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("interp", run, seed, gap, stall);
}

size_t col(const fxr::VecLayout& lay, const char* n) {
  for (size_t f = 0; f < lay.size(); ++f)
    if (lay[f].name == n) return f;
  ADD_FAILURE() << "no field " << n;
  return 0;
}

TEST(InterpTxn, CommittedDumpMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kCommitted, "interp");
  const SceneStageVectors setup = fxr::load_scene_stage(kCommitted, "setup");
  ASSERT_GT(v.out.rows, 10u);
  for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
    const TxnResult r =
        fxr::tb::run_txn<Vfxr_interp>(v, &setup.out, opts("interp_committed_" + std::to_string(seed), seed, gap, stall));
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
  }
}

// The committed back-end vectors (every geometric case; perspective and affine draw states).
TEST(InterpTxn, CommittedBackendSetsMatchTheModel) {
  for (const auto& [dir, name] : fxr::tb::committed_backend_dumps()) {
    const SceneStageVectors v = fxr::load_scene_stage(dir, "interp");
    const SceneStageVectors setup = fxr::load_scene_stage(dir, "setup");
    ASSERT_GT(v.out.rows, 0u) << dir;
    for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
      const TxnResult r = fxr::tb::run_txn<Vfxr_interp>(
          v, &setup.out, opts("interp_" + name + "_" + std::to_string(seed), seed, gap, stall));
      EXPECT_TRUE(r.passed()) << dir << " seed " << seed;
      EXPECT_EQ(r.outputs, v.out.rows) << dir;
      EXPECT_EQ(r.inputs, v.in.rows) << dir;
    }
  }
}

// Clocks per span and per fragment of the default scene (no gaps, no stalls: the unit's own
// rate), then the same stream under gaps and back-pressure.
TEST(InterpTxn, DefaultSceneMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kDefault, "interp");
  const SceneStageVectors setup = fxr::load_scene_stage(kDefault, "setup");
  ASSERT_GT(v.out.rows, 1000u);
  const TxnResult r = fxr::tb::run_txn<Vfxr_interp>(v, &setup.out, opts("interp_default", 1, 0, 0));
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.outputs, v.out.rows);
  const double clocks = (double)(r.last_out_cycle - r.first_in_cycle + 1);
  std::printf("interp default scene: %llu spans, %llu samples, %.0f clocks: %.3f clocks/span, %.3f clocks/sample, "
              "%.0f cycles/s\n",
              (unsigned long long)v.in.rows, (unsigned long long)v.out.rows, clocks, clocks / (double)v.in.rows,
              clocks / (double)v.out.rows, r.seconds > 0 ? (double)r.cycles / r.seconds : 0.0);
  const TxnResult s = fxr::tb::run_txn<Vfxr_interp>(v, &setup.out, opts("interp_default_stalls", 7, 25, 25));
  EXPECT_TRUE(s.passed());
  EXPECT_EQ(s.outputs, v.out.rows);
}

// The checker can fail: one bit of num1 of sample 4 flipped -> exactly that row and field.
TEST(InterpTxn, CorruptedExpectedSampleIsReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "interp");
  const SceneStageVectors setup = fxr::load_scene_stage(kCommitted, "setup");
  const size_t c = col(v.out.lay, "num1");
  ASSERT_GT(c, 0u);
  v.out.data[3 * v.out.lay.size() + c] ^= (fxr::vec_word)1 << 70;
  const TxnResult r = fxr::tb::run_txn<Vfxr_interp>(v, &setup.out, opts("interp_corrupt", 2, 25, 25));
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].out_row, 3u);
  EXPECT_EQ(r.mismatches[0].cls, "num1");
  EXPECT_TRUE(std::filesystem::exists(r.wave));
}

}  // namespace

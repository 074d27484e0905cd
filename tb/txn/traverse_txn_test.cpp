// Co-simulation of rtl/fxr_traverse.sv (Verilator) on transaction dumps (tb/txn_harness.hpp):
// the committed dump of scenes/transactions.json and the default scene dumped at build time, every
// span bit-identical and in order with the model's traverse.out, under random input gaps and
// output back-pressure; and the harness catching a corrupted and a swapped expected row.
// docs/rtl.md, "fxr_traverse".
#include <gtest/gtest.h>

#include <cstdio>
#include <utility>

#include "Vfxr_traverse.h"
#include "txn/backend_sets.hpp"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kDefault = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("traverse", run, seed, gap, stall);
}

TEST(TraverseTxn, CommittedDumpMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kCommitted, "traverse");
  ASSERT_GT(v.out.rows, 10u);
  for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
    const TxnResult r = fxr::tb::run_txn<Vfxr_traverse>(v, nullptr, opts("traverse_committed_" + std::to_string(seed), seed, gap, stall));
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
  }
}

// The committed back-end vectors (top-left ties, 1-pixel, sub-pixel, slivers, full-viewport and
// guard-band triangles, w ratio 10^6; every draw state).
TEST(TraverseTxn, CommittedBackendSetsMatchTheModel) {
  for (const auto& [dir, name] : fxr::tb::committed_backend_dumps()) {
    const SceneStageVectors v = fxr::load_scene_stage(dir, "traverse");
    ASSERT_GT(v.out.rows, 0u) << dir;
    for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
      const TxnResult r =
          fxr::tb::run_txn<Vfxr_traverse>(v, nullptr, opts("traverse_" + name + "_" + std::to_string(seed), seed, gap, stall));
      EXPECT_TRUE(r.passed()) << dir << " seed " << seed;
      EXPECT_EQ(r.outputs, v.out.rows) << dir;
      EXPECT_EQ(r.inputs, v.in.rows) << dir;
    }
  }
}

// Cycles per span / per row / per triangle of the default scene (no gaps, no stalls: the unit's
// own rate), then the same stream under gaps and back-pressure.
TEST(TraverseTxn, DefaultSceneMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kDefault, "traverse");
  ASSERT_GT(v.out.rows, 1000u);
  const TxnResult r = fxr::tb::run_txn<Vfxr_traverse>(v, nullptr, opts("traverse_default", 1, 0, 0));
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.outputs, v.out.rows);
  // Rows walked: y1 − y0 + 1 of every non-empty candidate rectangle (the record's own fields).
  uint64_t rows = 0;
  const auto& lay = v.in.lay;
  auto col = [&](const char* n) {
    for (size_t f = 0; f < lay.size(); ++f)
      if (lay[f].name == n) return f;
    ADD_FAILURE() << n;
    return (size_t)0;
  };
  const size_t cx0 = col("x0"), cx1 = col("x1"), cy0 = col("y0"), cy1 = col("y1");
  for (uint64_t i = 0; i < v.in.rows; ++i) {
    const fxr::VecRow row = v.in.row(i);
    const int64_t x0 = fxr::vec_unpack_signed(row[cx0], lay[cx0].width), x1 = fxr::vec_unpack_signed(row[cx1], lay[cx1].width);
    const int64_t y0 = fxr::vec_unpack_signed(row[cy0], lay[cy0].width), y1 = fxr::vec_unpack_signed(row[cy1], lay[cy1].width);
    if (x1 >= x0 && y1 >= y0) rows += (uint64_t)(y1 - y0 + 1);
  }
  std::printf("traverse default scene: %llu triangles, %llu rows, %llu spans, %llu busy cycles: %.3f cycles/triangle, "
              "%.3f cycles/row, %.3f cycles/span\n",
              (unsigned long long)v.in.rows, (unsigned long long)rows, (unsigned long long)v.out.rows,
              (unsigned long long)r.busy_cycles, (double)r.busy_cycles / (double)v.in.rows,
              (double)r.busy_cycles / (double)rows, (double)r.busy_cycles / (double)v.out.rows);
  const TxnResult s = fxr::tb::run_txn<Vfxr_traverse>(v, nullptr, opts("traverse_default_stalls", 7, 25, 25));
  EXPECT_TRUE(s.passed());
  EXPECT_EQ(s.outputs, v.out.rows);
}

// The checker can fail: one bit of x1 in row 6 of the expected spans is flipped -> exactly that
// row and field are reported (and the waveform written).
TEST(TraverseTxn, CorruptedExpectedRowIsReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "traverse");
  size_t cx1 = 0;
  for (size_t f = 0; f < v.out.lay.size(); ++f)
    if (v.out.lay[f].name == "x1") cx1 = f;
  ASSERT_GT(cx1, 0u);
  v.out.data[5 * v.out.lay.size() + cx1] ^= 1;
  TxnOptions o = opts("traverse_corrupt", 2, 25, 25);
  const TxnResult r = fxr::tb::run_txn<Vfxr_traverse>(v, nullptr, o);
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].out_row, 5u);
  EXPECT_EQ(r.mismatches[0].cls, "x1");
  EXPECT_NE(r.mismatches[0].text.find("traverse.out.hex:6: field 'x1'"), std::string::npos) << r.mismatches[0].text;
  EXPECT_TRUE(std::filesystem::exists(r.wave));
}

// Two expected rows of different rows swapped -> both reported; one row dropped -> the rest
// shifts (mismatches) and the last output is extra.
TEST(TraverseTxn, SwappedAndDroppedRowsAreReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "traverse");
  const size_t n = v.out.lay.size();
  SceneStageVectors sw = v;
  std::swap_ranges(sw.out.data.begin() + 3 * (ptrdiff_t)n, sw.out.data.begin() + 4 * (ptrdiff_t)n,
                   sw.out.data.begin() + 4 * (ptrdiff_t)n);
  TxnOptions o = opts("traverse_swapped", 3, 25, 25);
  o.write_wave = false;
  const TxnResult r = fxr::tb::run_txn<Vfxr_traverse>(sw, nullptr, o);
  EXPECT_EQ(r.errors, 2u);
  ASSERT_EQ(r.mismatches.size(), 2u);
  EXPECT_EQ(r.mismatches[0].out_row, 3u);
  EXPECT_EQ(r.mismatches[1].out_row, 4u);

  SceneStageVectors dr = v;
  dr.out.data.erase(dr.out.data.end() - (ptrdiff_t)n, dr.out.data.end());  // the final span
  --dr.out.rows;
  o.run_name = "traverse_dropped";
  const TxnResult d = fxr::tb::run_txn<Vfxr_traverse>(dr, nullptr, o);
  EXPECT_FALSE(d.passed());
  EXPECT_EQ(d.classes.count("extra"), 1u);
}

}  // namespace

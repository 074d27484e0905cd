// Co-simulation of rtl/fxr_divide.sv (stage 9, Verilator) on transaction dumps (tb/txn_harness.hpp):
// every fragment bit-identical and in order with the model's divide.out, under random input gaps
// and output back-pressure, for Lanes = NumVaryings (one fragment per clock) and Lanes = 1
// (NumVaryings clocks per fragment), with the default divider (radix2, per varying) on the committed
// dump and the default scene, and with div.algorithm = shared_recip (one reciprocal per pixel) on
// the default scene dumped with that configuration; the measured latency and II equal
// fxr::divide_cost; the harness catches a corrupted, a swapped and a dropped expected row.
// docs/rtl.md, "fxr_divide".
#include <gtest/gtest.h>

#include <cstdio>
#include <utility>

#include "Vfxr_divide.h"
#include "Vfxr_divide__shared_recip.h"
#include "Vfxr_divide_lanes1.h"
#include "Vfxr_divide_lanes1__shared_recip.h"
#include "model/vectors/codegen.hpp"
#include "model/config/config.hpp"
#include "model/stages/divide.hpp"
#include "txn/backend_sets.hpp"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kDefault = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";
const std::string kShared = std::string(FXR_BINARY_DIR) + "/vectors/scene_default_shared_recip";
constexpr int kVaryings = fxr::kRecordPackageVaryings;  // fxr_rec_pkg::NumVaryings of the build

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("divide", run, seed, gap, stall);
}

fxr::Config shared_config() { return fxr::load_config(FXR_SHARED_RECIP_CONFIG); }

// No gaps, no stalls: the first output comes `latency` clocks after the first input, then one
// every `ii` clocks (the stage is never starved nor blocked), so the last output is at
// first_in + latency + (rows − 1)·ii.
template <class Dut>
void expect_rate(const SceneStageVectors& v, const fxr::Config& cfg, int lanes, const std::string& run) {
  const TxnResult r = fxr::tb::run_txn<Dut>(v, nullptr, opts(run, 1, 0, 0));
  EXPECT_TRUE(r.passed()) << run;
  EXPECT_EQ(r.outputs, v.out.rows) << run;
  const fxr::StageCost k = fxr::divide_cost(cfg, kVaryings, lanes);
  const uint64_t expect_last = r.first_in_cycle + (uint64_t)k.latency + (v.out.rows - 1) * (uint64_t)k.ii;
  EXPECT_EQ(r.last_out_cycle, expect_last) << run << ": latency " << k.latency << ", ii " << k.ii;
  std::printf("%s: %llu fragments, %llu cycles from the first input to the last output: %.3f cycles per "
              "fragment (latency %d, ii %d)\n",
              run.c_str(), (unsigned long long)v.out.rows, (unsigned long long)(r.last_out_cycle - r.first_in_cycle),
              (double)(r.last_out_cycle - r.first_in_cycle) / (double)v.out.rows, k.latency, k.ii);
}

template <class Dut>
void expect_stalls(const SceneStageVectors& v, const std::string& run) {
  for (auto [seed, gap, stall] : {std::tuple{2u, 25u, 25u}, {3u, 60u, 70u}}) {
    const TxnResult r = fxr::tb::run_txn<Dut>(v, nullptr, opts(run + "_" + std::to_string(seed), seed, gap, stall));
    EXPECT_TRUE(r.passed()) << run << " seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
  }
}

}  // namespace

TEST(DivideTxn, CommittedDumpMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kCommitted, "divide");
  ASSERT_GT(v.out.rows, 10u);
  const fxr::Config cfg;
  expect_rate<Vfxr_divide>(v, cfg, kVaryings, "divide_committed");
  expect_stalls<Vfxr_divide>(v, "divide_committed");
  expect_rate<Vfxr_divide_lanes1>(v, cfg, 1, "divide_committed_lanes1");
  expect_stalls<Vfxr_divide_lanes1>(v, "divide_committed_lanes1");
}

// The committed back-end vectors (the fragments that pass in each; none under never / greater:
// an empty stream must stay empty), both lane counts.
TEST(DivideTxn, CommittedBackendSetsMatchTheModel) {
  const fxr::Config cfg;
  for (const auto& [dir, name] : fxr::tb::committed_backend_dumps()) {
    const SceneStageVectors v = fxr::load_scene_stage(dir, "divide");
    if (v.out.rows == 0) {
      const TxnResult r = fxr::tb::run_txn<Vfxr_divide>(v, nullptr, opts("divide_" + name, 1, 0, 0));
      EXPECT_TRUE(r.passed()) << dir;
      EXPECT_EQ(r.outputs, 0u) << dir;
      continue;
    }
    expect_rate<Vfxr_divide>(v, cfg, kVaryings, "divide_" + name);
    expect_stalls<Vfxr_divide>(v, "divide_" + name);
    expect_rate<Vfxr_divide_lanes1>(v, cfg, 1, "divide_" + name + "_lanes1");
    expect_stalls<Vfxr_divide_lanes1>(v, "divide_" + name + "_lanes1");
  }
}

TEST(DivideTxn, DefaultSceneMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kDefault, "divide");
  ASSERT_GT(v.out.rows, 1000u);
  const fxr::Config cfg;
  expect_rate<Vfxr_divide>(v, cfg, kVaryings, "divide_default");
  expect_rate<Vfxr_divide_lanes1>(v, cfg, 1, "divide_default_lanes1");
  const TxnResult s = fxr::tb::run_txn<Vfxr_divide>(v, nullptr, opts("divide_default_stalls", 7, 25, 25));
  EXPECT_TRUE(s.passed());
  const TxnResult s1 = fxr::tb::run_txn<Vfxr_divide_lanes1>(v, nullptr, opts("divide_default_lanes1_stalls", 8, 25, 25));
  EXPECT_TRUE(s1.passed());
}

// shared_recip: the dump of the default scene made with tb/variants/div/shared_recip.json (its
// fragments are the shared-reciprocal model's, not correctly rounded) against the RTL verilated
// with that configuration's package.
TEST(DivideTxn, SharedRecipDefaultSceneMatchesTheModel) {
  const SceneStageVectors v = fxr::load_scene_stage(kShared, "divide");
  ASSERT_GT(v.out.rows, 1000u);
  const fxr::Config cfg = shared_config();
  ASSERT_EQ(cfg.div.algorithm, fxr::DivAlgorithm::SharedRecip);
  expect_rate<Vfxr_divide__shared_recip>(v, cfg, kVaryings, "divide_shared_recip");
  expect_rate<Vfxr_divide_lanes1__shared_recip>(v, cfg, 1, "divide_shared_recip_lanes1");
  expect_stalls<Vfxr_divide__shared_recip>(v, "divide_shared_recip");
  expect_stalls<Vfxr_divide_lanes1__shared_recip>(v, "divide_shared_recip_lanes1");
}

// The two algorithms differ somewhere on the default scene (the dumps are not the same file), so
// the shared_recip run above checks the other datapath.
TEST(DivideTxn, SharedRecipDumpDiffersFromTheDefault) {
  const SceneStageVectors a = fxr::load_scene_stage(kDefault, "divide"), b = fxr::load_scene_stage(kShared, "divide");
  ASSERT_EQ(a.out.rows, b.out.rows);
  uint64_t differ = 0;
  for (size_t i = 0; i < a.out.data.size(); ++i) differ += a.out.data[i] != b.out.data[i];
  std::printf("divide: %llu of %llu fragment fields differ between radix2 and shared_recip\n",
              (unsigned long long)differ, (unsigned long long)a.out.data.size());
  EXPECT_GT(differ, 0u);
}

// The checker can fail: one bit of var1_sig in row 6 of the expected fragments is flipped ->
// exactly that row and field; a swapped pair -> both rows; a dropped row -> an extra output.
TEST(DivideTxn, CorruptedSwappedAndDroppedRowsAreReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "divide");
  const size_t n = v.out.lay.size();
  size_t col = 0;
  for (size_t f = 0; f < n; ++f)
    if (v.out.lay[f].name == "var1_sig") col = f;
  ASSERT_GT(col, 0u);
  SceneStageVectors c = v;
  c.out.data[5 * n + col] ^= 1;
  const TxnResult r = fxr::tb::run_txn<Vfxr_divide>(c, nullptr, opts("divide_corrupt", 2, 25, 25));
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].out_row, 5u);
  EXPECT_EQ(r.mismatches[0].cls, "var1_sig");
  EXPECT_NE(r.mismatches[0].text.find("divide.out.hex:6: field 'var1_sig'"), std::string::npos) << r.mismatches[0].text;
  EXPECT_TRUE(std::filesystem::exists(r.wave));

  SceneStageVectors sw = v;
  std::swap_ranges(sw.out.data.begin() + 3 * (ptrdiff_t)n, sw.out.data.begin() + 4 * (ptrdiff_t)n,
                   sw.out.data.begin() + 4 * (ptrdiff_t)n);
  TxnOptions o = opts("divide_swapped", 3, 25, 25);
  o.write_wave = false;
  const TxnResult s = fxr::tb::run_txn<Vfxr_divide_lanes1>(sw, nullptr, o);
  EXPECT_EQ(s.errors, 2u);
  ASSERT_EQ(s.mismatches.size(), 2u);
  EXPECT_EQ(s.mismatches[0].out_row, 3u);
  EXPECT_EQ(s.mismatches[1].out_row, 4u);

  SceneStageVectors dr = v;
  dr.out.data.erase(dr.out.data.end() - (ptrdiff_t)n, dr.out.data.end());
  --dr.out.rows;
  o.run_name = "divide_dropped";
  const TxnResult d = fxr::tb::run_txn<Vfxr_divide>(dr, nullptr, o);
  EXPECT_FALSE(d.passed());
  EXPECT_EQ(d.classes.count("extra"), 1u);
}

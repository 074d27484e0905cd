// Co-simulation of rtl/fxr_setup.sv (Verilator; record ports) on transaction dumps
// (tb/txn_harness.hpp): the committed dump of scenes/transactions.json (every setup outcome) and
// the default scene dumped at build time. Every drawn triangle's equations bit-identical and in
// order with the model's setup.out, nothing for a culled one, and the culled triangles' outcome
// codes equal to what the model's SetupStage::step() returned (re-stepped here on setup.in);
// under random input gaps and output back-pressure. The harness catches a corrupted expected
// row. docs/rtl.md, "fxr_setup".
#include <gtest/gtest.h>

#include <array>
#include <cstdio>

#include "Vfxr_setup.h"
#include "model/stages/setup.hpp"
#include "model/vectors/record_vectors.hpp"
#include "txn/draw_state_ports.hpp"
#include "txn/backend_sets.hpp"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::TxnHook;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kDefault = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";

constexpr int kOutcomes = 5;  // SetupOutcome: Ok … RejectedRange
using Counts = std::array<uint64_t, kOutcomes>;

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("setup", run, seed, gap, stall);
}

// The model's outcome of every setup.in record: SetupStage re-stepped on the record read back
// from the dump (the same reader as `fxraster vectors check`).
Counts model_outcomes(const SceneStageVectors& v, const fxr::DrawState& st) {
  Counts c{};
  fxr::SetupStage stage(v.cfg, st, true);
  const fxr::RecordShape shape{v.cfg, v.num_varyings};
  for (uint64_t i = 0; i < v.in.rows; ++i) {
    fxr::SetupTriangle t;
    fxr::unpack_record(t, shape, v.in.row(i), v.in.header);
    ++c[(size_t)stage.step(t, [](const fxr::TriangleEquations&) {})];
  }
  return c;
}

struct SetupRun {
  TxnResult r;
  Counts rtl{};  // outputs (ok) and cull pulses by code
};

SetupRun run_dump(const SceneStageVectors& v, const fxr::DrawState& st, const TxnOptions& o) {
  SetupRun out;
  Counts& c = out.rtl;
  TxnHook<Vfxr_setup> h;
  h.reset = [&c] { c = Counts{}; };
  h.drive = [&](Vfxr_setup& d) { fxr::tb::drive_draw_state(d, st, v.cfg.raster.window_int_bits); };
  h.observe = [&c](Vfxr_setup& d) {
    if (d.cull_valid_o) ++c[d.cull_outcome_o < kOutcomes ? d.cull_outcome_o : 0];
    if (d.out_valid_o && d.out_ready_i) ++c[0];
  };
  out.r = fxr::tb::run_txn<Vfxr_setup>(v, nullptr, o, &h);
  return out;
}

void check_dump(const std::string& dir, const std::string& name) {
  const SceneStageVectors v = fxr::load_scene_stage(dir, "setup");
  const fxr::DrawState st = fxr::tb::read_dump_draw_state(dir);
  ASSERT_GT(v.in.rows, 0u);
  const Counts want = model_outcomes(v, st);
  EXPECT_EQ(want[0], v.out.rows);  // the dump's outputs are the drawn triangles
  for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
    const SetupRun k = run_dump(v, st, opts("setup_" + name + "_" + std::to_string(seed), seed, gap, stall));
    EXPECT_TRUE(k.r.passed()) << "seed " << seed;
    EXPECT_EQ(k.r.outputs, v.out.rows);
    EXPECT_EQ(k.r.inputs, v.in.rows);
    EXPECT_EQ(k.rtl, want) << "outcome counts (ok, zero area, back face, no samples, range), seed " << seed;
    if (seed == 1)
      std::printf("setup %s: %llu triangles: ok %llu, zero area %llu, back face %llu, no samples %llu, range %llu; "
                  "%llu cycles (%.3f per triangle)\n",
                  name.c_str(), (unsigned long long)v.in.rows, (unsigned long long)want[0], (unsigned long long)want[1],
                  (unsigned long long)want[2], (unsigned long long)want[3], (unsigned long long)want[4],
                  (unsigned long long)k.r.cycles, (double)k.r.cycles / (double)v.in.rows);
  }
}

TEST(SetupTxn, CommittedDumpMatchesTheModel) {
  check_dump(kCommitted, "committed");
  // The committed scene reaches back face, zero area and no samples at setup (docs/vectors.md).
  const SceneStageVectors v = fxr::load_scene_stage(kCommitted, "setup");
  const Counts want = model_outcomes(v, fxr::tb::read_dump_draw_state(kCommitted));
  EXPECT_GT(want[1], 0u);
  EXPECT_GT(want[2], 0u);
  EXPECT_GT(want[3], 0u);
}

TEST(SetupTxn, DefaultSceneMatchesTheModel) { check_dump(kDefault, "default"); }

// The committed back-end vectors: the directed geometric cases and every draw state (cull mode,
// front face) of vectors/scenes/backend_state/.
TEST(SetupTxn, CommittedBackendSetsMatchTheModel) {
  for (const auto& [dir, name] : fxr::tb::committed_backend_dumps()) {
    SCOPED_TRACE(dir);
    check_dump(dir, name);
  }
}

// The checker can fail: one bit of area2 in row 2 of the expected equations flipped.
TEST(SetupTxn, CorruptedExpectedRowIsReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "setup");
  ASSERT_GT(v.out.rows, 2u);
  size_t ca = 0;
  for (size_t f = 0; f < v.out.lay.size(); ++f)
    if (v.out.lay[f].name == "area2") ca = f;
  ASSERT_GT(ca, 0u);
  v.out.data[1 * v.out.lay.size() + ca] ^= 4;
  const SetupRun k = run_dump(v, fxr::tb::read_dump_draw_state(kCommitted), opts("setup_corrupt", 2, 25, 25));
  EXPECT_FALSE(k.r.passed());
  EXPECT_EQ(k.r.errors, 1u);
  ASSERT_EQ(k.r.mismatches.size(), 1u);
  EXPECT_EQ(k.r.mismatches[0].out_row, 1u);
  EXPECT_EQ(k.r.mismatches[0].cls, "area2");
  EXPECT_TRUE(std::filesystem::exists(k.r.wave));
}

}  // namespace

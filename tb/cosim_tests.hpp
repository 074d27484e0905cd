// tb/cosim_tests.hpp — the co-simulation tests every unit gets (GoogleTest, label rtl):
//
//   <Suite>.VectorFieldsMatchThePorts            the adapter's field order is the manifest's
//   <Suite>.RtlMatchesCommittedVectors           vectors/<unit>/<unit>.hex through the DUT
//   <Suite>.RtlMatchesGeneratedVectors           build/vectors/<unit>/<unit>.hex (larger, made at build time)
//   <Suite>.RtlMatchesModelOnAMillionRandomInputs  lock-step: fresh random inputs, model vs RTL
//   <Suite>.LatencyAndThroughputMatchTheCostModel  no gaps, no back-pressure: the first result after
//                                                the cost model's latency, then one per II cycles
//   <Suite>.WithheldOutputsAreReportedLost       out_ready held low: timeout, every input lost
//   <Suite>.CorruptedExpectedValueIsCaught       one flipped output bit in a copy of the vectors
//                                                is reported as exactly that mismatch
//
// A unit's tb/<unit>_test.cpp defines its Ports adapter (harness.hpp) with
//   static std::vector<std::string> fields();   // vector fields in the order drive/sample use
//   static int latency(const fxr::Config&);     // cycles, from the cost model
//   static int ii(const fxr::Config&);          // initiation interval, from the cost model
// and writes FXR_COSIM_TESTS(Suite, Ports, "unit").
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "harness.hpp"

namespace fxr::tb {

// Lock-step vectors per unit: 10^6 (the product promise, docs/references.md#spec-speed), a few seconds under Verilator.
inline constexpr uint64_t kLockStepCount = 1000000;
inline constexpr uint64_t kLockStepSeed = 20240601;

inline std::string source_path(const std::string& rel) { return std::string(FXR_SOURCE_DIR) + "/" + rel; }
inline std::string binary_path(const std::string& rel) { return std::string(FXR_BINARY_DIR) + "/" + rel; }

template <class P>
void expect_fields_match(const std::string& unit) {
  const auto m = make_vector_model(unit, Config{});
  const auto want = P::fields();
  ASSERT_EQ(m->layout().size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(m->layout()[i].name, want[i]) << "field " << i;
}

template <class P>
RunResult run_file(const std::string& unit, const std::string& hex, const std::string& run_name,
                   HarnessOptions o = {}) {
  const Config cfg;  // the configuration the RTL was built from (fxr_config_pkg)
  const VecFile f = read_vectors(hex, &cfg);
  o.unit = unit;
  o.run_name = run_name;
  return run<P>(f.manifest.layout, file_source(f), o);
}

template <class P>
RunResult run_lockstep(const std::string& unit, const std::string& run_name, uint64_t count, uint64_t seed,
                       HarnessOptions o = {}, const Config& cfg = Config{}) {
  const auto m = make_vector_model(unit, cfg);
  o.unit = unit;
  o.run_name = run_name;
  return run<P>(m->layout(), model_source(*m, seed, count), o);
}

// The directed cases and `count` random ones of the unit at `cfg`, generated in memory (the
// parameter-set variants have no committed files), through the DUT.
template <class P>
RunResult run_generated(const std::string& unit, const std::string& run_name, const Config& cfg, uint64_t count) {
  const auto m = make_vector_model(unit, cfg);
  auto rows = std::make_shared<std::vector<VecRow>>();
  generate_vectors(*m, 1, count, false, [&](const VecRow& r) { rows->push_back(r); });
  SourceFactory src = [rows]() {
    auto i = std::make_shared<size_t>(0);
    return Source([rows, i](VecRow& r) {
      if (*i >= rows->size()) return false;
      r = (*rows)[(*i)++];
      return true;
    });
  };
  HarnessOptions o;
  o.unit = unit;
  o.run_name = run_name;
  return run<P>(m->layout(), src, o);
}

// No gaps, no back-pressure: the first result after exactly the cost model's latency, then one
// every II cycles.
template <class P>
void expect_latency_and_throughput(const std::string& unit, const std::string& run_name, const Config& cfg) {
  HarnessOptions o;
  o.in_gap_pct = 0;
  o.out_stall_pct = 0;
  const uint64_t n = 10000;
  const auto r = run_lockstep<P>(unit, run_name, n, 7, o, cfg);
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.first_latency, P::latency(cfg));
  // n results need n·II + latency cycles (+ reset and the idle drain at the end).
  EXPECT_LE(r.cycles, n * (uint64_t)P::ii(cfg) + (uint64_t)P::latency(cfg) + o.reset_cycles + o.drain_cycles + 2);
}

// Flips bit `bit` of output field `field` of vector `vec` in a copy of the file (same base name,
// in a scratch folder) and runs it: the harness must report exactly that one mismatch.
template <class P>
void expect_corruption_caught(const std::string& unit, const std::string& hex, size_t vec,
                              const std::string& field, int bit) {
  namespace fs = std::filesystem;
  const Config cfg;
  VecFile f = read_vectors(hex, &cfg);
  const auto& lay = f.manifest.layout;
  const int fi = lay.index(field);
  ASSERT_GE(fi, 0);
  ASSERT_LT(vec, f.rows());
  f.data[vec * lay.size() + (size_t)fi] ^= (vec_word)1 << bit;
  const fs::path dir = fs::path(out_dir()) / (unit + "_corrupt");
  fs::create_directories(dir);
  const std::string copy = (dir / fs::path(hex).filename()).string();
  {
    VecWriter w(copy, lay);
    for (size_t i = 0; i < f.rows(); ++i) w.write(f.row(i));
    w.finish(f.manifest);
  }
  std::printf("(this test flips bit %d of %s in vector %zu on purpose: one MISMATCH and FAILED are expected)\n",
              bit, field.c_str(), vec);
  const RunResult r = run_file<P>(unit, copy, unit + "_corrupt");
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  EXPECT_EQ(r.checked, f.rows());
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].vec, vec);
  EXPECT_EQ(r.mismatches[0].cls, field);
  EXPECT_EQ(r.classes.size(), 1u);
  EXPECT_FALSE(r.wave.empty());
  EXPECT_TRUE(fs::exists(r.wave) && fs::file_size(r.wave) > 0) << r.wave;
}

}  // namespace fxr::tb

// The standard tests of one unit. CORRUPT_FIELD / CORRUPT_BIT: the output bit the last test flips.
#define FXR_COSIM_TESTS(Suite, Ports, unit, CORRUPT_FIELD, CORRUPT_BIT)                               \
  TEST(Suite, VectorFieldsMatchThePorts) { fxr::tb::expect_fields_match<Ports>(unit); }               \
  TEST(Suite, RtlMatchesCommittedVectors) {                                                           \
    const auto r = fxr::tb::run_file<Ports>(                                                          \
        unit, fxr::tb::source_path("vectors/" unit "/" unit ".hex"), unit "_committed");              \
    EXPECT_TRUE(r.passed());                                                                          \
  }                                                                                                   \
  TEST(Suite, RtlMatchesGeneratedVectors) {                                                           \
    const auto r = fxr::tb::run_file<Ports>(                                                          \
        unit, fxr::tb::binary_path("vectors/" unit "/" unit ".hex"), unit "_generated");              \
    EXPECT_TRUE(r.passed());                                                                          \
  }                                                                                                   \
  TEST(Suite, RtlMatchesModelOnAMillionRandomInputs) {                                                \
    const auto r = fxr::tb::run_lockstep<Ports>(unit, unit "_lockstep", fxr::tb::kLockStepCount,      \
                                                fxr::tb::kLockStepSeed);                              \
    EXPECT_TRUE(r.passed());                                                                          \
    EXPECT_EQ(r.checked, fxr::tb::kLockStepCount);                                                    \
  }                                                                                                   \
  TEST(Suite, LatencyAndThroughputMatchTheCostModel) {                                                \
    fxr::tb::expect_latency_and_throughput<Ports>(unit, unit "_throughput", fxr::Config{});           \
  }                                                                                                   \
  TEST(Suite, WithheldOutputsAreReportedLost) {                                                       \
    /* out_ready held low: the DUT fills up and stops; the harness must time out and report every     \
       accepted input as lost (the checker can fail on missing outputs, not only on wrong ones). */   \
    fxr::tb::HarnessOptions o;                                                                        \
    o.out_stall_pct = 100;                                                                            \
    o.timeout_cycles = 100;                                                                           \
    o.write_wave = false;                                                                             \
    o.print = false;                                                                                  \
    const auto r = fxr::tb::run_lockstep<Ports>(unit, unit "_withheld", 1000, 3, o);                  \
    EXPECT_FALSE(r.passed());                                                                         \
    EXPECT_TRUE(r.timeout);                                                                           \
    EXPECT_EQ(r.checked, 0u);                                                                         \
    EXPECT_GT(r.sent, 0u);                                                                            \
    EXPECT_EQ(r.errors, r.sent);                                                                      \
    EXPECT_EQ(r.classes.at("lost"), r.sent);                                                          \
  }                                                                                                   \
  TEST(Suite, CorruptedExpectedValueIsCaught) {                                                       \
    fxr::tb::expect_corruption_caught<Ports>(unit, fxr::tb::source_path("vectors/" unit "/" unit ".hex"), \
                                             17, CORRUPT_FIELD, CORRUPT_BIT);                         \
  }

// The tests of one unit at another parameter set: CONFIG_JSON (tb/variants/<unit>/<name>.json) is
// the configuration the variant was verilated from (its own fxr_config_pkg) and the model's.
#define FXR_VARIANT_TESTS(Suite, Ports, unit, name, CONFIG_JSON)                                      \
  TEST(Suite, RtlMatchesModelOnDirectedAndRandomVectors) {                                            \
    const auto r = fxr::tb::run_generated<Ports>(unit, unit "_" name "_generated",                    \
                                                 fxr::load_config(CONFIG_JSON), 20000);               \
    EXPECT_TRUE(r.passed());                                                                          \
  }                                                                                                   \
  TEST(Suite, RtlMatchesModelOnRandomInputs) {                                                        \
    const auto r = fxr::tb::run_lockstep<Ports>(unit, unit "_" name "_lockstep", 200000,              \
                                                fxr::tb::kLockStepSeed, {}, fxr::load_config(CONFIG_JSON)); \
    EXPECT_TRUE(r.passed());                                                                          \
  }                                                                                                   \
  TEST(Suite, LatencyAndThroughputMatchTheCostModel) {                                                \
    fxr::tb::expect_latency_and_throughput<Ports>(unit, unit "_" name "_throughput",                  \
                                                  fxr::load_config(CONFIG_JSON));                     \
  }

// Co-simulation of rtl/fxr_input.sv (stage 1, the model's "convert") on transaction dumps
// (tb/txn_harness.hpp): the committed dump of scenes/transactions.json and the default scene
// dumped at build time, every exact triangle bit-identical and in order with the model's
// convert.out, rejected primitives producing no output, the NaN / Inf / replaced-varying pulses
// summing to the dump's statistics, under random input gaps and output back-pressure; and
// directed rows (NaN, ±Inf, denormals, ±0, the format limits, random words) whose expected
// values are computed here from the IEEE-754 value (frexp / ldexp on doubles), not from the
// model's decoder. docs/rtl.md, "fxr_input".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "Vfxr_input.h"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::TxnHook;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kDefault = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("convert", run, seed, gap, stall);
}

// The outcome pulses of the transfers, counted in the clock they happen.
struct Pulses {
  uint64_t nan = 0, inf = 0, repl = 0;
  TxnHook<Vfxr_input> hook() {
    TxnHook<Vfxr_input> h;
    h.reset = [this] { *this = Pulses{}; };
    h.observe = [this](Vfxr_input& d) {
      nan += d.rej_nan_o;
      inf += d.rej_inf_o;
      repl += d.var_replaced_o;
    };
    return h;
  }
};

nlohmann::json dump_stats(const std::string& dir) {
  std::ifstream f(dir + "/scene.json");
  return nlohmann::json::parse(f).at("stats");
}

void run_dump(const std::string& dir, const std::string& name, uint64_t min_rows) {
  const SceneStageVectors v = fxr::load_scene_stage(dir, "convert");
  ASSERT_GE(v.out.rows, min_rows);
  const nlohmann::json st = dump_stats(dir);
  for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
    Pulses p;
    const TxnHook<Vfxr_input> h = p.hook();
    const TxnResult r = fxr::tb::run_txn<Vfxr_input>(v, nullptr, opts(name + std::to_string(seed), seed, gap, stall), &h);
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
    EXPECT_EQ(p.nan, st.at("prims_rejected_nan").get<uint64_t>());
    EXPECT_EQ(p.inf, st.at("prims_rejected_inf").get<uint64_t>());
    EXPECT_EQ(p.repl, st.at("prims_varying_nonfinite").get<uint64_t>());
    EXPECT_EQ(p.nan + p.inf + r.outputs, r.inputs);
    if (seed == 1)
      std::printf("convert %s: %llu primitives, %llu busy cycles (%.3f cycles/primitive)\n", name.c_str(),
                  (unsigned long long)v.in.rows, (unsigned long long)r.busy_cycles, (double)r.busy_cycles / (double)v.in.rows);
  }
}

TEST(ConvertTxn, CommittedDumpMatchesTheModel) { run_dump(kCommitted, "convert_committed_", 5); }

TEST(ConvertTxn, DefaultSceneMatchesTheModel) { run_dump(kDefault, "convert_default_", 1000); }
// The committed back-end directed set (docs/vectors.md): a guard-band-sized triangle, w from
// 10^-3 to 10^3 inside one triangle, zero-area and sub-pixel ones.
TEST(ConvertTxn, CommittedBackendDirectedSetMatchesTheModel) {
  run_dump(std::string(FXR_SOURCE_DIR) + "/vectors/scenes/backend_directed", "convert_backend_directed_", 18);
}

// ---- directed rows ------------------------------------------------------------------------

struct Exact {
  uint64_t neg, sig;
  int64_t exp;
};

// The exact value of a finite float32 as (neg, sig, exp) in the stage's format: normal values
// with a 24-bit significand (msb set), subnormals and zeros at the fixed exponent of the
// smallest subnormal, 2^−149. Computed from the value (frexp), not from the bit fields.
Exact expect_finite(float f) {
  Exact e{std::signbit(f) ? 1u : 0u, 0, -149};
  const double a = std::fabs((double)f);
  if (a == 0) return e;
  if (a < (double)std::numeric_limits<float>::min()) {
    e.sig = (uint64_t)std::ldexp(a, 149);
    return e;
  }
  int x = 0;
  const double m = std::frexp(a, &x);  // a = m·2^x, m ∈ [½, 1)
  e.sig = (uint64_t)std::ldexp(m, 24);
  e.exp = x - 24;
  return e;
}

float from_bits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

struct Directed {
  const char* what;
  uint32_t pos[4];   // one vertex's position words (the others are finite)
  uint32_t var;      // its first varying's word
  int outcome;       // 0 emitted, 1 NaN, 2 Inf
  bool replaced;
  Exact var_exp;     // the varying's expected value (when emitted)
};

constexpr uint32_t kOne = 0x3f800000u, kNaN = 0x7fc00000u, kNegNaN = 0xffc00001u, kInf = 0x7f800000u,
                   kNegInf = 0xff800000u, kMax = 0x7f7fffffu, kNegMax = 0xff7fffffu, kMinDen = 0x00000001u,
                   kMaxDen = 0x007fffffu, kMinNorm = 0x00800000u, kNegZero = 0x80000000u;

TEST(ConvertTxn, DirectedRowsMatchIeee754Values) {
  const SceneStageVectors base = fxr::load_scene_stage(kCommitted, "convert");
  const int nv = base.num_varyings;
  ASSERT_GE(nv, 1);
  const int per_vertex = 4 + nv;
  ASSERT_EQ(base.in.lay.size(), base.in.header + 1 + 3 * (size_t)per_vertex);
  ASSERT_EQ(base.out.lay.size(), base.out.header + 1 + 3 * 3 * (size_t)per_vertex);
  const int exp_bits = base.out.lay[base.out.header + 3].width;
  // FLT_MAX = (2^24 − 1)·2^104; the varying rule's ±Inf → ±FLT_MAX.
  const Exact emax{0, (1u << 24) - 1, 104}, enmax{1, (1u << 24) - 1, 104}, ezero{0, 0, -149};
  std::vector<Directed> cases = {
      {"ones", {kOne, kOne, kOne, kOne}, kOne, 0, false, {0, 1u << 23, -23}},
      {"-0 position, +0 varying", {kNegZero, 0, kNegZero, kOne}, 0, 0, false, ezero},
      {"-0 varying", {kOne, kOne, kOne, kOne}, kNegZero, 0, false, {1, 0, -149}},
      {"smallest subnormal", {kMinDen, kMinDen | kNegZero, kMinDen, kOne}, kMinDen, 0, false, {0, 1, -149}},
      {"largest subnormal", {kMaxDen, kMaxDen, kMaxDen, kMaxDen}, kMaxDen | kNegZero, 0, false, {1, (1u << 23) - 1, -149}},
      {"smallest normal", {kMinNorm, kMinNorm, kMinNorm, kMinNorm}, kMinNorm, 0, false, {0, 1u << 23, -149}},
      {"FLT_MAX", {kMax, kNegMax, kMax, kMax}, kNegMax, 0, false, enmax},
      {"NaN varying", {kOne, kOne, kOne, kOne}, kNaN, 0, true, ezero},
      {"negative NaN varying", {kOne, kOne, kOne, kOne}, kNegNaN, 0, true, ezero},
      {"+Inf varying", {kOne, kOne, kOne, kOne}, kInf, 0, true, emax},
      {"-Inf varying", {kOne, kOne, kOne, kOne}, kNegInf, 0, true, enmax},
      {"NaN x", {kNaN, kOne, kOne, kOne}, kOne, 1, false, {}},
      {"NaN w, negative", {kOne, kOne, kOne, kNegNaN}, kOne, 1, false, {}},
      {"Inf z", {kOne, kOne, kInf, kOne}, kOne, 2, false, {}},
      {"-Inf y and NaN varying", {kOne, kNegInf, kOne, kOne}, kNaN, 2, false, {}},
      {"Inf and NaN: NaN wins", {kInf, kOne, kNaN, kOne}, kOne, 1, false, {}},
  };
  // Random finite words (sign, exponent and fraction uniform, the all-ones exponent excluded).
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) {
    auto word = [&] {
      uint32_t u;
      do u = (uint32_t)rng();
      while (((u >> 23) & 0xff) == 0xff);
      return u;
    };
    Directed d{"random", {word(), word(), word(), word()}, word(), 0, false, {}};
    d.var_exp = expect_finite(from_bits(d.var));
    cases.push_back(d);
  }

  SceneStageVectors v = base;
  const size_t ni = v.in.lay.size(), no = v.out.lay.size();
  v.in.data.clear();
  v.out.data.clear();
  v.in.rows = v.out.rows = 0;
  uint64_t want_nan = 0, want_inf = 0, want_repl = 0;
  for (size_t t = 0; t < cases.size(); ++t) {
    const Directed& d = cases[t];
    const int vi = (int)(t % 3);  // the vertex carrying the case
    std::vector<uint32_t> words(3 * (size_t)per_vertex, kOne);
    for (int c = 0; c < 4; ++c) words[(size_t)(vi * per_vertex + c)] = d.pos[c];
    words[(size_t)(vi * per_vertex + 4)] = d.var;
    for (int k = 1; k < nv; ++k) words[(size_t)(vi * per_vertex + 4 + k)] = (uint32_t)(0x40000000u + t);  // 2.0 + …
    fxr::VecRow in(ni, 0);
    in[0] = t;
    in[1] = d.outcome == 0 ? 1 : 0;
    in[2] = 1000 + t;  // prim
    for (size_t w = 0; w < words.size(); ++w) in[3 + w] = words[w];
    v.in.data.insert(v.in.data.end(), in.begin(), in.end());
    ++v.in.rows;
    want_nan += d.outcome == 1;
    want_inf += d.outcome == 2;
    want_repl += d.replaced;
    if (d.outcome != 0) continue;
    fxr::VecRow out(no, 0);
    out[0] = t;
    out[1] = 0;
    out[2] = 1;
    out[3] = 1000 + t;
    for (size_t w = 0; w < words.size(); ++w) {
      const bool is_var0 = w == (size_t)(vi * per_vertex + 4);
      const float f = from_bits(words[w]);
      Exact e = is_var0 ? d.var_exp : expect_finite(f);
      if (is_var0 && d.what != std::string("random")) {
        // the table's value; for finite words also the value's own decode must agree
        if (!d.replaced) {
          const Exact g = expect_finite(f);
          EXPECT_TRUE(g.neg == e.neg && g.sig == e.sig && g.exp == e.exp) << d.what;
        }
      }
      // (−1)^neg·sig·2^exp is the float's value (a check of the expectation itself).
      if (!d.replaced || !is_var0) EXPECT_EQ(std::ldexp((double)e.sig, (int)e.exp) * (e.neg ? -1 : 1), (double)f) << d.what;
      out[4 + 3 * w] = e.neg;
      out[5 + 3 * w] = e.sig;
      out[6 + 3 * w] = (uint64_t)e.exp & ((1ull << exp_bits) - 1);
    }
    v.out.data.insert(v.out.data.end(), out.begin(), out.end());
    ++v.out.rows;
  }
  ASSERT_GT(want_nan, 0u);
  ASSERT_GT(want_inf, 0u);
  ASSERT_GT(want_repl, 0u);
  for (auto [seed, gap, stall] : {std::tuple{4u, 0u, 0u}, {5u, 40u, 50u}}) {
    Pulses p;
    const TxnHook<Vfxr_input> h = p.hook();
    const TxnResult r = fxr::tb::run_txn<Vfxr_input>(v, nullptr, opts("convert_directed_" + std::to_string(seed), seed, gap, stall), &h);
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(p.nan, want_nan);
    EXPECT_EQ(p.inf, want_inf);
    EXPECT_EQ(p.repl, want_repl);
  }
}

// The checker can fail: one bit of an exponent in the committed expectation flipped -> exactly
// that row and field reported.
TEST(ConvertTxn, CorruptedExpectedRowIsReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "convert");
  size_t col = 0;
  for (size_t f = 0; f < v.out.lay.size(); ++f)
    if (v.out.lay[f].name == "v1_y_exp") col = f;
  ASSERT_GT(col, 0u);
  v.out.data[2 * v.out.lay.size() + col] ^= 1;
  TxnOptions o = opts("convert_corrupt", 2, 25, 25);
  o.write_wave = false;
  const TxnResult r = fxr::tb::run_txn<Vfxr_input>(v, nullptr, o);
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].out_row, 2u);
  EXPECT_EQ(r.mismatches[0].cls, "v1_y_exp");
}

}  // namespace

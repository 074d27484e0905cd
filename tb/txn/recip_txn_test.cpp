// Co-simulation of rtl/fxr_recip_stage.sv (stage 3, the model's "recip": 1/w of each vertex of a
// clipped triangle) on transaction dumps (tb/txn_harness.hpp): the committed dump of
// scenes/transactions.json and the default scene dumped at build time, every record bit-identical
// and in order with the model's recip.out, under random input gaps and output back-pressure; and
// directed rows (w = 1, powers of two, the smallest and largest w the unit takes, w = 0, lead
// exponents just outside the unit's range, 24-bit and denormal-like short significands, random
// w) whose 1/w is computed here as the correctly rounded quotient 2^k / m with 128-bit integers
// (not with the model's Newton-Raphson unit), and whose dropped triangles pulse err_o.
// docs/rtl.md, "fxr_recip_stage".
#include <gtest/gtest.h>

#include <random>

#include "Vfxr_recip_stage.h"
#include "model/stages/recip_stage.hpp"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::TxnHook;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kDefault = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("recip", run, seed, gap, stall);
}

struct Drops {
  uint64_t n = 0;
  TxnHook<Vfxr_recip_stage> hook() {
    TxnHook<Vfxr_recip_stage> h;
    h.reset = [this] { n = 0; };
    h.observe = [this](Vfxr_recip_stage& d) { n += d.err_o; };
    return h;
  }
};

// Inputs of the dump with no output (n_out = 0: RecipOutcome::RecipError).
uint64_t dropped_rows(const SceneStageVectors& v) {
  uint64_t n = 0;
  for (uint64_t r = 0; r < v.in.rows; ++r) n += v.in.data[r * v.in.lay.size() + 1] == 0;
  return n;
}

void run_dump(const std::string& dir, const std::string& name, uint64_t min_rows) {
  const SceneStageVectors v = fxr::load_scene_stage(dir, "recip");
  ASSERT_GE(v.out.rows, min_rows);
  for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
    Drops d;
    const TxnHook<Vfxr_recip_stage> h = d.hook();
    const TxnResult r = fxr::tb::run_txn<Vfxr_recip_stage>(v, nullptr, opts(name + std::to_string(seed), seed, gap, stall), &h);
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
    EXPECT_EQ(d.n, dropped_rows(v));
    if (seed == 1) {
      // One triangle per clock after the unit's latency (fxr::recip_cost: 7 at the default).
      const uint64_t lat = (uint64_t)fxr::RecipStage::cost(v.cfg).latency;
      EXPECT_LE(r.last_out_cycle - r.first_in_cycle, v.in.rows - 1 + lat);
      std::printf("recip %s: %llu triangles, %llu busy cycles (%.3f cycles/triangle, latency %llu)\n", name.c_str(),
                  (unsigned long long)v.in.rows, (unsigned long long)r.busy_cycles,
                  (double)r.busy_cycles / (double)v.in.rows, (unsigned long long)lat);
    }
  }
}

TEST(RecipTxn, CommittedDumpMatchesTheModel) { run_dump(kCommitted, "recip_committed_", 5); }

TEST(RecipTxn, DefaultSceneMatchesTheModel) { run_dump(kDefault, "recip_default_", 1000); }
// The committed back-end directed set (docs/vectors.md): a guard-band-sized triangle, w from
// 10^-3 to 10^3 inside one triangle, zero-area and sub-pixel ones.
TEST(RecipTxn, CommittedBackendDirectedSetMatchesTheModel) {
  run_dump(std::string(FXR_SOURCE_DIR) + "/vectors/scenes/backend_directed", "recip_backend_directed_", 18);
}

// ---- directed rows ------------------------------------------------------------------------

size_t col_of(const fxr::VecLayout& lay, const std::string& name) {
  for (size_t f = 0; f < lay.size(); ++f)
    if (lay[f].name == name) return f;
  ADD_FAILURE() << "no field " << name;
  return 0;
}

// w = sig · 2^exp (exp the lsb exponent). Expected 1/w, computed from the exact quotient: with
// p = msb(sig), w = x·2^L (L = exp + p, x = sig·2^−p ∈ [1, 2)); 1/x ∈ (½, 1]; the significand of
// o bits is RNE(2^(o−1)·2^p·2 / sig) (ties cannot occur: sig is not a power of two then), carried
// into the next binade at 2^o. Returns false when the unit must reject w: zero, or a lead exponent
// of w or of 1/w outside [−2^(E−1), 2^(E−1) − 1].
struct Recip {
  uint64_t sig = 0;
  int64_t lead = 0;
};
bool expect_recip(uint64_t sig, int64_t exp, int o, int e_bits, Recip* out) {
  if (sig == 0) return false;
  const int p = 63 - __builtin_clzll(sig);
  const int64_t lw = exp + p;
  const int64_t emin = -(int64_t(1) << (e_bits - 1)), emax = (int64_t(1) << (e_bits - 1)) - 1;
  if (lw < emin || lw > emax) return false;
  if ((sig & (sig - 1)) == 0) {  // a power of two: 1/x = 1 exactly
    out->sig = uint64_t(1) << (o - 1);
    out->lead = -lw;
  } else {
    const unsigned __int128 num = (unsigned __int128)1 << (o + p);  // 2^o / x = 2^(o+p) / sig
    unsigned __int128 q = num / sig;
    const unsigned __int128 rem = num % sig;
    if (2 * rem > sig || (2 * rem == sig && (q & 1))) ++q;
    out->sig = (uint64_t)q;
    out->lead = -lw - 1;
    if (out->sig == (uint64_t(1) << o)) {
      out->sig >>= 1;
      out->lead += 1;
    }
  }
  return out->lead >= emin && out->lead <= emax;
}

TEST(RecipTxn, DirectedRowsMatchExactQuotients) {
  const SceneStageVectors base = fxr::load_scene_stage(kCommitted, "recip");
  const int o = base.cfg.recip.out_sig_bits, eb = base.cfg.recip.exp_bits, n = base.cfg.recip.in_sig_bits;
  const int64_t emin = -(int64_t(1) << (eb - 1)), emax = (int64_t(1) << (eb - 1)) - 1;
  const int fx_exp = base.in.lay[col_of(base.in.lay, "v0_w_exp")].width;
  const uint64_t top = uint64_t(1) << (n - 1), ones = (uint64_t(1) << n) - 1;
  struct Case {
    uint64_t sig;
    int64_t exp;  // lsb exponent
  };
  std::vector<Case> cases = {
      {top, -(n - 1)},                  // 1
      {top, -(n - 1) + 5},              // 32
      {top, emin - (n - 1)},            // 2^emin: 1/w = 2^−emin overflows
      {top, emin + 1 - (n - 1)},        // 2^(emin+1): the largest 1/w
      {top + 1, emin - (n - 1)},        // just above 2^emin
      {ones, emax - (n - 1)},           // the largest w
      {top, emax + 1 - (n - 1)},        // lead exponent emax + 1: rejected
      {top, emin - 1 - (n - 1)},        // lead exponent emin − 1: rejected
      {0, 0},                           // w = 0: rejected
      {1, -149},                        // the smallest float32 denormal
      {0x7fffffu, -149},                // the largest float32 denormal
      {3, -149},                        // a short significand
      {ones, -(n - 1)},                 // just below 2
      {top | 1, -(n - 1)},              // just above 1
      {0xcccccdu, -24},                 // 0.8
  };
  std::mt19937_64 rng(11);
  for (int i = 0; i < 300; ++i) {
    const int bits = 1 + (int)(rng() % (uint64_t)n);
    const uint64_t sig = (rng() & ((uint64_t(1) << bits) - 1)) | (uint64_t(1) << (bits - 1));
    const int64_t exp = (int64_t)(rng() % (uint64_t)(emax - emin + 1)) + emin - (bits - 1);
    cases.push_back({sig, exp});
  }

  SceneStageVectors v = base;
  const size_t ni = v.in.lay.size(), no = v.out.lay.size();
  const fxr::VecRow tmpl_in = base.in.row(0), tmpl_out = base.out.row(0);
  v.in.data.clear();
  v.out.data.clear();
  v.in.rows = v.out.rows = 0;
  uint64_t want_drops = 0;
  const uint64_t exp_mask = (uint64_t(1) << fx_exp) - 1;
  for (size_t t = 0; t < cases.size(); ++t) {
    fxr::VecRow in = tmpl_in;
    in[0] = t;
    in[col_of(v.in.lay, "prim")] = 2000 + t;
    fxr::VecRow out(no, 0);
    bool ok = true;
    Recip r[3];
    for (int i = 0; i < 3; ++i) {
      // The case in vertex t % 3, the neighbouring cases in the other two (every lane sees all).
      const Case& c = cases[(t + (size_t)((i - (int)(t % 3) + 3) % 3)) % cases.size()];
      const std::string pre = "v" + std::to_string(i) + "_w_";
      in[col_of(v.in.lay, pre + "neg")] = 0;
      in[col_of(v.in.lay, pre + "sig")] = c.sig;
      in[col_of(v.in.lay, pre + "exp")] = (uint64_t)c.exp & exp_mask;
      ok = expect_recip(c.sig, c.exp, o, eb, &r[i]) && ok;
    }
    in[1] = ok ? 1 : 0;
    v.in.data.insert(v.in.data.end(), in.begin(), in.end());
    ++v.in.rows;
    if (!ok) {
      ++want_drops;
      continue;
    }
    out[0] = t;
    out[1] = 0;
    out[2] = 1;
    for (size_t f = v.in.header; f < ni; ++f) out[col_of(v.out.lay, v.in.lay[f].name)] = in[f];
    for (int i = 0; i < 3; ++i) {
      const std::string pre = "r" + std::to_string(i) + "_";
      out[col_of(v.out.lay, pre + "neg")] = 0;
      out[col_of(v.out.lay, pre + "sig")] = r[i].sig;
      out[col_of(v.out.lay, pre + "exp")] = (uint64_t)(r[i].lead - (o - 1)) & exp_mask;
    }
    v.out.data.insert(v.out.data.end(), out.begin(), out.end());
    ++v.out.rows;
  }
  (void)tmpl_out;
  ASSERT_GE(want_drops, 4u);
  ASSERT_GE(v.out.rows, 200u);
  for (auto [seed, gap, stall] : {std::tuple{4u, 0u, 0u}, {5u, 40u, 50u}}) {
    Drops d;
    const TxnHook<Vfxr_recip_stage> h = d.hook();
    const TxnResult res = fxr::tb::run_txn<Vfxr_recip_stage>(v, nullptr, opts("recip_directed_" + std::to_string(seed), seed, gap, stall), &h);
    EXPECT_TRUE(res.passed()) << "seed " << seed;
    EXPECT_EQ(res.outputs, v.out.rows);
    EXPECT_EQ(d.n, want_drops);
  }
}

// The checker can fail: one bit of r1's significand in the committed expectation flipped ->
// exactly that row and field reported.
TEST(RecipTxn, CorruptedExpectedRowIsReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "recip");
  ASSERT_GE(v.out.rows, 3u);
  const size_t col = col_of(v.out.lay, "r1_sig");
  v.out.data[2 * v.out.lay.size() + col] ^= 1;
  TxnOptions o = opts("recip_corrupt", 2, 25, 25);
  o.write_wave = false;
  const TxnResult r = fxr::tb::run_txn<Vfxr_recip_stage>(v, nullptr, o);
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].out_row, 2u);
  EXPECT_EQ(r.mismatches[0].cls, "r1_sig");
}

}  // namespace

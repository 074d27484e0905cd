// analysis/budget.hpp — the error budget of a scene (`fxraster budget`, issue 13; docs/reports.md,
// "Error budget"). For every sampled fragment the model drew, each output's error against the
// exact value of the unsnapped triangle at the pixel centre (IdealJudge, analysis/ideal.hpp),
// and each rounding point's share: the error with every point active minus the error with that
// one point exact (analysis/budget_path.hpp). The residual (error − Σ shares) is the
// interaction of the points, reported as such.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/budget_path.hpp"
#include "frontend/scene.hpp"

namespace fxr {

// Order statistics of signed values (nearest-rank percentiles, deterministic).
struct SignedStat {
  std::vector<double> all;
  void add(double v) { all.push_back(v); }
  uint64_t n() const { return all.size(); }
  double max() const;
  double mean() const;
  double pct(double q) const;  // q ∈ [0, 1]
  nlohmann::json to_json() const;
};

struct BudgetOptions {
  int samples = 3000;   // fragments re-evaluated (evenly spaced over the model's output); 0: every fragment
  int threads = 1;      // the result is the same for any count
  bool shares = true;   // false: only the error with every point active (fxraster plan)
  bool checks = true;   // false: skip the all-exact self-check (fxraster plan)
  std::vector<uint64_t> extra;  // sorted output indices sampled in addition (fxraster plan's failing fragments)
};

// One output of the unit: depth (LSB) or a varying (ulps of a quot_bits significand; also the
// absolute error, and texels for the scene's texture coordinates).
struct BudgetOutput {
  std::string name;     // "depth", "u", "v", "var2", …
  std::string unit;     // "LSB" or "ulp"
  int varying = -1;     // −1: depth
  int texels = 0;       // texture size along this coordinate (0: not a texture coordinate)
  SignedStat err;       // error with every point active (= the model's, see model_mismatches)
  SignedStat abs_err;   // varyings: absolute error
  SignedStat texel_err; // texture coordinates: absolute error × texels
  SignedStat share[kNumRoundPoints];
  SignedStat residual;
  uint64_t dominant[kNumRoundPoints + 1] = {};  // fragments where each point (last: the residual) has the largest share
};

struct BudgetFragment {
  uint64_t index = 0;       // position in the model's output order
  int32_t x = 0, y = 0;
  uint32_t prim = 0;
  bool exact_covered = true;
  bool texel_differs = false;
  std::vector<double> abs;  // per output: the absolute error (depth: 0)
  // Per output: error, then share per point, then residual.
  std::vector<double> err, share, residual;
};

struct BudgetResult {
  std::string scene;
  Config cfg;
  uint64_t fragments = 0;          // the model's output fragments (depth test passed)
  uint64_t sampled = 0;
  uint64_t skipped = 0;            // ideal undefined (edge-on) or zero-area attribute triangle
  uint64_t model_mismatches = 0;   // sampled fragments where the all-active path differs from the model
  uint64_t exact_nonzero = 0;      // sampled fragments where the all-exact path differs from the ideal
  uint64_t not_exactly_covered = 0;  // coverage_snap: drawn pixels whose centre lies outside the exact triangle
  uint64_t texel_differs = 0;      // sampled fragments whose nearest texel (⌊u·W⌋, ⌊v·H⌋) differs from the ideal's
  double model_seconds = 0;        // CPU-independent wall time of one model run (not in the files)
  std::vector<BudgetOutput> outputs;
  std::vector<BudgetFragment> frags;
};

// Contract: the budget of scene `sc` (its configuration; triangles only, lines are not part of
// it) on the documented sample. Deterministic for any thread count.
BudgetResult run_budget(const Scene& sc, const BudgetOptions& o);

nlohmann::json budget_json(const BudgetResult& r);
std::string budget_markdown(const BudgetResult& r, const std::vector<std::string>& images);
// Writes budget_fragments.csv (one row per sampled fragment and output) for the plots.
void write_budget_csv(const BudgetResult& r, const std::string& path);

}  // namespace fxr

// analysis/plan.hpp — the cheapest configuration that meets an error target on a set of scenes
// (`fxraster plan`, issue 13; docs/reports.md, "Planner").
//
// Target: a list like `u,v <= 1/16 texel; depth <= 1 LSB; image pixels differing from the exact
// image <= 0`, every figure measured by the error budget's analysis path (analysis/budget.hpp)
// against the exact value of the unsnapped triangle: per output the maximum error over the
// sample in its unit (texel, LSB or ulp), and the sampled fragments whose nearest texel differs
// from the ideal's. Search: coordinate descent from the scenes' configuration over the
// dimensions of plan_dimensions(), each narrowed while the cost falls and the target holds on
// every scene (all narrower values of one dimension evaluated in parallel; the result depends
// only on the evaluations, so it is the same for any thread count); then a minimality check
// (each dimension one step cheaper is evaluated and must miss the target).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frontend/scene.hpp"

namespace fxr {

struct PlanLimit {
  std::string output;  // "u", "v", "depth", "var2", or "pixels"
  std::string unit;    // "texel", "LSB", "ulp", "pixels"
  double max = 0;
  std::string text;    // as given
};
// Contract: parses a target list (items separated by ';'); ConfigError naming the item otherwise.
std::vector<PlanLimit> parse_plan_target(const std::string& spec);

// One searchable dimension: a configuration field and its values from cheapest to dearest.
struct PlanDimension {
  std::string name;
  std::vector<int> values;
  std::function<int(const Config&)> get;
  std::function<void(Config&, int)> set;
};
// Contract: the dimensions for configuration `c` (fixed: subpixel_bits, window_int_bits and the
// recip unit — coverage and the guard band are not error-budget questions; docs/reports.md).
// `min_depth_bits`: the narrowest depth format searched (16 or 24).
std::vector<PlanDimension> plan_dimensions(const Config& c, int min_depth_bits = 16);

// What the search minimises (docs/reports.md, "Planner", "Cost"):
//   Area    Σ over stages 1–9 of area_proxy() + ff_bits of the stages' cost() functions
//   Luts    the LUT4 cost model (analysis/lut_model.hpp) calibrated to the Yosys figures
//   Cycles  clocks per frame from the cycle model, summed over the scenes (PlanOptions::frame_clocks)
enum class PlanCost { Area, Luts, Cycles };
const char* plan_cost_name(PlanCost k);

struct LutModel;
// Contract: the unit's cost at `c` for `num_varyings` for Area (divide_cost with one lane per
// varying) and Luts (`luts` required); ConfigError for Cycles (it needs the scenes).
int64_t plan_cost(const Config& c, int num_varyings, PlanCost k, const LutModel* luts = nullptr);

struct PlanEval {
  Config cfg;
  std::string label;          // the dimensions' values
  int64_t cost = 0;
  bool valid = true;          // the configuration passes validate()
  bool meets = false;
  std::vector<double> figure; // per limit: the worst over the scenes
  double ratio = 0;           // max over limits of figure / max (≤ 1: meets; limits of 0 count as meets iff figure 0)
  double mfrags_per_s = 0;    // model speed over the scenes (not reproducible: never in plan.json / pareto.csv)
};

struct PlanOptions {
  std::vector<PlanLimit> target;
  PlanCost cost = PlanCost::Area;
  int samples = 1000;   // per scene and configuration
  int threads = 1;
  std::function<void(const std::string&)> progress;
  // PlanCost::Cycles: clocks per frame of `scene` drawn at `cfg` (app/cmd_plan.cpp and the sc
  // tests pass sc/frame_clocks.hpp's unit_frame_clocks; fxr_analysis does not link SystemC).
  // Called from several threads at once; results are cached per configuration and scene.
  std::function<uint64_t(const Config& cfg, const Scene& scene)> frame_clocks;
  const LutModel* luts = nullptr;  // PlanCost::Luts
  // Depth formats below what the scenes' overlapping surfaces need (fxraster analyze,
  // analysis/scene_analysis.hpp) are left out of the search: the error target does not see
  // visibility. false: search D16 and D24 regardless (tests of the cost ordering).
  bool depth_floor_from_analysis = true;
};

struct MinimalityRow {
  std::string dimension;
  int chosen = 0;
  int cheaper = 0;            // the next cheaper value (when there is one)
  std::string verdict;        // "misses (ratio …)", "range minimum", "cost unchanged", "invalid configuration"
  bool holds = true;          // false: one step cheaper still meets the target (the search stopped short)
};

struct PlanResult {
  PlanEval start, chosen;
  bool widened = false;
  PlanEval verified;        // the chosen configuration measured on every fragment of every scene
  int rounds = 0;           // search rounds (a round's failing fragments join the next round's sample)
  size_t total_evaluated = 0;  // the start missed the target: the search began at the widest configuration
  std::vector<PlanEval> evaluated;  // every distinct configuration, in evaluation order
  std::vector<MinimalityRow> minimality;
  std::vector<std::string> scenes;
  int min_depth_bits = 16;  // the depth-format floor the search used (from the analysis)
  int num_varyings = 1;     // the most of any scene (the divider's lanes)
};

// Contract: the plan for `scenes` (each with its own draw state; the configuration of the
// first is the starting point and is applied to all).
PlanResult run_plan(const std::vector<Scene>& scenes, const PlanOptions& o);

nlohmann::json plan_json(const PlanResult& r, const PlanOptions& o);
std::string plan_markdown(const PlanResult& r, const PlanOptions& o, const std::vector<std::string>& images);
void write_pareto_csv(const PlanResult& r, const PlanOptions& o, const std::string& path, bool with_speed);

}  // namespace fxr

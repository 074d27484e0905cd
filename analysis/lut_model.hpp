// analysis/lut_model.hpp — LUT4 of the raster unit as a function of the configuration widths
// (`fxraster plan --cost luts`, issue 13; docs/reports.md, "LUT4 cost model").
//
// Per RTL module (stages 1–9), LUT4(c) = M · P(c) / P(c0): M the module's Yosys LUT4 figure at the
// default configuration c0 (generic flow, `abc -lut 4 -fast`; analysis/lut_table.json "modules",
// each with its source), P the module's width proxy from its stage's cost() function
//   P = mult_bits + k_add · adder_bits + k_ff · ff_bits + table_bits / 16
// (products ∝ the product of their operand widths, adders and registers ∝ width, a LUT4 is a
// 16-bit table). k_add and k_ff are fitted to measured checkpoints: small modules synthesised at
// widths that are not the default (analysis/lut_table.json "checkpoints", each with the command that
// produced it; scripts/synth_lut_table.sh), by the ratio of two rows of one module. The
// leave-one-out error of the checkpoints is the model's stated error.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/config/config.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// The stages 1–9 in order, with their RTL modules: their cost() functions at `c` (divide_cost
// with one lane per varying, as fxr_raster_backend instantiates fxr_divide).
struct UnitStage {
  const char* stage;   // "input", "clip", …, "divide"
  const char* module;  // "fxr_input", …
};
extern const UnitStage kUnitStages[9];
std::vector<StageCost> unit_stage_costs(const Config& c, int num_varyings);

struct LutCheckpoint {
  std::string name, top, group, proxy;  // proxy: the cost function that stands for the module
  nlohmann::json config;                // fields over the default configuration (the proxy's too)
  double lut4 = 0;
  double loo_predicted = 0;  // leave-one-out: predicted from the group's other rows with k fitted without this row
  double loo_error = 0;      // loo_predicted / lut4 − 1
};

struct LutModel {
  std::vector<std::string> stage_source;  // per kUnitStages entry: where its M comes from
  std::vector<double> stage_lut4;         // M per stage at the default (0: not measured)
  double divide_shared_lut4 = 0;          // fxr_divide at shared_recip (the default is radix2)
  double k_add = 1, k_ff = 0;             // fitted
  double fit_rms_log = 0;                 // rms of log(predicted / measured ratio) over the pairs
  double unmeasured_lut_per_proxy = 0;    // modules without a figure: Σ M / Σ P(c0) of the measured ones
  std::vector<LutCheckpoint> checkpoints;
};

// Contract: reads analysis/lut_table.json (`path`), fits k_add, k_ff (grid search, deterministic)
// and the leave-one-out errors. ConfigError naming the file and field on a bad table.
LutModel load_lut_model(const std::string& path);
// Contract: per stage the modelled LUT4 at `c`, and their sum (rounded).
std::vector<double> lut_model_stages(const LutModel& m, const Config& c, int num_varyings);
int64_t lut_model_total(const LutModel& m, const Config& c, int num_varyings);
// Contract: Markdown: the coefficients, the checkpoints with their leave-one-out errors, and the
// modelled LUT4 per module at `a` and `b` (e.g. a plan's start and its choice).
std::string lut_model_markdown(const LutModel& m, const Config& a, const Config& b, int num_varyings);

}  // namespace fxr

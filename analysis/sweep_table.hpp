// app/report.hpp — the table behind every sweep report: one row per configuration, the
// configuration's parameters as columns (generic, from fxr::param_rows) followed by measured
// metrics; written as CSV (for scripts), Markdown (for people) and plotted by
// scripts/plot_sweep.py. docs/reports.md says how to read the result.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "model/config/param.hpp"

namespace fxr::app {

struct MetricCol {
  std::string name;  // CSV column, snake_case
  std::string doc;   // one line for the report's legend
  bool integer = false;  // printed without decimals
};

struct SweepRow {
  std::string id;     // configuration hash (config_id): join key and synthesis cache key
  std::string label;  // the unit's short label, e.g. "64x6+2NR f26 rem"
  bool is_default = false;
  std::vector<ParamRow> params;  // as visit() lists them
  std::vector<double> metrics;   // one per SweepTable::metrics; NaN = not measured
  std::vector<std::string> texts;  // one per SweepTable::text_cols (no commas)
};

struct SweepTable {
  std::string unit;
  std::vector<MetricCol> metrics;
  std::vector<MetricCol> text_cols;  // descriptive columns, e.g. the multiplier widths
  std::vector<SweepRow> rows;

  int metric_index(const std::string& name) const;  // −1 when absent
  // Appends a metric column (NaN in every row) and returns its index.
  int add_metric(const MetricCol& col);
};

// Short, stable identifier of a configuration: FNV-1a 64 of "<unit>:" + its parameter JSON,
// as 16 hex digits. Same parameters → same id on every machine.
std::string config_id(const std::string& unit, const nlohmann::json& params);

// Pareto front of the rows over (cost, error), both to be minimised (cost_higher_is_better
// flips the cost, e.g. Fmax). A row is on the front when no other row is at least as good in
// both and strictly better in one. Rows with a NaN in either column are never on it.
std::vector<bool> pareto_front(const SweepTable& t, int cost_col, bool cost_higher_is_better, int err_col);

// A Pareto front to mark: which cost against which error.
struct FrontSpec {
  std::string cost;
  bool higher_is_better = false;
};

// CSV: id,label,is_default,<every parameter>,<every metric>,<text columns>,pareto_<cost> per
// front (0/1).
void write_csv(const SweepTable& t, const std::string& error_col, const std::vector<FrontSpec>& fronts,
               const std::string& path);

// Markdown report: the setup paragraph `intro`, the default row, the Pareto fronts, the full
// table (parameters that are the same in every row are listed once above it), the plots
// (`images`, relative to the report), and the legend of the metrics.
void write_markdown(const SweepTable& t, const std::string& title, const std::string& intro,
                    const std::string& error_col, const std::vector<FrontSpec>& fronts,
                    const std::vector<std::string>& images, const std::string& path);

// Reads a CSV with a header line (no quoting: fields must not contain commas) into rows of
// strings; throws ConfigError naming the file and line on a wrong field count.
std::vector<std::vector<std::string>> read_csv(const std::string& path);

}  // namespace fxr::app

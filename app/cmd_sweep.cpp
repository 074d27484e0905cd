// `fxraster sweep recip|div`: error beside cost over the unit's configuration sweep.
//
// For every configuration of recip_sweep_configs() / div_sweep_configs(): the error against
// exact arithmetic (analysis/measure.hpp: recip exhaustive over all significands; div directed
// cases + random pairs), the cost model (latency, II, table bits, multipliers) and the model's
// own speed; with --synth also LUT4s, logic depth and Fmax from Yosys / nextpnr-ice40
// (scripts/synth_cost.py, cached by configuration id). Writes into --out:
//   sweep.csv      one row per configuration (parameters, metrics, Pareto flags)
//   report.md      default row, Pareto fronts, all rows, plots (docs/reports.md explains it)
//   error_vs_<cost>.png   made by scripts/plot_sweep.py (skipped with a message without matplotlib)
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include "command.hpp"
#include "out_folder.hpp"
#include "model/config/config.hpp"
#include "model/config/json_input.hpp"
#include "model/config/validate.hpp"
#include "model/arith/div.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/recip.hpp"
#include "analysis/measure.hpp"
#include "analysis/sweep_table.hpp"

namespace fs = std::filesystem;

namespace {

using fxr::app::FrontSpec;
using fxr::app::MetricCol;
using fxr::app::SweepRow;
using fxr::app::SweepTable;

struct Opts {
  std::string unit;
  std::string out;
  bool quick = false;
  uint64_t count = 0;  // div: random pairs per configuration (0: 10^6, or 2·10^4 with --quick)
  uint64_t seed = 1;
  bool synth = false;
  bool no_timing = false;
  bool no_plots = false;
  bool list = false;
};

// Random divider operand pairs per configuration (on top of the directed cases).
constexpr uint64_t kDivCountFull = 1000000;
constexpr uint64_t kDivCountQuick = 20000;
// Model speed is timed over this many calls of the unit's significand function.
constexpr uint64_t kTimingCalls = 1 << 18;

std::string multipliers_text(const std::vector<std::pair<int, int>>& m) {
  std::string s;
  for (const auto& [a, b] : m) s += (s.empty() ? "" : " ") + std::to_string(a) + "x" + std::to_string(b);
  return s.empty() ? "-" : s;
}

// Runs a command line through the shell; returns its exit status (−1 if it could not run).
int run_shell(const std::string& cmd) {
  const int st = std::system(cmd.c_str());
  if (st == -1) return -1;
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

using fxr::app::quote;

std::string script(const std::string& name) {
  const std::string p = std::string(FXR_SOURCE_DIR) + "/scripts/" + name;
  if (!fs::exists(p)) throw fxr::ConfigError(p + ": script not found (the source tree moved?)");
  return p;
}

template <class Cfg>
SweepRow make_row(const std::string& unit, const Cfg& c, const Cfg& def, const std::string& label) {
  SweepRow r;
  const auto j = fxr::to_json_params(c);
  r.id = fxr::app::config_id(unit, j);
  r.label = label;
  r.is_default = j == fxr::to_json_params(def);
  r.params = fxr::param_rows(c);
  return r;
}

volatile uint64_t g_timing_sink = 0;

// Nanoseconds per call of f over kTimingCalls calls (f gets the call index).
template <class F>
double ns_per_call(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  uint64_t sink = 0;
  for (uint64_t i = 0; i < kTimingCalls; ++i) sink += f(i);
  const auto t1 = std::chrono::steady_clock::now();
  g_timing_sink = sink;  // keeps the calls from being optimised away
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / (double)kTimingCalls;
}

// The columns every unit has: its StageCost (model/unit/stage.hpp), then its ErrorStats
// (analysis/measure.hpp); a unit adds its own columns after them.
const std::vector<MetricCol>& common_cols() {
  static const std::vector<MetricCol> cols = {
      {"latency", "cycles from input to output (RTL register stages)", true},
      {"ii", "initiation interval, cycles between inputs", true},
      {"table_bits", "seed ROM bits (entries x stored width)", true},
      {"multipliers", "number of multipliers", true},
      {"mult_bits", "sum of a*b over the multipliers (partial-product bits, an area proxy)", true},
      {"adder_bits", "adder / subtractor / comparator bits, summed (0: not estimated for the unit)", true},
      {"ff_bits", "pipeline register bits, estimate (0: not estimated for the unit)", true},
      {"area_proxy", "table_bits + mult_bits + adder_bits (ranking only)", true},
      {"max_err_ulp", "max |result - exact| over the measured inputs, ulps of the result", false},
      {"mean_err_ulp", "mean |result - exact|, ulps", false},
      {"rms_err_ulp", "RMS of result - exact, ulps", false},
      {"correctly_rounded_share", "share of inputs whose result equals RN(exact)", false},
      {"correctly_rounded", "1 when every measured input is correctly rounded", true},
      {"faithful", "1 when max_err_ulp < 1", true},
      {"count", "inputs measured", true},
  };
  return cols;
}

std::vector<double> common_metrics(const fxr::StageCost& k, const fxr::ErrorStats& e) {
  return {(double)k.latency,     (double)k.ii,        (double)k.table_bits, (double)k.multipliers.size(),
          (double)k.mult_bits,   (double)k.adder_bits, (double)k.ff_bits,    (double)k.area_proxy(),
          e.max_err_ulp,         e.mean_err_ulp,      e.rms_err_ulp,        e.correctly_rounded_share,
          (double)e.correctly_rounded, (double)e.faithful, (double)e.count};
}

// One sweep: for every configuration, the common columns, `extra(c, cost, stats)` (the unit's
// own columns, `extra_cols`), and the model speed of `call(c)` (a function j → significand).
template <class Cfg, class Extra, class Call>
SweepTable sweep_unit(const Opts& o, const std::string& unit, const std::vector<Cfg>& configs,
                      const std::vector<MetricCol>& extra_cols, const fxr::MeasureOptions& mo,
                      Extra&& extra, Call&& call, const std::string& speed_doc) {
  SweepTable t;
  t.unit = unit;
  t.metrics = common_cols();
  for (const auto& c : extra_cols) t.metrics.push_back(c);
  t.metrics.push_back({"model_ns_per_op", speed_doc, false});
  t.text_cols.push_back({"multiplier_widths", "operand widths a x b of every multiplier", false});
  const Cfg def;
  for (size_t i = 0; i < configs.size(); ++i) {
    const Cfg& c = configs[i];
    const std::string label = fxr::label(c);
    fxr::validate(c, unit + " sweep: " + label);  // ranges and the unit's rules
    SweepRow r = make_row(unit, c, def, label);
    const fxr::StageCost k = fxr::cost(c);
    const fxr::ErrorStats e = fxr::measure(c, mo);
    r.metrics = common_metrics(k, e);
    for (double v : extra(c, e)) r.metrics.push_back(v);
    r.metrics.push_back(o.no_timing ? NAN : ns_per_call(call(c)));
    r.texts = {multipliers_text(k.multipliers)};
    t.rows.push_back(std::move(r));
    fxr::app::progress("sweep " + unit, i + 1, configs.size());
  }
  return t;
}

SweepTable sweep_recip(const Opts& o) {
  const std::vector<MetricCol> extra = {
      {"error_bound_ulp", "a-priori bound on 1/x - y before rounding, output ulps", false},
      {"bound_valid", "1 when the bound proves correct rounding (remainder) / faithfulness (none)", true},
      {"max_err_ulp_before_round", "max |1/x - y|, y the Newton-Raphson result before rounding, ulps", false},
  };
  return sweep_unit(
      o, "recip", fxr::recip_sweep_configs(), extra, fxr::MeasureOptions{},  // exhaustive
      [](const fxr::RecipConfig& c, const fxr::ErrorStats& e) {
        const fxr::RecipBound b = fxr::recip_bound(c);
        return std::vector<double>{b.error_bound_ulp, (double)b.valid, e.max_err_ulp_before_round};
      },
      [](const fxr::RecipConfig& c) {
        auto u = std::make_shared<fxr::RecipUnit>(c);
        const uint64_t lo = uint64_t(1) << (c.in_sig_bits - 1);
        return [u, lo](uint64_t j) { return u->sig(lo | ((j * 0x9E3779B97F4A7C15ull) & (lo - 1))).sig; };
      },
      "model speed: ns per RecipUnit::sig call on this machine (not reproducible)");
}

// Stage 9 at a number of varyings, one fragment per clock (Lanes = varyings, rtl/fxr_divide.sv):
// the per-fragment cost that decides between per-varying dividers and one shared reciprocal.
fxr::StageCost stage_cost(const fxr::DivConfig& c, int varyings) {
  fxr::Config cfg;
  cfg.div = c;
  return fxr::divide_cost(cfg, varyings, varyings);
}

SweepTable sweep_div(const Opts& o, uint64_t count) {
  const std::vector<MetricCol> extra = {
      {"error_bound_ulp", "a-priori bound on max |result - exact|, ulps (div_bound; empty: none claimed)", false},
      {"stage_area_proxy_2v", "stage 9 (fxr_divide) area proxy, 2 varyings at one fragment per clock", true},
      {"stage_mult_bits_2v", "stage 9 partial-product bits, 2 varyings at one fragment per clock", true},
      {"stage_area_proxy_8v", "stage 9 area proxy, 8 varyings at one fragment per clock", true},
      {"stage_latency", "stage 9 latency (lane latency + 3), cycles", true},
  };
  return sweep_unit(
      o, "div", fxr::div_sweep_configs(), extra, fxr::MeasureOptions{false, count, o.seed},
      [](const fxr::DivConfig& c, const fxr::ErrorStats&) {
        const double bound = fxr::div_bound(c).error_bound_ulp;
        const fxr::StageCost k2 = stage_cost(c, 2), k8 = stage_cost(c, 8);
        return std::vector<double>{std::isinf(bound) ? NAN : bound, (double)k2.area_proxy(), (double)k2.mult_bits,
                                   (double)k8.area_proxy(), (double)k2.latency};
      },
      [](const fxr::DivConfig& c) {
        const uint64_t nlo = uint64_t(1) << (c.num_bits - 1), dlo = uint64_t(1) << (c.den_bits - 1);
        return [c, nlo, dlo](uint64_t j) {
          const uint64_t h = j * 0x9E3779B97F4A7C15ull;
          return fxr::div_sig(c, nlo | (h & (nlo - 1)), dlo | ((h >> 17) & (dlo - 1))).sig;
        };
      },
      "model speed: ns per div_sig call on this machine (not reproducible)");
}

// The units a sweep covers: adding one is adding an entry here (its configurations, measurement
// and cost come from analysis/measure.hpp and the unit's cost()).
struct SweepUnitDef {
  std::string name;   // CLI name and default folder out/sweep/<name>
  std::string title;  // report title
  std::function<SweepTable(const Opts&)> sweep;
  std::function<std::string(const Opts&, size_t rows)> intro;  // what was measured, how
};

uint64_t div_count_of(const Opts& o) { return o.count ? o.count : (o.quick ? kDivCountQuick : kDivCountFull); }

const std::vector<SweepUnitDef>& sweep_units() {
  static const std::vector<SweepUnitDef> units = {
      {"recip", "Reciprocal unit: error against cost", [](const Opts& o) { return sweep_recip(o); },
       [](const Opts&, size_t n) {
         return "Reciprocal unit (stage 3, `fxr::recip`), " + std::to_string(n) +
                " configurations of `recip_sweep_configs()`. Error: exhaustive over every input "
                "significand, against the exact reciprocal (integer arithmetic), in ulps of the "
                "result. Cost: `recip_cost()` (the RTL's latency formula, table and multiplier "
                "sizes).";
       }},
      {"div", "Divider: error against cost", [](const Opts& o) { return sweep_div(o, div_count_of(o)); },
       [](const Opts& o, size_t n) {
         return "Per-pixel divider (stage 9, `fxr::div_sig`), " + std::to_string(n) +
                " configurations of `div_sweep_configs()`. Error: directed cases plus " +
                std::to_string(div_count_of(o)) + " random operand pairs per configuration (mt19937_64, seed " +
                std::to_string(o.seed) + "), against the exact quotient, in ulps of the result. Cost: `div_cost()`.";
       }},
  };
  return units;
}

const SweepUnitDef& sweep_unit_def(const std::string& name) {
  std::string known;
  for (const auto& u : sweep_units()) {
    if (u.name == name) return u;
    known += (known.empty() ? "" : ", ") + u.name;
  }
  throw fxr::ConfigError("sweep: unknown unit '" + name + "' (known: " + known + ")");
}

// --synth: scripts/synth_cost.py synthesises every configuration (cached by id in
// OUT/synth_cache) and writes OUT/synth.csv; its figures join the table by id.
void add_synthesis(SweepTable& t, const std::string& out) {
  const std::string pkg = out + "/fxr_config_pkg.sv";
  {
    std::ofstream f(pkg);
    if (!f) throw fxr::ConfigError(pkg + ": cannot write");
    fxr::emit_sv_package(f, fxr::Config{});  // defaults; chparam sets every unit parameter
  }
  nlohmann::json list = nlohmann::json::array();
  for (const auto& r : t.rows) {
    nlohmann::json p = nlohmann::json::object();
    for (const auto& pr : r.params) p[fxr::camel_case(pr.name)] = pr.value;  // choices as index
    list.push_back({{"id", r.id}, {"label", r.label}, {"params", p}});
  }
  const std::string cfgs = out + "/synth_configs.json";
  std::ofstream(cfgs) << list.dump(1) << "\n";
  const std::string csv = out + "/synth.csv";
  const std::string cmd = quote(FXR_PYTHON) + " " + quote(script("synth_cost.py")) + " --unit " + t.unit +
                          " --configs " + quote(cfgs) + " --pkg " + quote(pkg) + " --rtl-dir " +
                          quote(std::string(FXR_SOURCE_DIR) + "/rtl") + " --cache " +
                          quote(out + "/synth_cache") + " --out " + quote(csv);
  std::cerr << "sweep " << t.unit << ": synthesising " << t.rows.size()
            << " configurations (Yosys + nextpnr-ice40, cached in " << out << "/synth_cache)\n";
  if (const int rc = run_shell(cmd); rc != 0)
    throw fxr::ConfigError("synth_cost.py failed (exit " + std::to_string(rc) + "): " + cmd);
  const auto rows = fxr::app::read_csv(csv);
  const auto& head = rows[0];
  auto col = [&](const std::string& n) {
    for (size_t i = 0; i < head.size(); ++i)
      if (head[i] == n) return (int)i;
    throw fxr::ConfigError(csv + ": no column '" + n + "'");
  };
  const int cid = col("id");
  const std::vector<std::pair<std::string, MetricCol>> add = {
      {"lut4", {"lut4", "LUT4 cells after Yosys generic synth + abc -lut 4", true}},
      {"depth", {"depth", "logic depth in LUT4 levels (Yosys ltp -noff on the generic netlist)", true}},
      {"ice40_lc", {"ice40_lc", "iCE40 logic cells after synth_ice40 (empty: not run)", true}},
      {"fmax_mhz", {"fmax_mhz", "nextpnr-ice40 HX8K Fmax, MHz (empty: does not fit or not run)", false}},
  };
  std::map<std::string, const std::vector<std::string>*> by_id;
  for (size_t i = 1; i < rows.size(); ++i) by_id[rows[i][cid]] = &rows[i];
  int fits_col = -1;
  for (size_t i = 0; i < head.size(); ++i)
    if (head[i] == "fit") fits_col = (int)i;
  t.text_cols.push_back({"ice40_fit", "nextpnr-ice40 HX8K outcome: fits, does not fit, or the tool error", false});
  for (auto& r : t.rows) r.texts.push_back(by_id.count(r.id) && fits_col >= 0 ? (*by_id[r.id])[fits_col] : "");
  for (const auto& [csv_name, mc] : add) {
    const int src = col(csv_name);
    const int dst = t.add_metric(mc);
    for (auto& r : t.rows) {
      auto it = by_id.find(r.id);
      if (it == by_id.end() || (*it->second)[src].empty()) continue;
      r.metrics[dst] = std::stod((*it->second)[src]);
    }
  }
}

// ---- output folder: written beside the target, renamed at the end (app/out_folder.hpp) -------

// What a sweep writes into --out (docs/reports.md). synth_cache/ is a cache, not output: it is
// carried from the previous run into the new one (and back when a run fails).
bool is_sweep_file(const std::string& name) {
  static const char* const kFiles[] = {"sweep.csv", "report.md", "fxr_config_pkg.sv", "synth_configs.json",
                                       "synth.csv"};
  for (const char* f : kFiles)
    if (name == f) return true;
  return name.rfind("error_vs_", 0) == 0 && name.size() > 4 && name.compare(name.size() - 4, 4, ".png") == 0;
}
constexpr const char* kSynthCache = "synth_cache";

std::string out_folder(const Opts& o) { return o.out.empty() ? "out/sweep/" + o.unit : o.out; }

int run_into(const Opts& o, const std::string& out);

int run(const Opts& o) {
  return fxr::app::write_out_folder({"sweep", is_sweep_file, kSynthCache}, fxr::app::out_path(out_folder(o)),
                                    [&](const fs::path& tmp) { return run_into(o, tmp.string()); });
}

int run_into(const Opts& o, const std::string& out) {
  const SweepUnitDef& def = sweep_unit_def(o.unit);
  SweepTable t = def.sweep(o);
  std::vector<FrontSpec> fronts = {{"latency", false}, {"table_bits", false}};
  if (o.synth) {
    add_synthesis(t, out);
    fronts.push_back({"lut4", false});
    fronts.push_back({"depth", false});
    fronts.push_back({"fmax_mhz", true});
  }
  const std::string error_col = "max_err_ulp";
  const std::string csv = out + "/sweep.csv";
  fxr::app::write_csv(t, error_col, fronts, csv);

  std::vector<std::string> images;
  std::string plot_note;
  if (!o.no_plots) {
    std::string cmd = quote(FXR_PYTHON) + " " + quote(script("plot_sweep.py")) + " --csv " + quote(csv) +
                      " --out " + quote(out) + " --unit " + o.unit + " --error " + error_col;
    for (const auto& f : fronts) cmd += " --cost " + f.cost + (f.higher_is_better ? ":max" : "");
    const int rc = run_shell(cmd);
    if (rc == 0) {
      for (const auto& f : fronts) images.push_back("error_vs_" + f.cost + ".png");
    } else if (rc == 3) {
      plot_note = "Plots skipped: matplotlib is not installed for " + std::string(FXR_PYTHON) +
                  " (apt-get install python3-matplotlib).";
      std::cerr << "sweep " << o.unit << ": warning: " << plot_note << "\n";
    } else {
      throw fxr::ConfigError("plot_sweep.py failed (exit " + std::to_string(rc) + "): " + cmd);
    }
  }

  std::ostringstream intro;
  intro << def.intro(o, t.rows.size());
  if (o.synth)
    intro << " Synthesis: Yosys generic `synth; abc -lut 4` (LUT4s, depth by `ltp -noff`) and "
             "`synth_ice40` + `nextpnr-ice40 --hx8k --package ct256 --freq 100` (Fmax), per "
             "configuration, from rtl/ with `chparam`.";
  intro << " Pareto fronts are against `" << error_col << "`. Data: `sweep.csv`. How to read "
        << "this report: docs/reports.md.";
  if (!plot_note.empty()) intro << "\n\n**" << plot_note << "**";
  fxr::app::write_markdown(t, def.title, intro.str(), error_col, fronts, images, out + "/report.md");
  const std::string final_out = fxr::app::out_path(out_folder(o)).string();
  std::cout << "sweep " << o.unit << ": " << t.rows.size() << " configurations; wrote " << final_out << "/sweep.csv, "
            << final_out << "/report.md" << (images.empty() ? "" : " and plots") << "\n";
  return 0;
}

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  std::string names;
  for (const auto& u : sweep_units()) names += (names.empty() ? "" : ", ") + u.name;
  auto* unit = sub.add_option("unit", o->unit, "unit to sweep: " + names);
  auto* list = sub.add_flag("--list", o->list, "print the units a sweep covers, one per line, and exit");
  unit->excludes(list);
  sub.add_option("--out", o->out, "report folder (default: out/sweep/UNIT)");
  sub.add_flag("--quick", o->quick, "fewer random divider pairs (2e4 instead of 1e6 per configuration)");
  sub.add_option("--count", o->count, "div: random operand pairs per configuration (overrides --quick)")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 32));
  sub.add_option("--seed", o->seed, "div: seed of the random pairs (mt19937_64)");
  sub.add_flag("--synth", o->synth,
               "also synthesise every configuration (Yosys LUT4s / depth, nextpnr-ice40 Fmax); slow, cached");
  sub.add_flag("--no-timing", o->no_timing, "leave out the model-speed column (byte-reproducible CSV)");
  sub.add_flag("--no-plots", o->no_plots, "do not call scripts/plot_sweep.py");
  sub.footer("Writes OUT/sweep.csv, OUT/report.md and OUT/error_vs_<cost>.png; docs/reports.md explains them.");
  return [o]() {
    if (o->list) {
      for (const auto& u : sweep_units()) std::cout << u.name << "\n";
      return 0;
    }
    if (o->unit.empty()) throw fxr::ConfigError("sweep: missing the unit to sweep (one of `fxraster sweep --list`)");
    return run(*o);
  };
}

fxr::app::Registrar reg("sweep", "error against cost over a unit's configuration sweep (CSV, Markdown, plots)",
                        setup);

}  // namespace

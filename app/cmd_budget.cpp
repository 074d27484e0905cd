// `fxraster budget SCENE|--default [--config F] --out DIR`: the error budget per rounding point
// (analysis/budget.hpp; docs/reports.md, "Error budget"). Writes budget.md, budget.json,
// budget_fragments.csv and, with matplotlib, hist_<output>.png and heat_<output>_<point>.png
// (scripts/plot_budget.py). Deterministic for any --threads.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "analysis/budget.hpp"
#include "analysis/error_stats.hpp"
#include "command.hpp"
#include "scene_input.hpp"
#include "frontend/scene.hpp"

namespace {

namespace fs = std::filesystem;

struct Opts {
  fxr::app::SceneInput in;
  std::string out;
  bool no_plots = false, quiet = false;
  int samples = 3000, threads = 0;
};

using fxr::app::quote;

int run(const Opts& o) {
  const fxr::Scene sc = fxr::app::load_scene_input(o.in, "budget");
  fxr::BudgetOptions bo;
  bo.samples = o.samples;
  bo.threads = o.threads > 0 ? o.threads : (int)std::max(1u, std::thread::hardware_concurrency());
  const fxr::BudgetResult r = fxr::run_budget(sc, bo);
  fs::create_directories(o.out);
  const std::string csv = o.out + "/budget_fragments.csv";
  fxr::write_budget_csv(r, csv);
  std::vector<std::string> images;
  if (!o.no_plots) {
    const std::string cmd = quote(FXR_PYTHON) + " " + quote(std::string(FXR_SOURCE_DIR) + "/scripts/plot_budget.py") +
                            " --csv " + quote(csv) + " --out " + quote(o.out) + " --width " +
                            std::to_string(sc.state.viewport_x + sc.state.viewport_w) + " --height " +
                            std::to_string(sc.state.viewport_y + sc.state.viewport_h);
    const int rc = std::system((cmd + " > " + quote(o.out + "/plots.txt")).c_str());
    if (rc == 0) {
      std::ifstream l(o.out + "/plots.txt");
      for (std::string s; std::getline(l, s);)
        if (!s.empty()) images.push_back(s);
    } else {
      std::cerr << "fxraster budget: warning: plots skipped (scripts/plot_budget.py exit " << rc
                << "; matplotlib installed?)\n";
    }
    fs::remove(o.out + "/plots.txt");
  }
  {
    std::ofstream j(o.out + "/budget.json");
    j << fxr::budget_json(r).dump(2) << "\n";
    std::ofstream m(o.out + "/budget.md");
    m << fxr::budget_markdown(r, images);
    if (!j || !m) throw fxr::ConfigError(o.out + ": cannot write budget.json / budget.md");
  }
  if (!o.quiet) {
    std::cout << "fxraster budget: " << sc.name << ": " << r.sampled << " of " << r.fragments
              << " fragments sampled, " << r.skipped << " skipped; all active vs model: " << r.model_mismatches
              << " mismatches; all exact vs ideal: " << r.exact_nonzero << " nonzero\n";
    for (const auto& out : r.outputs)
      std::cout << "  " << out.name << ": max " << fxr::fmt_num(out.err.max()) << " " << out.unit << ", p99 "
                << fxr::fmt_num(out.err.pct(0.99)) << ", mean " << fxr::fmt_num(out.err.mean()) << "\n";
    std::cout << "  wrote " << o.out << "/budget.md\n";
  }
  return r.model_mismatches == 0 && r.exact_nonzero == 0 ? 0 : 3;
}

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  fxr::app::add_scene_source(sub, o->in, "the embedded default scene");
  sub.add_option("--out", o->out, "output directory: budget.md, budget.json, budget_fragments.csv, PNG plots")
      ->required();
  sub.add_option("--samples", o->samples,
                 "fragments re-evaluated, evenly spaced over the model's output (0: every fragment; default 3000)")
      ->check(CLI::Range(0, 100000000));
  sub.add_option("--threads", o->threads, "worker threads (default: the cores; the output does not depend on it)")
      ->check(CLI::Range(0, 256));
  fxr::app::add_scene_overrides(sub, o->in);
  sub.add_flag("--no-plots", o->no_plots, "do not call scripts/plot_budget.py");
  sub.add_flag("--quiet", o->quiet, "print nothing on success");
  return [o]() { return run(*o); };
}

fxr::app::Registrar reg("budget",
                        "error budget per rounding point: each output's error against the exact unsnapped value "
                        "and each rounding point's share (docs/reports.md)",
                        setup);

}  // namespace

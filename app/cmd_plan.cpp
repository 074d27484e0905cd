// `fxraster plan SCENE... [--default] --target SPEC [--cost area|luts|cycles] --out DIR`: the cheapest
// configuration that meets an error target on every scene (analysis/plan.hpp; docs/reports.md,
// "Planner"). Writes plan.md, plan.json, plan_config.json (for `fxraster config --config F
// --emit-sv`), pareto.csv (reproducible), pareto_speed.csv (with the measured model speed) and,
// with matplotlib, error_vs_cost.png and error_vs_speed.png. Progress on stderr.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "analysis/lut_model.hpp"
#include "analysis/plan.hpp"
#include "command.hpp"
#include "scene_input.hpp"
#include "model/config/config.hpp"
#include "sc/frame_clocks.hpp"

namespace {

struct Opts {
  std::vector<std::string> scenes;
  fxr::app::SceneInput in;  // --default, the overrides (the files are `scenes`; --config starts the search)
  std::string out, config, target, cost = "area", lut_table;
  bool no_plots = false, quiet = false;
  int samples = 1000, threads = 0;
};

using fxr::app::quote;

int run(const Opts& o) {
  if (o.scenes.empty() && !o.in.use_default) throw fxr::ConfigError("give at least one SCENE or --default");
  const fxr::SceneOptions so = fxr::app::scene_options(o.in);
  std::vector<fxr::Scene> scenes;
  if (o.in.use_default) scenes.push_back(fxr::default_scene(so));
  for (const std::string& s : o.scenes) scenes.push_back(fxr::load_scene(s, so));
  if (!o.config.empty())
    for (fxr::Scene& s : scenes) fxr::apply_config_file(s, o.config);
  for (fxr::Scene& s : scenes) s.config = scenes.front().config;  // one configuration for every scene
  fxr::PlanOptions po;
  po.target = fxr::parse_plan_target(o.target);
  po.cost = o.cost == "cycles" ? fxr::PlanCost::Cycles : o.cost == "luts" ? fxr::PlanCost::Luts : fxr::PlanCost::Area;
  fxr::LutModel luts;
  if (po.cost == fxr::PlanCost::Luts) {
    luts = fxr::load_lut_model(o.lut_table.empty() ? std::string(FXR_SOURCE_DIR) + "/analysis/lut_table.json" : o.lut_table);
    po.luts = &luts;
  }
  // Clocks per frame: the cycle model of `fxraster cycles` (default architecture knobs), each run in
  // a child process (sc/frame_clocks.hpp).
  po.frame_clocks = [](const fxr::Config& c, const fxr::Scene& s) {
    return fxr::cyc::unit_frame_clocks(c, fxr::ArchConfig{}, s.state, s.tris);
  };
  po.samples = o.samples;
  po.threads = o.threads > 0 ? o.threads : (int)std::max(1u, std::thread::hardware_concurrency());
  if (!o.quiet) po.progress = [](const std::string& s) { std::cerr << "[plan] " << s << "\n"; };
  const fxr::PlanResult r = fxr::run_plan(scenes, po);
  std::filesystem::create_directories(o.out);
  fxr::write_pareto_csv(r, po, o.out + "/pareto.csv", false);
  fxr::write_pareto_csv(r, po, o.out + "/pareto_speed.csv", true);
  std::vector<std::string> images;
  if (!o.no_plots) {
    const std::string cmd = quote(FXR_PYTHON) + " " + quote(std::string(FXR_SOURCE_DIR) + "/scripts/plot_plan.py") +
                            " --csv " + quote(o.out + "/pareto_speed.csv") + " --out " + quote(o.out) + " --cost " +
                            fxr::plan_cost_name(po.cost);
    const int rc = std::system(cmd.c_str());
    if (rc == 0) images = {"error_vs_cost.png", "error_vs_speed.png"};
    else std::cerr << "fxraster plan: warning: plots skipped (scripts/plot_plan.py exit " << rc << "; matplotlib?)\n";
  }
  {
    std::ofstream j(o.out + "/plan.json"), m(o.out + "/plan.md"), c(o.out + "/plan_config.json");
    j << fxr::plan_json(r, po).dump(2) << "\n";
    m << fxr::plan_markdown(r, po, images);
    c << fxr::config_to_json(r.chosen.cfg).dump(2) << "\n";
    if (!j || !m || !c) throw fxr::ConfigError(o.out + ": cannot write plan files");
  }
  if (!o.quiet)
    std::cout << "fxraster plan: start cost " << r.start.cost << (r.start.meets ? " (meets)" : " (misses)") << ", plan cost "
              << r.chosen.cost << (r.verified.meets ? " (meets on every fragment)" : " (misses)") << ", " << r.total_evaluated
              << " configurations; wrote " << o.out << "/plan.md\n";
  bool minimal = true;
  for (const auto& m : r.minimality) minimal &= m.holds;
  return r.chosen.meets && r.verified.meets && minimal ? 0 : 3;
}

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  sub.add_option("scenes", o->scenes, "scene JSON files (docs/scene-format.md)");
  sub.add_flag("--default", o->in.use_default, "add the embedded default scene");
  sub.add_option("--target", o->target,
                 "error target, e.g. 'u,v <= 1/16 texel; depth <= 1 LSB; image pixels differing from the exact image <= 0'")
      ->required();
  sub.add_option("--cost", o->cost,
                 "what to minimise: area (Σ logic and register bits of the stages' cost functions), luts (the LUT4 "
                 "model calibrated to Yosys, analysis/lut_table.json) or cycles (clocks per frame of the cycle model, "
                 "summed over the scenes)")
      ->check(CLI::IsMember({"area", "cycles", "luts"}));
  sub.add_option("--config", o->config, "starting configuration JSON (default: the first scene's)");
  sub.add_option("--lut-table", o->lut_table, "the LUT4 table of --cost luts (default: analysis/lut_table.json of the source tree)");
  sub.add_option("--out", o->out, "output directory")->required();
  sub.add_option("--samples", o->samples, "fragments per scene and configuration (default 1000)")->check(CLI::Range(1, 10000000));
  sub.add_option("--threads", o->threads, "configurations evaluated in parallel (the result does not depend on it)")
      ->check(CLI::Range(0, 256));
  fxr::app::add_scene_overrides(sub, o->in);
  sub.add_flag("--no-plots", o->no_plots, "do not call scripts/plot_plan.py");
  sub.add_flag("--quiet", o->quiet, "no progress output");
  return [o]() { return run(*o); };
}

fxr::app::Registrar reg("plan",
                        "the cheapest configuration meeting an error target on every scene: search, Pareto front, "
                        "minimality check (docs/reports.md)",
                        setup);

}  // namespace

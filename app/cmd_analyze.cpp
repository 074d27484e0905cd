// `fxraster analyze SCENE|--default [--config F] [--out DIR]`: the ranges a scene exercises, the
// minimal widths they require and what it never exercises (analysis/scene_analysis.hpp;
// docs/reports.md, "Scene analysis"). Markdown on stdout; --out also writes analysis.md / .json.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "analysis/scene_analysis.hpp"
#include "command.hpp"
#include "scene_input.hpp"

namespace {

struct Opts {
  fxr::app::SceneInput in;
  std::string out;
};

int run(const Opts& o) {
  const fxr::Scene sc = fxr::app::load_scene_input(o.in, "analyze");
  const fxr::SceneAnalysis a = fxr::analyze_scene(sc);
  const std::string md = fxr::analysis_markdown(a);
  std::cout << md;
  if (!o.out.empty()) {
    std::filesystem::create_directories(o.out);
    std::ofstream m(o.out + "/analysis.md"), j(o.out + "/analysis.json");
    m << md;
    j << fxr::analysis_json(a).dump(2) << "\n";
    if (!m || !j) throw fxr::ConfigError(o.out + ": cannot write analysis.md / analysis.json");
  }
  return 0;
}

fxr::app::Runner setup(CLI::App& sub) {
  auto o = std::make_shared<Opts>();
  fxr::app::add_scene_source(sub, o->in, "the embedded default scene");
  sub.add_option("--out", o->out, "also write analysis.md and analysis.json into this directory");
  fxr::app::add_scene_overrides(sub, o->in);
  return [o]() { return run(*o); };
}

fxr::app::Registrar reg("analyze",
                        "the ranges a scene exercises, the minimal width of each format they require and the "
                        "features it never exercises (docs/reports.md)",
                        setup);

}  // namespace

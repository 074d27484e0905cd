// `fxraster analyze SCENE|--default [--config F] [--out DIR]`: the ranges a scene exercises, the
// minimal widths they require and what it never exercises (analysis/scene_analysis.hpp;
// docs/reports.md, "Scene analysis"). Markdown on stdout; --out also writes analysis.md / .json.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "analysis/scene_analysis.hpp"
#include "command.hpp"

namespace {

struct Opts {
  std::string scene, out, config;
  bool use_default = false, no_bunny = false;
  int width = 0, height = 0;
};

int run(const Opts& o) {
  if (o.scene.empty() == !o.use_default) throw fxr::ConfigError("give exactly one of SCENE or --default");
  fxr::SceneOptions so;
  so.width = o.width;
  so.height = o.height;
  so.no_optional = o.no_bunny;
  fxr::Scene sc = o.use_default ? fxr::default_scene(so) : fxr::load_scene(o.scene, so);
  if (!o.config.empty()) fxr::apply_config_file(sc, o.config);
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
  sub.add_option("scene", o->scene, "scene JSON file (docs/scene-format.md)");
  sub.add_flag("--default", o->use_default, "the embedded default scene");
  sub.add_option("--config", o->config, "configuration JSON whose fields override the scene's configuration");
  sub.add_option("--out", o->out, "also write analysis.md and analysis.json into this directory");
  sub.add_flag("--no-bunny", o->no_bunny, "leave out optional meshes (the default scene's bunny)");
  sub.add_option("--width", o->width, "override the viewport width (pixels)")->check(CLI::Range(1, 16384));
  sub.add_option("--height", o->height, "override the viewport height (pixels)")->check(CLI::Range(1, 16384));
  return [o]() { return run(*o); };
}

fxr::app::Registrar reg("analyze",
                        "the ranges a scene exercises, the minimal width of each format they require and the "
                        "features it never exercises (docs/reports.md)",
                        setup);

}  // namespace

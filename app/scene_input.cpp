// app/scene_input.hpp: SCENE|--default, --config, --no-bunny, --width, --height of the subcommands.
#include "scene_input.hpp"

namespace fxr::app {

// The largest --width / --height (pixels).
constexpr int kMaxViewportOverride = 16384;

void add_scene_source(CLI::App& sub, SceneInput& in, const std::string& default_help) {
  sub.add_option("scene", in.scene, "scene JSON file (docs/scene-format.md)");
  sub.add_flag("--default", in.use_default, default_help);
  sub.add_option("--config", in.config, "configuration JSON whose fields override the scene's configuration");
}

void add_scene_overrides(CLI::App& sub, SceneInput& in) {
  sub.add_flag("--no-bunny", in.no_bunny, "leave out optional meshes (the default scene's bunny)");
  sub.add_option("--width", in.width, "override the viewport width (pixels)")->check(CLI::Range(1, kMaxViewportOverride));
  sub.add_option("--height", in.height, "override the viewport height (pixels)")
      ->check(CLI::Range(1, kMaxViewportOverride));
}

fxr::SceneOptions scene_options(const SceneInput& in) {
  fxr::SceneOptions so;
  so.width = in.width;
  so.height = in.height;
  so.no_optional = in.no_bunny;
  return so;
}

void check_scene_source(const SceneInput& in, const std::string& command) {
  if (in.scene.empty() == !in.use_default) throw fxr::ConfigError(command + ": give exactly one of SCENE or --default");
}

fxr::Scene load_scene_input(const SceneInput& in, const std::string& command, bool wireframe) {
  check_scene_source(in, command);
  fxr::SceneOptions so = scene_options(in);
  so.wireframe = wireframe;
  fxr::Scene sc = in.use_default ? fxr::default_scene(so) : fxr::load_scene(in.scene, so);
  if (!in.config.empty()) fxr::apply_config_file(sc, in.config);
  return sc;
}

}  // namespace fxr::app

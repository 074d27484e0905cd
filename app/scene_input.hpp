// app/scene_input.hpp — the scene a subcommand reads (render, analyze, budget, cycles, plan): a
// scene file or the embedded default, with --config, --no-bunny, --width and --height, the same
// options with the same checks in every subcommand.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "frontend/scene.hpp"

namespace fxr::app {

struct SceneInput {
  std::string scene, config;  // SCENE (a file), --config F
  bool use_default = false, no_bunny = false;
  int width = 0, height = 0;  // > 0: override the scene's viewport
};

// SCENE (positional), --default (`default_help`: its help text) and --config.
void add_scene_source(CLI::App& sub, SceneInput& in, const std::string& default_help);
// --no-bunny, --width and --height (1 … 16384 pixels).
void add_scene_overrides(CLI::App& sub, SceneInput& in);

// The frontend's options of the overrides (for a subcommand reading several scenes).
fxr::SceneOptions scene_options(const SceneInput& in);

// Contract: throws fxr::ConfigError "<command>: give exactly one of SCENE or --default" unless
// exactly one is given (a usage error: exit 2).
void check_scene_source(const SceneInput& in, const std::string& command);

// Contract: check_scene_source, then the default scene or the file with the overrides (and
// `wireframe`: the default scene's wireframe variant), then --config's fields over its
// configuration. Throws fxr::ConfigError naming the file and the field.
fxr::Scene load_scene_input(const SceneInput& in, const std::string& command, bool wireframe = false);

}  // namespace fxr::app

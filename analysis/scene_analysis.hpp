// analysis/scene_analysis.hpp — what a scene needs (`fxraster analyze`, issue 13; docs/reports.md
// "Scene analysis"): the ranges the scene exercises and the minimal width of each format those
// ranges require, derived analytically (the derivations are in docs/reports.md), with the
// stages and features the scene never exercises.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frontend/scene.hpp"

namespace fxr {

struct MinWidth {
  std::string field;    // configuration field, e.g. "raster.window_int_bits"
  int min = 0;          // the smallest value the scene's ranges allow (−1: no value of the range does)
  int current = 0;      // the scene's configuration
  std::string why;      // the range it comes from
};

struct SceneAnalysis {
  std::string scene;
  int viewport_x = 0, viewport_y = 0, viewport_w = 0, viewport_h = 0;
  int64_t guard_limit_px = 0;             // the configuration's guard band L
  double max_abs_clip[4] = {0, 0, 0, 0};  // input |x_c|, |y_c|, |z_c|, |w_c|
  double w_min = 0, w_max = 0;            // input vertices with w > 0
  double w_ratio_max = 1, w_ratio_p50 = 1;  // per triangle max w / min w (all w > 0)
  double window_extent_px = 0;            // max |x_w|, |y_w| of the drawn (snapped) vertices
  double input_window_extent_px = 0;      // the same for every input vertex in front of the eye (w > 0)
  std::vector<double> var_min, var_max;   // per varying over input vertices
  int texture_w = 0, texture_h = 0;
  double min_area_px2 = 0, max_extent_px = 0;  // drawn triangles (snapped)
  uint32_t depth_min_code = 0, depth_max_code = 0;  // fragments written
  uint64_t overlapping_pixels = 0;        // pixels covered by two or more primitives
  int64_t min_depth_separation_lsb = -1;  // smallest |Δcode| between different primitives at one pixel (−1: none)
  uint64_t equal_depth_pairs = 0;         // …of which equal codes (z-fighting at this format)
  uint64_t prims = 0, prims_clipped = 0;
  uint64_t plane_clips[7] = {};           // primitives with a vertex strictly outside each plane (ClipPlane order)
  int max_block_lead_diff = 0;            // largest lead-exponent difference of 1/w or v/w within a triangle
  int max_attr_coord_need = 0;            // msb + 3 of the largest relative attribute coordinate
  bool u_outside_unit = false, v_outside_unit = false;
  std::vector<MinWidth> widths;
  std::vector<std::string> unused;        // stages / features never exercised
};

// Contract: the analysis of `sc` with its configuration (the model run with the depth test on
// as given, and once with every fragment kept for the overlap figures). Deterministic.
SceneAnalysis analyze_scene(const Scene& sc);
nlohmann::json analysis_json(const SceneAnalysis& a);
std::string analysis_markdown(const SceneAnalysis& a);

}  // namespace fxr

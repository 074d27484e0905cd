// analysis/line_analysis.hpp — the line fragments of a rendered frame against exact arithmetic
// (GMP), at the two levels of the triangles' spot checks (docs/lines.md, "The line path"):
//   own segment — GL's parameter t (clamped) from the model's own quantised segment (the positions,
//                 z, 1/w and v/w the line setup sees, rebuilt through the line chain): how well
//                 the line stages round;
//   ideal       — t, depth and the perspective-correct varyings from the unsnapped float32 input
//                 (window positions x_c/w_c exactly; both endpoints need w_c > 0, otherwise the
//                 fragment counts as undefined): what a user sees.
#pragma once

#include <cstdint>
#include <vector>

#include "analysis/error_stats.hpp"
#include "frontend/scene.hpp"
#include "model/unit/raster_unit.hpp"

namespace fxr {

struct LineChecks {
  uint64_t fragments = 0;                     // line fragments in the frame
  uint64_t checked = 0;                       // against the own segment
  uint64_t ideal_checked = 0, ideal_undefined = 0;
  ErrStat depth_lsb, ideal_depth_lsb;         // LSB of the depth code
  std::vector<ErrStat> var_ulp, ideal_var_ulp;  // ulps of the output format, per varying
};

// Contract: up to n line fragments of `fo` (primitive ≥ sc.tris.size(), evenly spaced in draw
// order) checked at both levels. Deterministic.
LineChecks line_checks(const Scene& sc, const FrameOutput& fo, int n);

}  // namespace fxr

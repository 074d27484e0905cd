// analysis/render_report.hpp — the render report: a scene through the bit-accurate unit and
// the double reference; writes the shaded, depth and other-interpolation images, the fragment
// dump, statistics, report.json and report.md into one directory. Deterministic: no timings in
// the files. docs/reports.md describes every file.
#pragma once

#include <string>

#include "analysis/render_analysis.hpp"

namespace fxr {

struct RenderOptions {
  std::string out;              // output directory (created)
  bool affine = false;          // the scene was switched to affine interpolation (names the images)
  bool no_affine_image = false; // skip the second image in the other interpolation mode
  int spot_checks = 2000;       // fragments re-evaluated exactly with GMP
  int threads = 1;              // model threads (model/unit/threads.hpp: the output does not depend on it)
};

struct RenderSummary {
  size_t fragments = 0;
  double model_seconds = 0, reference_seconds = 0;  // for the console only, never in the files
  RenderErrors err;
  SpotChecks spot;
  CoverageDiff cov;
  bool all_accounted = false;  // every input primitive drawn, culled or rejected
};

// Contract: renders `sc` (its configuration and draw state as given) and writes the report
// files into o.out. Throws on I/O errors.
RenderSummary render_with_report(const Scene& sc, const RenderOptions& o);

}  // namespace fxr

// tb/unit/unit_check.hpp — the checks of a whole draw through rtl/fxr_raster_unit.sv against the
// model, shared by tb/unit/unit_test.cpp (the default configuration) and
// tb/unit/unit_variant_test.cpp (the unit verilated at another configuration): fragment stream,
// final depth buffer, the back-end counters (per setup triangle) and the geometry counters
// (RasterStats, RasterStats::tris), all equal; the figures printed. docs/rtl.md, "fxr_raster_unit".
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "unit/unit_run.hpp"

namespace fxr::tb {

// The scene files of scenes/, sorted.
inline std::vector<std::filesystem::path> scene_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(FXR_SOURCE_DIR) + "/scenes"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

inline std::string geom_text(const GeomStats& s) {
  std::string t;
  for (int i = 0; i < kGeomStats; ++i)
    t += std::string(i ? ", " : "") + kGeomStatNames[i] + " " + std::to_string(s[(size_t)i]);
  return t;
}

inline void expect_match(const Draw& d, const UnitRun& k, const std::string& what) {
  EXPECT_TRUE(k.k.r.passed()) << what;
  EXPECT_EQ(k.k.r.inputs, d.u.in.rows) << what;
  EXPECT_EQ(k.k.r.outputs, d.u.out.rows) << what;
  EXPECT_EQ(k.k.bad_addresses, 0u) << what;
  EXPECT_TRUE(k.k.depth == d.depth) << what << ": the final depth buffer differs from the model's";
  EXPECT_EQ(k.k.stats, d.want) << what << "\n  rtl:   " << stats_text(k.k.stats)
                               << "\n  model: " << stats_text(d.want);
  const GeomStats g = model_geom_stats(d);
  EXPECT_EQ(k.geom, g) << what << "\n  rtl:   " << geom_text(k.geom) << "\n  model: " << geom_text(g);
}

inline void print_figures(const Draw& d, const UnitRun& k) {
  const TxnResult& r = k.k.r;
  const uint64_t cyc = r.last_out_cycle > r.first_in_cycle ? r.last_out_cycle - r.first_in_cycle + 1 : 0;
  std::printf("FIGURES unit %s: %llu primitives, %llu fragments generated, %llu passed; %llu cycles first input to "
              "last output, %.4f fragments/clock (generated); Verilator %.0f cycles/s, %.0f fragments/s; per CPU "
              "second %.0f cycles, %.0f fragments, %.0f primitives%s\n",
              d.name.c_str(), (unsigned long long)d.u.in.rows, (unsigned long long)d.want[7],
              (unsigned long long)d.want[8], (unsigned long long)cyc, cyc ? (double)d.want[7] / (double)cyc : 0.0,
              r.seconds > 0 ? (double)r.cycles / r.seconds : 0.0, r.seconds > 0 ? (double)d.want[7] / r.seconds : 0.0,
              r.cpu_seconds > 0 ? (double)r.cycles / r.cpu_seconds : 0.0,
              r.cpu_seconds > 0 ? (double)d.want[7] / r.cpu_seconds : 0.0,
              r.cpu_seconds > 0 ? (double)d.u.in.rows / r.cpu_seconds : 0.0, harness_text(r, d.want[7]).c_str());
  std::printf("FIGURES unit %s: utilisation (busy / stalled / starved %% of the clocks first input to last output):",
              d.name.c_str());
  for (int i = 0; i < kUnitStages; ++i) {
    const auto& u = k.util_window[(size_t)i];
    const double all = (double)(u[0] + u[1] + u[2]);
    std::printf(" %s %.1f/%.1f/%.1f", kUnitStageNames[i], all ? 100.0 * (double)u[0] / all : 0.0,
                all ? 100.0 * (double)u[1] / all : 0.0, all ? 100.0 * (double)u[2] / all : 0.0);
  }
  std::printf("\n");
}

}  // namespace fxr::tb

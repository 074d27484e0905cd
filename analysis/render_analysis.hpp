// analysis/render_analysis.hpp — how far a rendered frame of the model lies from the
// references: per-fragment error of depth and varyings against the double reference at the
// pixel centre, coverage sets against the reference, exact (GMP) spot checks on the model's own
// snapped triangles, and the vertex snap error. docs/reports.md explains every figure.
#pragma once

#include <cstdint>
#include <vector>

#include <gmpxx.h>
#include <nlohmann/json.hpp>

#include "analysis/error_stats.hpp"
#include "frontend/scene.hpp"
#include "model/unit/raster_unit.hpp"
#include "reference/reference.hpp"

namespace fxr {

// Error of every fragment of `fo` against the double reference of its input primitive at the
// pixel centre (unsnapped, unclipped clip-space solve: reference_at_pixel).
struct RenderErrors {
  std::vector<ErrStat> var_ulp, var_abs, var_texel;  // per varying
  std::vector<uint64_t> texel_diff;                  // nearest texel differs from the reference's
  ErrStat depth_lsb;
  uint64_t ref_invalid = 0;                          // reference undefined at the fragment
  uint64_t var_zero_ref = 0;                         // reference value 0: no ulp
  nlohmann::json worst = nlohmann::json::object();
  std::vector<double> heat;                          // per pixel: error of the visible fragment (texels; −1: none)
};
RenderErrors compare_to_reference(const Scene& sc, const FrameOutput& fo);

// Coverage sets of (prim, x, y): counts of each side and of the symmetric difference, with up to
// 20 examples.
struct CoverageDiff {
  uint64_t model = 0, ref = 0, common = 0, model_only = 0, ref_only = 0;
  nlohmann::json examples = nlohmann::json::array();
};
CoverageDiff compare_coverage(const FragmentStore& mf, const std::vector<RefFragment>& rf);

// Exact spot checks: for up to n fragments (evenly spaced in draw order), the snapped setup
// triangles of the fragment's primitive are rebuilt with geometry(), and the model's depth and
// varyings compared with the exact rational values (GMP) from those snapped vertices.
// Exact spot checks at two levels (docs/pipeline.md, "Accuracy against the ideal"): against exact
// arithmetic on the model's own quantised triangle (snapped positions, or the attribute positions
// the planes are set up from: how well each rounding is done), and against the IDEAL, the exact
// solve of the unsnapped float32 input at the pixel centre (analysis/ideal.hpp: what a user sees).
struct SpotChecks {
  uint64_t checked = 0, not_covered_exactly = 0;
  ErrStat depth_lsb;
  std::vector<ErrStat> var_ulp;
  uint64_t ideal_checked = 0, ideal_undefined = 0;
  ErrStat ideal_depth_lsb;
  std::vector<ErrStat> ideal_var_ulp;
  // The exact ideal texture coordinates of the checked fragments (when the scene has u and v):
  // index into fo.fragments, u, v. Read by the texel report (analysis/texel_errors.hpp).
  struct IdealUV {
    size_t fragment;
    mpq_class u, v;
  };
  std::vector<IdealUV> ideal_uv;
};
SpotChecks exact_spot_checks(const Scene& sc, const FrameOutput& fo, int n);

// Vertex snapping, stage 4: for every primitive the geometry stages pass unclipped, each
// snapped window x, y against the double window position of the nearest input vertex (pixels).
ErrStat snap_errors(const Scene& sc);

// The fragment dump: DIR/fragments.csv (integer codes, draw order) and DIR/fragments.json
// (column declarations, configuration). docs/reports.md.
void write_fragment_dump(const std::string& dir, const Scene& sc, const FrameOutput& fo);

// Statistics as JSON objects (one key per counter).
nlohmann::json stats_json(RasterStats s);
nlohmann::json ref_stats_json(const RefStats& s);

}  // namespace fxr

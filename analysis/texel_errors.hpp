// analysis/texel_errors.hpp — the texel report of a rendered frame (docs/reports.md, "Texel
// error"): the texture address unit and the texel filter on the model's fragments against exact
// references, for both filters (nearest and bilinear) whatever the image uses.
//
// Three levels per filter:
//   own:   the unit on the model's FxFloat u, v against the exact address of the same values
//          (GMP, reference/texture_ref.hpp): how well the unit rounds. Every triangle fragment
//          (line fragments are drawn in a flat colour).
//   ideal: against the exact address of the IDEAL u, v (analysis/ideal.hpp, exact solve of the
//          unsnapped input at the pixel centre): what a user sees. The exact spot-check sample.
//   double reference: against the same rules on the double reference's u, v (reference.png's
//          texels). Every fragment.
// Figures: fragments whose texels (every index and border flag of both axes) equal the
// reference's; the weight error in LSBs of the F-bit weight, |unit weight − exact fraction · 2^F|
// on fragments with the same texels (bilinear; both axes); the colour error, the largest channel
// difference in 8-bit levels between the unit's colour and the unrounded blend of the exact
// address (the double reference's for that level).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/error_stats.hpp"
#include "analysis/render_analysis.hpp"
#include "frontend/scene.hpp"
#include "model/unit/raster_unit.hpp"

namespace fxr {

struct TexelLevel {
  uint64_t checked = 0, same_texels = 0;
  ErrStat weight_lsb;  // bilinear only: fragments with the same texels, one sample per axis
  ErrStat colour;      // 8-bit levels, largest channel difference
  nlohmann::json to_json() const;
};

struct TexelFilterErrors {
  std::string filter;  // "nearest" / "bilinear"
  TexelLevel own, ideal, ref;
};

struct TexelErrors {
  bool textured = false;            // the scene has u and v
  std::string wrap;                 // tex_addr.wrap
  int weight_frac_bits = 0;
  uint64_t coords_exp_outside = 0;  // u, v codes whose exponent does not fit tex_addr.exp_bits (the RTL's field)
  std::vector<TexelFilterErrors> filters;  // nearest, bilinear
  nlohmann::json to_json() const;
};

// Contract: the figures above for the frame `fo` of scene `sc` (its tex_addr wrap and
// weight_frac_bits; both filters); `spot` supplies the ideal u, v of the spot-check sample.
// Deterministic. A scene without u, v gives textured = false and nothing else.
TexelErrors texel_errors(const Scene& sc, const FrameOutput& fo, const SpotChecks& spot);

}  // namespace fxr

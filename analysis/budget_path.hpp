// analysis/budget_path.hpp — every rounding point of the raster unit as a knob (issue 13).
//
// The bit-accurate model (model/) is not touched: this is a separate ANALYSIS path that
// recomputes one fragment of one primitive from the float32 clip-space input, in GMP rationals,
// with each rounding point of docs/pipeline.md either ACTIVE (rounded exactly as the model
// rounds it, at the width the configuration gives it) or EXACT (the unrounded rational goes on).
// Widening a point to a stated width is a configuration change: the path reads every width
// from the Config it is given and has no i128 / int64 limits (GMP), so any width works here.
// With every point active the path reproduces the model's fragment bit for bit (tested on
// whole scenes: tests/model/budget_test.cpp); with every point exact it is the exact value of
// the unsnapped triangle at the pixel centre, equal to analysis/ideal.hpp's IdealJudge (a
// separate derivation) as a rational. docs/reports.md, "Error budget".
//
// The rounding points (docs/pipeline.md lists each where precision is lost), in pipeline order:
//   coverage_snap  stage 4: vertex x, y snapped to raster.subpixel_bits — decides coverage
//                  only on the attribute-position path (the planes use their own positions);
//                  its effect is counted as pixels, never as a value error.
//   clip           stage 2: new x, y, z, v at raster.clip_sig_bits, w at recip.in_sig_bits,
//                  the attribute w at raster.clip_sig_bits (RNE, flush below 2^−192).
//   attr_position  stage 4: ax, ay = RNE(x_w·2^A), A = raster.attr_subpixel_bits.
//   attr_coord     stage 5: the drop of s low bits when a triangle's relative extent needs more
//                  than raster.attr_coord_bits (F = A − s).
//   depth_vertex   stage 4/5: z_k = RNE(z_c/w_c·2^z_frac_bits) (saturated), and the depth plane's
//                  vertex value RNE(z_k·(2^db − 1)/2^db) at z_frac_bits − db fraction bits.
//   recip          stage 4: 1/w_c to raster.attr_sig_bits (RNE of the exact quotient).
//   v_over_w       stage 4: v_k/w_c to raster.attr_sig_bits.
//   block_align    stage 5: the three 1/w and the three v/w of each varying put on one block
//                  exponent with raster.interp_block_bits (RNE).
//   normalise      stage 9: |N| and D rounded to div.num_bits / div.den_bits significant bits.
//   divider        stage 9: the quotient to div.quot_bits (= raster.varying_out_sig_bits) by
//                  div.algorithm (radix2: correctly rounded; shared_recip / recip_mul: the
//                  model's divider on the normalised operands; with normalise exact the
//                  operands are not dyadic and the point is the correctly rounded quotient).
//   depth_code     stage 8: the depth code RNE(z·(2^db − 1)), db from raster.depth_format.
// Only the attribute-position path (raster.attr_subpixel_bits > subpixel_bits, the default)
// and perspective interpolation are modelled; BudgetPath's constructor throws ConfigError
// otherwise.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <tuple>
#include <string>
#include <vector>

#include <gmpxx.h>

#include "model/config/config.hpp"
#include "model/stages/setup.hpp"
#include "model/unit/io.hpp"

namespace fxr {

enum class RoundPoint : int {
  CoverageSnap,
  Clip,
  AttrPosition,
  AttrCoord,
  DepthVertex,
  Recip,
  VaryingW,
  BlockAlign,
  Normalise,
  Divider,
  DepthCode,
};
inline constexpr int kNumRoundPoints = 11;

struct RoundPointInfo {
  const char* name;    // CLI / JSON name
  const char* fields;  // the configuration fields that give its width
  const char* stage;   // where it is in the pipeline
};
const RoundPointInfo& round_point_info(RoundPoint p);
// Contract: the point named `name` (RoundPointInfo::name); false when there is none.
bool round_point_from_name(const std::string& name, RoundPoint* out);
// Contract: the configuration's width(s) of point p, as text ("clip_sig_bits 32, in_sig_bits 24").
std::string round_point_width(const Config& cfg, RoundPoint p);

// Bit p set: rounding point p is exact.
using ExactMask = uint32_t;
inline constexpr ExactMask exact_bit(RoundPoint p) { return (ExactMask)1 << (int)p; }
inline constexpr ExactMask kAllExact = ((ExactMask)1 << kNumRoundPoints) - 1;

struct PathValue {
  bool valid = false;            // false: the pixel has no piece, or the attribute triangle has zero area
  mpq_class depth;               // depth in LSBs (the code when depth_code is active)
  mpq_class var[kMaxVaryings];   // output varyings
  bool exact_covered = false;    // with mask = kAllExact only: the pixel centre lies in the exact triangle
};

// The analysis path over one draw. Not thread-safe (per-primitive caches); one per thread.
class BudgetPath {
 public:
  BudgetPath(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris);
  // Contract: the fragment of primitive `prim` at pixel (px, py) — a pixel the model drew for
  // that primitive — with the points in `exact` exact and the others active.
  PathValue eval(uint32_t prim, int px, int py, ExactMask exact);

  // A clipped vertex: clip-space position, varyings, and the attribute w (docs/pipeline.md, stage 2).
  struct Vtx {
    mpq_class p[4];
    mpq_class v[kMaxVaryings];
    mpq_class wa;
  };
  // One fan triangle at one mask: window positions (pixels) as the planes see them, the depth
  // plane's vertex values (LSB), 1/w and v/w after block alignment (λ_k = E_k / ΣE).
  struct Piece {
    bool ok = false;
    mpq_class x[3], y[3];
    mpq_class zq[3];
    mpq_class rw[3];
    std::vector<mpq_class> vw[3];
  };

 private:
  struct ModelPrim;
  Config cfg_;
  DrawState st_;
  const std::vector<ClipTriangle>& tris_;
  uint32_t cached_prim_ = UINT32_MAX;
  std::vector<SetupTriangle> model_pieces_;
  std::vector<TriSetup> model_setup_;
  std::vector<bool> model_ok_;
  std::map<ExactMask, std::vector<Vtx>> poly_;            // per mask: the clipped polygon
  std::map<std::tuple<ExactMask, int, int>, Piece*> pieces_;  // per mask, fan index, model fan index
  std::vector<std::unique_ptr<Piece>> piece_store_;
  void load_prim(uint32_t prim);
  const std::vector<Vtx>& polygon(ExactMask m);
  const Piece& piece(ExactMask m, int fan, int model_fan);
};

}  // namespace fxr

// The whole raster unit: the UnitChain of model/unit/chain.hpp (stages 1–10), keeping every
// fragment.
#include "model/unit/raster_unit.hpp"

#include "model/unit/chain.hpp"
#include "model/unit/line_chain.hpp"

namespace fxr {

FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris) {
  FrameOutput f;
  KeepFragments keep(f.fragments);
  NoTaps taps;
  run_raster_unit_to(cfg, st, tris, f, &keep, taps);
  return f;
}

FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                            const DrawState& line_st, const std::vector<ClipLine>& lines) {
  FrameOutput f;
  KeepFragments keep(f.fragments);
  NoTaps taps;
  run_raster_unit_to(cfg, st, tris, line_st, lines, f, &keep, taps);
  return f;
}

}  // namespace fxr

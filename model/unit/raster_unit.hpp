// model/unit/raster_unit.hpp — the whole raster unit, stages 1–10, on a list of clip-space triangles.
#pragma once

#include <cstdint>
#include <vector>

#include "model/config/config.hpp"
#include "model/unit/fragment_store.hpp"
#include "model/unit/io.hpp"

namespace fxr {

struct FrameOutput {
  int width = 0, height = 0;           // the viewport size
  FragmentStore fragments;             // fragments that passed the depth test, in draw order
                                       // (compact records: model/unit/fragment_store.hpp)
  std::vector<uint32_t> depth;         // final depth buffer codes, row 0 at the bottom, w × h
  RasterStats stats;
};

// Contract: runs every triangle through geometry() and the raster stages, in order, with a
// depth buffer cleared to the maximum code. Integer arithmetic only; deterministic.
FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris);

// Contract: the triangles as above, then the line segments (docs/lines.md, model/unit/line_chain.hpp)
// with draw state `line_st` (same viewport; its depth and interpolation fields apply to the
// lines) into the same frame and depth buffer; segment k is primitive tris.size() + k.
FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                            const DrawState& line_st, const std::vector<ClipLine>& lines);

}  // namespace fxr

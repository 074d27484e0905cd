// The whole raster unit: geometry() (stages 1–4) then raster_triangle() (stages 5–10).
#include "model/unit/raster_unit.hpp"

#include "model/unit/geometry.hpp"
#include "model/unit/backend.hpp"

namespace fxr {

FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris) {
  FrameOutput f;
  frame_begin(cfg, st, f);
  RasterStats& s = f.stats;
  std::vector<SetupTriangle> pieces;
  for (size_t p = 0; p < tris.size(); ++p) {
    ++s.prims_in;
    pieces.clear();
    const GeomOutcome g = geometry(cfg, st, tris[p], (uint32_t)p, pieces, s);
    switch (g) {
      case GeomOutcome::CulledOutside: ++s.prims_culled_outside; continue;
      case GeomOutcome::RejectedNaN: ++s.prims_rejected_nan; continue;
      case GeomOutcome::RejectedInf: ++s.prims_rejected_inf; continue;
      case GeomOutcome::RejectedRange: ++s.prims_rejected_range; continue;
      case GeomOutcome::Emitted: break;
    }
    // A clipped primitive may become several triangles: it counts once, as drawn if any
    // piece was rasterised, else by the first reason in the order range > backface >
    // no samples > zero area (all pieces of one primitive share its facing).
    bool drawn = false, range = false, back = false, nosamp = false;
    for (const SetupTriangle& t : pieces) {
      switch (raster_triangle(cfg, st, t, f)) {
        case SetupOutcome::Ok: drawn = true; break;
        case SetupOutcome::RejectedRange: range = true; break;
        case SetupOutcome::CulledBackface: back = true; break;
        case SetupOutcome::CulledNoSamples: nosamp = true; break;
        case SetupOutcome::CulledZeroArea: break;
      }
    }
    if (drawn) ++s.prims_drawn;
    else if (range) ++s.prims_rejected_range;
    else if (back) ++s.prims_culled_backface;
    else if (nosamp) ++s.prims_culled_no_samples;
    else if (pieces.empty()) ++s.prims_culled_outside;  // geometry emitted nothing
    else ++s.prims_culled_zero_area;
  }
  return f;
}

}  // namespace fxr

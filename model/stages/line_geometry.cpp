// Stages 1–4 for line segments (line_geometry.hpp). Integer arithmetic only.
#include "model/stages/line_geometry.hpp"

namespace fxr {

int clip_segment(const GuardBand& gb, const ClipWidths& cw, const ClipVtx in[2], ClipVtx out[2], int* created,
                 bool* overflow) {
  out[0] = in[0];
  out[1] = in[1];
  for (int p = 0; p < kNumClipPlanes; ++p) {
    const PlaneEq pl = plane_eq(gb, (ClipPlane)p);
    const int s0 = plane_side(pl, out[0]), s1 = plane_side(pl, out[1]);
    if (s0 >= 0 && s1 >= 0) continue;
    if (s0 < 0 && s1 < 0) return 0;
    const int o = s0 < 0 ? 0 : 1;  // the endpoint strictly outside
    if ((o == 0 ? s1 : s0) == 0) {
      out[o] = out[1 - o];  // the inside endpoint lies on the plane: the segment shrinks to it
      continue;
    }
    bool ovf = false;
    const ClipVtx x = clip_intersect(cw, pl, out[0], out[1], &ovf);  // symmetric in its endpoints
    ++*created;
    if (ovf) {
      *overflow = true;
      return 0;
    }
    out[o] = x;
  }
  return 2;
}

}  // namespace fxr

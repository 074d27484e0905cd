// Stages 1–4 of the raster unit: input conversion, clipper, reciprocal + perspective divide,
// viewport + snap. Contract in model/unit/geometry.hpp; formats and derivations in docs/pipeline.md.
#include "model/unit/geometry.hpp"

#include "model/stages/clip.hpp"
#include "model/stages/viewport.hpp"

namespace fxr {

namespace {

// Stage 1 for one float32: exact decode; NaN / Inf flagged (never converted).
FxFloat convert_input(float f, bool& nan, bool& inf) {
  const F32Decoded d = decode_f32(f32_bits(f));
  nan |= d.cls == F32Class::NaN;
  inf |= d.cls == F32Class::Inf;
  return d.value;  // Zero / Denormal / Normal: exact (denormals are not flushed)
}

}  // namespace

GeomOutcome geometry(const Config& cfg, const DrawState& st, const ClipTriangle& tri, uint32_t prim,
                     std::vector<SetupTriangle>& out, RasterStats& stats) {
  // Stage 1: input conversion (exact). NaN takes precedence over Inf. Only the active varyings
  // (num_varyings) are inspected.
  const int nv = st.num_varyings;
  if (nv < 0 || nv > kMaxVaryings) return GeomOutcome::RejectedRange;  // bad draw state
  ClipVtx in[3];
  bool nan = false, inf = false;
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 4; ++c) in[i].p[c] = convert_input(tri.v[i].pos[c], nan, inf);
    for (int k = 0; k < nv; ++k) in[i].v[k] = convert_input(tri.v[i].var[k], nan, inf);
  }
  if (nan) return GeomOutcome::RejectedNaN;
  if (inf) return GeomOutcome::RejectedInf;

  // Stage 2: the clipper. An invalid viewport (empty, or outside the window format) leaves no
  // representable window coordinate: every primitive is RejectedRange.
  const GuardBand gb = guard_band(cfg.raster, st);
  if (!gb.valid) return GeomOutcome::RejectedRange;
  const uint32_t oc0 = outcode(gb, in[0]), oc1 = outcode(gb, in[1]), oc2 = outcode(gb, in[2]);
  if (oc0 & oc1 & oc2) return GeomOutcome::CulledOutside;  // trivial reject: all outside one plane
  if ((oc0 | oc1 | oc2) == 0) {  // trivial accept: all inside every plane, no clipper
    ++stats.prims_trivial_accept;
    out.emplace_back();
    SetupTriangle& t = out.back();
    t.prim = prim;
    for (int i = 0; i < 3; ++i)
      if (project_vertex(cfg, st, in[i], t.v[i]) != ProjectStatus::Ok) {
        out.pop_back();
        return GeomOutcome::RejectedRange;
      }
    return GeomOutcome::Emitted;
  }
  ++stats.prims_clipped;
  const ClipPolygon poly = clip_triangle(gb, clip_widths(cfg, nv), in);
  stats.clip_vertices_created += (uint64_t)poly.created;
  if (poly.overflow) return GeomOutcome::RejectedRange;  // internal bound; not reachable from float32
  if (poly.n == 0) return GeomOutcome::CulledOutside;
  stats.clip_triangles_out += (uint64_t)(poly.n - 2);

  // Stages 3 + 4 once per polygon vertex (shared by the fan's triangles).
  SetupVertex sv[kClipMaxPolyVerts];
  for (int i = 0; i < poly.n; ++i)
    if (project_vertex(cfg, st, poly.v[i], sv[i]) != ProjectStatus::Ok) return GeomOutcome::RejectedRange;

  // Fan triangulation of the convex polygon, in its winding: (v0, v_i, v_i+1).
  for (int i = 1; i + 1 < poly.n; ++i) {
    SetupTriangle t;
    t.v[0] = sv[0];
    t.v[1] = sv[i];
    t.v[2] = sv[i + 1];
    t.prim = prim;
    out.push_back(t);
  }
  return GeomOutcome::Emitted;
}

}  // namespace fxr

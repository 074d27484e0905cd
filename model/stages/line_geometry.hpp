// model/stages/line_geometry.hpp — stages 1–4 for line segments (issue 15; docs/lines.md, "The
// line path"): input conversion, the segment clipper, the reciprocal unit and viewport + snap,
// each the triangle stage's per-vertex arithmetic applied to two vertices.
//
//   InputLine → convert → ExactLine → clip → ClippedLine (0..1) → recip → RecipLine → viewport
//   → SetupLine
//
// Nothing here is new arithmetic: convert_input (input.hpp), the plane tests and the exact,
// once-rounded, direction-independent intersection clip_intersect (clip.hpp), recip
// (recip.hpp) and snap_vertex (viewport.hpp, attribute positions included). The clip volume is
// the triangles' (w ≥ 2^kWMinExp, 0 ≤ z ≤ w, the guard band); a segment is clipped against
// every plane that one of its endpoints is strictly outside of, in ClipPlane order: the outside
// endpoint is replaced by the intersection, which keeps the segment's direction (v[0] stays the
// first vertex, as the diamond-exit rule needs).
#pragma once

#include <cstdint>

#include "model/config/config.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/input.hpp"
#include "model/stages/recip_stage.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/viewport.hpp"
#include "model/unit/io.hpp"
#include "model/unit/record.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// Stage 1 input for a segment: float32 bit patterns as the vertex stage emits them.
struct InputLine {
  uint32_t prim = 0;
  ClipLine line;

  template <class V>
  void visit(V& v, const RecordShape& s) {
    v("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 2; ++i) visit_input_vertex(v, field_prefix("v", i), line.v[i], s);
  }
};

// Two exact clip-space vertices: the record after input conversion (ExactLine) and after the
// clipper (ClippedLine: a segment inside the clip volume). Both list the attribute w (an input
// vertex's is its w_c; not yet split into two records as ExactTriangle / ClippedTriangle are).
struct ClipSpaceLine {
  uint32_t prim = 0;
  ClipVtx v[2];

  template <class V>
  void visit(V& v_, const RecordShape& s) {
    v_("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 2; ++i) visit_clip_vertex(v_, field_prefix("v", i), v[i], s, true);
  }
};
using ExactLine = ClipSpaceLine;
using ClippedLine = ClipSpaceLine;

// Stage 3 output for a segment: the clipped vertices and 1/w_c of each (recip.out_sig_bits).
struct RecipLine {
  uint32_t prim = 0;
  ClipVtx v[2];
  FxFloat r[2];

  template <class V>
  void visit(V& v_, const RecordShape& s) {
    v_("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 2; ++i) visit_clip_vertex(v_, field_prefix("v", i), v[i], s, true);
    for (int i = 0; i < 2; ++i) visit_fx(v_, "r" + std::to_string(i), r[i], s.cfg.recip.out_sig_bits, s);
  }
};

// Stage 4 output for a segment: two snapped vertices (SetupVertex: coverage x, y; attribute
// positions ax, ay; z; 1/w; v/w), the line setup's input.
struct SetupLine {
  SetupVertex v[2];
  uint32_t prim = 0;

  template <class V>
  void visit(V& v_, const RecordShape& s) {
    v_("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 2; ++i) v[i].visit(v_, s, field_prefix("v", i));
  }
};

// ---- stage 1 ---------------------------------------------------------------------------------

class LineConvertStage {
 public:
  static constexpr const char* kName = "line_convert";
  using In = InputLine;
  using Out = ExactLine;

  LineConvertStage(const Config&, const DrawState& st) : nv_(st.num_varyings) {}

  // 1 → 0..1: as ConvertStage: a NaN / Inf in a position rejects the segment (NaN before
  // Inf); a non-finite varying is replaced (varying_input_bits, docs/pipeline.md stage 1).
  template <class Emit>
  ConvertOutcome step(const In& in, Emit&& emit) {
    replaced_ = false;
    if (nv_ < 0 || nv_ > kMaxVaryings) return ConvertOutcome::RejectedRange;
    bool nan = false, inf = false, replaced = false;
    out_.prim = in.prim;
    for (int i = 0; i < 2; ++i) {
      for (int c = 0; c < 4; ++c) out_.v[i].p[c] = convert_input(in.line.v[i].pos[c], nan, inf);
      out_.v[i].wa = out_.v[i].p[3];
      for (int k = 0; k < nv_; ++k)  // finite after the replacement: decoded exactly
        out_.v[i].v[k] = decode_f32(varying_input_bits(f32_bits(in.line.v[i].var[k]), &replaced)).value;
    }
    if (nan) return ConvertOutcome::RejectedNaN;
    if (inf) return ConvertOutcome::RejectedInf;
    replaced_ = replaced;
    emit(static_cast<const Out&>(out_));
    return ConvertOutcome::Emitted;
  }
  // The last emitted segment had a non-finite varying replaced (counted as varying_nonfinite).
  bool varyings_replaced() const { return replaced_; }

  // Two of the triangle converter's three vertex lanes (the same hardware, shared).
  static StageCost cost(const Config& cfg) { return ConvertStage::cost(cfg); }

 private:
  int nv_;
  bool replaced_ = false;
  ExactLine out_;
};

// ---- stage 2 ---------------------------------------------------------------------------------

struct LineClipReport {
  ClipOutcome outcome = ClipOutcome::Accepted;  // Accepted, Clipped, CulledOutside, ClippedAway,
                                                // RejectedViewport, RejectedOverflow
  int vertices_created = 0;
};

// Contract: the segment in[0] → in[1] clipped against every plane one endpoint is strictly
// outside of, in ClipPlane order (exact plane tests, clip_intersect for the new endpoint:
// rounded once per component, independent of the segment's direction). A segment with both
// endpoints strictly outside a plane is clipped away (n = 0); one with the inside endpoint ON
// the plane (d = 0) shrinks to that point. Returns 0 or 2 vertices in `out` (order kept).
int clip_segment(const GuardBand& gb, const ClipWidths& cw, const ClipVtx in[2], ClipVtx out[2], int* created,
                 bool* overflow);

class LineClipStage {
 public:
  static constexpr const char* kName = "line_clip";
  using In = ExactLine;
  using Out = ClippedLine;

  LineClipStage(const Config& cfg, const DrawState& st)
      : gb_(guard_band(cfg.raster, st)), cw_(clip_widths(cfg, st.num_varyings)), nv_(st.num_varyings) {}

  // 1 → 0..1.
  template <class Emit>
  LineClipReport step(const In& in, Emit&& emit) {
    LineClipReport r;
    if (!gb_.valid) return r.outcome = ClipOutcome::RejectedViewport, r;
    const uint32_t oc0 = outcode(gb_, in.v[0]), oc1 = outcode(gb_, in.v[1]);
    if (oc0 & oc1) return r.outcome = ClipOutcome::CulledOutside, r;
    out_.prim = in.prim;
    if ((oc0 | oc1) == 0) {
      for (int i = 0; i < 2; ++i) copy_clip_vertex(in.v[i], out_.v[i], nv_);
      emit(static_cast<const Out&>(out_));
      return r;
    }
    bool overflow = false;
    ClipVtx seg[2];
    const int n = clip_segment(gb_, cw_, in.v, seg, &r.vertices_created, &overflow);
    if (overflow) return r.outcome = ClipOutcome::RejectedOverflow, r;
    if (n == 0) return r.outcome = ClipOutcome::ClippedAway, r;
    r.outcome = ClipOutcome::Clipped;
    for (int i = 0; i < 2; ++i) copy_clip_vertex(seg[i], out_.v[i], nv_);
    emit(static_cast<const Out&>(out_));
    return r;
  }

  // The triangle clipper's plane tests and intersection unit (shared).
  static StageCost cost(const Config& cfg) { return ClipStage::cost(cfg); }

 private:
  GuardBand gb_;
  ClipWidths cw_;
  int nv_;
  ClippedLine out_;
};

// ---- stage 3 ---------------------------------------------------------------------------------

class LineRecipStage {
 public:
  static constexpr const char* kName = "line_recip";
  using In = ClippedLine;
  using Out = RecipLine;

  LineRecipStage(const Config& cfg, const DrawState& st) : cfg_(cfg.recip), nv_(st.num_varyings) {}

  template <class Emit>
  RecipOutcome step(const In& in, Emit&& emit) {
    for (int i = 0; i < 2; ++i) {
      const FxFloat w = normalize_fx(in.v[i].p[3], cfg_.in_sig_bits, Round::HalfEven);
      const RecipResult rr = recip(cfg_, w);
      if (rr.div_by_zero || rr.exp_overflow) return RecipOutcome::RecipError;
      out_.r[i] = rr.value;
    }
    out_.prim = in.prim;
    for (int i = 0; i < 2; ++i) copy_clip_vertex(in.v[i], out_.v[i], nv_);
    emit(static_cast<const Out&>(out_));
    return RecipOutcome::Emitted;
  }

  static StageCost cost(const Config& cfg) { return RecipStage::cost(cfg); }

 private:
  RecipConfig cfg_;
  int nv_;
  RecipLine out_;
};

// ---- stage 4 ---------------------------------------------------------------------------------

class LineViewportStage {
 public:
  static constexpr const char* kName = "line_viewport";
  using In = RecipLine;
  using Out = SetupLine;

  LineViewportStage(const Config& cfg, const DrawState& st) : cfg_(cfg), st_(st) {}

  template <class Emit>
  ViewportOutcome step(const In& in, Emit&& emit) {
    out_.prim = in.prim;
    for (int i = 0; i < 2; ++i)
      if (snap_vertex(cfg_, st_, in.v[i], in.r[i], out_.v[i]) != ProjectStatus::Ok) return ViewportOutcome::RejectedRange;
    emit(static_cast<const Out&>(out_));
    return ViewportOutcome::Emitted;
  }

  static StageCost cost(const Config& cfg) { return ViewportStage::cost(cfg); }

 private:
  const Config& cfg_;
  const DrawState& st_;
  SetupLine out_;
};

}  // namespace fxr

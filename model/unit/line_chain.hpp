// model/unit/line_chain.hpp — the line path of the raster unit as the chain of its stage steps, with
// a tap at every stage boundary, in the style of model/unit/chain.hpp (docs/lines.md, "The line
// path"; the tap protocol is chain.hpp's):
//
//   InputLine → line_convert → ExactLine → line_clip → ClippedLine (0..1) → line_recip → RecipLine
//   → line_viewport → SetupLine → line_setup → LineEquations → line → LineFragment (n)
//   → line_interp → PlaneSample → line_depth → PlaneSample (0..1) → line_divide → Fragment
//   → FragmentSink
//
// The depth stage (the frame's depth buffer) and the divider are the triangles' own stages
// (LineDepthStage, LineDivideStage: the same classes under the names of the line path's taps,
// since segments have their own draw state).
//
// Shared with chain.hpp where the logic is the same: the clipper's counters (count_clip) and
// stages 9–10 of a sample (depth_divide). Not shared: what follows a convert or clip outcome — a
// segment counts itself in LineStats and stops there, a triangle's outcome goes back as a
// GeomOutcome to the primitive accounting (count_geometry, PrimDisposition) while its other clipped
// pieces go on — and the stages 3–8 in between, which are the line path's own (docs/lines.md).
#pragma once

#include <cstdint>
#include <vector>

#include "model/config/config.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/line_geometry.hpp"
#include "model/stages/line_setup.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/chain.hpp"
#include "model/unit/io.hpp"
#include "model/unit/raster_unit.hpp"

namespace fxr {

// Stages 1–10 for segments, with the accounting of LineStats.
template <class Taps = NoTaps>
class LineChain {
 public:
  // `f` must be prepared (frame_begin) before. sink nullptr: fragments are counted and
  // depth-tested but not divided nor emitted.
  LineChain(const Config& cfg, const DrawState& st, FrameOutput& f, FragmentSink* sink, Taps& taps)
      : taps_(taps),
        stats_(f.stats),
        sink_(sink),
        convert_(cfg, st),
        clip_(cfg, st),
        recip_(cfg, st),
        viewport_(cfg, st),
        setup_(cfg, st, sink != nullptr),
        traverse_(cfg, st),
        interp_(cfg, st, sink != nullptr),
        depth_(cfg, st, DepthBufferView{f.depth.data(), f.width, st.viewport_x, st.viewport_y}),
        divide_(cfg, st, sink != nullptr) {
    if (sink) sink->draw_state(st);
  }

  // Contract: one input segment through every stage; it counts once in stats.lines: drawn (≥ 1
  // pixel inside viewport ∩ scissor), culled_outside, culled_no_pixels or rejected_*.
  void draw(const ClipLine& line, uint32_t prim) {
    LineStats& s = stats_.lines;
    ++s.in;
    in_.prim = prim;
    in_.line = line;
    taps_.template in<LineConvertStage>(in_);
    const ExactLine* ex = nullptr;
    switch (convert_.step(in_, [&](const ExactLine& e) {
      taps_.template out<LineConvertStage>(e);
      ex = &e;
    })) {
      case ConvertOutcome::Emitted:
        if (convert_.varyings_replaced()) ++s.varying_nonfinite;
        break;
      case ConvertOutcome::RejectedNaN: ++s.rejected_nan; return;
      case ConvertOutcome::RejectedInf: ++s.rejected_inf; return;
      case ConvertOutcome::RejectedRange: ++s.rejected_range; return;
    }
    taps_.template in<LineClipStage>(*ex);
    const ClippedLine* cl = nullptr;
    const LineClipReport r = clip_.step(*ex, [&](const ClippedLine& c) {
      taps_.template out<LineClipStage>(c);
      cl = &c;
    });
    count_clip(r.outcome, r.vertices_created, s.trivial_accept, s.clipped, s.clip_vertices_created);
    switch (r.outcome) {
      case ClipOutcome::CulledOutside:
      case ClipOutcome::ClippedAway: ++s.culled_outside; return;
      case ClipOutcome::RejectedViewport:
      case ClipOutcome::RejectedOverflow: ++s.rejected_range; return;
      case ClipOutcome::Accepted:
      case ClipOutcome::Clipped: break;
    }
    taps_.template in<LineRecipStage>(*cl);
    const SetupLine* sl = nullptr;
    const RecipOutcome ro = recip_.step(*cl, [&](const RecipLine& rl) {
      taps_.template out<LineRecipStage>(rl);
      taps_.template in<LineViewportStage>(rl);
      if (viewport_.step(rl, [&](const SetupLine& t) {
            taps_.template out<LineViewportStage>(t);
            sl = &t;
          }) != ViewportOutcome::Emitted)
        sl = nullptr;
    });
    if (ro != RecipOutcome::Emitted || sl == nullptr) {
      ++s.rejected_range;
      return;
    }
    uint64_t pixels = 0;
    taps_.template in<LineSetupStage>(*sl);
    const LineSetupOutcome so = setup_.step(*sl, [&](const LineEquations& eq) {
      taps_.template out<LineSetupStage>(eq);
      taps_.template in<LineTraverseStage>(eq);
      pixels = traverse_.step(eq, [&](const LineFragment& lf) {
        taps_.template out<LineTraverseStage>(lf);
        taps_.template in<LineInterpStage>(lf);
        interp_.step(eq, lf, [&](const PlaneSample& ps) {
          taps_.template out<LineInterpStage>(ps);
          depth_divide(ps, depth_, divide_, sink_, stats_, taps_);
        });
      });
    });
    if (so != LineSetupOutcome::Ok) {
      ++s.rejected_range;
      return;
    }
    s.fragments_generated += pixels;
    stats_.fragments_generated += pixels;
    if (pixels > 0) ++s.drawn;
    else ++s.culled_no_pixels;
  }

 private:
  Taps& taps_;
  RasterStats& stats_;
  FragmentSink* sink_;
  LineConvertStage convert_;
  LineClipStage clip_;
  LineRecipStage recip_;
  LineViewportStage viewport_;
  LineSetupStage setup_;
  LineTraverseStage traverse_;
  LineInterpStage interp_;
  LineDepthStage depth_;
  LineDivideStage divide_;
  InputLine in_;
};

// Contract: each segment through LineChain into the prepared frame `f`, segment k with the
// primitive index first_prim + k.
template <class Taps = NoTaps>
void draw_lines(const Config& cfg, const DrawState& line_st, const std::vector<ClipLine>& lines, size_t first_prim,
                FrameOutput& f, FragmentSink* sink, Taps& taps) {
  LineChain<Taps> chain(cfg, line_st, f, sink, taps);
  for (size_t k = 0; k < lines.size(); ++k) chain.draw(lines[k], (uint32_t)(first_prim + k));
}

// Contract: a draw of triangles followed by segments into one frame (one depth buffer): the
// triangles as run_raster_unit_to, then each segment through LineChain, segment k with the
// primitive index tris.size() + k. Prepares `f` (frame_begin).
template <class Taps = NoTaps>
void run_raster_unit_to(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                        const DrawState& line_st, const std::vector<ClipLine>& lines, FrameOutput& f,
                        FragmentSink* sink, Taps& taps) {
  run_raster_unit_to(cfg, st, tris, f, sink, taps);
  draw_lines(cfg, line_st, lines, tris.size(), f, sink, taps);
}

}  // namespace fxr

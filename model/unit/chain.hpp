// model/unit/chain.hpp — the raster unit as the chain of its stage steps, with a tap at every
// stage boundary (docs/architecture.md: the stage table; docs/pipeline.md: the stages).
//
//   InputTriangle → convert → ExactTriangle → clip → ClippedTriangle (0..n) → recip →
//   RecipTriangle → viewport → SetupTriangle → setup → TriangleEquations → traverse → Span (n)
//   → interp → PlaneSample (n) → depth → PlaneSample (0..1) → divide → Fragment → FragmentSink
//
// Taps. A chain is a template over a Taps type with two member templates
//     template <class S> void in(const typename S::In&);    before stage S steps on a record
//     template <class S> void out(const typename S::Out&);  for every record S emits
// called depth-first in stream order: every out<S> follows the in<S> of the record it came
// from, before the next in<S>, so a tap can pair outputs with inputs (the vector dump of
// model/vectors/scene_dump.hpp does). NoTaps has empty inline members: the compiler removes
// them and the chain is the fused streaming loop (measured in docs/pipeline.md, stage 10).
// The records are valid only during the call.
//
// Geometry (stages 1–4) runs one input primitive to completion before setup sees any of its
// triangles. A clipped piece that fails in stage 3 (reciprocal error) or stage 4 (a code out of
// range) is dropped alone, as a streaming clipper and the RTL (rtl/fxr_raster_unit.sv) do: the
// primitive's other pieces go on; it is RejectedRange only when every piece was dropped
// (docs/pipeline.md, "Statistics: primitives, pieces, setup triangles").
#pragma once

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "model/config/config.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/fused_triangle.hpp"
#include "model/stages/input.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/interp_span.hpp"
#include "model/stages/recip_stage.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/stages/viewport.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/geometry.hpp"
#include "model/unit/io.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/unit/vertex_cache.hpp"

namespace fxr {

// No observer: every tap compiles to nothing.
struct NoTaps {
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out&) {}
};

// The clipper's counters of one input primitive, for triangles (RasterStats' prims_trivial_accept,
// prims_clipped, clip_vertices_created) and segments (LineStats' trivial_accept, clipped,
// clip_vertices_created) alike: what follows an outcome differs between the two paths.
inline void count_clip(const ClipOutcome o, const int vertices_created, uint64_t& trivial_accept, uint64_t& clipped,
                       uint64_t& clip_vertices_created) {
  switch (o) {
    case ClipOutcome::Accepted: ++trivial_accept; break;
    case ClipOutcome::Clipped:
    case ClipOutcome::ClippedAway:
    case ClipOutcome::RejectedOverflow:
      ++clipped;
      clip_vertices_created += (uint64_t)vertices_created;
      break;
    case ClipOutcome::CulledOutside:
    case ClipOutcome::RejectedViewport: break;
  }
}

// Stages 9–10 of one plane sample, for triangles and segments alike (the line path's
// LineDepthStage / LineDivideStage are DepthStage / DivideStage under the names of its taps): the
// depth test, then with a sink the divider and the sink; the sample counts once in
// stats.fragments_depth_pass or _fail.
template <class Depth, class Divide, class Taps>
inline void depth_divide(const PlaneSample& ps, Depth& depth, Divide& divide, FragmentSink* sink, RasterStats& stats,
                         Taps& taps) {
  taps.template in<Depth>(ps);
  const bool pass = depth.step(ps, [&](const PlaneSample& p) {
    taps.template out<Depth>(p);
    if (!sink) return;
    taps.template in<Divide>(p);
    divide.step(p, [&](const Fragment& fr) {
      taps.template out<Divide>(fr);
      sink->emit(fr);
    });
  });
  if (pass) ++stats.fragments_depth_pass;
  else ++stats.fragments_depth_fail;
}

// Stages 1–4: one input primitive to 0..n snapped triangles.
template <class Taps = NoTaps>
class GeometryChain {
 public:
  GeometryChain(const Config& cfg, const DrawState& st, Taps& taps)
      : taps_(taps), convert_(cfg, st), clip_(cfg, st), recip_(cfg, st), viewport_(cfg, st), cache_(cfg, st) {}

  // Contract: as fxr::geometry() (model/unit/geometry.hpp): appends the snapped triangles of
  // `in` to `out`, updates the geometry counters of `s`.
  GeomOutcome run(const InputTriangle& in, std::vector<SetupTriangle>& out, RasterStats& s) {
    if constexpr (std::is_same<Taps, NoTaps>::value) {
      // Three cached accepted vertices: the trivial accept's one triangle, as the stages below
      // would emit it (model/unit/vertex_cache.hpp; docs/speed.md "Shortcuts").
      if (const SetupTriangle* t = cached(in.tri, in.prim, s)) {
        out.push_back(*t);
        return GeomOutcome::Emitted;
      }
    }
    return run_stages(in, out, s);
  }

  // Contract: run() through the stages themselves, without the vertex cache (after cached()
  // returned nullptr for the same primitive).
  GeomOutcome run_stages(const InputTriangle& in, std::vector<SetupTriangle>& out, RasterStats& s) {
    taps_.template in<ConvertStage>(in);
    const ExactTriangle* ex = nullptr;
    switch (convert_.step(in, [&](const ExactTriangle& e) {
      taps_.template out<ConvertStage>(e);
      ex = &e;
    })) {
      case ConvertOutcome::Emitted:
        if (convert_.varyings_replaced()) ++s.prims_varying_nonfinite;
        break;
      case ConvertOutcome::RejectedNaN: return GeomOutcome::RejectedNaN;
      case ConvertOutcome::RejectedInf: return GeomOutcome::RejectedInf;
      case ConvertOutcome::RejectedRange: return GeomOutcome::RejectedRange;
    }
    taps_.template in<ClipStage>(*ex);
    uint64_t pieces = 0;
    rejected_ = 0;
    const ClipReport r = clip_.step(*ex, [&](const ClippedTriangle& c) {
      taps_.template out<ClipStage>(c);
      ++pieces;
      taps_.template in<RecipStage>(c);
      const RecipOutcome ro = recip_.step(c, [&](const RecipTriangle& rt) {
        taps_.template out<RecipStage>(rt);
        taps_.template in<ViewportStage>(rt);
        const ViewportOutcome vo = viewport_.step(rt, [&](const SetupTriangle& t) {
          taps_.template out<ViewportStage>(t);
          out.push_back(t);
        });
        if (vo != ViewportOutcome::Emitted) ++rejected_;  // this piece only
      });
      if (ro != RecipOutcome::Emitted) ++rejected_;  // this piece only
    });
    s.tris.geom_rejected_range += rejected_;
    count_clip(r.outcome, r.vertices_created, s.prims_trivial_accept, s.prims_clipped, s.clip_vertices_created);
    switch (r.outcome) {
      case ClipOutcome::CulledOutside:
      case ClipOutcome::ClippedAway: return GeomOutcome::CulledOutside;
      case ClipOutcome::RejectedViewport:
      case ClipOutcome::RejectedOverflow: ++s.tris.geom_rejected_range; return GeomOutcome::RejectedRange;
      case ClipOutcome::Clipped: s.clip_triangles_out += pieces; break;
      case ClipOutcome::Accepted: break;
    }
    if (pieces > 0 && rejected_ == pieces) return GeomOutcome::RejectedRange;  // every piece dropped
    return GeomOutcome::Emitted;
  }

  // NoTaps only: the one triangle stages 1–4 emit for primitive `prim` when the vertex cache
  // knows all three vertices as accepted ones (run() would emit the same and count the same:
  // one trivial accept), counted in `s`; nullptr when it does not (then call run()). The
  // triangle is valid until the next call. Saves run()'s copies of the input and the output.
  const SetupTriangle* cached(const ClipTriangle& tri, uint32_t prim, RasterStats& s) {
    static_assert(std::is_same<Taps, NoTaps>::value, "the vertex cache is used without taps only");
    if (!cache_.triangle(tri, prim, cached_)) return nullptr;
    rejected_ = 0;
    ++s.prims_trivial_accept;
    return &cached_;
  }

  // A hint (VertexCache::prefetch): primitive `tri` comes soon; no effect on any output. The
  // slots it locates are kept for cached() on the same object (`tri` must stay in place).
  void prefetch(const ClipTriangle& tri) {
    if constexpr (std::is_same<Taps, NoTaps>::value) cache_.prefetch(tri);
  }

  // Pieces of the last run()'s primitive dropped in stage 3 or 4 (its other pieces were emitted).
  uint64_t pieces_rejected() const { return rejected_; }
  // The vertex cache (used without taps only): vertices found / computed.
  const VertexCache& vertex_cache() const { return cache_; }
  VertexCache& vertex_cache() { return cache_; }  // (to share a table: model/unit/threads.cpp)

 private:
  Taps& taps_;
  uint64_t rejected_ = 0;
  ConvertStage convert_;
  ClipStage clip_;
  RecipStage recip_;
  ViewportStage viewport_;
  VertexCache cache_;
  SetupTriangle cached_;
};

// Stages 5–10: one snapped triangle to fragments, against the depth buffer of a frame.
template <class Taps = NoTaps>
class FragmentChain {
 public:
  // `f` must be prepared (frame_begin) before: the chain tests against f.depth. sink nullptr:
  // fragments are counted and depth-tested but not divided nor emitted (no varyings computed).
  FragmentChain(const Config& cfg, const DrawState& st, FrameOutput& f, FragmentSink* sink, Taps& taps)
      : FragmentChain(cfg, st, f.stats, f.depth.data(), f.width, sink, taps) {}
  // The same on a depth buffer of `width` columns (from the viewport origin) and fragment
  // counters `stats` (the threaded unit, model/unit/threads.hpp: one chain per thread).
  FragmentChain(const Config& cfg, const DrawState& st, RasterStats& stats, uint32_t* depth, int width,
                FragmentSink* sink, Taps& taps)
      : taps_(taps),
        stats_(stats),
        sink_(sink),
        setup_(cfg, st, sink != nullptr),
        traverse_(cfg, st),
        interp_(cfg, st, sink != nullptr),
        depth_(cfg, st, DepthBufferView{depth, width, st.viewport_x, st.viewport_y}),
        divide_(cfg, st, sink != nullptr),
        count_only_(sink == nullptr && !st.depth_test && std::is_same<Taps, NoTaps>::value),
        fused_(cfg, st, DepthBufferView{depth, width, st.viewport_x, st.viewport_y}, sink != nullptr),
        use_fused_(std::is_same<Taps, NoTaps>::value && FusedSpan::applies(cfg)),
        tri_(cfg, st, DepthBufferView{depth, width, st.viewport_x, st.viewport_y}),
        use_tri_(use_fused_ && fused_.num_varyings() == 0) {
    if (sink) sink->draw_state(st);
  }

  // false: every triangle takes the span path (the tests run both and compare).
  void set_triangle_kernel(bool on) { use_tri_ = on && use_fused_ && fused_.num_varyings() == 0; }
  const FusedTriangle::Counts& triangle_counts() const { return tri_.counts(); }

  // Contract: as fxr::raster_triangle_to() (model/unit/backend.hpp).
  SetupOutcome run(const SetupTriangle& tri) {
    if (use_tri_) tri_.prefetch(tri);  // a hint: the depth rows the kernel reads after setup
    taps_.template in<SetupStage>(tri);
    return setup_.step(tri, [&](const TriangleEquations& eq) {
      taps_.template out<SetupStage>(eq);
      taps_.template in<TraverseStage>(eq);
      if (use_tri_ && FusedTriangle::narrow(eq.edges) && triangle(eq, eq.edges.y0, eq.edges.y1)) return;
      if (use_fused_) fused_.begin(eq);  // eq is setup's record, rewritten per triangle
      traverse_.step(eq, [&](const Span& sp) { span(eq, sp); });
    });
  }

  // Contract: stages 6–10 of a set-up triangle restricted to rows y0 … y1: exactly the spans of
  // those rows that run() would traverse (traversal starts a row with a direct evaluation, so
  // the rows do not depend on where it starts), through the same stages.
  void rows(const TriangleEquations& eq, int y0, int y1) {
    if (use_tri_ && FusedTriangle::narrow(eq.edges) && triangle(eq, y0, y1)) return;
    TriSetup t = eq.edges;
    t.y0 = std::max(t.y0, y0);
    t.y1 = std::min(t.y1, y1);
    Span sp;
    sp.prim = eq.prim;
    if (use_fused_) fused_.begin(eq);
    traverse(t, [&](int j, int xb, int xe) {
      sp.y = j, sp.x0 = xb, sp.x1 = xe;
      span(eq, sp);
    });
  }

 private:
  // Stages 6–10 of a narrow triangle without varyings, rows y0 … y1, in one kernel
  // (model/stages/fused_triangle.hpp): no Span, no call per span. Its records go to the sink as
  // span() sends a span's: into the sink's store (room for the whole rectangle reserved once),
  // else to emit_span, one call per row with passing pixels (FragmentSink's contract: one row
  // per call). A sink lending memory (span_space) keeps the span path: its room is counted in
  // fragments (model/unit/threads.cpp WindowSink). false: nothing done (the depth bound failed,
  // or a lending sink), the caller takes the span path.
  bool triangle(const TriangleEquations& eq, int y0, int y1) {
    FusedTriangle::Result res;
    if (!sink_) {
      if (!tri_.run(eq, y0, y1, nullptr, res, [](const uint8_t*, size_t) {})) return false;
    } else if (FragmentStore* store = sink_->record_store(); store && store->num_varyings() == 0) {
      if (!tri_.run(eq, y0, y1, store->append_space(FusedTriangle::room(eq.edges, y0, y1)), res,
                    [](const uint8_t*, size_t) {}))
        return false;
      store->append_commit((size_t)res.passed);
    } else if (sink_->offers_span_space()) {
      return false;
    } else {
      const size_t need = FusedTriangle::room(eq.edges, y0, y1) * fragment_record_bytes(0);
      if (records_.size() < need) records_.resize(need);
      FragmentSink* const sink = sink_;
      if (!tri_.run(eq, y0, y1, records_.data(), res, [sink](const uint8_t* first, size_t n) {
            if (n) sink->emit_span(FragmentRecords{first, n, 0});
          }))
        return false;
    }
    stats_.fragments_generated += res.generated;
    stats_.fragments_depth_pass += res.passed;
    stats_.fragments_depth_fail += res.generated - res.passed;
    return true;
  }

  // Stages 7–10 on one span of `eq` (from run() or rows(), which began eq).
  void span(const TriangleEquations& eq, const Span& sp) {
    taps_.template out<TraverseStage>(sp);
    stats_.fragments_generated += (uint64_t)(sp.x1 - sp.x0 + 1);
    if (count_only_) {  // nothing reads a depth code: every pixel passes (docs/speed.md "Shortcuts")
      stats_.fragments_depth_pass += (uint64_t)(sp.x1 - sp.x0 + 1);
      return;
    }
    // No tap: stages 7–9 in one loop (model/stages/interp_span.hpp); run() and rows() called
    // fused_.begin(eq) for this triangle.
    if (use_fused_ && fused_.fits_of_begun()) {
      const uint64_t n = (uint64_t)(sp.x1 - sp.x0 + 1);
      const int nv = fused_.num_varyings();
      uint64_t pass;
      // The span's passing fragments as records: none without a sink; into the sink's store
      // (non-virtual, FragmentSink::record_store) or memory it lends (span_space); else to the
      // sink in one call.
      FragmentStore* store = sink_ ? sink_->record_store() : nullptr;
      uint8_t* lent = nullptr;
      if (!sink_) {
        pass = fused_.run_begun(eq, sp, nullptr);
      } else if (store && store->num_varyings() == nv) {
        pass = fused_.run_begun(eq, sp, store->append_space((size_t)n));
        store->append_commit((size_t)pass);
      } else if (sink_->offers_span_space() && (lent = sink_->span_space((size_t)n, nv)) != nullptr) {
        pass = fused_.run_begun(eq, sp, lent);
        sink_->span_done((size_t)pass);
      } else {
        const size_t need = (size_t)n * fragment_record_bytes(nv);
        if (records_.size() < need) records_.resize(need);
        pass = fused_.run_begun(eq, sp, records_.data());
        if (pass) sink_->emit_span(FragmentRecords{records_.data(), (size_t)pass, nv});
      }
      stats_.fragments_depth_pass += pass;
      stats_.fragments_depth_fail += n - pass;
      return;
    }
    taps_.template in<InterpStage>(sp);
    interp_.step(eq, sp, [&](const PlaneSample& ps) {
      taps_.template out<InterpStage>(ps);
      depth_divide(ps, depth_, divide_, sink_, stats_, taps_);
    });
  }

  Taps& taps_;
  RasterStats& stats_;
  FragmentSink* sink_;
  SetupStage setup_;
  TraverseStage traverse_;
  InterpStage interp_;
  DepthStage depth_;
  DivideStage divide_;
  // No sink, the depth test off and no tap: stages 7–8 are skipped, the pixels only counted
  // (Shortcut.CountOnlyChainWithTheDepthTestOffEqualsTheFullPath, tests/model/shortcut_test.cpp).
  bool count_only_;
  FusedSpan fused_;
  bool use_fused_;  // NoTaps and FusedSpan::applies: span() takes the fused stages 7–9
  FusedTriangle tri_;
  bool use_tri_;  // use_fused_ and no varyings: narrow triangles take FusedTriangle (triangle())
  std::vector<uint8_t> records_;  // the fused span's records, handed to sink_->emit_span
};

// The primitive accounting of run_raster_unit. count_geometry: a primitive that left the
// geometry stages with `g` counts as culled / rejected unless it emitted triangles (true).
inline bool count_geometry(RasterStats& s, GeomOutcome g) {
  switch (g) {
    case GeomOutcome::CulledOutside: ++s.prims_culled_outside; return false;
    case GeomOutcome::RejectedNaN: ++s.prims_rejected_nan; return false;
    case GeomOutcome::RejectedInf: ++s.prims_rejected_inf; return false;
    case GeomOutcome::RejectedRange: ++s.prims_rejected_range; return false;
    case GeomOutcome::Emitted: break;
  }
  return true;
}
// Then its setup triangles' outcomes decide (range also set when a piece was dropped in stage 3
// or 4): drawn if any was rasterised, else by the first reason in the order range > backface >
// no samples > zero area (all pieces of one primitive share its facing). add() also counts
// the setup triangle in s.tris.
struct PrimDisposition {
  bool drawn = false, range = false, back = false, nosamp = false;
  void add(RasterStats& s, SetupOutcome o) {
    ++s.tris.in;
    switch (o) {
      case SetupOutcome::Ok: drawn = true; ++s.tris.drawn; break;
      case SetupOutcome::RejectedRange: range = true; ++s.tris.range; break;
      case SetupOutcome::CulledBackface: back = true; ++s.tris.backface; break;
      case SetupOutcome::CulledNoSamples: nosamp = true; ++s.tris.no_samples; break;
      case SetupOutcome::CulledZeroArea: ++s.tris.zero_area; break;
    }
  }
  void count(RasterStats& s, bool no_pieces) const {
    if (drawn) ++s.prims_drawn;
    else if (range) ++s.prims_rejected_range;
    else if (back) ++s.prims_culled_backface;
    else if (nosamp) ++s.prims_culled_no_samples;
    else if (no_pieces) ++s.prims_culled_outside;  // geometry emitted nothing
    else ++s.prims_culled_zero_area;
  }
};

// How many primitives ahead UnitChain::draw_all prefetches the input triangle itself (its key
// words are hashed kVertexCachePrefetchAhead primitives ahead: 27 % of the draw loop's samples
// were on that load after the vertex table moved to huge pages; 16 ahead, ≈ one 4 KB page of
// triangles: bunny stream v0 / v2 +8 / +4 %, docs/speed.md "Session 11: per triangle"), and
// the line it steps by. A hint: no effect on any output.
inline constexpr size_t kInputPrefetchAhead = 16;
inline constexpr size_t kInputPrefetchLine = 64;

// Stages 1–10 with the primitive accounting of run_raster_unit.
template <class Taps = NoTaps>
class UnitChain {
 public:
  UnitChain(const Config& cfg, const DrawState& st, FrameOutput& f, FragmentSink* sink, Taps& taps)
      : stats_(f.stats), geometry_(cfg, st, taps), fragments_(cfg, st, f, sink, taps) {
    // Setup reads a vertex's rw for the 1/w plane only, built with a sink and varyings
    // (SetupStage's with_varyings): otherwise the vertex cache need not compute it.
    geometry_.vertex_cache().set_rw_unread(sink == nullptr || st.num_varyings <= 0);
  }

  // Contract: draw() of tris[0 … n) in order, primitive numbers first + p. The vertex cache's
  // slots of primitive p + kVertexCachePrefetchAhead are prefetched before primitive p is drawn
  // (a hint: the output is draw()'s).
  void draw_all(const ClipTriangle* tris, size_t n, uint32_t first = 0) {
    for (size_t p = 0; p < n; ++p) {
      if (p + kInputPrefetchAhead < n) {
        const char* t = reinterpret_cast<const char*>(&tris[p + kInputPrefetchAhead]);
        for (size_t o = 0; o < sizeof(ClipTriangle); o += kInputPrefetchLine) __builtin_prefetch(t + o);
      }
      if (p + kVertexCachePrefetchAhead < n) geometry_.prefetch(tris[p + kVertexCachePrefetchAhead]);
      draw(tris[p], first + (uint32_t)p);
    }
  }

  // Contract: one input primitive through every stage. It counts once in the dispositions: as
  // drawn if any of its triangles was rasterised, else by the first reason in the order
  // range > backface > no samples > zero area over its pieces (range: a piece dropped in stage 3
  // or 4, or rejected by setup; all pieces of one primitive share its facing). Its setup
  // triangles count once each by their setup outcome (s.tris, the unit's tri_* counters).
  void draw(const ClipTriangle& tri, uint32_t prim) {
    ++stats_.prims_in;
    if constexpr (std::is_same<Taps, NoTaps>::value) {
      // The vertex cache's triangle (GeometryChain::cached): Emitted, no piece dropped, one setup
      // triangle — as below, without copying the input or the triangle.
      if (const SetupTriangle* t = geometry_.cached(tri, prim, stats_)) {
        PrimDisposition d;
        d.add(stats_, fragments_.run(*t));
        d.count(stats_, false);
        return;
      }
    }
    in_.prim = prim;
    in_.tri = tri;
    pieces_.clear();
    if (!count_geometry(stats_, geometry_.run_stages(in_, pieces_, stats_))) return;
    PrimDisposition d;
    d.range = geometry_.pieces_rejected() > 0;
    for (const SetupTriangle& t : pieces_) d.add(stats_, fragments_.run(t));
    d.count(stats_, pieces_.empty());
  }

 private:
  RasterStats& stats_;
  GeometryChain<Taps> geometry_;
  FragmentChain<Taps> fragments_;
  InputTriangle in_;
  std::vector<SetupTriangle> pieces_;
};

// Contract: run_raster_unit with fragments streamed to `sink` (nullptr: none kept, no
// varyings) and `taps` observing every stage boundary. Prepares `f` (frame_begin).
template <class Taps = NoTaps>
void run_raster_unit_to(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                        FrameOutput& f, FragmentSink* sink, Taps& taps) {
  frame_begin(cfg, st, f);
  UnitChain<Taps> chain(cfg, st, f, sink, taps);
  chain.draw_all(tris.data(), tris.size());
}

}  // namespace fxr

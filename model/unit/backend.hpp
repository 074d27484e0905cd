// model/unit/backend.hpp — stages 5–10 on snapped triangles: setup, traversal, interpolators, depth,
// divider, output (the FragmentChain of model/unit/chain.hpp). run_raster_unit (raster_unit.hpp)
// is geometry() followed by these.
#pragma once

#include "model/config/config.hpp"
#include "model/unit/fragment_store.hpp"
#include "model/unit/io.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/stages/setup.hpp"

namespace fxr {

// Contract: prepares `f` for a frame: size = viewport, depth buffer (w × h, row 0 at the
// bottom, indexed from the viewport origin) cleared to the maximum code, no fragments, zero
// statistics. Checks the configuration widths and the draw state (num_varyings within
// 0 … kMaxVaryings, viewport ≥ 1×1): ConfigError otherwise.
void frame_begin(const Config& cfg, const DrawState& st, FrameOutput& f);
// Contract: the checks of frame_begin alone (ConfigError as there); frame_begin calls it.
void frame_check(const Config& cfg, const DrawState& st);

// Contract: stages 5–10 on one snapped triangle into frame `f` (after frame_begin):
//   setup (SetupOutcome other than Ok: nothing drawn, returned for the caller to count);
//   for each covered pixel: fragments_generated++, depth code, depth test (st.depth_test
//   false: always passes and never writes, as in GL), depth write if st.depth_write; passing
//   fragments get their varyings (stage 9) and are appended to f.fragments when keep_fragments.
//   Updates f.stats' fragment counters only (primitive counters are the caller's).
SetupOutcome raster_triangle(const Config& cfg, const DrawState& st, const SetupTriangle& tri, FrameOutput& f,
                             bool keep_fragments = true);

// Receives the fragments that pass the depth test in the unit's order (rows bottom to top, left
// to right within a row): one at a time (emit), or a span's passing fragments at once
// (emit_span: the fused span path of FragmentChain, model/stages/interp_span.hpp). The Fragment
// and the records are only valid during the call; var[k] is set for k < num_varyings only.
class FragmentSink {
 public:
  virtual ~FragmentSink() = default;
  virtual void emit(const Fragment& f) = 0;
  // A block of passing fragments, consecutive in the unit's order, as compact records
  // (model/unit/fragment_store.hpp) of the chain's num_varyings: the same fragments, in the same
  // order, as that many emit calls — which is what the default does. A sink that can take them
  // in bulk overrides it (docs/speed.md "Session 8: the span path"). The sequential chain hands
  // one row of one triangle per call (x increasing, not necessarily adjacent); the threaded
  // unit's output merge hands longer blocks that may cover several rows and triangles
  // (model/unit/threads.cpp): an override reads each record's own y.
  virtual void emit_span(const FragmentRecords& b) {
    Fragment f;
    for (size_t i = 0; i < b.count; ++i) {
      get_fragment(b.record(i), b.num_varyings, f);
      emit(f);
    }
  }
  // Optional, for a sink keeping records as they are in memory of its own: room for
  // `max_records` records of `num_varyings` varyings (nullptr: not offered). The fused chain then
  // writes a span's passing fragments there and calls span_done(count) — the same fragments as
  // emit_span, without the copy. Asked only of a sink that called offer_span_space() (no
  // virtual call per span for the others).
  virtual uint8_t* span_space(size_t /*max_records*/, int /*num_varyings*/) { return nullptr; }
  virtual void span_done(size_t /*count*/) {}
  // Called once by each chain that will emit into the sink (triangles, then line segments, whose
  // draw state may have more varyings), before its first emit.
  virtual void draw_state(const DrawState&) {}

  // A sink keeping the records in a FragmentStore (KeepFragments) names it: where its
  // num_varyings is the chain's, the fused chain appends each span's passing fragments to it
  // directly (FragmentStore::append_space / append_commit) — the same fragments as emit_span,
  // without the copy and without a virtual call per span (docs/speed.md "Session 10: the span
  // and the sink"). nullptr (the default): span_space if offered, else emit_span.
  FragmentStore* record_store() const { return store_; }
  bool offers_span_space() const { return lends_; }

 protected:
  void set_record_store(FragmentStore* s) { store_ = s; }
  void offer_span_space() { lends_ = true; }

 private:
  FragmentStore* store_ = nullptr;
  bool lends_ = false;
};

// Holds every fragment: appends them to a compact store (FrameOutput::fragments in
// run_raster_unit), widened to the varyings of every draw it receives.
class KeepFragments final : public FragmentSink {
 public:
  explicit KeepFragments(FragmentStore& out) : out_(&out) { set_record_store(out_); }
  // Appends to `out` from now on (the threaded driver's per-step stores, model/unit/threads.cpp).
  void retarget(FragmentStore& out) {
    out_ = &out;
    set_record_store(out_);
  }
  void emit(const Fragment& f) override { out_->push_back(f); }
  // A wider store (a later draw with more varyings): emit_span widens each record, one copy.
  void emit_span(const FragmentRecords& b) override { out_->append(b); }
  void draw_state(const DrawState& st) override { out_->widen(st.num_varyings); }

 private:
  FragmentStore* out_;
};

// Contract: as raster_triangle, but passing fragments go to `sink` (nullptr: none, and the
// varyings are not computed) instead of f.fragments. A streaming consumer (images, vectors)
// avoids holding a frame's fragments (sizeof(Fragment) bytes each) in memory. (Convenience entry
// point: it sets the stages up per call; FragmentChain in model/unit/chain.hpp sets them up once
// per frame.)
SetupOutcome raster_triangle_to(const Config& cfg, const DrawState& st, const SetupTriangle& tri, FrameOutput& f,
                                FragmentSink* sink);

}  // namespace fxr

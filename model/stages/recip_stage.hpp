// model/stages/recip_stage.hpp — stage 3 as a stage of the unit: the reciprocal unit
// (model/stages/recip.hpp, docs/arith.md) applied to the w of every vertex of a clipped
// triangle. The products x_c·(1/w), v·(1/w) are formed exactly in stage 4 (viewport.hpp):
// nothing is rounded between the reciprocal and the snap. docs/pipeline.md, stage 3.
#pragma once

#include <cstdint>
#include <type_traits>

#include "model/stages/clip.hpp"
#include "model/stages/recip.hpp"
#include "model/unit/record.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// Stage 3 output: the clipped triangle and 1/w_c of each vertex (recip.out_sig_bits significand,
// normalised).
struct RecipTriangle {
  uint32_t prim = 0;
  ClipVtx v[3];
  FxFloat r[3];

  template <class V>
  void visit(V& v_, const RecordShape& s) {
    v_("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 3; ++i) visit_clip_vertex(v_, field_prefix("v", i), v[i], s, true);
    for (int i = 0; i < 3; ++i) visit_fx(v_, "r" + std::to_string(i), r[i], s.cfg.recip.out_sig_bits, s);
  }
};

enum class RecipOutcome : uint8_t {
  Emitted,
  RecipError,  // the unit flagged a zero divisor or an exponent overflow (not reachable for
               // vertices inside the clip volume: w ≥ 2^kWMinExp)
};

// The StageCost of a cost record of another shape (recip_cost's, div_cost's): the common fields.
template <class C>
StageCost as_stage_cost(const C& c) {
  if constexpr (std::is_same_v<C, StageCost>) {
    return c;
  } else {
    StageCost s;
    s.latency = c.latency;
    s.ii = c.ii;
    s.table_bits = c.table_bits;
    for (const auto& m : c.multipliers) s.add_mult(m.first, m.second);
    return s;
  }
}

// Stage 3 on one vertex: r = recip(w_c normalised to recip.in_sig_bits); false when the unit
// flags a zero divisor or an exponent overflow. `unit(w)` is the reciprocal unit of c.
template <class Unit>
inline bool recip_vertex_with(const RecipConfig& c, const ClipVtx& v, FxFloat& r, Unit&& unit) {
  const FxFloat w = normalize_fx(v.p[3], c.in_sig_bits, Round::HalfEven);
  const RecipResult rr = unit(w);
  if (rr.div_by_zero || rr.exp_overflow) return false;
  r = rr.value;
  return true;
}
inline bool recip_vertex(const RecipConfig& c, const ClipVtx& v, FxFloat& r) {
  return recip_vertex_with(c, v, r, [&c](const FxFloat& w) { return recip(c, w); });
}
// The same on the caller's unit (the vertex cache keeps one per draw: recip()'s lookup of its
// thread's unit compared the whole configuration per vertex, docs/speed.md "Session 12: per
// triangle").
inline bool recip_vertex(const RecipUnit& u, const ClipVtx& v, FxFloat& r) {
  return recip_vertex_with(u.config(), v, r, u);
}

class RecipStage {
 public:
  static constexpr const char* kName = "recip";
  using In = ClippedTriangle;
  using Out = RecipTriangle;

  RecipStage(const Config& cfg, const DrawState& st) : cfg_(cfg.recip), nv_(st.num_varyings) {}

  // 1 → 0..1. w is exact at recip.in_sig_bits (float32: 24 bits; the clipper rounds its w to
  // exactly this width), so the normalisation before the unit never rounds.
  template <class Emit>
  RecipOutcome step(const In& in, Emit&& emit) {
    for (int i = 0; i < 3; ++i)
      if (!recip_vertex(cfg_, in.v[i], out_.r[i])) return RecipOutcome::RecipError;
    out_.prim = in.prim;
    for (int i = 0; i < 3; ++i) copy_clip_vertex(in.v[i], out_.v[i], nv_);
    emit(static_cast<const Out&>(out_));
    return RecipOutcome::Emitted;
  }

  // The reciprocal unit's own cost (recip_cost, rtl/fxr_recip.sv), one unit per vertex lane.
  static StageCost cost(const Config& cfg) { return as_stage_cost(recip_cost(cfg.recip)); }

 private:
  RecipConfig cfg_;
  int nv_;
  RecipTriangle out_;
};

}  // namespace fxr

// model/stages/input.hpp — stage 1: input conversion. float32 bit patterns → exact FxFloats;
// NaN / Inf in a position flagged (the primitive is rejected), NaN / ±Inf in an active varying
// replaced by a finite value (0 / ±FLT_MAX) and counted. docs/pipeline.md, stage 1.
//
// Nothing is rounded: every finite float32 is exactly an FxFloat with a significand below 2^24
// (model/arith/fxfloat.hpp), denormals included. The stage reads no configuration field; only
// the active varyings (DrawState::num_varyings) are converted and inspected.
#pragma once

#include <cstdint>

#include "model/config/config.hpp"
#include "model/unit/io.hpp"
#include "model/unit/record.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// A vertex inside the geometry stages: exact dyadic values (FxFloat), position then varyings.
struct ClipVtx {
  FxFloat p[4];               // x_c, y_c, z_c, w_c
  FxFloat v[kMaxVaryings];    // v_0 … v_{N−1}
  // w_c for the attribute positions (docs/pipeline.md, stage 2 "New vertices"): an input
  // vertex's w_c itself; a new vertex's w_c rounded once to raster.clip_sig_bits like x, y, z,
  // where p[3] is rounded to recip.in_sig_bits for the reciprocal unit. 0 = not set (then
  // p[3] serves).
  FxFloat wa;
  const FxFloat& attr_w() const { return wa.sig ? wa : p[3]; }
};

// Copies the active part of a vertex (position, attribute w, the first nv varyings); an unset
// attribute w (an input vertex) becomes the vertex's w_c.
inline void copy_clip_vertex(const ClipVtx& a, ClipVtx& b, int nv) {
  for (int c = 0; c < 4; ++c) b.p[c] = a.p[c];
  b.wa = a.attr_w();
  for (int k = 0; k < nv; ++k) b.v[k] = a.v[k];
}

// Records carry `wa` only where the attribute positions exist (raster.attr_subpixel_bits >
// subpixel_bits) and only after the clipper: before it, wa is w_c.
inline bool clip_vertex_has_wa(const Config& c) { return c.raster.attr_subpixel_bits > c.raster.subpixel_bits; }

// Significand bits of a ClipVtx component in a record: float32 inputs carry kF32SigBits, the
// clipper's new x, y, z and varyings raster.clip_sig_bits and its new w recip.in_sig_bits.
inline int clip_vertex_sig_bits(const Config& c) {
  return std::max({kF32SigBits, c.raster.clip_sig_bits, c.recip.in_sig_bits});
}

// with_wa: the record is after the clipper (ClippedTriangle, RecipTriangle) and lists `wa`
// when the configuration has attribute positions.
template <class V>
void visit_clip_vertex(V& v, const std::string& pre, ClipVtx& x, const RecordShape& s, bool with_wa = false) {
  static const char* const kPos[4] = {"x", "y", "z", "w"};
  const int sb = clip_vertex_sig_bits(s.cfg);
  for (int c = 0; c < 4; ++c) visit_fx(v, pre + kPos[c], x.p[c], sb, s);
  if (with_wa && clip_vertex_has_wa(s.cfg)) visit_fx(v, pre + "wa", x.wa, sb, s);
  for (int k = 0; k < s.num_varyings; ++k) visit_fx(v, pre + "var" + std::to_string(k), x.v[k], sb, s);
}

// Stage 1 input: one primitive as the vertex stage emits it (float32 bit patterns).
struct InputTriangle {
  uint32_t prim = 0;  // index of the primitive in the draw
  ClipTriangle tri;

  template <class V>
  void visit(V& v, const RecordShape& s) {
    v("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 3; ++i) visit_input_vertex(v, field_prefix("v", i), tri.v[i], s);
  }
};

// Three exact clip-space vertices of one primitive (only the active varyings are set): the
// record at the clipper → recip boundary (ClippedTriangle: a triangle inside the clip volume,
// with the attribute w of its vertices).
struct ClipSpaceTriangle {
  uint32_t prim = 0;
  ClipVtx v[3];

  template <class V>
  void visit(V& v_, const RecordShape& s) {
    v_("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 3; ++i) visit_clip_vertex(v_, field_prefix("v", i), v[i], s, true);
  }
};

// Stage 1 output: the primitive as exact FxFloats (wa = w_c: not a wire of its own).
struct ExactTriangle : ClipSpaceTriangle {
  template <class V>
  void visit(V& v_, const RecordShape& s) {
    v_("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 3; ++i) visit_clip_vertex(v_, field_prefix("v", i), v[i], s, false);
  }
  void restore(const RecordShape&) {
    for (auto& x : v) x.wa = x.p[3];
  }
};

enum class ConvertOutcome : uint8_t {
  Emitted,        // (non-finite varyings, if any, replaced: ConvertStage::varyings_replaced())
  RejectedNaN,    // a NaN in a position (takes precedence over Inf)
  RejectedInf,    // an infinity in a position
  RejectedRange,  // the draw state asks for more than kMaxVaryings varyings
};

// Contract: exact decode of one float32; NaN / Inf set the flags (the value is then unusable).
inline FxFloat convert_input(float f, bool& nan, bool& inf) {
  const F32Decoded d = decode_f32(f32_bits(f));
  nan |= d.cls == F32Class::NaN;
  inf |= d.cls == F32Class::Inf;
  return d.value;  // Zero / Denormal / Normal: exact (denormals are not flushed)
}

// Contract (the varying rule, docs/pipeline.md stage 1): the float32 bits a varying is converted
// from. NaN (any sign, any payload) → +0 (all bits zero); ±Inf → ±FLT_MAX (sign kept, exponent
// kF32ExpMax − 1, fraction all ones); every finite value unchanged. *replaced is set when a
// value was replaced. In hardware: the exponent all-ones detect of the component selects a
// constant (one 32-bit 2:1 multiplexer per varying lane), nothing else.
inline uint32_t varying_input_bits(uint32_t bits, bool* replaced) {
  constexpr uint32_t kSign = 1u << (kF32FracBits + kF32ExpBits);
  constexpr uint32_t kFracMask = (1u << kF32FracBits) - 1;
  constexpr uint32_t kMaxFinite = ((uint32_t)(kF32ExpMax - 1) << kF32FracBits) | kFracMask;  // FLT_MAX
  if (((bits >> kF32FracBits) & kF32ExpMax) != (uint32_t)kF32ExpMax) return bits;
  *replaced = true;
  if (bits & kFracMask) return 0;       // NaN → +0
  return (bits & kSign) | kMaxFinite;   // ±Inf → ±FLT_MAX
}

// Stage 1 on one vertex: positions decoded exactly (nan / inf set by a NaN / Inf position),
// the first nv varyings after varying_input_bits (replaced set when one was replaced).
inline void convert_vertex(const ClipVertex& in, int nv, ClipVtx& out, bool& nan, bool& inf, bool& replaced) {
  // Decoded in place (decode_f32_to: convert_input's returned copy stalled, docs/speed.md
  // "Session 10: per triangle"); the same values.
  for (int c = 0; c < 4; ++c) {
    const F32Class k = decode_f32_to(f32_bits(in.pos[c]), out.p[c]);
    nan |= k == F32Class::NaN;
    inf |= k == F32Class::Inf;
  }
  out.wa = out.p[3];
  for (int k = 0; k < nv; ++k)  // finite after the replacement: decoded exactly
    decode_f32_to(varying_input_bits(f32_bits(in.var[k]), &replaced), out.v[k]);
}

class ConvertStage {
 public:
  static constexpr const char* kName = "convert";
  using In = InputTriangle;
  using Out = ExactTriangle;

  ConvertStage(const Config&, const DrawState& st) : nv_(st.num_varyings) {}

  // 1 → 0..1: the exact triangle, or the reason it was rejected. A NaN / Inf in a position
  // rejects the primitive; in an active varying it is replaced (varying_input_bits) and the
  // triangle goes on exactly as if that finite value had been given.
  template <class Emit>
  ConvertOutcome step(const In& in, Emit&& emit) {
    replaced_ = false;
    if (nv_ < 0 || nv_ > kMaxVaryings) return ConvertOutcome::RejectedRange;  // bad draw state
    bool nan = false, inf = false, replaced = false;
    out_.prim = in.prim;
    for (int i = 0; i < 3; ++i) convert_vertex(in.tri.v[i], nv_, out_.v[i], nan, inf, replaced);
    if (nan) return ConvertOutcome::RejectedNaN;
    if (inf) return ConvertOutcome::RejectedInf;
    replaced_ = replaced;
    emit(static_cast<const Out&>(out_));
    return ConvertOutcome::Emitted;
  }

  // After an Emitted step: whether a NaN / Inf varying of that primitive was replaced (counted
  // as prims_varying_nonfinite).
  bool varyings_replaced() const { return replaced_; }

  // Planned RTL (one register stage): per float32 an all-ones / all-zeros exponent detect and
  // the hidden-bit insert, per varying a 2:1 multiplexer onto a constant; no arithmetic.
  static StageCost cost(const Config& cfg);

 private:
  int nv_;
  bool replaced_ = false;
  ExactTriangle out_;
};

}  // namespace fxr

// model/stages/input.hpp — stage 1: input conversion. float32 bit patterns → exact FxFloats,
// NaN / Inf flagged (never converted). docs/pipeline.md, stage 1.
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
};

// Significand bits of a ClipVtx component in a record: float32 inputs carry kF32SigBits, the
// clipper's new x, y, z and varyings raster.clip_sig_bits and its new w recip.in_sig_bits.
inline int clip_vertex_sig_bits(const Config& c) {
  return std::max({kF32SigBits, c.raster.clip_sig_bits, c.recip.in_sig_bits});
}

template <class V>
void visit_clip_vertex(V& v, const std::string& pre, ClipVtx& x, const RecordShape& s) {
  static const char* const kPos[4] = {"x", "y", "z", "w"};
  const int sb = clip_vertex_sig_bits(s.cfg);
  for (int c = 0; c < 4; ++c) visit_fx(v, pre + kPos[c], x.p[c], sb, s);
  for (int k = 0; k < s.num_varyings; ++k) visit_fx(v, pre + "var" + std::to_string(k), x.v[k], sb, s);
}

// Stage 1 input: one primitive as the vertex stage emits it (float32 bit patterns).
struct InputTriangle {
  uint32_t prim = 0;  // index of the primitive in the draw
  ClipTriangle tri;

  template <class V>
  void visit(V& v, const RecordShape& s) {
    v("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 3; ++i) {
      const std::string p = field_prefix("v", i);
      static const char* const kPos[4] = {"x", "y", "z", "w"};
      for (int c = 0; c < 4; ++c) v(p + kPos[c], tri.v[i].pos[c], kF32Bits, false);
      for (int k = 0; k < s.num_varyings; ++k) v(p + "var" + std::to_string(k), tri.v[i].var[k], kF32Bits, false);
    }
  }
};

// Three exact clip-space vertices of one primitive (only the active varyings are set): the
// record at the input-conversion → clipper boundary (ExactTriangle) and at the clipper → recip
// boundary (ClippedTriangle: a triangle inside the clip volume).
struct ClipSpaceTriangle {
  uint32_t prim = 0;
  ClipVtx v[3];

  template <class V>
  void visit(V& v_, const RecordShape& s) {
    v_("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 3; ++i) visit_clip_vertex(v_, field_prefix("v", i), v[i], s);
  }
};

// Stage 1 output: the primitive as exact FxFloats.
using ExactTriangle = ClipSpaceTriangle;

enum class ConvertOutcome : uint8_t {
  Emitted,
  RejectedNaN,    // a NaN in a position or an active varying (takes precedence over Inf)
  RejectedInf,    // an infinity
  RejectedRange,  // the draw state asks for more than kMaxVaryings varyings
};

// Contract: exact decode of one float32; NaN / Inf set the flags (the value is then unusable).
inline FxFloat convert_input(float f, bool& nan, bool& inf) {
  const F32Decoded d = decode_f32(f32_bits(f));
  nan |= d.cls == F32Class::NaN;
  inf |= d.cls == F32Class::Inf;
  return d.value;  // Zero / Denormal / Normal: exact (denormals are not flushed)
}

class ConvertStage {
 public:
  static constexpr const char* kName = "convert";
  using In = InputTriangle;
  using Out = ExactTriangle;

  ConvertStage(const Config&, const DrawState& st) : nv_(st.num_varyings) {}

  // 1 → 0..1: the exact triangle, or the reason it was rejected.
  template <class Emit>
  ConvertOutcome step(const In& in, Emit&& emit) {
    if (nv_ < 0 || nv_ > kMaxVaryings) return ConvertOutcome::RejectedRange;  // bad draw state
    bool nan = false, inf = false;
    out_.prim = in.prim;
    for (int i = 0; i < 3; ++i) {
      for (int c = 0; c < 4; ++c) out_.v[i].p[c] = convert_input(in.tri.v[i].pos[c], nan, inf);
      for (int k = 0; k < nv_; ++k) out_.v[i].v[k] = convert_input(in.tri.v[i].var[k], nan, inf);
    }
    if (nan) return ConvertOutcome::RejectedNaN;
    if (inf) return ConvertOutcome::RejectedInf;
    emit(static_cast<const Out&>(out_));
    return ConvertOutcome::Emitted;
  }

  // Planned RTL (one register stage): per float32 an all-ones / all-zeros exponent detect and
  // the hidden-bit insert; no arithmetic.
  static StageCost cost(const Config& cfg);

 private:
  int nv_;
  ExactTriangle out_;
};

}  // namespace fxr

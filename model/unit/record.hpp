// model/unit/record.hpp — helpers for the visit() of stage records (the protocol is in
// model/unit/stage.hpp): the record shape and the fields of an FxFloat.
#pragma once

#include <algorithm>
#include <string>

#include "model/arith/fxfloat.hpp"
#include "model/config/config.hpp"

namespace fxr {

// A float32 field: its bit pattern (sign, exponent, fraction).
inline constexpr int kF32Bits = 1 + kF32ExpBits + kF32FracBits;
// Primitive indices are uint32_t (a draw holds fewer than 2^32 primitives).
inline constexpr int kPrimIdBits = 32;

// What a record's visit() needs to know to size its fields.
struct RecordShape {
  const Config& cfg;
  int num_varyings = 0;  // active varyings (DrawState::num_varyings)
};

// Exponent field of an FxFloat in a record (the exponent of its lsb, two's complement).
// Lead exponents in the unit stay within ±2^(E−1), E = max(recip.exp_bits, kF32ExpBits + 1):
// float32 values lead in [−149, 127], clipper outputs are flushed below 2^−192 (9 bits), the
// reciprocal unit's I/O uses recip.exp_bits. A product v·(1/w) adds one bit, the lsb lies at most
// 63 < 2^(E−1) below the lead: one more. The vector writer rejects a value that does not fit.
inline int fx_exp_field_bits(const Config& c) { return std::max(c.recip.exp_bits, kF32ExpBits + 1) + 2; }

// The fields of an FxFloat: <name>_neg (1 bit), <name>_sig (sig_bits, unsigned), <name>_exp.
template <class V>
void visit_fx(V& v, const std::string& name, FxFloat& f, int sig_bits, const RecordShape& s) {
  v(name + "_neg", f.neg, 1, false);
  v(name + "_sig", f.sig, sig_bits, false);
  v(name + "_exp", f.exp, fx_exp_field_bits(s.cfg), true);
}

// "v0_", "v1_", …: prefixes of array elements in field names.
inline std::string field_prefix(const char* base, int k) { return std::string(base) + std::to_string(k) + "_"; }

}  // namespace fxr

namespace fxr {

// Total bits of a record as its visit() lists them (register width of one pipeline stage).
struct RecordBitCounter {
  int64_t bits = 0;
  template <class T>
  void operator()(const std::string&, T&, int width, bool) { bits += width; }
};
template <class R>
int64_t record_bits(const Config& cfg, int num_varyings) {
  R r{};
  RecordBitCounter c;
  r.visit(c, RecordShape{cfg, num_varyings});
  return c.bits;
}

}  // namespace fxr

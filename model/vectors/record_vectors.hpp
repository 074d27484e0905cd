// model/vectors/record_vectors.hpp — a stage record (model/unit/stage.hpp: its visit()) as the
// fields of a vector row: the layout, packing a record into a row and unpacking a row into a
// record. The layouts of the transaction vectors (model/vectors/scene_dump.hpp) come from here,
// never from a hand-written field list (docs/vectors.md, "Transaction vectors").
#pragma once

#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "model/arith/fixed.hpp"
#include "model/config/config.hpp"
#include "model/unit/record.hpp"
#include "model/vectors/vectors.hpp"

namespace fxr {

// Decimal text of a 128-bit integer (error messages).
inline std::string i128_to_string(i128 x) {
  if (x == 0) return "0";
  const bool neg = x < 0;
  u128 m = neg ? (u128)0 - (u128)x : (u128)x;
  std::string s;
  while (m) {
    s.insert(s.begin(), (char)('0' + (int)(m % 10)));
    m /= 10;
  }
  return neg ? "-" + s : s;
}

// Records may hold configuration constants that are not wires (the sample grid's fraction bits,
// the depth clamp, the number of varyings): visit() does not list them, and a record read back
// from vectors gets them from `restore(const RecordShape&)` when the record has one.
template <class R, class = void>
struct HasRestore : std::false_type {};
template <class R>
struct HasRestore<R, std::void_t<decltype(std::declval<R&>().restore(std::declval<const RecordShape&>()))>>
    : std::true_type {};
template <class R>
void restore_record(R& r, const RecordShape& s) {
  if constexpr (HasRestore<R>::value) r.restore(s);
}

// The fields a record's visit() lists, in order, with direction `dir`.
struct RecordFieldCollector {
  VecDir dir;
  std::vector<VecField>* out;
  template <class T>
  void operator()(const std::string& name, T&, int width, bool is_signed) {
    std::string fmt = is_signed ? "signed, two's complement, " : "unsigned, ";
    if constexpr (std::is_same_v<T, float>) fmt = "float32 bit pattern, ";
    if constexpr (std::is_same_v<T, bool>) fmt = "flag, ";
    out->push_back({name, dir, width, is_signed, fmt + std::to_string(width) + " bits (docs/vectors.md)"});
  }
};

template <class R>
void append_record_fields(const RecordShape& s, VecDir dir, std::vector<VecField>& out) {
  R r{};
  RecordFieldCollector c{dir, &out};
  r.visit(c, s);
}

// Packs the fields of a record into row[first …]. A value that does not fit the width visit()
// gives it throws ConfigError naming `where` and the field: the widths are checked on every
// record written (a record's visit() that under-sizes a field cannot produce a vector file).
struct RecordPacker {
  VecRow* row;
  size_t col;
  const std::string* where;
  template <class T>
  void operator()(const std::string& name, T& v, int width, bool is_signed) {
    vec_word bits = 0;
    if constexpr (std::is_same_v<T, float>) {
      uint32_t u = 0;
      std::memcpy(&u, &v, sizeof u);
      bits = u;
    } else {
      const i128 x = (i128)v;
      const bool fits = is_signed ? fits_signed(x, width) : (x >= 0 && ((vec_word)x & ~vec_mask(width)) == 0);
      if (!fits)
        throw ConfigError(*where + ": field '" + name + "': value " + i128_to_string(x) + " does not fit its " +
                          std::to_string(width) + (is_signed ? " signed" : " unsigned") +
                          " bits (the record's visit() width is too small)");
      bits = vec_pack(x, width);
    }
    (*row)[col++] = bits;
  }
  static bool fits_signed(i128 x, int width) {
    if (width >= kVecMaxFieldBits) return true;
    const i128 lim = (i128)1 << (width - 1);
    return x >= -lim && x < lim;
  }
};

template <class R>
void pack_record(const R& r, const RecordShape& s, VecRow& row, size_t first, const std::string& where) {
  RecordPacker p{&row, first, &where};
  const_cast<R&>(r).visit(p, s);  // visit() is non-const (readers assign through it); the packer only reads
}

// Unpacks row[first …] into the fields of a record (signed fields sign-extended).
struct RecordUnpacker {
  const VecRow* row;
  size_t col;
  template <class T>
  void operator()(const std::string&, T& v, int width, bool is_signed) {
    const vec_word bits = (*row)[col++];
    if constexpr (std::is_same_v<T, float>) {
      const uint32_t u = (uint32_t)bits;
      std::memcpy(&v, &u, sizeof u);
    } else if constexpr (std::is_same_v<T, bool>) {
      v = bits != 0;
    } else {
      v = is_signed ? (T)vec_unpack_signed(bits, width) : (T)bits;
    }
  }
};

template <class R>
void unpack_record(R& r, const RecordShape& s, const VecRow& row, size_t first) {
  RecordUnpacker u{&row, first};
  r.visit(u, s);
  restore_record(r, s);
}

}  // namespace fxr

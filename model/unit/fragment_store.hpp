// model/unit/fragment_store.hpp — the fragments of a frame as compact fixed-stride records
// (FrameOutput::fragments). docs/speed.md, "Compact fragment records".
//
// A Fragment (model/unit/io.hpp) holds kMaxVaryings FxFloats: 272 bytes whatever the draw. The
// store keeps only what the draw has: a record is kFragmentHeaderBytes (prim, x, y, depth as
// 32-bit words) plus kFragmentVaryingBytes per active varying (the significand as 32 bits and
// the exponent with the sign in one 32-bit word; push_back checks each value with
// fragment_var_storable, and the fused span writes records only where FusedSpan::applies and its
// per-triangle exponent bound prove every value storable, model/stages/interp_span.hpp). With 2 varyings a record is 32 bytes instead of 272.
// Records live in one malloc'd byte buffer grown by realloc (glibc moves a large block with
// mremap, no copy), never zero-filled.
//
// The store reads like a std::vector<Fragment> of values: size(), operator[] and iteration
// decode a record into a Fragment (var[k] = 0 for k ≥ num_varyings, as the model leaves them).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/unit/io.hpp"

namespace fxr {

// Record layout (bytes). The header: prim, x, y, depth, one 32-bit word each.
inline constexpr int kFragmentHeaderWords = 4;
inline constexpr int kFragmentHeaderBytes = kFragmentHeaderWords * 4;
// One varying: significand (32 bits), exponent·2 + sign (32 bits, two's complement).
inline constexpr int kStoredSigBits = 32;
inline constexpr int kStoredExpBits = 31;  // the exponent's field: [−2^30, 2^30 − 1]
inline constexpr int kStoredExpMax = (1 << (kStoredExpBits - 1)) - 1;
inline constexpr int kFragmentVaryingBytes = 8;

// The record of a fragment with `num_varyings` varyings, in bytes.
inline constexpr size_t fragment_record_bytes(int num_varyings) {
  return (size_t)kFragmentHeaderBytes + (size_t)num_varyings * kFragmentVaryingBytes;
}
// Writing and reading one record (the store's and the fused span's writer, model/stages/
// interp_span.hpp, share these). put_* do not check: the caller knows sig < 2^kStoredSigBits and
// |exp| ≤ kStoredExpMax (fragment_var_storable).
inline bool fragment_var_storable(uint64_t sig, int exp) {
  return (sig >> kStoredSigBits) == 0 && exp <= kStoredExpMax && exp >= -kStoredExpMax - 1;
}
inline void put_fragment_header(uint8_t* rec, uint32_t prim, int32_t x, int32_t y, uint32_t depth) {
  const uint32_t h[kFragmentHeaderWords] = {prim, (uint32_t)x, (uint32_t)y, depth};
  std::memcpy(rec, h, sizeof h);
}
// Two consecutive 32-bit words of a record as one 64-bit value, `first` at the lower address
// (FusedTriangle writes a header as two such stores: prim and x, y and depth).
inline uint64_t fragment_word_pair(uint32_t first, uint32_t second) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ || __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__, "byte order");
  return __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ ? (uint64_t)first | (uint64_t)second << 32
                                                   : (uint64_t)second | (uint64_t)first << 32;
}
// Varying k as its two words: the significand and exp·2 + sign (the one writer of a varying's
// place in the record; the fused span's word segments assemble the second word themselves).
inline void put_fragment_var_words(uint8_t* rec, int k, uint32_t sig_word, uint32_t exp_sign_word) {
  const uint32_t w[2] = {sig_word, exp_sign_word};
  std::memcpy(rec + kFragmentHeaderBytes + (size_t)k * kFragmentVaryingBytes, w, sizeof w);
}
inline void put_fragment_var(uint8_t* rec, int k, uint64_t sig, int exp, bool neg) {
  put_fragment_var_words(rec, k, (uint32_t)sig, ((uint32_t)exp << 1) | (uint32_t)neg);
}
inline uint32_t fragment_word(const uint8_t* rec, int w) {
  uint32_t v;
  std::memcpy(&v, rec + (size_t)w * 4, 4);
  return v;
}
inline FxFloat get_fragment_var(const uint8_t* rec, int k) {
  uint32_t w[2];
  std::memcpy(w, rec + kFragmentHeaderBytes + (size_t)k * kFragmentVaryingBytes, sizeof w);
  FxFloat v;
  v.sig = w[0];
  v.neg = (w[1] & 1u) != 0;
  v.exp = (int32_t)w[1] >> 1;  // arithmetic shift (C++20 defines it; every C++17 target here does)
  return v;
}
// Decodes a record into f (var[k] for k < num_varyings; the others are left as they are).
inline void get_fragment(const uint8_t* rec, int num_varyings, Fragment& f) {
  uint32_t h[kFragmentHeaderWords];
  std::memcpy(h, rec, sizeof h);
  f.prim = h[0], f.x = (int32_t)h[1], f.y = (int32_t)h[2], f.depth = h[3];
  for (int k = 0; k < num_varyings; ++k) f.var[k] = get_fragment_var(rec, k);
}

// A block of consecutive records (fragments of one span, in order: FragmentSink::emit_span,
// model/unit/backend.hpp), not owned.
struct FragmentRecords {
  const uint8_t* data = nullptr;
  size_t count = 0;
  int num_varyings = 0;

  size_t stride() const { return fragment_record_bytes(num_varyings); }
  const uint8_t* record(size_t i) const { return data + i * stride(); }
  int32_t x(size_t i) const { return (int32_t)fragment_word(record(i), 1); }
  int32_t y(size_t i) const { return (int32_t)fragment_word(record(i), 2); }
  uint32_t depth(size_t i) const { return fragment_word(record(i), 3); }
  Fragment operator[](size_t i) const {
    Fragment f;
    get_fragment(record(i), num_varyings, f);
    return f;
  }
};

class FragmentStore {
 public:
  FragmentStore() = default;
  explicit FragmentStore(int num_varyings) { shape(num_varyings); }
  FragmentStore(const FragmentStore& o) { *this = o; }
  FragmentStore(FragmentStore&& o) noexcept { swap(o); }
  FragmentStore& operator=(const FragmentStore& o) {
    if (this == &o) return *this;
    nv_ = o.nv_;
    stride_ = o.stride_;
    n_ = 0;
    reserve(o.n_);
    if (o.n_) std::memcpy(buf_, o.buf_, o.n_ * stride_);
    n_ = o.n_;
    return *this;
  }
  FragmentStore& operator=(FragmentStore&& o) noexcept {
    swap(o);
    return *this;
  }
  ~FragmentStore() { std::free(buf_); }
  void swap(FragmentStore& o) noexcept {
    std::swap(buf_, o.buf_), std::swap(cap_, o.cap_), std::swap(n_, o.n_);
    std::swap(nv_, o.nv_), std::swap(stride_, o.stride_);
  }

  // Contract: empties the store and sets the record shape (0 ≤ num_varyings ≤ kMaxVaryings);
  // the buffer's capacity is kept (a frame renders into the memory of the last one).
  void shape(int num_varyings) {
    if (num_varyings < 0 || num_varyings > kMaxVaryings)
      throw std::invalid_argument("FragmentStore: num_varyings " + std::to_string(num_varyings) + " outside 0.." +
                                  std::to_string(kMaxVaryings));
    const size_t stride = fragment_record_bytes(num_varyings);
    if (stride != stride_) cap_ = cap_ * stride_ / stride;  // the same bytes, counted in new records
    nv_ = num_varyings;
    stride_ = stride;
    n_ = 0;
  }
  // Contract: num_varyings > num_varyings(): re-encodes the records held to the wider shape (their
  // extra varyings 0, as a Fragment leaves them); else nothing. A frame whose line segments
  // have more varyings than its triangles (FragmentSink::draw_state).
  void widen(int num_varyings) {
    if (num_varyings <= nv_) return;
    FragmentStore w(num_varyings);
    w.reserve(n_);
    for (size_t i = 0; i < n_; ++i) w.push_back((*this)[i]);
    swap(w);
  }
  int num_varyings() const { return nv_; }
  size_t record_bytes() const { return stride_; }

  size_t size() const { return n_; }
  size_t capacity() const { return cap_; }  // records the buffer holds before it must grow
  bool empty() const { return n_ == 0; }
  void clear() { n_ = 0; }
  void reserve(size_t n) {
    if (n > cap_) grow_to(n);
  }
  // The raw records (size() · record_bytes() bytes), for a bulk copy between stores of one shape.
  const uint8_t* data() const { return buf_; }

  // Contract: appends f (its first num_varyings() varyings). Throws std::logic_error if a
  // significand needs more than kStoredSigBits bits or an exponent more than 30 bits (the
  // model's outputs never do: raster.varying_out_sig_bits ≤ 32, exponents docs/pipeline.md).
  void push_back(const Fragment& f) {
    if (n_ == cap_) grow_to(n_ + 1);
    uint8_t* p = buf_ + n_ * stride_;
    put_fragment_header(p, f.prim, f.x, f.y, f.depth);
    for (int k = 0; k < nv_; ++k) {
      const FxFloat& v = f.var[k];
      if (!fragment_var_storable(v.sig, v.exp)) unstorable(v);
      put_fragment_var(p, k, v.sig, v.exp, v.neg);
    }
    ++n_;
  }

  // Contract: appends the block's records in order. The same num_varyings: one copy (the
  // records are taken as they are: their writer checked fragment_var_storable); fewer: each
  // record widened (extra varyings 0, as push_back of its Fragment); more: std::logic_error.
  void append(const FragmentRecords& b) {
    if (b.num_varyings == nv_) {
      reserve(n_ + b.count);
      if (b.count) std::memcpy(buf_ + n_ * stride_, b.data, b.count * stride_);
      n_ += b.count;
      return;
    }
    if (b.num_varyings > nv_) throw std::logic_error("FragmentStore::append: a block with more varyings than the store");
    reserve(n_ + b.count);
    for (size_t i = 0; i < b.count; ++i) push_back(b[i]);
  }

  // Contract: room for n more records at the end, returned for the caller to write (in this
  // store's layout, varyings checked by their writer); append_commit(count ≤ n) then appends the
  // first count of them. Nothing else may change the store in between.
  uint8_t* append_space(size_t n) {
    reserve(n_ + n);
    return buf_ + n_ * stride_;
  }
  void append_commit(size_t count) {
    if (n_ + count > cap_) throw std::logic_error("FragmentStore::append_commit: beyond append_space");
    n_ += count;
  }

  // Contract: appends records [first, first + count) of `o` (same num_varyings) in one copy.
  void append(const FragmentStore& o, size_t first, size_t count) {
    if (o.nv_ != nv_) throw std::logic_error("FragmentStore::append: stores of different shapes");
    reserve(n_ + count);
    if (count) std::memcpy(buf_ + n_ * stride_, o.buf_ + first * o.stride_, count * stride_);
    n_ += count;
  }

  // Contract: size() becomes n; records below the old size are kept, the others are
  // unspecified until written (write_at). Several threads may then write_at disjoint ranges.
  void resize_for_overwrite(size_t n) {
    reserve(n);
    n_ = n;
  }
  // Contract: the memory of records [first, size()) for the caller to write in this store's
  // layout (varyings checked by their writer), as write_at; valid until the store grows. Several
  // threads may write disjoint records (the threaded driver's direct rows, model/unit/threads.cpp).
  uint8_t* records_for_overwrite(size_t first) {
    if (first > n_) throw std::logic_error("FragmentStore::records_for_overwrite: beyond size()");
    return buf_ + first * stride_;
  }
  // Contract: records [dst, dst + count) (within size()) become records [first, first + count)
  // of `o` (same num_varyings), in one copy.
  void write_at(size_t dst, const FragmentStore& o, size_t first, size_t count) {
    if (o.nv_ != nv_ || dst + count > n_) throw std::logic_error("FragmentStore::write_at: shape or range");
    if (count) std::memcpy(buf_ + dst * stride_, o.buf_ + first * o.stride_, count * stride_);
  }

  // The accessors of a record without decoding the whole Fragment.
  uint32_t prim(size_t i) const { return word(i, 0); }
  int32_t x(size_t i) const { return (int32_t)word(i, 1); }
  int32_t y(size_t i) const { return (int32_t)word(i, 2); }
  uint32_t depth(size_t i) const { return word(i, 3); }
  FxFloat var(size_t i, int k) const { return get_fragment_var(buf_ + i * stride_, k); }

  Fragment operator[](size_t i) const {
    Fragment f;
    get_fragment(buf_ + i * stride_, nv_, f);
    return f;
  }
  Fragment at(size_t i) const {
    if (i >= n_) throw std::out_of_range("FragmentStore::at");
    return (*this)[i];
  }
  Fragment front() const { return (*this)[0]; }
  Fragment back() const { return (*this)[n_ - 1]; }

  // Iteration by value: `for (const Fragment& f : store)` binds each decoded record.
  class const_iterator {
   public:
    using iterator_category = std::random_access_iterator_tag;
    using value_type = Fragment;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = Fragment;
    const_iterator(const FragmentStore* s, size_t i) : s_(s), i_(i) {}
    Fragment operator*() const { return (*s_)[i_]; }
    Fragment operator[](difference_type d) const { return (*s_)[i_ + d]; }
    const_iterator& operator++() { ++i_; return *this; }
    const_iterator operator++(int) { const_iterator t = *this; ++i_; return t; }
    const_iterator& operator--() { --i_; return *this; }
    const_iterator& operator+=(difference_type d) { i_ += d; return *this; }
    const_iterator& operator-=(difference_type d) { i_ -= d; return *this; }
    const_iterator operator+(difference_type d) const { return {s_, i_ + d}; }
    const_iterator operator-(difference_type d) const { return {s_, i_ - d}; }
    difference_type operator-(const const_iterator& o) const { return (difference_type)i_ - (difference_type)o.i_; }
    bool operator==(const const_iterator& o) const { return i_ == o.i_; }
    bool operator!=(const const_iterator& o) const { return i_ != o.i_; }
    bool operator<(const const_iterator& o) const { return i_ < o.i_; }

   private:
    const FragmentStore* s_;
    size_t i_;
  };
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, n_}; }

  std::vector<Fragment> to_vector() const { return std::vector<Fragment>(begin(), end()); }

 private:
  uint32_t word(size_t i, int w) const { return fragment_word(buf_ + i * stride_, w); }
  [[noreturn]] static void unstorable(const FxFloat& v);
  void grow_to(size_t n) {
    if (stride_ == 0) throw std::logic_error("FragmentStore: push before shape()");
    size_t c = cap_ ? cap_ : kFirstRecords;
    while (c < n) c *= 2;
    void* p = std::realloc(buf_, c * stride_);
    if (!p) throw std::bad_alloc();
    buf_ = (uint8_t*)p;
    cap_ = c;
  }
  static constexpr size_t kFirstRecords = 4096;

  uint8_t* buf_ = nullptr;
  size_t cap_ = 0, n_ = 0;  // in records
  int nv_ = 0;
  size_t stride_ = 0;       // 0: not shaped
};

inline void FragmentStore::unstorable(const FxFloat& v) {
  throw std::logic_error("FragmentStore: varying (sig " + std::to_string(v.sig) + ", exp " + std::to_string(v.exp) +
                         ") does not fit the compact record (" + std::to_string(kStoredSigBits) +
                         "-bit significand, 31-bit exponent)");
}

}  // namespace fxr

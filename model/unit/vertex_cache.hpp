// model/unit/vertex_cache.hpp — stages 1–4 once per distinct vertex of trivially accepted
// triangles (docs/speed.md "Shortcuts": a model-side post-transform vertex cache).
//
// A triangle whose three vertices are finite, have no varying replaced, lie inside every clip
// plane (outcode 0), get a reciprocal and snap into the window format goes through stages 1–4
// vertex by vertex: convert_vertex, the trivial accept (copy_clip_vertex leaves such a vertex
// unchanged), recip_vertex, snap_vertex. Each is a function of the vertex's float32 bits and
// the draw, so the SetupVertex of such a vertex is the same in every triangle that shares it
// (a mesh shares each vertex among ≈ 6 triangles). The cache keeps, per vertex bit pattern,
// whether it is such a vertex and its SetupVertex; GeometryChain<NoTaps> (model/unit/chain.hpp)
// emits a triangle of three such vertices from it and gives every other triangle to the full
// stage chain (which also counts it). Bit-identical to the full chain by construction; tested
// by running both on the same scenes (tests/model/shortcut_test.cpp, Shortcut.VertexCache*).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "model/config/config.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/input.hpp"
#include "model/stages/recip_stage.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/viewport.hpp"

namespace fxr {

// Size of the direct-mapped cache: the most slots, up to 2^kVertexCacheMaxSlotBits, whose
// arrays fit kVertexCacheBytes (a slot: the SetupVertex without varyings, 4 + nv key words, nv
// varyings; 144 bytes at 2 varyings: 2^14 slots). Measured on the bunny (docs/speed.md
// "Shortcuts"): 2^10 / 2^12 / 2^14 slots answer 51 / 64 / 75 % of the default scene's vertex
// lookups; the bunny's stream rate at 2^12 … 2^16 slots is within the noise.
inline constexpr int kVertexCacheMaxSlotBits = 14;
inline constexpr size_t kVertexCacheBytes = size_t{4} << 20;
// A chain allocates its cache only after this many primitives (fxr::geometry() sets a chain up
// per primitive; a few primitives gain nothing from it).
inline constexpr uint64_t kVertexCacheMinPrims = 64;
// How many primitives ahead UnitChain::draw_all prefetches the vertex cache's slots: 2 (a
// bunny triangle takes ≈ 0.1 µs… 1 µs; 1, 2 and 4 were within 2 % of each other, docs/speed.md
// "Session 9: per triangle").
inline constexpr size_t kVertexCachePrefetchAhead = 2;

// Contract: true when `in`, as a vertex of a triangle whose three vertices all return true,
// passes stages 1–4 unchanged by the clipper: positions finite, no active varying replaced,
// strictly inside no clip plane's outside (outcode 0), a reciprocal without error, a snapped
// position in range; `out` is then its SetupVertex (varyings past nv zero, as snap_vertex).
// `v`: scratch storage, any contents (its members past the draw's varyings are not read: the
// caller's one ClipVtx saves a 504-byte zero fill per vertex computed).
inline bool accepted_vertex(const Config& cfg, const DrawState& st, const GuardBand& gb, const ClipVertex& in,
                            SetupVertex& out, ClipVtx& v) {
  bool nan = false, inf = false, replaced = false;
  convert_vertex(in, st.num_varyings, v, nan, inf, replaced);
  if (nan || inf || replaced || outcode(gb, v) != 0) return false;
  FxFloat r;
  return recip_vertex(cfg.recip, v, r) && snap_vertex(cfg, st, v, r, out) == ProjectStatus::Ok;
}
inline bool accepted_vertex(const Config& cfg, const DrawState& st, const GuardBand& gb, const ClipVertex& in,
                            SetupVertex& out) {
  ClipVtx v;
  return accepted_vertex(cfg, st, gb, in, out, v);
}

class VertexCache;

// A table of vertex-cache slots that several VertexCaches share (VertexCache::share: the threads
// of model/unit/threads.cpp, one cache object each), kept from draw to draw. begin() before each
// draw empties it: a new epoch, written into every slot filled during the draw, makes the slots
// of earlier draws empty; the words are cleared only when the slot layout (the varying count)
// changes or the epochs wrap. Used by one draw at a time.
class SharedVertexTable {
 public:
  void begin(int num_varyings) {
    const size_t words = kVertexCacheBytes / sizeof(uint64_t);
    if (words_.size() != words || nv_ != num_varyings || epoch_ == kMaxEpoch) {
      words_.assign(words, 0);
      epoch_ = 0;
      nv_ = num_varyings;
    }
    ++epoch_;
  }

 private:
  friend class VertexCache;
  static constexpr uint32_t kMaxEpoch = (uint32_t{1} << 30) - 1;  // a slot's state keeps 2 bits beside it
  std::vector<uint64_t> words_;
  int nv_ = -1;
  uint32_t epoch_ = 0;
};

class VertexCache {
 public:
  // Usable for a draw whose stage 1 accepts its varying count and whose guard band is valid
  // (otherwise every primitive is rejected by the stages themselves).
  // max_slot_bits and min_prims: the defaults, or a tiny cache from the first primitive (tests:
  // one slot shared by every vertex).
  VertexCache(const Config& cfg, const DrawState& st, int max_slot_bits = kVertexCacheMaxSlotBits,
              uint64_t min_prims = kVertexCacheMinPrims)
      : cfg_(cfg), st_(st), gb_(guard_band(cfg.raster, st)), nv_(st.num_varyings),
        usable_(gb_.valid && nv_ >= 0 && nv_ <= kMaxVaryings), min_prims_(min_prims), bits_(max_slot_bits) {}

  // Contract: true when all three vertices of `in` are accepted vertices (accepted_vertex);
  // `out` is then the triangle stages 1–4 emit for it (prim set; the varyings past nv are only
  // ever written with zero, as snap_vertex does: keep `out` from a default SetupTriangle).
  // false: nothing is known (`out` may be partly written), the caller runs the full chain.
  // Counts hits and misses per vertex looked up.
  bool triangle(const InputTriangle& in, SetupTriangle& out) { return triangle(in.tri, in.prim, out); }
  // The same for primitive `prim` with vertices `tri`.
  bool triangle(const ClipTriangle& tri, uint32_t prim, SetupTriangle& out) {
    if (!usable_) return false;
    if (++prims_ <= min_prims_) return false;
    if (!table_) allocate();
    // The three slots are looked up after all three are requested (their cache misses overlap).
    uint32_t key[3][4 + kMaxVaryings];
    unsigned char* slot[3];
    for (int i = 0; i < 3; ++i) {
      slot[i] = locate(tri.v[i], key[i]);
      prefetch_slot(slot[i]);
    }
    for (int i = 0; i < 3; ++i)
      if (!vertex(tri.v[i], key[i], slot[i], out.v[i])) return false;
    out.prim = prim;
    return true;
  }

  // Contract: a hint without effect on any answer or counter: locates the slots of the vertices
  // of `tri` (a later triangle of the draw) and prefetches them, so that triangle() for it finds
  // them in the cache (docs/speed.md "Session 9: per triangle": the table's memory latency was
  // most of a hit's cost). Nothing before the table exists (the first kVertexCacheMinPrims).
  void prefetch(const ClipTriangle& tri) const {
    if (!table_) return;
    for (int i = 0; i < 3; ++i) prefetch_slot(reinterpret_cast<const unsigned char*>(table_ + index(tri.v[i]) * stride_));
  }

  // Contract: this cache looks up and fills `table` (begun for this draw's varying count) instead
  // of a table of its own, with any number of other caches at the same time, each from one
  // thread. A slot is read and written under its sequence number (a seqlock): one being written,
  // or rewritten while it was read, counts as a miss, computed here and not stored. The answers
  // are those of an unshared cache (a slot only ever holds accepted_vertex of its key), so a
  // draw's output does not depend on how its threads interleave.
  void share(SharedVertexTable& table) {
    if (!usable_ || table.nv_ != nv_) return;  // (a table begun for another draw: not shared)
    layout(table.words_.size() * sizeof(uint64_t));
    table_ = table.words_.data();
    epoch_ = table.epoch_;
    shared_ = true;
  }

  uint64_t hits() const { return hits_; }
  uint64_t misses() const { return misses_; }

 private:
  // A slot's state: epoch · 4 + kAccepted / kNotAccepted (epoch 0 unless shared), or kEmpty.
  enum : uint32_t { kEmpty = 0, kAccepted = 1, kNotAccepted = 2 };
  // A slot, contiguous (one or two adjacent cache lines at 2 varyings): the head, then the key
  // words, then the varyings. The head's first word holds the state and the sequence number of
  // a shared table (odd while a thread writes the slot).
  struct Head {
    uint32_t state = kEmpty;
    uint32_t seq = 0;
    int64_t x = 0, y = 0, ax = 0, ay = 0;
    uint64_t z = 0;
    FxFloat rw;
  };
  static constexpr size_t kKeyOffset = sizeof(Head);
  static_assert(offsetof(Head, seq) == sizeof(uint32_t), "state and seq are the head's first 64-bit word");

  static constexpr size_t kMaxSlotWords =
      ((kKeyOffset + (4 + kMaxVaryings) * sizeof(uint32_t) + 7) / 8 * 8 + kMaxVaryings * sizeof(FxFloat) + 7) / 8;

  // The slot layout of nv_ varyings, in a table of at most `bytes`.
  void layout(size_t bytes) {
    kw_ = 4 + (size_t)nv_;
    vw_offset_ = (kKeyOffset + kw_ * sizeof(uint32_t) + 7) / 8 * 8;
    stride_ = (vw_offset_ + (size_t)nv_ * sizeof(FxFloat) + 7) / 8;  // in 64-bit words
    while (bits_ > 8 && ((stride_ * 8) << bits_) > bytes) --bits_;
  }
  void allocate() {
    layout(kVertexCacheBytes);
    buf_.assign(stride_ << bits_, 0);  // state 0 = kEmpty
    table_ = buf_.data();
  }
  bool filled(uint32_t state) const { return state != kEmpty && state >> 2 == epoch_; }
  // The slot's key words equal `key` (a loop over the 4 + nv words: std::memcmp of a run-time
  // length stayed a libc call, 3 % of the bunny's profile).
  bool same_key(const unsigned char* slot, const uint32_t* key) const {
    const unsigned char* k = slot + kKeyOffset;
    for (size_t w = 0; w < kw_; ++w) {
      uint32_t v;
      std::memcpy(&v, k + w * sizeof(uint32_t), sizeof(uint32_t));
      if (v != key[w]) return false;
    }
    return true;
  }

  // n units of kUnit bytes: a fixed-size copy (inline moves) for n ≤ 8, where a std::memcpy of a
  // run-time length is a libc call (the key and varying copies: 2.5 % of the bunny's profile).
  template <size_t kUnit>
  static void copy_units(void* dst, const void* src, size_t n) {
    switch (n) {
      case 0: break;
      case 1: std::memcpy(dst, src, 1 * kUnit); break;
      case 2: std::memcpy(dst, src, 2 * kUnit); break;
      case 3: std::memcpy(dst, src, 3 * kUnit); break;
      case 4: std::memcpy(dst, src, 4 * kUnit); break;
      case 5: std::memcpy(dst, src, 5 * kUnit); break;
      case 6: std::memcpy(dst, src, 6 * kUnit); break;
      case 7: std::memcpy(dst, src, 7 * kUnit); break;
      case 8: std::memcpy(dst, src, 8 * kUnit); break;
      default: std::memcpy(dst, src, n * kUnit);
    }
  }
  void copy_varyings(FxFloat* vw, const unsigned char* from) const {
    copy_units<sizeof(FxFloat)>(vw, from, (size_t)nv_);
  }
  // The slot number of a vertex whose key words are `key`.
  size_t index(const uint32_t* key) const {
    uint64_t h = 0;
    for (size_t k = 0; k < kw_; ++k) h = (h ^ key[k]) * 0x9E3779B97F4A7C15ull;
    return bits_ > 0 ? (size_t)(h >> (64 - bits_)) : 0;
  }
  // The key words of `cv` (its float32 bits).
  void key_of(const ClipVertex& cv, uint32_t* key) const {
    // Fixed sizes (a run-time length is a libc call, with the varying copies 2.5 % of the bunny's
    // profile); the words past 4 + nv_ are never read.
    static_assert(sizeof(cv.pos) + sizeof(cv.var) == (4 + kMaxVaryings) * sizeof(uint32_t), "key words");
    std::memcpy(key, cv.pos, sizeof(cv.pos));
    std::memcpy(key + 4, cv.var, sizeof(cv.var));
  }
  size_t index(const ClipVertex& cv) const {
    uint32_t key[4 + kMaxVaryings];
    key_of(cv, key);
    return index(key);
  }
  // Every cache line of a slot (a slot of 144 bytes at 2 varyings spans 3 lines where it starts
  // past a line's first 32 bytes; the head, key and varyings are all read on a hit).
  void prefetch_slot(const unsigned char* slot) const {
    const uintptr_t last = reinterpret_cast<uintptr_t>(slot) + stride_ * sizeof(uint64_t) - 1;
    for (uintptr_t line = reinterpret_cast<uintptr_t>(slot) & ~(uintptr_t)(kCacheLine - 1); line <= last;
         line += kCacheLine)
      __builtin_prefetch(reinterpret_cast<const void*>(line));
  }
  static constexpr size_t kCacheLine = 64;
  // The key words of `cv` and its slot.
  unsigned char* locate(const ClipVertex& cv, uint32_t* key) {
    key_of(cv, key);
    return reinterpret_cast<unsigned char*>(table_ + index(key) * stride_);
  }

  bool vertex(const ClipVertex& cv, const uint32_t* key, unsigned char* slot, SetupVertex& out) {
    if (shared_) return vertex_shared(cv, key, reinterpret_cast<uint64_t*>(slot), out);
    uint32_t state;
    std::memcpy(&state, slot, sizeof(state));
    if (filled(state) && same_key(slot, key)) {
      ++hits_;
      if ((state & 3) != kAccepted) return false;
      // Field by field from the slot (a copy of the whole head to the stack, read back in other
      // widths, stalled on store forwarding: a quarter of the hit path's samples).
      std::memcpy(&out.x, slot + offsetof(Head, x), sizeof(out.x));
      std::memcpy(&out.y, slot + offsetof(Head, y), sizeof(out.y));
      std::memcpy(&out.ax, slot + offsetof(Head, ax), sizeof(out.ax));
      std::memcpy(&out.ay, slot + offsetof(Head, ay), sizeof(out.ay));
      std::memcpy(&out.z, slot + offsetof(Head, z), sizeof(out.z));
      std::memcpy(&out.rw, slot + offsetof(Head, rw), sizeof(out.rw));
      copy_varyings(out.vw, slot + vw_offset_);
      return true;
    }
    ++misses_;
    Head head;
    copy_units<sizeof(uint32_t)>(slot + kKeyOffset, key, kw_);
    const bool ok = accepted_vertex(cfg_, st_, gb_, cv, out, scratch_);
    fill(head, ok, out, slot);
    std::memcpy(slot, &head, sizeof(Head));
    return ok;
  }

  // The head and varyings of a slot holding accepted_vertex's answer `ok`, `out` (its key
  // words are written by the caller).
  void fill(Head& head, bool ok, const SetupVertex& out, unsigned char* slot) const {
    head.state = epoch_ << 2 | (ok ? kAccepted : kNotAccepted);
    if (ok) {
      head.x = out.x, head.y = out.y, head.ax = out.ax, head.ay = out.ay, head.z = out.z, head.rw = out.rw;
      copy_units<sizeof(FxFloat)>(slot + vw_offset_, out.vw, (size_t)nv_);
    }
  }

  // vertex() on a shared table: the slot's words are read with atomic loads between two loads of
  // its head word (equal, with an even sequence number: a consistent copy), and written by the
  // thread that moved the sequence number from the even value it read to odd (then even again
  // with the new state). Others' writes are never waited for: a miss.
  bool vertex_shared(const ClipVertex& cv, const uint32_t* key, uint64_t* slot, SetupVertex& out) {
    uint64_t copy[kMaxSlotWords];
    const uint64_t w0 = __atomic_load_n(slot, __ATOMIC_ACQUIRE);
    uint32_t state_seq[2];  // the head's first word: state, seq
    std::memcpy(state_seq, &w0, sizeof(uint64_t));
    const uint32_t state = state_seq[0], seq = state_seq[1];
    const bool idle = (seq & 1) == 0;
    if (idle && filled(state)) {
      copy[0] = w0;
      for (size_t k = 1; k < stride_; ++k) copy[k] = __atomic_load_n(slot + k, __ATOMIC_RELAXED);
      __atomic_thread_fence(__ATOMIC_ACQUIRE);
      const unsigned char* c = reinterpret_cast<const unsigned char*>(copy);
      if (__atomic_load_n(slot, __ATOMIC_RELAXED) == w0 &&
          same_key(c, key)) {
        ++hits_;
        if ((state & 3) != kAccepted) return false;
        Head head;
        std::memcpy(&head, c, sizeof(Head));
        out.x = head.x, out.y = head.y, out.ax = head.ax, out.ay = head.ay, out.z = head.z, out.rw = head.rw;
        std::memcpy(out.vw, c + vw_offset_, (size_t)nv_ * sizeof(FxFloat));
        return true;
      }
    }
    ++misses_;
    const bool ok = accepted_vertex(cfg_, st_, gb_, cv, out, scratch_);
    uint64_t expect = w0, busy;
    state_seq[1] = seq + 1;  // odd: being written
    std::memcpy(&busy, state_seq, sizeof(uint64_t));
    if (!idle || !__atomic_compare_exchange_n(slot, &expect, busy, false, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED))
      return ok;  // another thread writes the slot
    __atomic_thread_fence(__ATOMIC_RELEASE);
    std::memset(copy, 0, stride_ * sizeof(uint64_t));
    unsigned char* c = reinterpret_cast<unsigned char*>(copy);
    std::memcpy(c + kKeyOffset, key, kw_ * sizeof(uint32_t));
    Head fresh;
    fill(fresh, ok, out, c);
    fresh.seq = seq + 2;
    std::memcpy(c, &fresh, sizeof(Head));
    for (size_t k = 1; k < stride_; ++k) __atomic_store_n(slot + k, copy[k], __ATOMIC_RELAXED);
    __atomic_store_n(slot, copy[0], __ATOMIC_RELEASE);
    return ok;
  }

  const Config& cfg_;
  const DrawState& st_;
  GuardBand gb_;
  int nv_;
  bool usable_;
  uint64_t min_prims_;
  uint64_t prims_ = 0, hits_ = 0, misses_ = 0;
  int bits_;
  size_t kw_ = 4, vw_offset_ = 0, stride_ = 0;
  std::vector<uint64_t> buf_;  // the table, unless shared
  uint64_t* table_ = nullptr;
  uint32_t epoch_ = 0;
  bool shared_ = false;
  ClipVtx scratch_;  // accepted_vertex's working vertex
};

}  // namespace fxr

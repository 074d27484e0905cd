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
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "model/config/config.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/input.hpp"
#include "model/stages/recip_stage.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/viewport.hpp"

namespace fxr {

// Size of the direct-mapped cache: the most slots, up to 2^kVertexCacheMaxSlotBits, whose
// arrays fit kVertexCacheBytes (a slot: the SetupVertex without varyings, 4 + nv key words, nv
// varyings; 88 bytes without varyings, 144 bytes at 2: 2^16 slots, 5.8 / 9.4 MB). Measured on
// the bunny (docs/speed.md "Shortcuts", "Session 8: the bunny's per-triangle cost"): 2^10 /
// 2^12 / 2^14 / 2^16 / 2^17 slots answer 51 / 64 / 75 / 81 / 82 % of the default scene's vertex
// lookups. With the slots prefetched ahead (session 9) the larger table pays: same-run A/B,
// bunny stream v0 / v2 at 2^14 (4 MB) 17.75 / 9.92, 2^16 (16 MB) 18.45 / 10.32, 2^17 (32 MB)
// 18.94 / 10.09 M fragments/s (docs/speed.md "Session 10: per triangle").
inline constexpr int kVertexCacheMaxSlotBits = 16;
inline constexpr size_t kVertexCacheBytes = size_t{16} << 20;
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
// position in range; `out` is then its SetupVertex but for the varyings past nv, which are not
// written (snap_vertex_active: the caller keeps them zero, as snap_vertex writes them; a
// 336-byte fill per vertex computed at 2 varyings, docs/speed.md "Session 11: per triangle").
// `v`: scratch storage, any contents (its members past the draw's varyings are not read: the
// caller's one ClipVtx saves a 504-byte zero fill per vertex computed).
// `unit`: nullptr, or the reciprocal unit of cfg.recip (the cache's, per draw). rw_unread:
// snap_vertex_active's (out.rw is then 0 with separate attribute positions).
inline bool accepted_vertex(const Config& cfg, const DrawState& st, const GuardBand& gb, const ClipVertex& in,
                            SetupVertex& out, ClipVtx& v, const RecipUnit* unit = nullptr, bool rw_unread = false) {
  bool nan = false, inf = false, replaced = false;
  convert_vertex(in, st.num_varyings, v, nan, inf, replaced);
  if (nan || inf || replaced || outcode(gb, v) != 0) return false;
  FxFloat r;
  return (unit ? recip_vertex(*unit, v, r) : recip_vertex(cfg.recip, v, r)) &&
         snap_vertex_active(cfg, st, v, r, out, rw_unread) == ProjectStatus::Ok;
}
inline bool accepted_vertex(const Config& cfg, const DrawState& st, const GuardBand& gb, const ClipVertex& in,
                            SetupVertex& out) {
  ClipVtx v;
  return accepted_vertex(cfg, st, gb, in, out, v);
}

class VertexCache;

// The vertex table's word: slots, the varyings after a slot's key words and a shared slot's
// atomic accesses are aligned to it. vertex_table_words: table words holding `bytes` bytes.
inline constexpr size_t kVertexTableWordBytes = sizeof(uint64_t);
constexpr size_t vertex_table_words(size_t bytes) { return (bytes + kVertexTableWordBytes - 1) / kVertexTableWordBytes; }
// A slot's stride is a multiple of half a cache line: a slot then starts at a line's first or
// second half and spans the fewest lines its bytes can (0 varyings: 88 → 96 bytes, always 2
// lines; 2 varyings: 144 → 160, always 3), where strides of whole words spanned 2.25 and 3.25
// lines on average and the slot prefetch's loop ran 2 or 3 (3 or 4) times by the slot's
// position, a mispredicted exit (docs/speed.md "Session 13: per vertex and per triangle"). A
// table holds as many slots as with unpadded strides at every varying count.
inline constexpr size_t kVertexSlotAlignBytes = 32;
static_assert(kVertexSlotAlignBytes % kVertexTableWordBytes == 0, "a stride is whole table words");
constexpr size_t vertex_slot_stride_bytes(size_t bytes) {
  return (bytes + kVertexSlotAlignBytes - 1) / kVertexSlotAlignBytes * kVertexSlotAlignBytes;
}

// A slot's state keeps 2 bits beside its epoch (VertexCache's kAccepted / kNotAccepted): the
// epochs of a table kept from draw to draw run up to this, then its words are cleared.
inline constexpr uint32_t kVertexTableMaxEpoch = (uint32_t{1} << 30) - 1;

// The words of a vertex table, zero when (re)allocated, on 2 MB pages where the system gives
// them: Linux's transparent huge pages asked for by madvise (the mode this machine runs), a
// hint that leaves 4 KB pages where it is refused. The table is read at random (9.4 MB at 2
// varyings): on 4 KB pages nearly every slot prefetch missed the TLB, and the page walk held the
// prefetch instruction (40 % of the inlined hit path's samples; docs/speed.md "Session 11: per
// triangle"). Move-only.
class VertexTableWords {
 public:
  // 2 MB: the x86-64 huge page.
  static constexpr size_t kHugePageBytes = size_t{2} << 20;

  VertexTableWords() = default;
  VertexTableWords(const VertexTableWords&) = delete;
  VertexTableWords& operator=(const VertexTableWords&) = delete;
  VertexTableWords(VertexTableWords&& o) noexcept : base_(o.base_), map_(o.map_), words_(o.words_), n_(o.n_) {
    o.base_ = nullptr, o.map_ = 0, o.words_ = nullptr, o.n_ = 0;
  }
  ~VertexTableWords() { release(); }

  // Contract: the table is n words, all zero (what it held is gone).
  void assign_zero(size_t n) {
    if (n == n_) {
      if (n) std::memset(words_, 0, n * kVertexTableWordBytes);
      return;
    }
    release();
    if (n) allocate(n);
  }
  uint64_t* data() const { return words_; }
  size_t size() const { return n_; }

 private:
  void allocate(size_t n) {
    const size_t bytes = n * kVertexTableWordBytes;
#if defined(__linux__)
    // Anonymous memory is zero. Mapped with one huge page to spare, so that the words start on a
    // 2 MB boundary and every 2 MB of them can be one page.
    const size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    const size_t map = rounded + kHugePageBytes;
    void* p = mmap(nullptr, map, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    const uintptr_t a = (reinterpret_cast<uintptr_t>(p) + kHugePageBytes - 1) & ~(uintptr_t)(kHugePageBytes - 1);
    madvise(reinterpret_cast<void*>(a), rounded, MADV_HUGEPAGE);  // a hint: its failure changes nothing
    base_ = p, map_ = map;
    words_ = reinterpret_cast<uint64_t*>(a);
#else
    base_ = std::calloc(n, kVertexTableWordBytes);
    if (!base_) throw std::bad_alloc();
    words_ = static_cast<uint64_t*>(base_);
#endif
    n_ = n;
  }
  void release() {
#if defined(__linux__)
    if (base_) munmap(base_, map_);
#else
    std::free(base_);
#endif
    base_ = nullptr, map_ = 0, words_ = nullptr, n_ = 0;
  }
  void* base_ = nullptr;
  size_t map_ = 0;
  uint64_t* words_ = nullptr;
  size_t n_ = 0;
};

// The table a VertexCache that has no shared table uses from draw to draw on its thread (one per
// thread, lent to one cache at a time: a second cache alive on the thread allocates its own). A
// new epoch per draw empties it where a table allocated and zero-filled per draw cost 2.2 % of
// the bunny's v2 profile (std::vector's fill) plus its page faults (docs/speed.md "Session 11:
// per triangle"). Its words are cleared when the slot layout changes or the epochs wrap. It keeps
// up to kVertexCacheBytes per thread that drew a mesh until the thread ends.
struct KeptVertexTable {
  VertexTableWords words;
  size_t stride = 0;  // the slot layout of the words (VertexCache::layout), 0: none yet
  int bits = -1;
  uint32_t epoch = 0;  // the last draw's
  bool lent = false;   // a cache uses it
};
inline KeptVertexTable& kept_vertex_table() {
  thread_local KeptVertexTable t;
  return t;
}

// A table of vertex-cache slots that several VertexCaches share (VertexCache::share: the threads
// of model/unit/threads.cpp, one cache object each), kept from draw to draw. begin() before each
// draw empties it: a new epoch, written into every slot filled during the draw, makes the slots
// of earlier draws empty; the words are cleared only when the slot layout (the varying count)
// changes or the epochs wrap. Used by one draw at a time.
class SharedVertexTable {
 public:
  // rw_unread: no reader of the draw's triangles reads SetupVertex::rw (VertexCache::set_rw_unread's
  // condition); every cache sharing the table in this draw then leaves rw = 0 with separate
  // attribute positions, as one that does not share (the flag is the table's, so the caches that
  // write and read its slots agree; a slot of an earlier draw reads as empty: the epoch).
  void begin(int num_varyings, bool rw_unread = false) {
    const size_t words = kVertexCacheBytes / kVertexTableWordBytes;
    if (words_.size() != words || nv_ != num_varyings || epoch_ == kVertexTableMaxEpoch) {
      words_.assign_zero(words);
      epoch_ = 0;
      nv_ = num_varyings;
    }
    ++epoch_;
    rw_unread_ = rw_unread;
  }

 private:
  friend class VertexCache;
  VertexTableWords words_;
  int nv_ = -1;
  uint32_t epoch_ = 0;
  bool rw_unread_ = false;
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
  // `out` is then the triangle stages 1–4 emit for it (prim set; the varyings past nv are never
  // written: keep `out` from a default SetupTriangle, whose zeros are what snap_vertex writes).
  // false: nothing is known (`out` may be partly written), the caller runs the full chain.
  // Counts hits and misses per vertex looked up.
  bool triangle(const InputTriangle& in, SetupTriangle& out) { return triangle(in.tri, in.prim, out); }
  // The same for primitive `prim` with vertices `tri`.
  bool triangle(const ClipTriangle& tri, uint32_t prim, SetupTriangle& out) {
    if (!usable_) return false;
    if (++prims_ <= min_prims_) return false;
    if (!table_) allocate();
    // The slots prefetch() located for this triangle (its ring entry, used once), else located
    // and requested here, all three before any is read (their cache misses overlap).
    unsigned char* slot[3];
    if (!take_prefetched(tri, slot))
      for (int i = 0; i < 3; ++i) {
        slot[i] = slot_of(tri.v[i]);
        prefetch_slot(slot[i]);
      }
    for (int i = 0; i < 3; ++i)
      if (!vertex(tri.v[i], slot[i], out.v[i])) return false;
    out.prim = prim;
    return true;
  }

  // Contract: a hint without effect on any answer or counter: locates the slots of the vertices
  // of `tri` (a later triangle of the draw) and prefetches them, so that triangle() for it finds
  // them in the cache (docs/speed.md "Session 9: per triangle": the table's memory latency was
  // most of a hit's cost). Nothing before the table exists (the first kVertexCacheMinPrims).
  // The slot numbers are kept in a ring of kPrefetchRing entries tagged with the address of
  // `tri`: triangle() on the same ClipTriangle object takes them instead of hashing its keys a
  // second time (docs/speed.md "Session 10: per triangle"). They are hints too: triangle()
  // compares the key in the slot, and a slot only ever holds accepted_vertex of the key written
  // in it, so a stale entry (the object rewritten between the two calls) cannot change an
  // answer; at most a hit or miss counter.
  void prefetch(const ClipTriangle& tri) {
    if (!table_) return;
    Pending& e = ring_[ring_next_++ % kPrefetchRing];
    e.tri = &tri;
    for (int i = 0; i < 3; ++i) {
      e.slot[i] = (uint32_t)index(tri.v[i]);
      prefetch_slot(reinterpret_cast<const unsigned char*>(table_ + e.slot[i] * stride_));
    }
  }

  // Contract: this cache looks up and fills `table` (begun for this draw's varying count) instead
  // of a table of its own, with any number of other caches at the same time, each from one
  // thread. A slot is read and written under its sequence number (a seqlock): one being written,
  // or rewritten while it was read, counts as a miss, computed here and not stored. The answers
  // are those of an unshared cache (a slot only ever holds accepted_vertex of its key), so a
  // draw's output does not depend on how its threads interleave.
  void share(SharedVertexTable& table) {
    if (!usable_ || table.nv_ != nv_) return;  // (a table begun for another draw: not shared)
    layout(table.words_.size() * kVertexTableWordBytes);
    forget_prefetched();
    kept_.release();
    table_ = table.words_.data();
    epoch_ = table.epoch_;
    rw_unread_ = table.rw_unread_;
    shared_ = true;
  }

  // Contract: the caller reads no SetupVertex::rw of this cache's triangles (UnitChain when its
  // setup builds no 1/w plane: no sink or no varyings). With separate attribute positions the
  // triangles then carry rw = 0 where stages 1–4 emit the exact 1/w_c (a division per vertex
  // computed: model only what a scene needs, docs/speed.md "Session 12: per triangle"); every
  // other field and every answer are unchanged. Before the first triangle. A cache that shares a
  // table (share()) takes the table's flag instead (SharedVertexTable::begin: the caches that
  // write and read its slots agree) and ignores this.
  void set_rw_unread(bool unread) {
    if (!shared_) rw_unread_ = unread;
  }

  uint64_t hits() const { return hits_; }
  uint64_t misses() const { return misses_; }
  // True when this cache looks up its thread's KeptVertexTable (false: none yet, its own table,
  // or a shared one). For the tests, which run a kept table against an own one.
  bool uses_kept_table() const { return kept_.table != nullptr; }

 private:
  // A slot's state: epoch · 4 + kAccepted / kNotAccepted (epoch 0 in a table of its own), or kEmpty.
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

  static constexpr size_t kWordBytes = kVertexTableWordBytes;
  static constexpr size_t round_up_to_word(size_t bytes) { return vertex_table_words(bytes) * kWordBytes; }
  static constexpr size_t kMaxSlotWords =
      vertex_slot_stride_bytes(vertex_table_words(kKeyOffset + (4 + kMaxVaryings) * sizeof(uint32_t)) * kWordBytes +
                             kMaxVaryings * sizeof(FxFloat)) / kWordBytes;
  static_assert(kKeyOffset % kWordBytes == 0, "the key words start on a table word");

  // The slot layout of nv_ varyings, in a table of at most `bytes`.
  void layout(size_t bytes) {
    kw_ = 4 + (size_t)nv_;
    vw_offset_ = round_up_to_word(kKeyOffset + kw_ * sizeof(uint32_t));
    used_ = round_up_to_word(vw_offset_ + (size_t)nv_ * sizeof(FxFloat)) / kWordBytes;  // in words
    stride_ = vertex_slot_stride_bytes(used_ * kWordBytes) / kWordBytes;
    while (bits_ > 8 && ((stride_ * kWordBytes) << bits_) > bytes) --bits_;
  }
  // The table of a cache without a shared one: its thread's KeptVertexTable at a new epoch (its
  // slots of earlier draws read as empty: filled() compares the epoch), or, when another cache
  // of the thread holds that, a table of its own (zero: state kEmpty, epoch 0).
  void allocate() {
    layout(kVertexCacheBytes);
    forget_prefetched();
    const size_t words = stride_ << bits_;
    KeptVertexTable& k = kept_vertex_table();
    if (!k.lent) {
      if (k.words.size() != words || k.stride != stride_ || k.bits != bits_ || k.epoch == kVertexTableMaxEpoch) {
        k.words.assign_zero(words);
        k.stride = stride_, k.bits = bits_, k.epoch = 0;
      }
      epoch_ = ++k.epoch;
      k.lent = true;
      kept_.table = &k;
      table_ = k.words.data();
      return;
    }
    buf_.assign_zero(words);
    table_ = buf_.data();
  }
  // The kept table lent to this cache (released when the cache ends or shares a table). Move-only.
  struct KeptLease {
    KeptVertexTable* table = nullptr;
    KeptLease() = default;
    KeptLease(const KeptLease&) = delete;
    KeptLease& operator=(const KeptLease&) = delete;
    KeptLease(KeptLease&& o) noexcept : table(o.table) { o.table = nullptr; }
    ~KeptLease() { release(); }
    void release() {
      if (table) table->lent = false;
      table = nullptr;
    }
  };
  bool filled(uint32_t state) const { return state != kEmpty && state >> 2 == epoch_; }
  // A vertex's key words are its float32 bits in place: pos[0 … 3], then var[0 … nv) (the
  // words past 4 + nv_ are never read). Neither compared nor hashed through a copy (an 80-byte
  // copy of the key to the stack per vertex, read back at once: docs/speed.md "Session 10").
  static_assert(offsetof(ClipVertex, var) == sizeof(ClipVertex::pos) &&
                    sizeof(ClipVertex::pos) == 4 * sizeof(uint32_t) && sizeof(float) == sizeof(uint32_t),
                "a vertex's key words are contiguous");
  static const unsigned char* key_bytes(const ClipVertex& cv) { return reinterpret_cast<const unsigned char*>(&cv); }
  static uint32_t key_word(const unsigned char* k, size_t w) {
    uint32_t v;
    std::memcpy(&v, k + w * sizeof(uint32_t), sizeof(uint32_t));
    return v;
  }
  // The slot's key words equal the vertex's (a loop over the 4 + nv words: std::memcmp of a
  // run-time length stayed a libc call, 3 % of the bunny's profile).
  bool same_key(const unsigned char* slot, const ClipVertex& cv) const {
    const unsigned char* k = slot + kKeyOffset;
    const unsigned char* c = key_bytes(cv);
    for (size_t w = 0; w < kw_; ++w)
      if (key_word(k, w) != key_word(c, w)) return false;
    return true;
  }

  // n units of kUnit bytes: a fixed-size copy (inline moves) for n ≤ 8, where a std::memcpy of a
  // run-time length is a libc call (the key and varying copies: 2.5 % of the bunny's profile).
  template <size_t kUnit>
  __attribute__((always_inline)) static void copy_units(void* dst, const void* src, size_t n) {
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
  void copy_varyings_to(unsigned char* to, const FxFloat* vw) const {
    copy_units<sizeof(FxFloat)>(to, vw, (size_t)nv_);
  }
  // The slot number of vertex `cv` (a multiplicative hash of its key words).
  size_t index(const ClipVertex& cv) const {
    const unsigned char* k = key_bytes(cv);
    uint64_t h = 0;
    for (size_t w = 0; w < kw_; ++w) h = (h ^ key_word(k, w)) * 0x9E3779B97F4A7C15ull;
    return bits_ > 0 ? (size_t)(h >> (64 - bits_)) : 0;
  }
  unsigned char* slot_of(const ClipVertex& cv) const {
    return reinterpret_cast<unsigned char*>(table_ + index(cv) * stride_);
  }
  // Every cache line of a slot (the head, key and varyings are all read on a hit; a stride of
  // half lines: the same count of lines for every slot).
  void prefetch_slot(const unsigned char* slot) const {
    const uintptr_t last = reinterpret_cast<uintptr_t>(slot) + used_ * kWordBytes - 1;
    for (uintptr_t line = reinterpret_cast<uintptr_t>(slot) & ~(uintptr_t)(kCacheLine - 1); line <= last;
         line += kCacheLine)
      __builtin_prefetch(reinterpret_cast<const void*>(line));
  }
  static constexpr size_t kCacheLine = 64;

  // The ring of slot numbers prefetch() located: the primitives ahead of the one drawn
  // (kVertexCachePrefetchAhead, plus the one being looked up).
  static constexpr unsigned kPrefetchRing = 4;
  static_assert(kPrefetchRing >= kVertexCachePrefetchAhead + 1, "a prefetched triangle's entry outlives its wait");
  struct Pending {
    const ClipTriangle* tri = nullptr;
    uint32_t slot[3] = {0, 0, 0};
  };
  // The slots of `tri` from its ring entry (which is then cleared); false when there is none.
  bool take_prefetched(const ClipTriangle& tri, unsigned char* slot[3]) {
    for (Pending& e : ring_)
      if (e.tri == &tri) {
        e.tri = nullptr;
        for (int i = 0; i < 3; ++i) slot[i] = reinterpret_cast<unsigned char*>(table_ + e.slot[i] * stride_);
        return true;
      }
    return false;
  }
  void forget_prefetched() {
    for (Pending& e : ring_) e.tri = nullptr;
  }

  bool vertex(const ClipVertex& cv, unsigned char* slot, SetupVertex& out) {
    if (shared_) return vertex_shared(cv, reinterpret_cast<uint64_t*>(slot), out);
    uint32_t state;
    std::memcpy(&state, slot, sizeof(state));
    if (filled(state) && same_key(slot, cv)) {
      ++hits_;
      if ((state & 3) != kAccepted) return false;
      // Field by field from the slot (a copy of the whole head to the stack, read back in other
      // widths, stalled on store forwarding: a quarter of the hit path's samples).
      read_head(slot, out);
      copy_varyings(out.vw, slot + vw_offset_);
      return true;
    }
    ++misses_;
    copy_units<sizeof(uint32_t)>(slot + kKeyOffset, key_bytes(cv), kw_);
    const bool ok = accepted_vertex(cfg_, st_, gb_, cv, out, scratch_, recip_unit(), rw_unread_);
    write_head(slot, ok, out);  // seq stays 0 in a table of one cache
    return ok;
  }
  // The SetupVertex fields of a slot's head (`h`: the slot, or a copy of it).
  static void read_head(const unsigned char* h, SetupVertex& out) {
    std::memcpy(&out.x, h + offsetof(Head, x), sizeof(out.x));
    std::memcpy(&out.y, h + offsetof(Head, y), sizeof(out.y));
    std::memcpy(&out.ax, h + offsetof(Head, ax), sizeof(out.ax));
    std::memcpy(&out.ay, h + offsetof(Head, ay), sizeof(out.ay));
    std::memcpy(&out.z, h + offsetof(Head, z), sizeof(out.z));
    std::memcpy(&out.rw, h + offsetof(Head, rw), sizeof(out.rw));
  }

  // The head and varyings of a slot holding accepted_vertex's answer `ok`, `out` (its key
  // words are written by the caller).
  // A slot's state, head fields and varyings (`h`: the slot, or a copy of it), the one writer of
  // the layout read_head reads: field by field (a Head built on the stack and copied whole
  // stalled on store forwarding, docs/speed.md "Session 10: per triangle"). seq is left as it is.
  void write_head(unsigned char* h, bool ok, const SetupVertex& out) const {
    const uint32_t state = epoch_ << 2 | (ok ? kAccepted : kNotAccepted);
    std::memcpy(h + offsetof(Head, state), &state, sizeof(state));
    if (ok) {
      std::memcpy(h + offsetof(Head, x), &out.x, sizeof(out.x));
      std::memcpy(h + offsetof(Head, y), &out.y, sizeof(out.y));
      std::memcpy(h + offsetof(Head, ax), &out.ax, sizeof(out.ax));
      std::memcpy(h + offsetof(Head, ay), &out.ay, sizeof(out.ay));
      std::memcpy(h + offsetof(Head, z), &out.z, sizeof(out.z));
      std::memcpy(h + offsetof(Head, rw), &out.rw, sizeof(out.rw));
      copy_varyings_to(h + vw_offset_, out.vw);
    }
  }

  // vertex() on a shared table: the slot's words are read with atomic loads between two loads of
  // its head word (equal, with an even sequence number: a consistent read), and written by the
  // thread that moved the sequence number from the even value it read to odd (then even again
  // with the new state). Others' writes are never waited for: a miss. The key words are
  // compared as they are loaded, and the rest of the slot is copied only when they are the
  // vertex's (a whole-slot copy before the compare was 21 M instructions per bunny frame,
  // docs/speed.md "Session 9: threads"). A slot's padding after an odd number of key words is
  // zero (the writer's copy is zeroed first), so the key compares as table words.
  bool vertex_shared(const ClipVertex& cv, uint64_t* slot, SetupVertex& out) {
    uint64_t copy[kMaxSlotWords];
    const uint64_t w0 = __atomic_load_n(slot, __ATOMIC_ACQUIRE);
    uint32_t state_seq[2];  // the head's first word: state, seq
    std::memcpy(state_seq, &w0, sizeof(uint64_t));
    const uint32_t state = state_seq[0], seq = state_seq[1];
    const bool idle = (seq & 1) == 0;
    if (idle && filled(state) && same_key_shared(slot, cv)) {
      copy[0] = w0;
      for (size_t k = 1; k < kKeyOffset / kWordBytes; ++k) copy[k] = __atomic_load_n(slot + k, __ATOMIC_RELAXED);
      for (size_t k = vw_offset_ / kWordBytes; k < used_; ++k) copy[k] = __atomic_load_n(slot + k, __ATOMIC_RELAXED);
      __atomic_thread_fence(__ATOMIC_ACQUIRE);
      if (__atomic_load_n(slot, __ATOMIC_RELAXED) == w0) {  // nothing written since w0: the key compare held
        ++hits_;
        if ((state & 3) != kAccepted) return false;
        const unsigned char* c = reinterpret_cast<const unsigned char*>(copy);
        read_head(c, out);
        copy_varyings(out.vw, c + vw_offset_);
        return true;
      }
    }
    ++misses_;
    const bool ok = accepted_vertex(cfg_, st_, gb_, cv, out, scratch_, recip_unit(), rw_unread_);
    uint64_t expect = w0, busy;
    state_seq[1] = seq + 1;  // odd: being written
    std::memcpy(&busy, state_seq, sizeof(uint64_t));
    if (!idle || !__atomic_compare_exchange_n(slot, &expect, busy, false, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED))
      return ok;  // another thread writes the slot
    __atomic_thread_fence(__ATOMIC_RELEASE);
    std::memset(copy, 0, used_ * kWordBytes);
    unsigned char* c = reinterpret_cast<unsigned char*>(copy);
    std::memcpy(c + kKeyOffset, key_bytes(cv), kw_ * sizeof(uint32_t));
    write_head(c, ok, out);
    const uint32_t next_seq = seq + 2;  // even again: written
    std::memcpy(c + offsetof(Head, seq), &next_seq, sizeof(next_seq));
    for (size_t k = 1; k < used_; ++k) __atomic_store_n(slot + k, copy[k], __ATOMIC_RELAXED);
    __atomic_store_n(slot, copy[0], __ATOMIC_RELEASE);
    return ok;
  }
  // The shared slot's key words (atomic loads of table words) equal the vertex's.
  bool same_key_shared(const uint64_t* slot, const ClipVertex& cv) const {
    const unsigned char* c = key_bytes(cv);
    const uint64_t* k = slot + kKeyOffset / kWordBytes;
    const size_t pairs = kw_ / 2;
    for (size_t j = 0; j < pairs; ++j) {
      uint64_t v;
      std::memcpy(&v, c + j * kWordBytes, kWordBytes);
      if (__atomic_load_n(k + j, __ATOMIC_RELAXED) != v) return false;
    }
    if (kw_ % 2 == 0) return true;
    uint64_t last = 0;  // the odd last key word, then the zero padding
    std::memcpy(&last, c + pairs * kWordBytes, sizeof(uint32_t));
    return __atomic_load_n(k + pairs, __ATOMIC_RELAXED) == last;
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
  size_t used_ = 0;  // the words of a slot in use (the stride's padding past them is never read)
  VertexTableWords buf_;  // the table, when neither shared nor the thread's kept one
  KeptLease kept_;
  uint64_t* table_ = nullptr;
  uint32_t epoch_ = 0;
  bool shared_ = false;
  Pending ring_[kPrefetchRing];
  unsigned ring_next_ = 0;
  ClipVtx scratch_;  // accepted_vertex's working vertex
  bool rw_unread_ = false;  // set_rw_unread, or a shared table's (SharedVertexTable::begin)
  // The reciprocal unit of the draw, made at the first vertex computed (a cache is set up per
  // primitive by fxr::geometry(): the unit's seed table is not built for nothing).
  std::unique_ptr<RecipUnit> recip_;
  const RecipUnit* recip_unit() {
    if (!recip_) recip_ = std::make_unique<RecipUnit>(cfg_.recip);
    return recip_.get();
  }
};

}  // namespace fxr

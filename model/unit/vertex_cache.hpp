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

// Contract: true when `in`, as a vertex of a triangle whose three vertices all return true,
// passes stages 1–4 unchanged by the clipper: positions finite, no active varying replaced,
// strictly inside no clip plane's outside (outcode 0), a reciprocal without error, a snapped
// position in range; `out` is then its SetupVertex (varyings past nv zero, as snap_vertex).
inline bool accepted_vertex(const Config& cfg, const DrawState& st, const GuardBand& gb, const ClipVertex& in,
                            SetupVertex& out) {
  ClipVtx v;
  bool nan = false, inf = false, replaced = false;
  convert_vertex(in, st.num_varyings, v, nan, inf, replaced);
  if (nan || inf || replaced || outcode(gb, v) != 0) return false;
  FxFloat r;
  return recip_vertex(cfg.recip, v, r) && snap_vertex(cfg, st, v, r, out) == ProjectStatus::Ok;
}

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
  // `out` is then the triangle stages 1–4 emit for it (prim set; the varyings past nv are not
  // written: zero in a default SetupTriangle, as snap_vertex leaves them). false: nothing is
  // known, the caller runs the full chain. Counts hits and misses per vertex looked up.
  bool triangle(const InputTriangle& in, SetupTriangle& out) {
    if (!usable_) return false;
    if (++prims_ <= min_prims_) return false;
    if (slots_.empty()) allocate();
    for (int i = 0; i < 3; ++i)
      if (!vertex(in.tri.v[i], out.v[i])) return false;
    out.prim = in.prim;
    return true;
  }

  uint64_t hits() const { return hits_; }
  uint64_t misses() const { return misses_; }

 private:
  enum : uint8_t { kEmpty = 0, kAccepted = 1, kNotAccepted = 2 };
  struct Slot {
    uint8_t state = kEmpty;
    int64_t x = 0, y = 0, ax = 0, ay = 0;
    uint64_t z = 0;
    FxFloat rw;
  };

  void allocate() {
    kw_ = 4 + (size_t)nv_;
    const size_t slot_bytes = sizeof(Slot) + kw_ * sizeof(uint32_t) + (size_t)nv_ * sizeof(FxFloat);
    while (bits_ > 8 && (slot_bytes << bits_) > kVertexCacheBytes) --bits_;
    const size_t n = (size_t)1 << bits_;
    slots_.assign(n, Slot{});
    keys_.assign(n * kw_, 0);
    vw_.assign(n * (size_t)nv_, FxFloat{});
  }

  bool vertex(const ClipVertex& cv, SetupVertex& out) {
    uint32_t key[4 + kMaxVaryings];
    std::memcpy(key, cv.pos, sizeof(float) * 4);
    std::memcpy(key + 4, cv.var, sizeof(float) * (size_t)nv_);
    uint64_t h = 0;
    for (size_t k = 0; k < kw_; ++k) h = (h ^ key[k]) * 0x9E3779B97F4A7C15ull;
    const size_t i = bits_ > 0 ? (size_t)(h >> (64 - bits_)) : 0;
    Slot& s = slots_[i];
    uint32_t* sk = &keys_[i * kw_];
    FxFloat* svw = &vw_[i * (size_t)nv_];
    if (s.state != kEmpty && std::memcmp(sk, key, kw_ * sizeof(uint32_t)) == 0) {
      ++hits_;
    } else {
      ++misses_;
      std::memcpy(sk, key, kw_ * sizeof(uint32_t));
      SetupVertex v;
      s.state = accepted_vertex(cfg_, st_, gb_, cv, v) ? kAccepted : kNotAccepted;
      if (s.state == kAccepted) {
        s.x = v.x, s.y = v.y, s.ax = v.ax, s.ay = v.ay, s.z = v.z, s.rw = v.rw;
        for (int k = 0; k < nv_; ++k) svw[k] = v.vw[k];
      }
    }
    if (s.state != kAccepted) return false;
    out.x = s.x, out.y = s.y, out.ax = s.ax, out.ay = s.ay, out.z = s.z, out.rw = s.rw;
    for (int k = 0; k < nv_; ++k) out.vw[k] = svw[k];
    return true;
  }

  const Config& cfg_;
  const DrawState& st_;
  GuardBand gb_;
  int nv_;
  bool usable_;
  uint64_t min_prims_;
  uint64_t prims_ = 0, hits_ = 0, misses_ = 0;
  int bits_;
  size_t kw_ = 4;
  std::vector<Slot> slots_;
  std::vector<uint32_t> keys_;
  std::vector<FxFloat> vw_;
};

}  // namespace fxr

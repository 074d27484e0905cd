// The external peer (Mesa llvmpipe through OSMesa) against exact integer coverage and, where
// the model is built, against the model. Expected coverage comes from exact integer edge
// functions on the 1/256 grid (written here, independent of the model and of Mesa).
//
// If no OSMesa context can be created the tests FAIL (PeerError), unless FXR_NO_PEER is set,
// in which case they are skipped with a message.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "reference/float_raster.hpp"
#include "reference/peer/peer_osmesa.hpp"
#include "reference/peer/peer_scenes.hpp"
#include "model/unit/raster_unit.hpp"

using namespace fxr;
using namespace fxr::peer;

namespace {

// llvmpipe's subpixel grid: 8 fraction bits (GL_SUBPIXEL_BITS, checked below;
// docs/references.md#peer-fill-rule).
constexpr int kPeerSubpixelBits = 8;
constexpr int64_t kSub = int64_t(1) << kPeerSubpixelBits;
constexpr int64_t kHalfPixel = kSub / 2;

// ---- the peer, one per fill-rule mirror setting, shared by the whole binary -----------------

OsmesaPeer* get_peer(bool mirror) {
  static std::unique_ptr<OsmesaPeer> peers[2];
  std::unique_ptr<OsmesaPeer>& p = peers[mirror ? 1 : 0];
  if (!p) {
    PeerOptions opt;
    opt.mirror_y = mirror;
    p.reset(new OsmesaPeer(opt));  // throws PeerError: the test fails loudly
  }
  return p.get();
}

bool peer_disabled() { return std::getenv("FXR_NO_PEER") != nullptr; }

#define FXR_PEER_OR_SKIP(var, mirror)                                             \
  if (peer_disabled()) GTEST_SKIP() << "FXR_NO_PEER is set: peer tests skipped"; \
  OsmesaPeer* var = nullptr;                                                      \
  try {                                                                           \
    var = get_peer(mirror);                                                       \
  } catch (const PeerError& e) {                                                  \
    FAIL() << "no Mesa peer: " << e.what() << " (set FXR_NO_PEER to skip)";       \
  }

// ---- orthographic scenes on the 1/256 grid ---------------------------------------------------

// Window coordinates in 1/256 px, y up (row 0 at the bottom).
struct GridTri {
  int64_t x[3], y[3];
};

// Clip coordinates with w = 1 whose window coordinates are exactly X / 256: x_c = 2(X/256 − vx)/vw − 1.
// Exact in float32 for power-of-two viewport sizes and |X| < 2^20 (checked).
ClipTriangle to_clip(const GridTri& g, const DrawState& st) {
  ClipTriangle t;
  for (int i = 0; i < 3; ++i) {
    const double xn = 2.0 * ((double)g.x[i] / kSub - st.viewport_x) / st.viewport_w - 1.0;
    const double yn = 2.0 * ((double)g.y[i] / kSub - st.viewport_y) / st.viewport_h - 1.0;
    t.v[i].pos[0] = (float)xn;
    t.v[i].pos[1] = (float)yn;
    t.v[i].pos[2] = 0.5f;
    t.v[i].pos[3] = 1.0f;
    if ((double)t.v[i].pos[0] != xn || (double)t.v[i].pos[1] != yn) {
      ADD_FAILURE() << "scene vertex not exact in float32: " << g.x[i] << "," << g.y[i];
    }
    t.v[i].var[0] = (float)i;
  }
  return t;
}

enum class FillRule { TopLeft, BottomLeft };

// Exact coverage count per pixel (row 0 at the bottom): pixel centre (256·px + 128, 256·py + 128),
// inside when every edge function is > 0, or == 0 on an inclusive edge. Zero-area triangles
// cover nothing. int64 is exact: coordinates < 2^20, products < 2^42.
std::vector<uint32_t> exact_count(const std::vector<GridTri>& tris, int W, int H, FillRule rule) {
  std::vector<uint32_t> cnt((size_t)W * H, 0);
  for (const GridTri& g : tris) {
    int64_t X[3] = {g.x[0], g.x[1], g.x[2]}, Y[3] = {g.y[0], g.y[1], g.y[2]};
    const int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
    if (area == 0) continue;
    if (area < 0) {  // counter-clockwise (y up)
      std::swap(X[1], X[2]);
      std::swap(Y[1], Y[2]);
    }
    int64_t dx[3], dy[3];
    bool incl[3];
    for (int i = 0; i < 3; ++i) {
      const int a = (i + 1) % 3, b = (i + 2) % 3;
      dx[i] = X[b] - X[a];
      dy[i] = Y[b] - Y[a];
      const bool left = dy[i] < 0;  // counter-clockwise, y up: left edges run downwards
      const bool top = dy[i] == 0 && dx[i] < 0, bottom = dy[i] == 0 && dx[i] > 0;
      incl[i] = left || (rule == FillRule::TopLeft ? top : bottom);
    }
    // Pixels whose centre lies in the closed bounding box, clamped to the image.
    const auto lo = [](int64_t v) { return (int)std::max<int64_t>(0, (v - kHalfPixel + kSub - 1) / kSub); };
    const auto hi = [](int64_t v, int n) { return (int)std::min<int64_t>(n - 1, (v - kHalfPixel) / kSub); };
    const int x0 = lo(std::min({X[0], X[1], X[2]})), x1 = hi(std::max({X[0], X[1], X[2]}), W);
    const int y0 = lo(std::min({Y[0], Y[1], Y[2]})), y1 = hi(std::max({Y[0], Y[1], Y[2]}), H);
    for (int py = y0; py <= y1; ++py)
      for (int px = x0; px <= x1; ++px) {
        const int64_t cx = px * kSub + kHalfPixel, cy = py * kSub + kHalfPixel;
        bool in = true;
        for (int i = 0; i < 3 && in; ++i) {
          const int a = (i + 1) % 3;
          const int64_t e = dx[i] * (cy - Y[a]) - dy[i] * (cx - X[a]);
          in = e > 0 || (e == 0 && incl[i]);
        }
        if (in) ++cnt[(size_t)py * W + px];
      }
  }
  return cnt;
}

struct GridScene {
  std::string name;
  DrawState st;
  std::vector<GridTri> tris;
};

DrawState ortho_state(int vx, int vy, int vw, int vh) {
  DrawState st;
  st.viewport_x = vx;
  st.viewport_y = vy;
  st.viewport_w = vw;
  st.viewport_h = vh;
  st.depth_test = false;  // count every covering triangle
  st.num_varyings = 0;
  return st;
}

// n triangles around a centre (cx, cy) (1/256 px), rim on a circle of radius r px rounded to the grid.
std::vector<GridTri> fan(int64_t cx, int64_t cy, double r, int n) {
  std::vector<GridTri> out;
  std::vector<int64_t> rx(n), ry(n);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    rx[i] = cx + std::llround(r * kSub * std::cos(a));
    ry[i] = cy + std::llround(r * kSub * std::sin(a));
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    out.push_back({{cx, rx[i], rx[j]}, {cy, ry[i], ry[j]}});
  }
  return out;
}

// cells × cells quads of `cell` (1/256 px) from (x0, y0), split along alternating diagonals,
// alternating windings.
std::vector<GridTri> grid(int64_t x0, int64_t y0, int64_t cell, int cells) {
  std::vector<GridTri> out;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int64_t xa = x0 + i * cell, xb = xa + cell, ya = y0 + j * cell, yb = ya + cell;
      if ((i + j) % 2 == 0) {
        out.push_back({{xa, xb, xb}, {ya, ya, yb}});
        out.push_back({{xa, xa, xb}, {ya, yb, yb}});  // clockwise
      } else {
        out.push_back({{xa, xb, xa}, {ya, ya, yb}});
        out.push_back({{xb, xb, xa}, {ya, yb, yb}});
      }
    }
  return out;
}

std::vector<GridScene> ortho_scenes() {
  std::vector<GridScene> s;
  const int64_t P = kSub;  // one pixel
  // Fans: centre on a pixel centre and on a pixel corner; 257 and 1024 triangles.
  s.push_back({"fan_257_centre", ortho_state(0, 0, 256, 256), fan(128 * P + P / 2, 128 * P + P / 2, 100.3, 257)});
  s.push_back({"fan_257_corner", ortho_state(0, 0, 256, 256), fan(128 * P, 128 * P, 90.0, 257)});
  s.push_back({"fan_1024_offgrid", ortho_state(0, 0, 256, 256), fan(128 * P + 37, 127 * P + 201, 120.7, 1024)});
  // Grids whose edges run exactly through pixel centres (cell 7.5 px) and along pixel borders.
  s.push_back({"grid_pixel_centre_edges", ortho_state(0, 0, 256, 256), grid(P / 2, P / 2, 15 * P / 2, 32)});
  s.push_back({"grid_pixel_border_edges", ortho_state(0, 0, 256, 256), grid(3 * P, 5 * P, 8 * P, 30)});
  s.push_back({"grid_fine_offgrid", ortho_state(0, 0, 128, 128), grid(1 * P + 77, 2 * P + 13, 3 * P + 100, 40)});
  // Random triangles on the grid: a third snapped to pixel centres (ties everywhere).
  {
    std::mt19937_64 rng(0x5eed0001);
    GridScene r{"random_mixed", ortho_state(0, 0, 256, 256), {}};
    for (int t = 0; t < 3000; ++t) {
      const int kind = t % 3;
      const int64_t span = kind == 0 ? 4 * P : kind == 1 ? 40 * P : 256 * P;
      const int64_t bx = (int64_t)(rng() % (256 * P)), by = (int64_t)(rng() % (256 * P));
      GridTri g;
      for (int i = 0; i < 3; ++i) {
        int64_t x = bx + (int64_t)(rng() % span) - span / 2, y = by + (int64_t)(rng() % span) - span / 2;
        if (t % 2) {  // onto pixel centres
          x = (x / P) * P + P / 2;
          y = (y / P) * P + P / 2;
        }
        // Inside the viewport: llvmpipe clips at the viewport border (no guard band), which
        // moves vertices off the grid (docs/peer.md).
        x = std::clamp<int64_t>(x, 0, 256 * P);
        y = std::clamp<int64_t>(y, 0, 256 * P);
        g.x[i] = x;
        g.y[i] = y;
      }
      r.tris.push_back(g);
    }
    s.push_back(r);
  }
  // Axis-aligned right triangles with legs through pixel centres: every edge case of the rule.
  {
    GridScene r{"axis_aligned_ties", ortho_state(0, 0, 64, 64), {}};
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) {
        const int64_t x0 = (2 + 10 * i) * P + P / 2, y0 = (2 + 10 * j) * P + P / 2, d = (3 + (i + j) % 4) * P;
        const int o = (i + 6 * j) % 8;
        const int64_t sx = (o & 1) ? -1 : 1, sy = (o & 2) ? -1 : 1;
        GridTri g{{x0, x0 + sx * d, x0}, {y0, y0, y0 + sy * d}};
        if (o & 4) std::swap(g.x[1], g.x[2]), std::swap(g.y[1], g.y[2]);
        r.tris.push_back(g);
      }
    s.push_back(r);
  }
  // Slivers (aspect > 1000) and sub-pixel triangles.
  {
    std::mt19937_64 rng(0x5eed0002);
    GridScene r{"slivers_and_tiny", ortho_state(0, 0, 256, 256), {}};
    for (int t = 0; t < 500; ++t) {
      const int64_t x0 = (int64_t)(rng() % (250 * P)), y0 = (int64_t)(rng() % (250 * P));
      if (t % 2) {
        const int64_t len = 200 * P, off = 1 + (int64_t)(rng() % 40);
        r.tris.push_back({{x0 % (50 * P), x0 % (50 * P) + len, x0 % (50 * P) + len + off}, {y0, y0 + off, y0 + 2 * off}});
      } else {
        r.tris.push_back({{x0, x0 + (int64_t)(rng() % P), x0 + (int64_t)(rng() % P)},
                          {y0, y0 + (int64_t)(rng() % P), y0 + (int64_t)(rng() % P)}});
      }
    }
    s.push_back(r);
  }
  // Offset, non-square viewport; and a 1024² viewport.
  s.push_back({"viewport_offset", ortho_state(16, 8, 128, 64), fan((16 + 64) * P + 3, (8 + 32) * P + 100, 30.2, 300)});
  s.push_back({"fan_1024px", ortho_state(0, 0, 1024, 1024), fan(512 * P + P / 2, 512 * P, 500.0, 600)});
  return s;
}

std::string count_mismatches(const std::vector<uint32_t>& got, const std::vector<uint32_t>& exp, int W,
                             size_t* n_out) {
  std::string msg;
  size_t n = 0;
  for (size_t i = 0; i < exp.size(); ++i)
    if (got[i] != exp[i]) {
      if (++n <= 20)
        msg += "MISMATCH pixel=(" + std::to_string(i % W) + "," + std::to_string(i / W) +
               ") got=" + std::to_string(got[i]) + " exp=" + std::to_string(exp[i]) + "\n";
    }
  *n_out = n;
  return msg;
}

}  // namespace

TEST(Peer, ContextIsLlvmpipeWithClipControlAndEightSubpixelBits) {
  FXR_PEER_OR_SKIP(peer, true);
  const PeerInfo& in = peer->info();
  std::printf("peer: %s | %s | subpixel bits %d | max viewport %d\n", in.version.c_str(), in.renderer.c_str(),
              in.subpixel_bits, in.max_viewport);
  EXPECT_NE(in.renderer.find("llvmpipe"), std::string::npos);
  EXPECT_TRUE(in.clip_control);
  EXPECT_EQ(in.subpixel_bits, kPeerSubpixelBits);
}

// llvmpipe's own rule, unmirrored: left and bottom edges inclusive in y-up window coordinates.
TEST(Peer, UnmirroredFillRuleIsLeftBottom) {
  FXR_PEER_OR_SKIP(peer, false);
  for (const GridScene& s : ortho_scenes()) {
    std::vector<ClipTriangle> tris;
    for (const GridTri& g : s.tris) tris.push_back(to_clip(g, s.st));
    const PeerImage img = peer->render(s.st, tris);
    size_t n = 0;
    const std::string msg = count_mismatches(img.count, exact_count(s.tris, img.width, img.height, FillRule::BottomLeft),
                                             img.width, &n);
    EXPECT_EQ(n, 0u) << s.name << "\n" << msg;
  }
}

// Mirrored (the default): the peer's coverage is the exact top-left coverage, pixel for pixel,
// counts included (no pixel twice on shared edges, none missed).
TEST(Peer, MirroredCoverageEqualsExactTopLeftCoverageOnTheGrid) {
  FXR_PEER_OR_SKIP(peer, true);
  for (const GridScene& s : ortho_scenes()) {
    std::vector<ClipTriangle> tris;
    for (const GridTri& g : s.tris) tris.push_back(to_clip(g, s.st));
    const PeerImage img = peer->render(s.st, tris);
    const std::vector<uint32_t> exp = exact_count(s.tris, img.width, img.height, FillRule::TopLeft);
    size_t n = 0, covered = 0;
    const std::string msg = count_mismatches(img.count, exp, img.width, &n);
    for (uint32_t c : exp) covered += c != 0;
    std::printf("%-26s tris=%5zu covered=%7zu peer-vs-exact differences=%zu\n", s.name.c_str(), s.tris.size(), covered, n);
    EXPECT_EQ(n, 0u) << s.name << "\n" << msg;
  }
}

// The float baseline agrees with exact coverage where float32 edge functions are exact
// (integer-pixel vertices: products stay below 2^24).
TEST(FloatRaster, CoverageIsExactForIntegerPixelVertices) {
  for (const GridScene& s : ortho_scenes()) {
    if (s.name != "grid_pixel_border_edges" && s.name != "axis_aligned_ties") continue;
    std::vector<ClipTriangle> tris;
    for (const GridTri& g : s.tris) tris.push_back(to_clip(g, s.st));
    FloatFrame f;
    float_raster(s.st, tris, f);
    const std::vector<uint32_t> exp = exact_count(s.tris, f.width, f.height, FillRule::TopLeft);
    uint64_t n = 0;
    for (uint32_t c : exp) n += c;
    EXPECT_EQ(f.fragments_generated, n) << s.name;
  }
}

// ---- perspective scenes ----------------------------------------------------------------------

namespace {

// Round-to-nearest-even of a rational, exactly.
int64_t rne(const mpq_class& q) {
  mpz_class fl, rem;
  mpz_fdiv_qr(fl.get_mpz_t(), rem.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  const int c = cmp(mpz_class(2 * rem), q.get_den());
  if (c > 0 || (c == 0 && mpz_odd_p(fl.get_mpz_t()))) fl += 1;
  return fl.get_si();
}

// Exact window coordinate of a float32 clip coordinate, snapped to 1/256 px by RNE:
// RNE(256 · (v0 + (c / w + 1) · size / 2)), all in rationals.
int64_t exact_snap(float c, float w, int v0, int size) {
  const mpq_class q = mpq_class(kSub) * (mpq_class(v0) + (mpq_class(c) / mpq_class(w) + 1) * mpq_class(size, 2));
  return rne(q);
}

// True when the triangle needs no clipping against w > 0 and 0 ≤ z ≤ w (x, y are left to the
// guard band: the exact coverage is that of the whole triangle, cut to the image).
bool inside_depth_range(const ClipTriangle& t) {
  for (const ClipVertex& v : t.v)
    if (!(v.pos[3] > 0) || v.pos[2] < 0 || v.pos[2] > v.pos[3]) return false;
  return true;
}

GridTri exact_snapped(const ClipTriangle& t, const DrawState& st) {
  GridTri g;
  for (int i = 0; i < 3; ++i) {
    g.x[i] = exact_snap(t.v[i].pos[0], t.v[i].pos[3], st.viewport_x, st.viewport_w);
    g.y[i] = exact_snap(t.v[i].pos[1], t.v[i].pos[3], st.viewport_y, st.viewport_h);
  }
  return g;
}

constexpr int kDepth = -1;  // ref_varying's index for window depth

// Perspective-correct varying k (or window depth, k = kDepth) of triangle t at the centre of
// pixel (px, py), in double from
// window positions (snapped to the 1/256 grid when `snapped`, else unsnapped). The double
// rounding error (~1e-13 relative) is negligible at float32 scale.
double ref_varying(const ClipTriangle& t, const DrawState& st, int px, int py, int k, bool snapped) {
  double X[3], Y[3], rw[3];
  for (int i = 0; i < 3; ++i) {
    const ClipVertex& v = t.v[i];
    rw[i] = 1.0 / (double)v.pos[3];
    X[i] = st.viewport_x + ((double)v.pos[0] * rw[i] + 1) * st.viewport_w / 2;
    Y[i] = st.viewport_y + ((double)v.pos[1] * rw[i] + 1) * st.viewport_h / 2;
    if (snapped) {
      X[i] = std::nearbyint(X[i] * kSub) / kSub;
      Y[i] = std::nearbyint(Y[i] * kSub) / kSub;
    }
  }
  const double cx = px + 0.5, cy = py + 0.5;
  double l[3], num = 0, den = 0;
  for (int i = 0; i < 3; ++i) {
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    l[i] = (X[b] - X[a]) * (cy - Y[a]) - (Y[b] - Y[a]) * (cx - X[a]);
  }
  if (k == kDepth) {  // window z = z_c / w_c, linear in screen space
    for (int i = 0; i < 3; ++i) {
      num += l[i] * (double)t.v[i].pos[2] * rw[i];
      den += l[i];
    }
    return num / den;
  }
  for (int i = 0; i < 3; ++i) {
    num += l[i] * (double)t.v[i].var[k] * rw[i];
    den += l[i] * rw[i];
  }
  return num / den;
}

// Distance in float32 ulps (ordered bit patterns).
int64_t ulp_distance(float a, float b) {
  auto ord = [](float f) {
    const int32_t i = (int32_t)f32_bits(f);
    return i < 0 ? (int64_t)INT32_MIN - i : (int64_t)i;
  };
  return std::llabs(ord(a) - ord(b));
}

struct DiffStats {
  uint64_t n = 0;
  double max_abs = 0, sum_abs = 0;
  int64_t max_ulps = 0;
  std::vector<int64_t> ulps;
  void add(double got, double exp) {
    const double d = std::fabs(got - exp);
    ++n;
    max_abs = std::max(max_abs, d);
    sum_abs += d;
    const int64_t u = ulp_distance((float)got, (float)exp);
    max_ulps = std::max(max_ulps, u);
    ulps.push_back(u);
  }
  int64_t percentile_ulps(double p) {
    if (ulps.empty()) return 0;
    std::sort(ulps.begin(), ulps.end());
    return ulps[std::min(ulps.size() - 1, (size_t)(p * (double)ulps.size()))];
  }
  std::string str() {
    char b[256];
    std::snprintf(b, sizeof b, "n=%llu max_abs=%.3g mean_abs=%.3g ulps: p50=%lld p99=%lld max=%lld",
                  (unsigned long long)n, max_abs, n ? sum_abs / (double)n : 0.0, (long long)percentile_ulps(0.5),
                  (long long)percentile_ulps(0.99), (long long)max_ulps);
    return b;
  }
};

std::vector<PeerScene> perspective_scenes() {
  std::vector<PeerScene> s;
  s.push_back(grazing_plane_scene(512, 2));
  s.push_back(bunny_scene(512, 2));
  return s;
}

// docs/references.md#peer-disagreement: llvmpipe's perspective-correct varyings are off the
// exact value by up to 1.1e-3 for u, v in 0..16 across a grazing plane. Scenes here keep u, v
// in [0, 16].
constexpr double kLlvmpipeVaryingError = 1.1e-3;
constexpr float kUvMax = 16.0f;

// Perspective triangles whose vertices still land exactly on the 1/256 grid: w is a power of
// two (1 … 16) and x_c = x_ndc · w, y_c = y_ndc · w, z_c = z_ndc · w are exact, and so is the
// divide. Snapping then moves nothing, so exact references need no snapping model, and coverage
// must agree bit for bit. u, v ∈ [0, 16] random (seeded).
struct GridPerspectiveScene {
  DrawState st;
  std::vector<GridTri> grid;
  std::vector<ClipTriangle> tris;
};

GridPerspectiveScene grid_perspective_scene() {
  GridPerspectiveScene s;
  s.st = ortho_state(0, 0, 256, 256);
  s.st.num_varyings = 2;
  std::mt19937_64 rng(0x5eed0003);
  const int64_t span = 256 * kSub;
  std::uniform_real_distribution<float> uv(0.0f, kUvMax);
  for (int t = 0; t < 400; ++t) {
    GridTri g;
    ClipTriangle c;
    const int64_t size = t % 4 == 0 ? span : span / 8;
    const int64_t bx = (int64_t)(rng() % span), by = (int64_t)(rng() % span);
    for (int i = 0; i < 3; ++i) {
      g.x[i] = std::clamp<int64_t>(bx + (int64_t)(rng() % size) - size / 2, 0, span);
      g.y[i] = std::clamp<int64_t>(by + (int64_t)(rng() % size) - size / 2, 0, span);
    }
    const ClipTriangle o = to_clip(g, s.st);  // w = 1 clip coordinates of the grid points
    for (int i = 0; i < 3; ++i) {
      const float w = (float)(1 << (rng() % 5));
      c.v[i].pos[0] = o.v[i].pos[0] * w;
      c.v[i].pos[1] = o.v[i].pos[1] * w;
      c.v[i].pos[2] = (float)(rng() % 1024) / 1024.0f * w;
      c.v[i].pos[3] = w;
      c.v[i].var[0] = uv(rng);
      c.v[i].var[1] = uv(rng);
    }
    s.grid.push_back(g);
    s.tris.push_back(c);
  }
  return s;
}

size_t count_differences(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b, size_t* any) {
  size_t diff = 0;
  *any = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    *any += a[i] || b[i];
    diff += a[i] != b[i];
  }
  return diff;
}

}  // namespace


TEST(PeerPerspective, GridVerticesWithPowerOfTwoWCoverExactly) {
  FXR_PEER_OR_SKIP(peer, true);
  const GridPerspectiveScene s = grid_perspective_scene();
  const PeerImage img = peer->render(s.st, s.tris);
  size_t n = 0;
  const std::string msg =
      count_mismatches(img.count, exact_count(s.grid, img.width, img.height, FillRule::TopLeft), img.width, &n);
  std::printf("grid_perspective: tris=%zu fragments=%llu peer-vs-exact differences=%zu\n", s.tris.size(),
              (unsigned long long)img.fragments(), n);
  EXPECT_EQ(n, 0u) << msg;
}

// llvmpipe interpolates from the unsnapped float positions (its error against the exact value
// from unsnapped positions is ~10× smaller than against the exact value from snapped ones).
// The bound of docs/references.md#peer-disagreement (1.1e-3 for u, v in 0..16) was measured on a
// grazing plane: asserted there only; the other scenes are reported (random triangles with w
// ratios up to 16 exceed it).
TEST(PeerPerspective, GrazingPlaneVaryingsWithinAnchoredLlvmpipeErrorOfExact) {
  FXR_PEER_OR_SKIP(peer, true);
  std::vector<PeerScene> scenes = perspective_scenes();
  GridPerspectiveScene g = grid_perspective_scene();
  scenes.push_back({"grid_perspective", "", g.st, g.tris});
  for (PeerScene& s : scenes) {
    s.st.depth_test = true;
    const PeerImage img = peer->render(s.st, s.tris);
    DiffStats unsnapped[2], snapped[2];
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const int32_t p = img.prim[img.index(x, y)];
        if (p < 0) continue;
        for (int k = 0; k < 2; ++k) {
          unsnapped[k].add(img.varying(x, y, k), ref_varying(s.tris[p], s.st, x, y, k, false));
          snapped[k].add(img.varying(x, y, k), ref_varying(s.tris[p], s.st, x, y, k, true));
        }
      }
    for (int k = 0; k < 2; ++k) {
      std::printf("%-16s v%d peer vs exact(unsnapped positions): %s\n", s.name.c_str(), k, unsnapped[k].str().c_str());
      std::printf("%-16s v%d peer vs exact(snapped positions):   %s\n", s.name.c_str(), k, snapped[k].str().c_str());
      EXPECT_GT(unsnapped[k].n, 0u);
      if (s.name == "grazing_plane") {
        EXPECT_LE(unsnapped[k].max_abs, kLlvmpipeVaryingError) << s.name << " v" << k;
      }
    }
  }
}

// Clip-space scenes off the grid: llvmpipe snaps with a float32 divide and viewport transform,
// exact snapping is rational round-to-nearest-even (docs/references.md#snapping: they differ for
// about 3 % of vertices at 4096 px), so only near-total agreement is certain. Printed: the counts.
TEST(PeerPerspective, CoverageAgreesWithExactSnappedCoverage) {
  FXR_PEER_OR_SKIP(peer, true);
  for (const PeerScene& s : perspective_scenes()) {
    DrawState cst = s.st;
    cst.depth_test = false;
    const PeerImage cov = peer->render(cst, s.tris);
    std::vector<GridTri> g;
    for (const ClipTriangle& t : s.tris) {
      ASSERT_TRUE(inside_depth_range(t)) << s.name << ": scene needs near/far clipping";
      g.push_back(exact_snapped(t, s.st));
    }
    size_t any = 0;
    const size_t diff = count_differences(cov.count, exact_count(g, cov.width, cov.height, FillRule::TopLeft), &any);
    const double agree = 100.0 * (1.0 - (double)diff / (double)any);
    std::printf("%-16s tris=%zu pixels=%zu peer-vs-exact count differences=%zu agreement=%.4f%%\n", s.name.c_str(),
                s.tris.size(), any, diff, agree);
    EXPECT_GT(agree, 99.9) << s.name;
  }
}

// ---- the model against the peer --------------------------------------------------------------

namespace {

double fx_to_double(const FxFloat& f) {
  const double m = std::ldexp((double)f.sig, f.exp);  // exact for sig < 2^53
  return f.neg ? -m : m;
}

struct ModelImage {
  int width = 0, height = 0, num_varyings = 0;
  std::vector<uint32_t> count;
  std::vector<int32_t> prim;
  std::vector<double> var;
  std::vector<uint32_t> depth;  // unorm code of the fragment written last
  uint64_t fragments = 0;
};

// The model's fragments as an image like the peer's: per-pixel count, last primitive, its varyings.
// Fragment (x, y) are window pixels, row 0 at the bottom.
ModelImage model_image(const DrawState& st, const std::vector<ClipTriangle>& tris) {
  const Config cfg;
  const FrameOutput out = run_raster_unit(cfg, st, tris);
  ModelImage m;
  m.width = st.viewport_x + st.viewport_w;
  m.height = st.viewport_y + st.viewport_h;
  m.num_varyings = st.num_varyings;
  const size_t n = (size_t)m.width * m.height;
  m.count.assign(n, 0);
  m.prim.assign(n, -1);
  m.var.assign(n * (size_t)st.num_varyings, 0.0);
  m.depth.assign(n, 0);
  for (const Fragment& f : out.fragments) {
    if (f.x < 0 || f.y < 0 || f.x >= m.width || f.y >= m.height) {
      ADD_FAILURE() << "model fragment outside the window: " << f.x << "," << f.y;
      continue;
    }
    const size_t o = (size_t)f.y * m.width + f.x;
    ++m.count[o];
    m.prim[o] = (int32_t)f.prim;
    m.depth[o] = f.depth;
    for (int k = 0; k < st.num_varyings; ++k) m.var[o * st.num_varyings + k] = fx_to_double(f.var[k]);
  }
  m.fragments = out.fragments.size();
  return m;
}

// The model's output varyings are budgeted at 2^-20 of the u, v range (the product aims at
// 24 bits, docs/references.md#vulkan-cts; the model's accuracy against exact arithmetic is
// tested in tests/model, not here).
constexpr double kModelVaryingBudget = kUvMax / (1 << 20);

}  // namespace

// (a) Orthographic scenes on the 1/256 grid: the model, llvmpipe and exact coverage agree pixel
// for pixel, counts included.
TEST(PeerModel, OrthographicGridCoverageIdenticalToLlvmpipe) {
  FXR_PEER_OR_SKIP(peer, true);
  for (const GridScene& s : ortho_scenes()) {
    std::vector<ClipTriangle> tris;
    for (const GridTri& g : s.tris) tris.push_back(to_clip(g, s.st));
    const PeerImage img = peer->render(s.st, tris);
    const ModelImage mod = model_image(s.st, tris);
    size_t n = 0, covered = 0;
    const std::string msg = count_mismatches(mod.count, img.count, img.width, &n);
    for (uint32_t c : img.count) covered += c != 0;
    std::printf("%-26s tris=%5zu covered=%7zu model-vs-llvmpipe differences=%zu\n", s.name.c_str(), s.tris.size(),
                covered, n);
    EXPECT_EQ(n, 0u) << s.name << " (got = model, exp = llvmpipe)\n" << msg;
  }
  const GridPerspectiveScene g = grid_perspective_scene();
  DrawState st = g.st;
  const PeerImage img = peer->render(st, g.tris);
  const ModelImage mod = model_image(st, g.tris);
  size_t n = 0;
  const std::string msg = count_mismatches(mod.count, img.count, img.width, &n);
  std::printf("%-26s tris=%5zu fragments=%7llu model-vs-llvmpipe differences=%zu\n", "grid_perspective (w=1..16)",
              g.tris.size(), (unsigned long long)img.fragments(), n);
  EXPECT_EQ(n, 0u) << "grid_perspective\n" << msg;
}

// (b) Perspective scenes: coverage agreement and varying differences, printed; asserted: coverage
// agreement above 99.9 %, and on the grazing plane (the scene the llvmpipe figure of
// docs/references.md#peer-disagreement is for)
// |model − llvmpipe| ≤ 1.1e-3 (llvmpipe) + |exact(snapped) − exact(unsnapped)| (llvmpipe
// interpolates from unsnapped positions, the model from snapped ones; computed per pixel in
// double) + the model's budget, at every pixel both drew from the same triangle.
TEST(PeerModel, PerspectiveCoverageAndVaryingsAgreeWithLlvmpipe) {
  FXR_PEER_OR_SKIP(peer, true);
  std::vector<PeerScene> scenes = perspective_scenes();
  GridPerspectiveScene g = grid_perspective_scene();
  scenes.push_back({"grid_perspective", "", g.st, g.tris});
  for (PeerScene& s : scenes) {
    DrawState cst = s.st;
    cst.depth_test = false;
    const PeerImage pc = peer->render(cst, s.tris);
    const ModelImage mc = model_image(cst, s.tris);
    size_t any = 0;
    const size_t diff = count_differences(mc.count, pc.count, &any);
    const double agree = 100.0 * (1.0 - (double)diff / (double)any);
    std::vector<GridTri> grid;
    for (const ClipTriangle& t : s.tris) grid.push_back(exact_snapped(t, s.st));
    size_t any_exact = 0;
    const size_t diff_exact =
        count_differences(mc.count, exact_count(grid, mc.width, mc.height, FillRule::TopLeft), &any_exact);
    std::printf("%-16s tris=%zu pixels=%zu model-vs-llvmpipe count differences=%zu agreement=%.4f%% "
                "(model vs exact RNE snapping: %zu differences)\n",
                s.name.c_str(), s.tris.size(), any, diff, agree, diff_exact);
    EXPECT_GT(agree, 99.9) << s.name;

    s.st.depth_test = true;
    const PeerImage pi = peer->render(s.st, s.tris);
    const ModelImage mi = model_image(s.st, s.tris);
    DiffStats d[2];
    size_t same_prim = 0, both = 0, over = 0;
    // Depth in units of the model's depth code (D24 by default): llvmpipe's float z · (2^n − 1).
    const double depth_max = (double)((1u << Config().raster.depth_bits()) - 1);
    double depth_max_lsb = 0, depth_sum_lsb = 0, dz_model = 0, dz_peer = 0, dz_snap = 0;
    for (int y = 0; y < pi.height; ++y)
      for (int x = 0; x < pi.width; ++x) {
        const size_t o = pi.index(x, y);
        if (pi.prim[o] < 0 || mi.prim[o] < 0) continue;
        ++both;
        if (pi.prim[o] != mi.prim[o]) continue;
        ++same_prim;
        const double dl = std::fabs((double)pi.depth[o] * depth_max - (double)mi.depth[o]);
        depth_max_lsb = std::max(depth_max_lsb, dl);
        depth_sum_lsb += dl;
        {
          const ClipTriangle& t = s.tris[pi.prim[o]];
          const double zs = ref_varying(t, s.st, x, y, kDepth, true) * depth_max;
          const double zu = ref_varying(t, s.st, x, y, kDepth, false) * depth_max;
          dz_model = std::max(dz_model, std::fabs((double)mi.depth[o] - zs));
          dz_peer = std::max(dz_peer, std::fabs((double)pi.depth[o] * depth_max - zu));
          dz_snap = std::max(dz_snap, std::fabs(zs - zu));
        }
        for (int k = 0; k < 2; ++k) {
          const double mv = mi.var[o * 2 + k], pv = pi.varying(x, y, k);
          d[k].add(pv, mv);
          const ClipTriangle& t = s.tris[pi.prim[o]];
          const double bound = kLlvmpipeVaryingError + kModelVaryingBudget +
                               std::fabs(ref_varying(t, s.st, x, y, k, true) - ref_varying(t, s.st, x, y, k, false));
          if (std::fabs(mv - pv) > bound && s.name == "grazing_plane") {
            if (++over <= 10)
              ADD_FAILURE() << s.name << " pixel (" << x << "," << y << ") v" << k << " model=" << mv
                            << " llvmpipe=" << pv << " bound=" << bound;
          }
        }
      }
    std::printf("%-16s pixels drawn by both=%zu same triangle=%zu depth |llvmpipe - model| max=%.2f mean=%.3f LSB\n",
                s.name.c_str(), both, same_prim, depth_max_lsb, same_prim ? depth_sum_lsb / (double)same_prim : 0.0);
    std::printf("%-16s depth max LSB: model vs exact(snapped)=%.2f llvmpipe vs exact(unsnapped)=%.2f "
                "exact snapped vs unsnapped=%.2f\n", s.name.c_str(), dz_model, dz_peer, dz_snap);
    for (int k = 0; k < 2; ++k)
      std::printf("%-16s v%d llvmpipe vs model: %s\n", s.name.c_str(), k, d[k].str().c_str());
    EXPECT_EQ(over, 0u) << s.name;
  }
}

// (c) NaN / ±Inf varyings (docs/pipeline.md, stage 1): GL rasterises such a triangle, and so does
// the model (NaN → 0, ±Inf → ±FLT_MAX, counted). The covered pixels are compared with llvmpipe's:
// pixel for pixel on the orthographic grid scene, by count (and agreement as in (b)) on a
// perspective triangle; and with the model's own pixels for the same triangles with finite
// varyings (exact).
TEST(PeerModel, NonFiniteVaryingsAreRasterisedLikeLlvmpipe) {
  FXR_PEER_OR_SKIP(peer, true);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const auto poison = [&](std::vector<ClipTriangle>& tris) {
    for (size_t t = 0; t < tris.size(); ++t) {
      tris[t].v[t % 3].var[0] = nan;
      tris[t].v[(t + 1) % 3].var[1] = t % 2 ? inf : -inf;
    }
  };
  // Orthographic: the random grid scene with two varyings.
  for (const GridScene& s : ortho_scenes()) {
    if (s.name != "random_mixed") continue;
    DrawState st = s.st;
    st.num_varyings = 2;
    std::vector<ClipTriangle> finite, tris;
    for (const GridTri& g : s.tris) {
      finite.push_back(to_clip(g, st));
      finite.back().v[0].var[1] = 2.0f;
    }
    tris = finite;
    poison(tris);
    const PeerImage img = peer->render(st, tris);
    const ModelImage mod = model_image(st, tris), fin = model_image(st, finite);
    size_t n = 0, nf = 0, covered = 0;
    const std::string msg = count_mismatches(mod.count, img.count, img.width, &n);
    count_mismatches(mod.count, fin.count, img.width, &nf);
    for (uint32_t c : img.count) covered += c != 0;
    std::printf("non-finite varyings, %s: tris=%zu llvmpipe covered=%zu model-vs-llvmpipe differences=%zu "
                "model-vs-model(finite) differences=%zu\n", s.name.c_str(), tris.size(), covered, n, nf);
    EXPECT_GT(covered, 10000u);
    EXPECT_EQ(n, 0u) << msg;
    EXPECT_EQ(nf, 0u);
    const RasterStats rs = run_raster_unit(Config(), st, tris).stats;
    EXPECT_EQ(rs.prims_varying_nonfinite, tris.size());
    EXPECT_EQ(rs.prims_rejected_nan + rs.prims_rejected_inf, 0u);
  }
  // Perspective: one large triangle, w from 1 to 6, NaN in v0 at one vertex, +Inf in v1 at another.
  DrawState st;
  st.viewport_w = 128;
  st.viewport_h = 128;
  st.num_varyings = 2;
  st.depth_test = false;
  ClipTriangle t;
  const float p[3][4] = {{-0.9f, -0.8f, 0.2f, 1.0f}, {5.1f, -3.0f, 3.0f, 6.0f}, {-0.6f, 2.7f, 1.5f, 3.0f}};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) t.v[i].pos[c] = p[i][c];
  for (int i = 0; i < 3; ++i) t.v[i].var[0] = (float)i, t.v[i].var[1] = 3.0f - (float)i;
  const ModelImage fin = model_image(st, {t});
  t.v[1].var[0] = nan;
  t.v[2].var[1] = inf;
  const PeerImage img = peer->render(st, {t});
  const ModelImage mod = model_image(st, {t});
  size_t any = 0, nf = 0;
  const size_t diff = count_differences(mod.count, img.count, &any);
  count_mismatches(mod.count, fin.count, img.width, &nf);
  uint64_t mc = 0, pc = 0;
  for (uint32_t c : mod.count) mc += c;
  for (uint32_t c : img.count) pc += c;
  std::printf("non-finite varyings, perspective triangle: llvmpipe covered=%llu model covered=%llu "
              "differing pixels=%zu model-vs-model(finite) differences=%zu\n",
              (unsigned long long)pc, (unsigned long long)mc, diff, nf);
  EXPECT_GT(pc, 4000u);
  EXPECT_EQ(nf, 0u);
  EXPECT_GT(100.0 * (1.0 - (double)diff / (double)any), 99.9);
  // llvmpipe's varyings there are not finite (NaN / Inf in IEEE arithmetic); the model's are
  // defined: v0 interpolates 0, 0, 2 where the NaN was, v1 reaches FLT_MAX-sized values.
  size_t nonfinite_peer = 0, huge_model = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t o = img.index(x, y);
      if (!img.count[o] || !mod.count[o]) continue;
      nonfinite_peer += !std::isfinite(img.varying(x, y, 0)) || !std::isfinite(img.varying(x, y, 1));
      EXPECT_TRUE(std::isfinite(mod.var[o * 2]) && std::isfinite(mod.var[o * 2 + 1]));
      huge_model += mod.var[o * 2 + 1] > 1e30;
    }
  std::printf("  llvmpipe fragments with a non-finite varying=%zu; model fragments with v1 > 1e30=%zu\n",
              nonfinite_peer, huge_model);
  EXPECT_GT(huge_model, 0u);
}

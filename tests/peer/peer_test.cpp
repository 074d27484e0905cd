// The external peer (Mesa llvmpipe through OSMesa) against exact integer coverage and, where
// the model is built, against the model. Expected coverage comes from exact integer edge
// functions on the 1/256 grid (written here, independent of the model and of Mesa).
//
// If no OSMesa context can be created the tests FAIL (PeerError), unless FXR_NO_PEER is set,
// in which case they are skipped with a message.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fxr/float_raster.hpp"
#include "fxr/peer_osmesa.hpp"

using namespace fxr;
using namespace fxr::peer;

namespace {

// llvmpipe's subpixel grid: 8 fraction bits (GL_SUBPIXEL_BITS, checked below; ANCHORS).
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

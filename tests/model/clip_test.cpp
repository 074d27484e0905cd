// Stage 2, the clipper: against the rational Sutherland–Hodgman of tests/model/geom_ref.hpp
// (0 differences expected: same plane order, exact intersections, same rounding points), the
// symmetry that makes shared edges clip identically, watertightness of clipped meshes (with an
// exact top-left coverage count written here), and the hard cases of docs/references.md#spec-hard-cases.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>

#include "geom_ref.hpp"

using namespace fxr;
using namespace georef;

namespace {

ClipVertex vtx(double x, double y, double z, double w) {
  ClipVertex v;
  v.pos[0] = (float)x;
  v.pos[1] = (float)y;
  v.pos[2] = (float)z;
  v.pos[3] = (float)w;
  return v;
}

struct Counts {
  int diffs = 0;
  RasterStats stats;
};

// Runs a batch through geometry() (for the counters) and through the reference comparison.
void check(const Config& cfg, const DrawState& st, const ClipTriangle& t, Counts& c) {
  std::vector<SetupTriangle> out;
  geometry(cfg, st, t, 0, out, c.stats);
  c.diffs += compare_with_reference(cfg, st, t);
}

// A random clip-space vertex: NDC-ish position scaled by `spread`, w in [wlo, whi].
ClipVertex random_vertex(std::mt19937_64& rng, double spread, double wlo, double whi, double zlo,
                         double zhi, int nv) {
  std::uniform_real_distribution<double> u(-1, 1), w(wlo, whi), z(zlo, zhi), var(-50, 50);
  const double wc = w(rng);
  ClipVertex v = vtx(u(rng) * spread * wc, u(rng) * spread * wc, z(rng) * wc, wc);
  for (int k = 0; k < nv; ++k) v.var[k] = (float)var(rng);
  return v;
}

}  // namespace

TEST(Clip, MatchesRationalSutherlandHodgmanOnRandomTriangles) {
  std::mt19937_64 rng(11);
  Counts c;
  for (int i = 0; i < 3000; ++i) {
    Config cfg;
    cfg.raster.window_int_bits = 8 + (i % 6);  // small guard bands: the x / y planes get hit
    const int nv = i % 5;
    const DrawState st = state(40 + i % 50, 30 + i % 70, i % 7, -(i % 5), nv);
    ClipTriangle t;
    for (auto& v : t.v) v = random_vertex(rng, 30, -2, 4, -1.5, 2.5, nv);
    check(cfg, st, t, c);
  }
  EXPECT_EQ(c.diffs, 0);
  EXPECT_GT(c.stats.prims_clipped, 1000u);
  EXPECT_GT(c.stats.clip_vertices_created, 2000u);
  std::printf("random: %lu clipped, %lu trivially accepted, %lu vertices created, %lu triangles out\n",
              (unsigned long)c.stats.prims_clipped, (unsigned long)c.stats.prims_trivial_accept,
              (unsigned long)c.stats.clip_vertices_created, (unsigned long)c.stats.clip_triangles_out);
}

TEST(Clip, ClipWidthsFollowTheConfiguration) {
  std::mt19937_64 rng(12);
  int diffs = 0;
  for (int i = 0; i < 600; ++i) {
    Config cfg;
    cfg.raster.clip_sig_bits = 16 + (i % 45);
    cfg.raster.window_int_bits = 9;
    const DrawState st = state(100, 100, 0, 0, 2);
    ClipTriangle t;
    for (auto& v : t.v) v = random_vertex(rng, 10, -1, 3, -1, 2, 2);
    diffs += compare_with_reference(cfg, st, t);
  }
  EXPECT_EQ(diffs, 0);
}

TEST(Clip, IntersectionIsSymmetricInEdgeDirection) {
  std::mt19937_64 rng(13);
  Config cfg;
  const DrawState st = state(320, 200);
  const GuardBand gb = guard_band(cfg.raster, st);
  const ClipWidths cw = clip_widths(cfg, 3);
  int tested = 0;
  for (int i = 0; i < 20000 && tested < 3000; ++i) {
    ClipVtx a, b;
    for (int c = 0; c < 4; ++c) {
      a.p[c] = decode_f32(f32_bits((float)std::ldexp((double)(rng() % 2000000) - 1e6, (int)(rng() % 40) - 20))).value;
      b.p[c] = decode_f32(f32_bits((float)std::ldexp((double)(rng() % 2000000) - 1e6, (int)(rng() % 40) - 20))).value;
    }
    for (int k = 0; k < 3; ++k) {
      a.v[k] = decode_f32(f32_bits((float)(rng() % 1000) - 500)).value;
      b.v[k] = decode_f32(f32_bits((float)(rng() % 1000) * 1e-7f)).value;
    }
    for (int p = 0; p < kNumClipPlanes; ++p) {
      const PlaneEq pl = plane_eq(gb, (ClipPlane)p);
      const int sa = plane_side(pl, a), sb = plane_side(pl, b);
      if (sa * sb >= 0) continue;
      bool of = false;
      const ClipVtx r1 = clip_intersect(cw, pl, a, b, &of), r2 = clip_intersect(cw, pl, b, a, &of);
      ASSERT_FALSE(of);
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(r1.p[c].sig, r2.p[c].sig);
        EXPECT_EQ(r1.p[c].exp, r2.p[c].exp);
        EXPECT_EQ(r1.p[c].neg, r2.p[c].neg);
      }
      for (int k = 0; k < 3; ++k) EXPECT_EQ(q_of(r1.v[k]), q_of(r2.v[k]));
      ++tested;
    }
  }
  EXPECT_GE(tested, 3000);
}

namespace {

// Exact coverage with the top-left rule, written independently of the raster stages: pixel
// centres (i + ½, j + ½), y up; a triangle is brought to counter-clockwise order, then a
// sample on an edge counts only for a left edge (going down) or a top edge (horizontal, going
// left). Counts per pixel of a W × H viewport at (x0, y0).
void cover(const SetupTriangle& t, int s, int x0, int y0, int w, int h, std::vector<int>& count) {
  i128 x[3], y[3];
  for (int i = 0; i < 3; ++i) x[i] = t.v[i].x, y[i] = t.v[i].y;
  i128 area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  if (area == 0) return;
  if (area < 0) std::swap(x[1], x[2]), std::swap(y[1], y[2]);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      // Multiplications, not << (x0 + i may be negative: a negative left shift is undefined in C++17).
      const i128 px = (i128)(x0 + i) * ((i128)1 << s) + ((i128)1 << s >> 1), py = (i128)(y0 + j) * ((i128)1 << s) + ((i128)1 << s >> 1);
      bool in = true;
      for (int e = 0; e < 3 && in; ++e) {
        const int f = (e + 1) % 3;
        const i128 dx = x[f] - x[e], dy = y[f] - y[e];
        const i128 ev = dx * (py - y[e]) - dy * (px - x[e]);  // > 0: left of the edge (inside)
        in = ev > 0 || (ev == 0 && (dy < 0 || (dy == 0 && dx < 0)));
      }
      if (in) ++count[(size_t)j * w + i];
    }
}

// D3D-style perspective projection (z_c = 0 at the near plane, z_c = w_c at the far plane),
// in double (the scene front end), of a view-space point; the model gets float32.
ClipVertex project(const std::array<double, 3>& e, double fx, double fy, double n, double f) {
  return vtx(fx * e[0], fy * e[1], f / (n - f) * e[2] + n * f / (n - f), -e[2]);
}

std::array<double, 3> rotate(const std::array<double, 3>& p, double a, double b, double c) {
  auto r = p;
  auto rot = [](double& u, double& v, double ang) {
    const double cu = std::cos(ang) * u - std::sin(ang) * v, cv = std::sin(ang) * u + std::cos(ang) * v;
    u = cu, v = cv;
  };
  rot(r[0], r[1], a);
  rot(r[1], r[2], b);
  rot(r[0], r[2], c);
  return r;
}

}  // namespace

// docs/references.md#spec-hard-cases: shared edges (no pixel twice, none missed) after clipping. The eye sits inside a
// tessellated box, so every view ray meets the mesh exactly once in front of the eye: each
// pixel must be covered exactly once. Triangles behind the eye cross w = 0 and the near
// plane; the side walls run far beyond the guard band.
TEST(Clip, BoxAroundTheEyeCoversEveryPixelExactlyOnce) {
  Config cfg;
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> ang(-3.14159, 3.14159), off(-2, 2);
  const int N = 6;  // quads per box edge
  RasterStats total;
  for (int view = 0; view < 12; ++view) {
    const int W = 48 + view, H = 40, X0 = view * 3 - 10, Y0 = 5 - view;
    const DrawState st = state(W, H, X0, Y0);
    const double a = ang(rng), b = ang(rng), c = ang(rng);
    const std::array<double, 3> centre{off(rng), off(rng), off(rng)};
    const double near = view % 2 ? 1e-4 : 0.05, far = 200, fx = 1.3, fy = 1.7;
    std::map<std::array<int, 3>, ClipVertex> lattice;  // shared vertices: identical float32
    auto vertex = [&](int i, int j, int k) {
      const std::array<int, 3> key{i, j, k};
      auto it = lattice.find(key);
      if (it != lattice.end()) return it->second;
      std::array<double, 3> p{10.0 * i / N - 5 + centre[0], 10.0 * j / N - 5 + centre[1],
                              10.0 * k / N - 5 + centre[2]};
      const ClipVertex v = project(rotate(p, a, b, c), fx, fy, near, far);
      lattice[key] = v;
      return v;
    };
    std::vector<ClipTriangle> tris;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side <= N; side += N)
        for (int u = 0; u < N; ++u)
          for (int v = 0; v < N; ++v) {
            auto at = [&](int du, int dv) {
              std::array<int, 3> ijk;
              ijk[axis] = side;
              ijk[(axis + 1) % 3] = u + du;
              ijk[(axis + 2) % 3] = v + dv;
              return vertex(ijk[0], ijk[1], ijk[2]);
            };
            tris.push_back({{at(0, 0), at(1, 0), at(1, 1)}});
            tris.push_back({{at(0, 0), at(1, 1), at(0, 1)}});
          }
    std::vector<int> count((size_t)W * H, 0);
    RasterStats stats;
    for (size_t i = 0; i < tris.size(); ++i) {
      std::vector<SetupTriangle> out;
      const GeomOutcome o = geometry(cfg, st, tris[i], (uint32_t)i, out, stats);
      ASSERT_TRUE(o == GeomOutcome::Emitted || o == GeomOutcome::CulledOutside) << (int)o;
      for (const auto& t : out) cover(t, cfg.raster.subpixel_bits, X0, Y0, W, H, count);
    }
    int twice = 0, missed = 0;
    for (int n : count) twice += n > 1, missed += n == 0;
    EXPECT_EQ(twice, 0) << "view " << view;
    EXPECT_EQ(missed, 0) << "view " << view;
    total.prims_clipped += stats.prims_clipped;
    total.clip_vertices_created += stats.clip_vertices_created;
  }
  EXPECT_GT(total.prims_clipped, 100u);
  EXPECT_GT(total.clip_vertices_created, 200u);
}

// docs/references.md#spec-hard-cases: a near plane very close to the eye (n = 1e-7 … 1e-3 of the scene scale).
TEST(Clip, NearPlaneVeryCloseToTheEye) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> u(-3, 3), ze(-5, 0.5);
  Counts c;
  for (int i = 0; i < 1500; ++i) {
    Config cfg;
    const double n = std::pow(10.0, -7 + (i % 5)), f = 1000;
    const DrawState st = state(640, 480, 0, 0, 1);
    ClipTriangle t;
    for (auto& v : t.v) {
      v = project({u(rng), u(rng), ze(rng)}, 1, 1.3, n, f);
      v.var[0] = (float)u(rng);
    }
    check(cfg, st, t, c);
  }
  EXPECT_EQ(c.diffs, 0);
  EXPECT_GT(c.stats.prims_clipped, 300u);
}

// docs/references.md#spec-hard-cases: triangles crossing w = 0, with one or two vertices behind the eye.
TEST(Clip, TrianglesCrossingWZeroWithOneOrTwoVerticesBehind) {
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> front(0.5, 20), behind(-20, -1e-3);
  Counts c;
  for (int i = 0; i < 1500; ++i) {
    Config cfg;
    const DrawState st = state(512, 512, 0, 0, 2);
    const int nbehind = 1 + i % 2;
    ClipTriangle t;
    for (int j = 0; j < 3; ++j) {
      const double w = j < nbehind ? behind(rng) : front(rng);
      t.v[j] = random_vertex(rng, 1.5, 1, 1, 0.1, 0.9, 2);  // w = 1 template
      for (int k = 0; k < 3; ++k) t.v[j].pos[k] = (float)(t.v[j].pos[k] * std::fabs(w));
      t.v[j].pos[3] = (float)w;
    }
    std::vector<SetupTriangle> out;
    RasterStats s;
    const GeomOutcome o = geometry(cfg, st, t, 0, out, s);
    EXPECT_TRUE(o == GeomOutcome::Emitted || o == GeomOutcome::CulledOutside);
    c.diffs += compare_with_reference(cfg, st, t);
    c.stats.prims_clipped += s.prims_clipped;
  }
  EXPECT_EQ(c.diffs, 0);
  EXPECT_GT(c.stats.prims_clipped, 1000u);
}

// docs/references.md#spec-hard-cases: triangles far larger than the viewport are clipped to the guard band; every
// snapped coordinate fits the window format.
TEST(Clip, TrianglesFarLargerThanTheViewportAreClippedToTheGuardBand) {
  std::mt19937_64 rng(17);
  Counts c;
  int emitted = 0;
  for (int i = 0; i < 1000; ++i) {
    Config cfg;
    const DrawState st = state(256, 256, 0, 0, 1);
    ClipTriangle t;
    for (auto& v : t.v) v = random_vertex(rng, 1e6, 0.5, 2, 0.2, 0.8, 1);
    std::vector<SetupTriangle> out;
    RasterStats s;
    if (geometry(cfg, st, t, 0, out, s) == GeomOutcome::Emitted) ++emitted;
    const int64_t lim = (int64_t(1) << (cfg.raster.window_int_bits + cfg.raster.subpixel_bits - 1));
    for (auto& tr : out)
      for (auto& v : tr.v) {
        EXPECT_LT(v.x, lim);
        EXPECT_GE(v.x, -lim);
        EXPECT_LT(v.y, lim);
        EXPECT_GE(v.y, -lim);
      }
    c.diffs += compare_with_reference(cfg, st, t);
  }
  EXPECT_EQ(c.diffs, 0);
  EXPECT_GT(emitted, 100);
}

// docs/references.md#spec-hard-cases: vertices exactly on planes are inside and create no vertex (z = 0, z = w, x on the
// guard band: with W = 256, X0 = 0, L = 32767 the band is x_n ∈ [−65790/256, 65278/256], exact
// in float32).
TEST(Clip, VerticesExactlyOnPlanesCreateNoVertices) {
  Config cfg;
  const DrawState st = state(256, 256);
  const double band = (2.0 * 32767 - 256) / 256, band_lo = -(2.0 * 32767 + 256) / 256;
  ClipTriangle t;
  t.v[0] = vtx(band * 2, 0, 0, 2);         // on the right guard plane and on the near plane
  t.v[1] = vtx(0, band_lo * 4, 4, 4);       // on the bottom guard plane and on the far plane
  t.v[2] = vtx(0, 0, 0.5, 1);
  std::vector<SetupTriangle> out;
  RasterStats s;
  ASSERT_EQ(geometry(cfg, st, t, 0, out, s), GeomOutcome::Emitted);
  EXPECT_EQ(s.prims_trivial_accept, 1u);
  EXPECT_EQ(s.clip_vertices_created, 0u);
  EXPECT_EQ(out[0].v[0].x, 32767 * 256);   // exactly the guard band's window limit
  EXPECT_EQ(out[0].v[1].y, -32767 * 256);
  EXPECT_EQ(out[0].v[1].z, 1ull << cfg.raster.z_frac_bits);
  EXPECT_EQ(compare_with_reference(cfg, st, t), 0);
  // One ulp further out: now the triangle is clipped, and the new vertices are on the band.
  t.v[0].pos[0] = std::nextafter(t.v[0].pos[0], 1e30f);
  s = RasterStats{};
  out.clear();
  ASSERT_EQ(geometry(cfg, st, t, 0, out, s), GeomOutcome::Emitted);
  EXPECT_EQ(s.prims_clipped, 1u);
  EXPECT_EQ(compare_with_reference(cfg, st, t), 0);
}

// Trivial reject: all three vertices outside one plane; nothing is created.
TEST(Clip, TrivialRejectOutsideOnePlane) {
  Config cfg;
  const DrawState st = state(100, 100);
  ClipTriangle t;
  t.v[0] = vtx(0, 0, 2, 1);  // beyond far
  t.v[1] = vtx(0.5, 0, 3, 1);
  t.v[2] = vtx(0, 0.5, 1.5, 1);
  std::vector<SetupTriangle> out;
  RasterStats s;
  EXPECT_EQ(geometry(cfg, st, t, 0, out, s), GeomOutcome::CulledOutside);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(s.prims_clipped, 0u);
  EXPECT_EQ(s.prims_trivial_accept, 0u);
}

namespace {

// The ideal pipeline in double (docs/references.md#spec-error-measure): same planes and plane order, intersections and divide
// in double, no snapping. Returns the unsnapped window polygon (x, y in subpixel units, z_n).
struct DV {
  double p[4];
  int depth = 0;  // intersections in its history: 0 input vertex, 1 made from input vertices, …
};
std::vector<std::array<double, 4>> double_pipeline(const RasterConfig& rc, const DrawState& st,
                                                   const ClipTriangle& t) {
  const double L = (1 << (rc.window_int_bits - 1)) - 1.0, W = st.viewport_w, H = st.viewport_h;
  const double xlo = 2 * (-L - st.viewport_x) / W - 1, xhi = 2 * (L - st.viewport_x) / W - 1;
  const double ylo = 2 * (-L - st.viewport_y) / H - 1, yhi = 2 * (L - st.viewport_y) / H - 1;
  auto dist = [&](int p, const DV& v) {
    const double x = v.p[0], y = v.p[1], z = v.p[2], w = v.p[3];
    switch (p) {
      case 0: return w - std::ldexp(1.0, kWMinExp);
      case 1: return z;
      case 2: return w - z;
      case 3: return x - xlo * w;
      case 4: return xhi * w - x;
      case 5: return y - ylo * w;
      default: return yhi * w - y;
    }
  };
  std::vector<DV> poly(3);
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) poly[i].p[c] = t.v[i].pos[c];
  for (int p = 0; p < 7 && !poly.empty(); ++p) {
    std::vector<DV> next;
    const size_t n = poly.size();
    for (size_t i = 0; i < n; ++i) {
      const DV &a = poly[i], &b = poly[(i + 1) % n];
      const double da = dist(p, a), db = dist(p, b);
      if (da >= 0) next.push_back(a);
      if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
        DV r;
        r.depth = std::max(a.depth, b.depth) + 1;
        const double tt = da / (da - db);
        for (int c = 0; c < 4; ++c) r.p[c] = a.p[c] + tt * (b.p[c] - a.p[c]);
        next.push_back(r);
      }
    }
    poly = next.size() < 3 ? std::vector<DV>{} : next;
  }
  std::vector<std::array<double, 4>> out;
  const double s = std::ldexp(1.0, rc.subpixel_bits);
  for (auto& v : poly)
    out.push_back({((v.p[0] / v.p[3] + 1) * W / 2 + st.viewport_x) * s,
                   ((v.p[1] / v.p[3] + 1) * H / 2 + st.viewport_y) * s, v.p[2] / v.p[3], (double)v.depth});
  return out;
}

}  // namespace

// Sanity check against the double pipeline. Documented bound for a window coordinate of an input
// vertex or of a vertex made by one intersection of input vertices, in subpixels:
//   ½ (snap) + |x_w − centre|·2^subpixel_bits · 2^−22
// (reciprocal ½ ulp at 24 bits, clipped w ½ ulp at 24 bits, clipped x ½ ulp at 32 bits: 2^−23
// relative, with a factor 2 to spare), + 1e−6 for the double arithmetic. A vertex made from an
// already rounded intersection (two or more planes) inherits that vertex's error scaled by the
// edge's obliquity to the second plane, which has no bound independent of the geometry: those
// are measured and reported (the exact GMP tests pin them bit for bit), and held only to a
// coarse sanity bound of 1 subpixel + 2^−16 relative.
TEST(Clip, AgreesWithTheDoublePipelineWithinTheDocumentedBound) {
  std::mt19937_64 rng(18);
  Config cfg;
  int compared = 0, skipped = 0;
  double worst_ratio = 0, worst_sub = 0, worst_multi_rel = 0, worst_multi_sub = 0;
  int multi = 0;
  for (int i = 0; i < 3000; ++i) {
    cfg.raster.window_int_bits = 10 + i % 7;
    const DrawState st = state(64 + i % 300, 48 + i % 200, i % 11, i % 13);
    ClipTriangle t;
    // w > 0 only: at the w_min plane (w = 2^−160) a double intersection is pure cancellation
    // noise (absolute error ~1e−16 ≫ w), so the double pipeline is no reference there; the
    // exact GMP tests cover w ≤ 0.
    for (auto& v : t.v) v = random_vertex(rng, 20, 0.05, 3, -1, 2, 0);
    std::vector<SetupTriangle> out;
    RasterStats s;
    const GeomOutcome o = geometry(cfg, st, t, 0, out, s);
    const auto ref = double_pipeline(cfg.raster, st, t);
    if ((o == GeomOutcome::Emitted) != !ref.empty() || (!ref.empty() && out.size() != ref.size() - 2)) {
      ++skipped;  // a vertex within double rounding of a plane: classified differently
      continue;
    }
    for (size_t k = 0; k < out.size(); ++k)
      for (int j = 0; j < 3; ++j) {
        const auto& r = ref[j == 0 ? 0 : k + j];
        const SetupVertex& m = out[k].v[j];
        const double cx = (st.viewport_x + st.viewport_w / 2.0) * 256, cy = (st.viewport_y + st.viewport_h / 2.0) * 256;
        const bool tight = r[3] <= 1;
        const double rel = std::ldexp(1.0, tight ? -22 : -16), base = tight ? 0.5 : 1.0;
        const double bx = base + std::fabs(r[0] - cx) * rel + 1e-6;
        const double by = base + std::fabs(r[1] - cy) * rel + 1e-6;
        const double ex = std::fabs(m.x - r[0]), ey = std::fabs(m.y - r[1]);
        EXPECT_LE(ex, bx);
        EXPECT_LE(ey, by);
        const double rx = std::max(ex - 0.5, 0.0) / std::max(std::fabs(r[0] - cx), 1.0),
                     ry = std::max(ey - 0.5, 0.0) / std::max(std::fabs(r[1] - cy), 1.0);
        if (tight) {
          worst_ratio = std::max({worst_ratio, rx, ry});
          worst_sub = std::max({worst_sub, ex, ey});
          ++compared;
        } else {
          worst_multi_rel = std::max({worst_multi_rel, rx, ry});
          worst_multi_sub = std::max({worst_multi_sub, ex, ey});
          ++multi;
        }
      }
  }
  std::printf("double pipeline: %d vertices with <= 1 intersection: worst error %.4f subpixel, worst "
              "(error - 1/2) / distance from centre 2^%.1f (bound 2^-22); %d vertices with >= 2: worst %.4f subpixel, worst (error - 1/2) / "
              "distance from centre 2^%.1f; %d triangles skipped\n", compared, worst_sub, std::log2(std::max(worst_ratio, 1e-30)), multi,
              worst_multi_sub, std::log2(std::max(worst_multi_rel, 1e-30)), skipped);
  EXPECT_GT(compared, 5000);
  EXPECT_LT(skipped, 30);
}

// The trivial-accept test's plane sides in 64-bit words (docs/speed.md "Trivial accept in 64
// bits") against the u128 path and the exact rational sign (GMP): float32-like vertices (every
// product in 64 bits), wide significands (the fallback), equal leading ones (the aligned sum,
// exact zeros on a plane), zero components, over several guard bands.
TEST(Clip, PlaneSide64EqualsTheU128PathAndTheRationalSign) {
  std::mt19937_64 rng(64);
  const Config cfg;
  int fast = 0, wide = 0, zero = 0;
  for (const int size : {1, 320, 1024, 4096}) {
    const GuardBand gb = guard_band(cfg.raster, state(size, size - 7 > 0 ? size - 7 : 1));
    for (int i = 0; i < 40000; ++i) {
      ClipVtx v;
      const int sig_bits = i % 5 == 0 ? 40 + (int)(rng() % 25) : 1 + (int)(rng() % 24);
      for (int c = 0; c < 4; ++c) {
        v.p[c].neg = rng() & 1;
        v.p[c].sig = rng() >> (64 - sig_bits);
        v.p[c].exp = (int)(rng() % 60) - 40;
        if (rng() % 16 == 0) v.p[c].sig = 0;
      }
      if (i % 3 == 0) {  // a vertex on or next to a plane: x = ±(n/W)·w, z = w, z = 0
        const int p = (int)(rng() % kNumClipPlanes);
        const PlaneEq pl = plane_eq(gb, (ClipPlane)p);
        if (pl.comp >= 0 && pl.a != 0 && pl.b != 0) {
          // a·x + b·w = 0 with x = −b·t, w = a·t (t a random significand)
          const uint64_t t = (rng() >> 44) | 1;
          const int e = (int)(rng() % 20) - 10;
          v.p[pl.comp] = FxFloat{(pl.b > 0) != ((rng() & 1) != 0), (uint64_t)std::llabs(pl.b) * t, e};
          v.p[3] = FxFloat{v.p[pl.comp].neg == (pl.b > 0) ? (pl.a < 0) : (pl.a > 0), (uint64_t)std::llabs(pl.a) * t, e};
          if (rng() & 1) v.p[3].sig += (rng() & 1) ? 1 : -1;  // just off the plane
        }
      }
      for (int p = 0; p < kNumClipPlanes; ++p) {
        const PlaneEq pl = plane_eq(gb, (ClipPlane)p);
        const int s = plane_side(pl, v);
        if (pl.wmin) continue;  // no products: one path
        const int s128 = plane_side_u128(pl, v);
        const mpq_class d = (pl.comp >= 0 ? mpq_class(mpz_class((long)pl.a)) * q_of(v.p[pl.comp]) : mpq_class(0)) +
                            mpq_class(mpz_class((long)pl.b)) * q_of(v.p[3]);
        const int ref = sgn(d);
        ASSERT_EQ(s128, ref) << "plane " << p;
        ASSERT_EQ(s, ref) << "plane " << p << " sig bits " << sig_bits;
        if (ref == 0) ++zero;
        const int mb = v.p[3].sig ? 64 - __builtin_clzll(v.p[3].sig) : 0;
        (mb + 24 <= 62 ? fast : wide) += 1;
      }
    }
  }
  EXPECT_GT(zero, 1000);  // the aligned-sum case reached, exact zeros included
  EXPECT_GT(fast, 100000);
  EXPECT_GT(wide, 10000);  // the fallback reached
}

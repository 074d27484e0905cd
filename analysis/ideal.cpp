// The exact judge of the ideal image and the scene suite of issue 8 (analysis/ideal.hpp).
// Floating point appears only in the scene front end (GLM, double) and in error summaries.
#include "analysis/ideal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "model/stages/attr.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/geometry.hpp"
#include "analysis/error_stats.hpp"
#include "reference/reference.hpp"

namespace fxr {

namespace {

// Every finite float32 times 2^kF32Scale is an integer (the smallest denormal is 2^−149).
constexpr int kF32Scale = 149;

mpz_class scaled(float f, bool* finite) {
  const F32Decoded d = decode_f32(f32_bits(f));
  if (d.cls == F32Class::NaN || d.cls == F32Class::Inf) {
    *finite = false;
    return 0;
  }
  mpz_class m = (unsigned long)d.value.sig;
  m <<= (unsigned long)(d.value.exp + kF32Scale);
  return d.value.neg ? mpz_class(-m) : m;
}

}  // namespace

mpq_class to_mpq_float(float f) {
  bool fin = true;
  mpz_class m = scaled(f, &fin);
  mpq_class q(m, mpz_class(1) << kF32Scale);
  q.canonicalize();
  return q;
}

IdealJudge::IdealJudge(const DrawState& st, const std::vector<ClipTriangle>& tris) : st_(st) {
  tris_.resize(tris.size() * 3);
  for (size_t t = 0; t < tris.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      V& v = tris_[t * 3 + i];
      for (int c = 0; c < 4; ++c) v.p[c] = scaled(tris[t].v[i].pos[c], &v.finite);
      // Varyings under the unit's rule for non-finite values (docs/pipeline.md, stage 1).
      for (int k = 0; k < st.num_varyings; ++k) {
        bool replaced = false;
        v.v[k] = scaled((float)ref_varying_input(tris[t].v[i].var[k], &replaced), &v.finite);
      }
    }
}

// n = a × c for the pixel whose NDC is x_n = xnum / W, y_n = ynum / H (all scaled by W, H:
// a_i = W·x_i − xnum·w_i, c_i = H·y_i − ynum·w_i; a common factor of a or c cancels in every ratio).
void IdealJudge::solve(uint32_t prim, const mpz_class& xnum, const mpz_class& ynum, mpz_class n[3]) const {
  mpz_class a[3], c[3];
  for (int i = 0; i < 3; ++i) {
    const V& v = tris_[prim * 3 + i];
    a[i] = st_.viewport_w * v.p[0] - xnum * v.p[3];
    c[i] = st_.viewport_h * v.p[1] - ynum * v.p[3];
  }
  n[0] = a[1] * c[2] - a[2] * c[1];
  n[1] = a[2] * c[0] - a[0] * c[2];
  n[2] = a[0] * c[1] - a[1] * c[0];
}

IdealValue IdealJudge::eval(uint32_t prim, int px, int py, bool in_front) const {
  IdealValue r;
  if ((size_t)prim * 3 >= tris_.size()) return r;
  for (int i = 0; i < 3; ++i)
    if (!tris_[prim * 3 + i].finite) return r;
  // x_n = (2·px + 1 − 2·X0 − W) / W
  const mpz_class xnum = 2L * px + 1 - 2L * st_.viewport_x - st_.viewport_w;
  const mpz_class ynum = 2L * py + 1 - 2L * st_.viewport_y - st_.viewport_h;
  mpz_class n[3];
  solve(prim, xnum, ynum, n);
  const mpz_class s = n[0] + n[1] + n[2];
  if (sgn(s) == 0) return r;
  mpz_class nw = 0, nz = 0;
  for (int i = 0; i < 3; ++i) {
    nw += n[i] * tris_[prim * 3 + i].p[3];
    nz += n[i] * tris_[prim * 3 + i].p[2];
  }
  if (sgn(nw) == 0 || (in_front && sgn(nw) * sgn(s) < 0)) return r;  // at w = 0, or behind the eye
  r.valid = true;
  r.z = mpq_class(nz, nw);
  r.z.canonicalize();
  for (int k = 0; k < st_.num_varyings; ++k) {
    mpz_class nv = 0;
    for (int i = 0; i < 3; ++i) nv += n[i] * tris_[prim * 3 + i].v[k];
    // v_i are scaled by 2^149: divide it out.
    r.v[k] = mpq_class(nv, s * (mpz_class(1) << kF32Scale));
    r.v[k].canonicalize();
  }
  return r;
}

double IdealJudge::depth_gradient(uint32_t prim, int px, int py) const {
  // Depth is affine in window x, y on the primitive's plane: two exact differences.
  const IdealValue c = eval(prim, px, py, false), x = eval(prim, px + 1, py, false), y = eval(prim, px, py + 1, false);
  if (!c.valid || !x.valid || !y.valid) return -1;
  return std::fabs(mpq_class(x.z - c.z).get_d()) + std::fabs(mpq_class(y.z - c.z).get_d());
}

// ---- the model as an image -----------------------------------------------------------------

namespace {
struct ImageSink final : FragmentSink {
  ModelImage& m;
  explicit ImageSink(ModelImage& mi) : m(mi) {}
  void emit(const Fragment& f) override {
    if (f.x < 0 || f.y < 0 || f.x >= m.width || f.y >= m.height) return;
    const size_t o = m.index(f.x, f.y);
    m.prim[o] = (int32_t)f.prim;
    m.depth[o] = f.depth;
    for (int k = 0; k < m.num_varyings; ++k) m.var[o * m.num_varyings + k] = f.var[k];
  }
  // A span's records (the fused chain, model/unit/backend.hpp): read in place, no Fragment.
  void emit_span(const FragmentRecords& b) override {
    if (b.count == 0) return;
    for (size_t i = 0; i < b.count; ++i) {  // one row or several (FragmentSink::emit_span)
      const uint8_t* r = b.record(i);
      const int32_t x = (int32_t)fragment_word(r, 1), y = b.y(i);
      if (x < 0 || x >= m.width || y < 0 || y >= m.height) continue;
      const size_t o = m.index(x, y);
      m.prim[o] = (int32_t)fragment_word(r, 0);
      m.depth[o] = fragment_word(r, 3);
      for (int k = 0; k < m.num_varyings; ++k)
        m.var[o * m.num_varyings + k] = k < b.num_varyings ? get_fragment_var(r, k) : FxFloat{};
    }
  }
};
}  // namespace

ModelImage model_image(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris) {
  ModelImage m;
  m.width = st.viewport_x + st.viewport_w;
  m.height = st.viewport_y + st.viewport_h;
  m.num_varyings = st.num_varyings;
  const size_t n = (size_t)m.width * m.height;
  m.prim.assign(n, -1);
  m.depth.assign(n, 0);
  m.var.assign(n * (size_t)st.num_varyings, FxFloat{});
  FrameOutput f;
  frame_begin(cfg, st, f);
  ImageSink sink(m);
  std::vector<SetupTriangle> pieces;
  for (size_t p = 0; p < tris.size(); ++p) {
    pieces.clear();
    if (geometry(cfg, st, tris[p], (uint32_t)p, pieces, f.stats) != GeomOutcome::Emitted) continue;
    for (const SetupTriangle& t : pieces) raster_triangle_to(cfg, st, t, f, &sink);
  }
  m.stats = f.stats;
  return m;
}

IdealValue snapped_at(const Config& cfg, const DrawState& st, const ClipTriangle& tri, int px, int py) {
  IdealValue r;
  std::vector<SetupTriangle> pieces;
  RasterStats scratch;
  if (geometry(cfg, st, tri, 0, pieces, scratch) != GeomOutcome::Emitted) return r;
  const bool affine = st.interp == InterpMode::Affine;
  for (const SetupTriangle& t : pieces) {
    ExactVertex ev[3];
    for (int k = 0; k < 3; ++k) ev[k] = exact_vertex(cfg.raster, t.v[k], -1);
    if (!exact_at_pixel(ev, px, py, affine).inside) continue;  // coverage: the snapped triangle
    // The positions the planes are set up from: the attribute triangle at its F fraction bits
    // (model/stages/attr.hpp), or the snapped one.
    TriSetup ts;
    AttrSetup as;
    if (attr_separate(cfg.raster) && setup_triangle(cfg, st, t, ts) == SetupOutcome::Ok) as = attr_setup(cfg, t, ts);
    auto place = [&](ExactVertex& e, int k) {
      if (!as.ok) return;
      const mpq_class unit(mpz_class(1), mpz_class(1) << (unsigned long)as.F);
      e.x = mpq_class(mpz_class(std::to_string(as.ox + as.x[k]))) * unit;
      e.y = mpq_class(mpz_class(std::to_string(as.oy + as.y[k]))) * unit;
      // The depth plane's vertex value: z·(2^db − 1) at z_frac_bits − db fraction bits.
      const RasterConfig& rc = cfg.raster;
      e.z = mpq_class(mpz_class(std::to_string(attr_depth_q(rc, t.v[k].z))),
                      (mpz_class(1) << (unsigned long)(rc.z_frac_bits - rc.depth_bits())) *
                          ((mpz_class(1) << (unsigned long)rc.depth_bits()) - 1));
      e.z.canonicalize();  // GMP arithmetic needs canonical operands
    };
    for (int k = 0; k < 3; ++k) place(ev[k], k);
    r.valid = true;
    r.z = exact_at_pixel(ev, px, py, affine).z;
    for (int m = 0; m < st.num_varyings; ++m) {
      for (int k = 0; k < 3; ++k) ev[k] = exact_vertex(cfg.raster, t.v[k], m), place(ev[k], k);
      r.v[m] = exact_at_pixel(ev, px, py, affine).v;
    }
    return r;
  }
  return r;
}

// ---- error measures --------------------------------------------------------------------------

double depth_err_lsb(const mpq_class& got_z, const mpq_class& ideal_z, int depth_bits) {
  const mpq_class m = mpq_class((mpz_class(1) << depth_bits) - 1);
  return std::fabs(mpq_class((got_z - ideal_z) * m).get_d());
}

double abs_err(const mpq_class& got, const mpq_class& ideal) { return std::fabs(mpq_class(got - ideal).get_d()); }

double ulp_err(const mpq_class& got, const mpq_class& ideal, int p) {
  if (sgn(ideal) == 0) return -1;
  // ulp = 2^(⌊log2 |ideal|⌋ − (p − 1)), ⌊log2⌋ exact from the sizes of numerator and denominator.
  const mpq_class a = abs(ideal);
  long e = (long)mpz_sizeinbase(a.get_num_mpz_t(), 2) - (long)mpz_sizeinbase(a.get_den_mpz_t(), 2);
  // 2^e is within a factor 2 of |ideal|: fix up to the exact floor.
  auto pow2 = [](long k) {
    mpq_class q = 1;
    if (k >= 0) q = mpq_class(mpz_class(1) << (unsigned long)k);
    else q = mpq_class(mpz_class(1), mpz_class(1) << (unsigned long)(-k));
    return q;
  };
  while (pow2(e) > a) --e;
  while (pow2(e + 1) <= a) ++e;
  const mpq_class d = abs(mpq_class(got - ideal)) / pow2(e - (p - 1));
  return d.get_d();
}

std::string ErrSummary::str(int prec) const {
  char b[160];
  std::snprintf(b, sizeof b, "n=%llu max=%.*g p99=%.*g mean=%.*g", (unsigned long long)n, prec, max, prec, p99, prec,
                mean);
  return b;
}

ErrSummary summarize(std::vector<double> v) {
  ErrStat e;  // the reports' statistics (nearest-rank percentiles), negatives left out
  for (double x : v)
    if (x >= 0) e.add(x);
  ErrSummary s;
  s.n = e.n;
  s.max = e.max;
  s.mean = e.mean();
  s.p99 = e.pct(0.99);
  return s;
}

// ---- scenes ----------------------------------------------------------------------------------

namespace {

constexpr double kUv = 16.0;  // u, v ∈ [0, 16], as the peer scenes (docs/peer.md)

// depth_less: the depth test resolves overlaps (less); otherwise every fragment passes and
// writes (always), so the peer's depth buffer holds the last fragment's depth like the model's.
DrawState suite_state(int size, bool depth_less) {
  DrawState st;
  st.viewport_w = st.viewport_h = size;
  st.num_varyings = 2;
  st.depth_test = true;
  st.depth_func = depth_less ? DepthFunc::Less : DepthFunc::Always;
  return st;
}

ClipVertex cv(const glm::dvec4& c, double u, double v) {
  ClipVertex o;
  for (int i = 0; i < 4; ++i) o.pos[i] = (float)c[i];  // the only rounding: double → float32
  o.var[0] = (float)u;
  o.var[1] = (float)v;
  return o;
}

}  // namespace

IdealScene ideal_grazing_plane(int size) {
  IdealScene s{"grazing_plane", suite_state(size, true), {}};
  // Floor y = 0, eye 1 unit above it looking slightly down at the horizon; fov 60°, near 0.1.
  const glm::dmat4 mvp = glm::perspectiveRH_ZO(glm::radians(60.0), 1.0, 0.1, 1000.0) *
                         glm::lookAtRH(glm::dvec3(0, 1, 0), glm::dvec3(0, 0.7, -10), glm::dvec3(0, 1, 0));
  const double x0 = -60, x1 = 60, zn = -1.0, zf = -600;
  const glm::dvec3 c[4] = {{x0, 0, zn}, {x1, 0, zn}, {x1, 0, zf}, {x0, 0, zf}};
  const double uv[4][2] = {{0, 0}, {kUv, 0}, {kUv, kUv}, {0, kUv}};
  const int idx[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& ti : idx) {
    ClipTriangle t;
    for (int k = 0; k < 3; ++k) t.v[k] = cv(mvp * glm::dvec4(c[ti[k]], 1), uv[ti[k]][0], uv[ti[k]][1]);
    s.tris.push_back(t);
  }
  return s;
}

namespace {
glm::dmat4 suite_camera(double near, double far) {
  return glm::perspectiveRH_ZO(glm::radians(60.0), 1.0, near, far) *
         glm::lookAtRH(glm::dvec3(0, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
}
}  // namespace

IdealScene ideal_slivers(int size) {
  IdealScene s{"perspective_slivers", suite_state(size, false), {}};
  std::mt19937_64 rng(0x1dea1001);
  std::uniform_real_distribution<double> U(0, 1);
  const glm::dmat4 mvp = suite_camera(0.1, 1000.0);
  for (int t = 0; t < 300; ++t) {
    // A long thin triangle in eye space: from depth d0 to d1 (0.2 … 200), width 1e-3 … 1e-2 of its length.
    const double d0 = 0.2 * std::pow(1000.0, U(rng)), d1 = 0.2 * std::pow(1000.0, U(rng));
    const double sx = U(rng) * 1.0 - 0.5, sy = U(rng) * 1.0 - 0.5;  // direction on screen (NDC-ish)
    const glm::dvec3 a(sx * d0 * 0.9, sy * d0 * 0.9, -d0);
    const glm::dvec3 b((U(rng) - 0.5) * d1 * 0.9, (U(rng) - 0.5) * d1 * 0.9, -d1);
    const double len = glm::length(b - a), width = len * (1e-3 + 9e-3 * U(rng));
    glm::dvec3 side = glm::normalize(glm::cross(b - a, glm::dvec3(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5)));
    const glm::dvec3 c = a + 0.5 * (b - a) * U(rng) + side * width;
    ClipTriangle tri;
    tri.v[0] = cv(mvp * glm::dvec4(a, 1), kUv * U(rng), kUv * U(rng));
    tri.v[1] = cv(mvp * glm::dvec4(b, 1), kUv * U(rng), kUv * U(rng));
    tri.v[2] = cv(mvp * glm::dvec4(c, 1), kUv * U(rng), kUv * U(rng));
    s.tris.push_back(tri);
  }
  return s;
}

IdealScene ideal_near_clipped(int size) {
  IdealScene s{"near_clipped", suite_state(size, false), {}};
  std::mt19937_64 rng(0x1dea1002);
  std::uniform_real_distribution<double> U(0, 1);
  const glm::dmat4 mvp = suite_camera(0.1, 1000.0);
  for (int t = 0; t < 60; ++t) {
    // One or two vertices behind the near plane (eye z between +2 and −0.09), the others in view.
    const int behind = 1 + t % 2;
    ClipTriangle tri;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 p;
      if (k < behind) {
        const double z = -0.09 + 2.09 * U(rng);  // z_e ∈ (−0.09, 2): in front of the eye but before near, or behind it
        p = glm::dvec3((U(rng) - 0.5) * 4, (U(rng) - 0.5) * 4, z);
      } else {
        const double d = 0.5 + 50 * U(rng);
        p = glm::dvec3((U(rng) - 0.5) * d, (U(rng) - 0.5) * d, -d);
      }
      tri.v[k] = cv(mvp * glm::dvec4(p, 1), kUv * U(rng), kUv * U(rng));
    }
    s.tris.push_back(tri);
  }
  return s;
}

IdealScene ideal_w_ratio(int size) {
  IdealScene s{"w_ratio_1e6", suite_state(size, false), {}};
  std::mt19937_64 rng(0x1dea1003);
  std::uniform_real_distribution<double> U(0, 1);
  const double n = 1e-3, f = 1e3;  // projection near / far: z_c = f/(f − n)·(w − n)
  for (int t = 0; t < 120; ++t) {
    // w of one vertex n … 10n, the others up to 10^(1 + 5·t/120) times larger (ratios 10 … 10^6).
    const double w0 = n * (1 + 9 * U(rng));
    const double ratio = std::pow(10.0, 1 + 5.0 * t / 119.0);
    ClipTriangle tri;
    for (int k = 0; k < 3; ++k) {
      const double w = k == 0 ? w0 : w0 * ratio * (0.5 + 0.5 * U(rng));
      const double xn = (U(rng) - 0.5) * 1.6, yn = (U(rng) - 0.5) * 1.6;
      const glm::dvec4 c(xn * w, yn * w, f / (f - n) * (w - n), w);
      tri.v[k] = cv(c, kUv * U(rng), kUv * U(rng));
    }
    s.tris.push_back(tri);
  }
  return s;
}

IdealScene ideal_one_pixel(int size) {
  IdealScene s{"one_pixel", suite_state(size, false), {}};
  std::mt19937_64 rng(0x1dea1004);
  std::uniform_real_distribution<double> U(0, 1);
  const glm::dmat4 mvp = suite_camera(0.1, 1000.0);
  const glm::dmat4 inv = glm::inverse(mvp);
  for (int t = 0; t < 3000; ++t) {
    // A triangle about one pixel across at a random place and depth, random orientation in depth.
    const double px = 1 + (size - 2) * U(rng), py = 1 + (size - 2) * U(rng);
    const double d = 0.2 * std::pow(2000.0, U(rng));
    ClipTriangle tri;
    for (int k = 0; k < 3; ++k) {
      const double ox = px + (U(rng) - 0.5) * 1.6, oy = py + (U(rng) - 0.5) * 1.6;
      const double de = d * (1 + (U(rng) - 0.5) * 0.2);  // depth varies by up to ±10 % across it
      // Eye point on the ray through window (ox, oy) at eye depth de.
      const glm::dvec4 ndc(2 * ox / size - 1, 2 * oy / size - 1, 0.5, 1);
      glm::dvec4 e = inv * ndc;
      glm::dvec3 dir = glm::dvec3(e) / e.w;
      dir *= de / -dir.z;
      tri.v[k] = cv(mvp * glm::dvec4(dir, 1), kUv * U(rng), kUv * U(rng));
    }
    s.tris.push_back(tri);
  }
  return s;
}

}  // namespace fxr

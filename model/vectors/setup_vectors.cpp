// Golden vectors of stage 5, triangle setup (model/vectors/setup_vectors.hpp, docs/vectors.md).
// The field list comes from SetupTriangle::visit, visit_setup_state and TriangleEquations::visit;
// the outputs from SetupStage::step.
#include "model/vectors/setup_vectors.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "model/stages/setup.hpp"
#include "model/vectors/record_vectors.hpp"

namespace fxr {

namespace {

// What a field means, for the manifest (by its name without the v0_ / e0_ / num0_ prefixes).
std::string describe(const std::string& name, int width, bool is_signed) {
  std::string base = name;
  const size_t us = base.find('_');
  if (us != std::string::npos && us + 1 < base.size() &&
      (base.compare(0, 1, "v") == 0 || base.compare(0, 1, "e") == 0) && std::isdigit((unsigned char)base[1]))
    base = base.substr(us + 1);
  static const std::pair<const char*, const char*> kMeaning[] = {
      {"prim", "primitive index (passes through)"},
      {"x", "snapped window x, subpixel_bits fraction bits"},
      {"y", "snapped window y, subpixel_bits fraction bits"},
      {"ax", "attribute window x, attr_subpixel_bits fraction bits"},
      {"ay", "attribute window y, attr_subpixel_bits fraction bits"},
      {"z", "z/w, z_frac_bits fraction bits (more than 1: rejected)"},
      {"viewport_x", "viewport origin x, pixels"},
      {"viewport_y", "viewport origin y, pixels"},
      {"viewport_w", "viewport width, pixels"},
      {"viewport_h", "viewport height, pixels"},
      {"scissor_x", "scissor origin x, pixels"},
      {"scissor_y", "scissor origin y, pixels"},
      {"scissor_w", "scissor width, pixels (negative: no scissor)"},
      {"scissor_h", "scissor height, pixels (negative: no scissor)"},
      {"cull", "CullMode: 0 none, 1 back, 2 front"},
      {"front_ccw", "1: counter-clockwise (y up) is front-facing"},
      {"interp", "InterpMode: 0 perspective, 1 affine"},
      {"outcome", "SetupOutcome: 0 ok, 1 zero area, 2 back face, 3 no samples, 4 range"},
      {"a", "edge coefficient of X (y_a - y_b), counter-clockwise normalised"},
      {"b", "edge coefficient of Y (x_b - x_a)"},
      {"c", "edge constant (x_a y_b - x_b y_a)"},
      {"bias", "top-left bias: 0 on top / left edges, -1 otherwise"},
      {"area2", "twice the area on the sample grid (> 0)"},
      {"front", "front-facing"},
      {"x0", "first candidate pixel column"},
      {"x1", "last candidate pixel column (inclusive)"},
      {"y0", "first candidate pixel row"},
      {"y1", "last candidate pixel row (inclusive)"},
      {"z_den", "depth divisor 2A * 2^z_frac_bits (attribute planes: 2A' * 2^(z_frac_bits - depth bits))"},
      {"den_exp", "block exponent of the 1/w plane"},
  };
  std::string meaning;
  for (const auto& [n, m] : kMeaning)
    if (base == n) meaning = m;
  if (meaning.empty()) {
    auto ends = [&](const char* s) {
      const std::string t = s;
      return base.size() >= t.size() && base.compare(base.size() - t.size(), t.size(), t) == 0;
    };
    if (ends("_neg")) meaning = "sign of the FxFloat";
    else if (ends("_sig")) meaning = "FxFloat significand, msb set (0 for zero)";
    else if (ends("_exp")) meaning = "exponent (of the significand's lsb / of the block)";
    else if (ends("_c")) meaning = "plane value at the anchor pixel";
    else if (ends("_dx")) meaning = "plane step per pixel in x";
    else if (ends("_dy")) meaning = "plane step per pixel in y";
    else if (ends("_i0")) meaning = "plane anchor column";
    else if (ends("_j0")) meaning = "plane anchor row";
  }
  return std::string(is_signed ? "signed" : "unsigned") + ", " + std::to_string(width) + " bits" +
         (meaning.empty() ? "" : ": " + meaning);
}

// The draw state the stage reads as a record (visit_setup_state), for the record packers.
struct SetupState {
  DrawState st;
  template <class V>
  void visit(V& v, const RecordShape& s) { visit_setup_state(v, s, st); }
};

// Raw-bit helpers for the generators (platform-independent: no std distributions).
// Signed value with |v| < 2^bits (bits ≤ 62), uniform bit pattern.
int64_t random_signed(std::mt19937_64& rng, int bits) {
  const int64_t m = (int64_t)(uint64_t)low_bits(rng(), bits);
  return (rng() & 1) ? -m : m;
}

class SetupVectors : public VectorModel {
 public:
  explicit SetupVectors(const Config& c) : cfg_(c), shape_{cfg_, kSetupVecVaryings} {
    const RasterConfig& r = cfg_.raster;
    attr_ = attr_planes(r);
    sp_ = r.subpixel_bits;
    wib_ = r.window_int_bits;
    cb_ = wib_ + sp_;
    sig_rw_ = attr_ ? r.attr_sig_bits : cfg_.recip.out_sig_bits;
    sig_vw_ = attr_ ? r.attr_sig_bits : r.varying_sig_bits;
    std::vector<VecField> f;
    append_record_fields<SetupTriangle>(shape_, VecDir::In, f);
    append_record_fields<SetupState>(shape_, VecDir::In, f);
    n_in_ = f.size();
    f.push_back({"outcome", VecDir::Out, kSetupOutcomeBits, false, ""});
    append_record_fields<TriangleEquations>(shape_, VecDir::Out, f);
    for (size_t k = n_in_; k < f.size(); ++k)
      for (size_t j = 0; j < n_in_; ++j)
        if (f[j].name == f[k].name) f[k].name = "out_" + f[k].name;
    for (VecField& x : f) x.format = describe(x.name, x.width, x.is_signed);
    lay_ = VecLayout(f);
  }

  const VecLayout& layout() const override { return lay_; }

  nlohmann::json config_json() const override {
    // Setup reads the raster formats and the exponent field width (recip.exp_bits) and, on the
    // snapped path, the significand width of 1/w (recip.out_sig_bits).
    return {{"version", kConfigFormatVersion},
            {"raster", to_json_params(cfg_.raster)},
            {"recip", to_json_params(cfg_.recip)}};
  }

  void compute(VecRow& r) const override {
    SetupTriangle tri;
    SetupState st;
    unpack_record(tri, shape_, r, 0);
    unpack_record(st, shape_, r, record_size<SetupTriangle>());
    st.st.num_varyings = kSetupVecVaryings;
    SetupStage stage(cfg_, st.st, true);
    TriangleEquations eq;
    const SetupOutcome o = stage.step(tri, [&eq](const TriangleEquations& e) { eq = e; });
    r[n_in_] = (vec_word)o;
    for (size_t k = n_in_ + 1; k < r.size(); ++k) r[k] = 0;  // not drawn: every other output 0
    if (o == SetupOutcome::Ok) pack_record(eq, shape_, r, n_in_ + 1, "setup vectors");
  }

  std::vector<VecRow> directed() const override;
  void random(std::mt19937_64& rng, VecRow& r) const override;

 private:
  // A vertex at (x, y) in subpixel units with attribute position x·2^(A−sp) + (dx, dy), depth z,
  // 1/w = (1 + f/8)·2^e_rw (normalised), v/w of varying m = ±(1 + m/4)·2^e_v.
  SetupVertex vertex(int64_t x, int64_t y, int64_t dx = 0, int64_t dy = 0, uint64_t z = 0, int e_rw = 0,
                     int e_v = 0) const;
  template <class R>
  size_t record_size() const {
    std::vector<VecField> f;
    append_record_fields<R>(shape_, VecDir::In, f);
    return f.size();
  }
  void pack(VecRow& r, const SetupTriangle& t, const DrawState& st) const {
    pack_record(t, shape_, r, 0, "setup vectors");
    pack_record(SetupState{st}, shape_, r, record_size<SetupTriangle>(), "setup vectors");
  }
  FxFloat norm(bool neg, uint64_t sig, int lead, int bits) const {
    FxFloat f;
    f.neg = neg;
    f.sig = sig;
    f.exp = lead - (bits - 1);
    return f;
  }
  int64_t clamp_xy(int64_t v) const { return std::clamp<int64_t>(v, -(1ll << (cb_ - 1)), (1ll << (cb_ - 1)) - 1); }
  int64_t clamp_axy(int64_t v) const {
    const int ab = attr_position_bits();
    return std::clamp<int64_t>(v, -(1ll << (ab - 1)), (1ll << (ab - 1)) - 1);
  }
  int attr_position_bits() const { return wib_ + cfg_.raster.attr_subpixel_bits; }
  // Attribute position of a snapped coordinate: x·2^(A−sp) + offset (A > sp), clamped.
  int64_t attr_of(int64_t x, int64_t off) const {
    if (!attr_) return x;
    return clamp_axy(x * (1ll << (cfg_.raster.attr_subpixel_bits - sp_)) + off);
  }

  Config cfg_;
  RecordShape shape_;
  bool attr_ = false;
  int sp_ = 0, wib_ = 0, cb_ = 0, sig_rw_ = 0, sig_vw_ = 0;
  size_t n_in_ = 0;
  VecLayout lay_;
};

SetupVertex SetupVectors::vertex(int64_t x, int64_t y, int64_t dx, int64_t dy, uint64_t z, int e_rw,
                                 int e_v) const {
  SetupVertex v;
  v.x = clamp_xy(x);
  v.y = clamp_xy(y);
  v.ax = attr_ ? attr_of(v.x, dx) : v.x;
  v.ay = attr_ ? attr_of(v.y, dy) : v.y;
  v.z = z;
  v.rw = norm(false, (1ull << (sig_rw_ - 1)) | (1ull << (sig_rw_ - 4)), e_rw, sig_rw_);
  for (int m = 0; m < kSetupVecVaryings; ++m)
    v.vw[m] = norm(m & 1, (1ull << (sig_vw_ - 1)) | ((uint64_t)m << (sig_vw_ - 3)), e_v + m, sig_vw_);
  return v;
}

std::vector<VecRow> SetupVectors::directed() const {
  std::vector<VecRow> out;
  const int64_t S = 1ll << sp_;  // one pixel in subpixel units
  const int64_t H = S / 2;       // half a pixel (0 when subpixel_bits = 0)
  const uint64_t one_z = 1ull << cfg_.raster.z_frac_bits;
  DrawState base;
  base.num_varyings = kSetupVecVaryings;
  auto add = [&](const SetupTriangle& t, const DrawState& st) {
    VecRow r = blank();
    pack(r, t, st);
    out.push_back(r);
  };
  auto tri = [&](int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t x2, int64_t y2) {
    SetupTriangle t;
    t.prim = (uint32_t)out.size();
    t.v[0] = vertex(x0, y0, 3, -5, one_z / 4, 0, 0);
    t.v[1] = vertex(x1, y1, -7, 2, one_z / 2, -1, 1);
    t.v[2] = vertex(x2, y2, 1, 1, one_z - 1, -2, -3);
    return t;
  };
  auto flip = [](SetupTriangle t) {  // the other winding
    std::swap(t.v[1], t.v[2]);
    return t;
  };
  const SetupTriangle ccw = tri(10 * S + 3, 10 * S + 1, 100 * S + 5, 20 * S + 7, 50 * S + 1, 90 * S + 2);
  // Every cull mode × front face × winding: ok or back face.
  for (CullMode c : {CullMode::None, CullMode::Back, CullMode::Front})
    for (bool fccw : {true, false})
      for (bool w : {true, false}) {
        DrawState st = base;
        st.cull = c;
        st.front_ccw = fccw;
        add(w ? ccw : flip(ccw), st);
      }
  // Zero area: collinear, two equal vertices, all equal (culled even with culling on).
  for (CullMode c : {CullMode::None, CullMode::Back}) {
    DrawState st = base;
    st.cull = c;
    add(tri(10 * S, 10 * S, 20 * S, 20 * S, 40 * S, 40 * S), st);
    add(tri(10 * S, 10 * S, 10 * S, 10 * S, 40 * S, 7 * S), st);
    add(tri(5 * S, 5 * S, 5 * S, 5 * S, 5 * S, 5 * S), st);
  }
  // No samples: a triangle between pixel centres, one outside the viewport, one outside the scissor.
  add(tri(10 * S + 1, 10 * S + 1, 10 * S + H - 1, 10 * S + 1, 10 * S + 1, 10 * S + H - 1), base);
  add(tri(-50 * S, -50 * S, -10 * S, -50 * S, -30 * S, -10 * S), base);
  add(tri(300 * S, 10 * S, 400 * S, 10 * S, 350 * S, 90 * S), base);
  {
    DrawState st = base;
    st.scissor_x = 200, st.scissor_y = 200, st.scissor_w = 20, st.scissor_h = 20;
    add(ccw, st);
    st.scissor_x = 20, st.scissor_y = 20, st.scissor_w = 20, st.scissor_h = 20;
    add(ccw, st);  // inside: drawn, the rectangle clipped to the scissor
    st.scissor_w = 0;
    add(ccw, st);  // empty scissor
    st.scissor_w = -1;
    add(ccw, st);  // negative: no scissor
  }
  // Range: z > 1 on each vertex (the only input that can leave its range at these widths).
  for (int k = 0; k < 3; ++k) {
    SetupTriangle t = ccw;
    t.v[k].z = one_z + 1;
    add(t, base);
    t.v[k].z = one_z;  // z = 1 exactly: drawn
    add(t, base);
  }
  // Top-left ties: edges through pixel centres (horizontal top / bottom, vertical left / right,
  // diagonal), both windings; one-pixel and sub-pixel triangles around a centre.
  {
    const int64_t c = 20 * S + H;  // pixel centre coordinate
    const std::vector<SetupTriangle> ties = {
        tri(c, c, c + 8 * S, c, c, c + 8 * S),          // left and bottom edges on centres
        tri(c, c + 8 * S, c + 8 * S, c, c + 8 * S, c + 8 * S),  // top and right edges on centres
        tri(c, c, c + 8 * S, c + 4 * S, c, c + 8 * S),
        tri(c - H, c - H, c + H, c - H, c, c + H),        // one pixel around a centre
        tri(c - 1, c - 1, c + 1, c - 1, c, c + 1),        // sub-pixel, containing a centre
        tri(c, c, c + 1, c, c, c + 1),                    // sub-pixel, a vertex on the centre
        tri(c, c, c + 3 * S, c + 3 * S, c - 3 * S, c + 3 * S),
    };
    for (const SetupTriangle& t : ties) {
      add(t, base);
      add(flip(t), base);
    }
  }
  // Guard-band extremes: vertices at the ends of the coordinate range, viewport at the window's
  // ends, a full-range triangle, the viewport's corners (partly outside the window range).
  {
    const int64_t lo = -(1ll << (cb_ - 1)), hi = (1ll << (cb_ - 1)) - 1;
    DrawState st = base;
    add(tri(lo, lo, hi, lo, lo, hi), st);
    add(tri(hi, hi, lo, hi, hi, lo), st);
    add(tri(lo, lo, hi, hi, lo, hi), st);
    st.viewport_x = -(1 << (wib_ - 1));
    st.viewport_y = -(1 << (wib_ - 1));
    st.viewport_w = (1 << wib_) - 1;  // the largest size: the whole range but its last pixel
    st.viewport_h = (1 << wib_) - 1;
    add(tri(lo, lo, hi, lo, lo, hi), st);
    add(tri(hi, hi, lo, hi, hi, lo), st);
    add(tri(lo, lo, lo + 5 * S, lo, lo, lo + 5 * S), st);
    add(tri(hi, hi, hi - 5 * S, hi, hi, hi - 5 * S), st);
    st.viewport_x = (1 << (wib_ - 1)) - 10;  // the viewport runs past the window range
    st.viewport_y = (1 << (wib_ - 1)) - 10;
    st.viewport_w = 100;
    st.viewport_h = 100;
    add(tri(hi - 20 * S, hi - 20 * S, hi, hi - 20 * S, hi, hi), st);
    st.viewport_x = 0;  // runs past the window range
    st.viewport_y = -5;
    st.viewport_w = (1 << wib_) - 1;
    st.viewport_h = (1 << wib_) - 1;
    add(tri(lo, lo, hi, lo, lo, hi), st);
    add(tri(hi, hi, 0, hi, hi, 0), st);
  }
  // Slivers and a full-viewport pair.
  add(tri(0, 0, 255 * S, 1, 0, 2), base);
  add(tri(3, 0, 3 + 1, 255 * S, 5, 100 * S), base);
  add(tri(0, 0, 256 * S, 0, 0, 256 * S), base);
  add(tri(256 * S, 0, 256 * S, 256 * S, 0, 256 * S), base);
  // Planes: w ratio 2^20 inside a triangle (beyond exact block alignment), zero and negative
  // v/w, affine mode, the attribute triangle of zero area (planes from the snapped triangle),
  // and large triangles whose attribute coordinates drop fraction bits.
  {
    SetupTriangle t = ccw;
    t.v[1].rw = norm(false, (1ull << (sig_rw_ - 1)) + 12345, -20, sig_rw_);
    t.v[2].rw = norm(false, (1ull << sig_rw_) - 1, 5, sig_rw_);
    add(t, base);
    t.v[0].vw[0] = FxFloat{};
    t.v[1].vw[1] = norm(true, (1ull << sig_vw_) - 1, 40, sig_vw_);
    add(t, base);
    DrawState st = base;
    st.interp = InterpMode::Affine;
    add(t, st);
    SetupTriangle z = ccw;
    for (int k = 0; k < 3; ++k) z.v[k].ax = z.v[0].ax, z.v[k].ay = z.v[0].ay;
    add(z, base);
    st = base;
    st.viewport_x = -(1 << (wib_ - 1));
    st.viewport_y = -(1 << (wib_ - 1));
    st.viewport_w = (1 << wib_) - 1;
    st.viewport_h = (1 << wib_) - 1;
    add(tri(-9000 * S, -9000 * S, 9000 * S + 5, -8000 * S, 100 * S, 9000 * S), st);
    add(tri(-100 * S, -100 * S, 100 * S, -100 * S, 0, 20000 * S), st);
  }
  return out;
}

// Random: one raw rng() word per decision. Draw state: the 256² viewport half the time, else a
// random one (anywhere in the window range, the whole range, or 1..16 px); a scissor one time in
// four; no culling half the time, else back or front; winding rule uniform; affine one time in 8. Vertices around a point of the viewport, at
// one of 8 sizes: sub-pixel, 8 px, 128 px, a quarter of the range, anywhere, on pixel centres
// (top-left ties), slivers, degenerate (collinear or repeated). Attribute positions: the snapped
// position plus up to half a subpixel (as the snap made it), a few subpixels, or all equal.
// 1/w: a common exponent with spreads of 0..3, 0..20 (w ratios to 10^6) or 0..60 binades; v/w
// independent, one in eight zero.
void SetupVectors::random(std::mt19937_64& rng, VecRow& r) const {
  const RasterConfig& rc = cfg_.raster;
  DrawState st;
  const int64_t half_range = 1ll << (wib_ - 1);
  switch (rng() & 7) {
    case 0: case 1: case 2: case 3: break;  // 256², origin 0
    case 4: case 5:
      st.viewport_x = (int)vec_random_in(rng, -half_range, half_range - 1);
      st.viewport_y = (int)vec_random_in(rng, -half_range, half_range - 1);
      st.viewport_w = (int)vec_random_in(rng, 1, (1ll << vec_random_in(rng, 1, wib_)) - 1);
      st.viewport_h = (int)vec_random_in(rng, 1, (1ll << vec_random_in(rng, 1, wib_)) - 1);
      break;
    case 6:
      st.viewport_x = st.viewport_y = (int)-half_range;
      st.viewport_w = st.viewport_h = (int)(2 * half_range - 1);
      break;
    default:
      st.viewport_x = (int)vec_random_in(rng, -300, 300);
      st.viewport_y = (int)vec_random_in(rng, -300, 300);
      st.viewport_w = (int)vec_random_in(rng, 1, 16);
      st.viewport_h = (int)vec_random_in(rng, 1, 16);
  }
  if ((rng() & 3) == 0) {
    const int64_t lim = half_range;  // the field: signed window_int_bits
    st.scissor_x = (int)std::clamp<int64_t>(st.viewport_x + vec_random_in(rng, -8, st.viewport_w), -lim, lim - 1);
    st.scissor_y = (int)std::clamp<int64_t>(st.viewport_y + vec_random_in(rng, -8, st.viewport_h), -lim, lim - 1);
    st.scissor_w = (int)vec_random_in(rng, (rng() & 15) == 0 ? -3 : 0, st.viewport_w);
    st.scissor_h = (int)vec_random_in(rng, 0, st.viewport_h);
  }
  st.cull = (rng() & 1) ? CullMode::None : (rng() & 1) ? CullMode::Back : CullMode::Front;
  st.front_ccw = rng() & 1;
  st.interp = (rng() & 7) == 0 ? InterpMode::Affine : InterpMode::Perspective;

  // A point of the viewport (subpixel units), then the vertices around it.
  const int64_t S = 1ll << sp_;
  // One draw per statement (the operands of + are unsequenced): pixel, then subpixel.
  const int64_t cx_px = (int64_t)st.viewport_x + vec_random_in(rng, 0, st.viewport_w - 1);
  const int64_t cx = cx_px * S + (int64_t)(uint64_t)low_bits(rng(), sp_);
  const int64_t cy_px = (int64_t)st.viewport_y + vec_random_in(rng, 0, st.viewport_h - 1);
  const int64_t cy = cy_px * S + (int64_t)(uint64_t)low_bits(rng(), sp_);
  int64_t x[3], y[3];
  const uint64_t size = rng() & 7;
  auto around = [&](int bits) {
    for (int k = 0; k < 3; ++k) x[k] = cx + random_signed(rng, bits), y[k] = cy + random_signed(rng, bits);
  };
  switch (size) {
    case 0: around(sp_); break;
    case 1: around(sp_ + 3); break;
    case 2: around(sp_ + 7); break;
    case 3: around(cb_ - 2); break;
    case 4:
      for (int k = 0; k < 3; ++k) x[k] = random_signed(rng, cb_ - 1), y[k] = random_signed(rng, cb_ - 1);
      break;
    case 5: {  // pixel centres, up to 8 px apart: edges through centres, ties
      const int64_t px = cx >> sp_, py = cy >> sp_;
      for (int k = 0; k < 3; ++k) {
        x[k] = (px + vec_random_in(rng, -8, 8)) * S + S / 2;
        y[k] = (py + vec_random_in(rng, -8, 8)) * S + S / 2;
      }
      break;
    }
    case 6: {  // sliver: v2 near the segment v0 → v1
      const int bits = (int)vec_random_in(rng, sp_, cb_ - 2);
      x[0] = cx, y[0] = cy;
      x[1] = cx + random_signed(rng, bits), y[1] = cy + random_signed(rng, bits);
      const int64_t t = vec_random_in(rng, 0, 16);
      x[2] = x[0] + (x[1] - x[0]) * t / 16 + vec_random_in(rng, -2, 2);
      y[2] = y[0] + (y[1] - y[0]) * t / 16 + vec_random_in(rng, -2, 2);
      break;
    }
    default: {  // degenerate: collinear on a lattice line, or a repeated vertex
      around(sp_ + 5);
      if (rng() & 1) {
        const int64_t k = vec_random_in(rng, -3, 3);
        x[2] = x[0] + k * (x[1] - x[0]);
        y[2] = y[0] + k * (y[1] - y[0]);
      } else {
        const int a = (int)vec_random_in(rng, 0, 2);
        x[(a + 1) % 3] = x[a], y[(a + 1) % 3] = y[a];
      }
    }
  }
  SetupTriangle t;
  t.prim = (uint32_t)rng();
  const int d = rc.attr_subpixel_bits - sp_;  // attribute bits below a subpixel (> 0 on the attribute path)
  const uint64_t amode = rng() & 15;
  const uint64_t one_z = 1ull << rc.z_frac_bits;
  const int rw_base = (int)vec_random_in(rng, -24, 24);
  const uint64_t spread_sel = rng() & 15;
  const int rw_spread = spread_sel < 12 ? 3 : spread_sel < 15 ? 20 : 60;
  for (int k = 0; k < 3; ++k) {
    SetupVertex& v = t.v[k];
    v.x = clamp_xy(x[k]);
    v.y = clamp_xy(y[k]);
    if (attr_) {
      int64_t ox = 0, oy = 0;
      if (amode < 12) {  // as the snap left it: within half a subpixel
        ox = vec_random_in(rng, -(1ll << (d - 1)), 1ll << (d - 1));
        oy = vec_random_in(rng, -(1ll << (d - 1)), 1ll << (d - 1));
      } else if (amode < 15) {  // a few subpixels away
        ox = random_signed(rng, d + 3);
        oy = random_signed(rng, d + 3);
      }
      v.ax = attr_of(v.x, ox);
      v.ay = attr_of(v.y, oy);
      if (amode == 15) v.ax = t.v[0].ax, v.ay = t.v[0].ay;  // attribute triangle of zero area
    } else {
      v.ax = v.x, v.ay = v.y;
    }
    const uint64_t zsel = rng() & 63;
    v.z = zsel == 0 ? one_z + 1 + (uint64_t)low_bits(rng(), rc.z_frac_bits - 1)  // z > 1: range
          : zsel == 1 ? 0
          : zsel == 2 ? one_z
          : (uint64_t)low_bits(rng(), rc.z_frac_bits);
    const uint64_t rsel = rng() & 63;
    // One draw per statement: the order of draws inside one function call's arguments is
    // unspecified (g++ and clang differ), and the file must be the same on every platform. The
    // order is the one the committed vectors/setup files were generated with (exponent first).
    const int rw_exp = rw_base + (int)vec_random_in(rng, 0, rw_spread);
    const uint64_t rw_sig = (1ull << (sig_rw_ - 1)) | (uint64_t)low_bits(rng(), sig_rw_ - 1);
    v.rw = norm(rsel == 0, rw_sig, rw_exp, sig_rw_);
    if (rsel == 1) v.rw = FxFloat{};
    for (int m = 0; m < kSetupVecVaryings; ++m) {
      const uint64_t vsel = rng() & 7;
      const int vw_exp = (int)vec_random_in(rng, -40, 40);  // draw order as for rw above
      const uint64_t vw_sig = (1ull << (sig_vw_ - 1)) | (uint64_t)low_bits(rng(), sig_vw_ - 1);
      const bool vw_neg = rng() & 1;
      v.vw[m] = norm(vw_neg, vw_sig, vw_exp, sig_vw_);
      if (vsel == 0) v.vw[m] = FxFloat{};
    }
  }
  pack(r, t, st);
}

}  // namespace

std::unique_ptr<VectorModel> make_setup_vectors(const Config& cfg) {
  return std::make_unique<SetupVectors>(cfg);
}

}  // namespace fxr

// Co-simulation of rtl/fxr_viewport.sv (stage 4, the model's "viewport") on transaction dumps
// (tb/txn_harness.hpp): the committed dump of scenes/transactions.json and the default scene
// dumped at build time, every snapped triangle bit-identical and in order with the model's
// viewport.out, triangles out of range producing no output and one rej_range_o pulse, under random
// input gaps and output back-pressure; and directed and random rows whose expected values are
// computed here with GMP rationals from the stage's definition (docs/pipeline.md, stage 4 and
// "Attribute positions"), not with the model's functions: snap ties at ½ subpixel of both
// parities, negative coordinates, both ends of the code ranges, w at the w_min plane, very large
// and very small w, depth saturation, zero varyings, the affine mode. docs/rtl.md, "fxr_viewport".
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "Vfxr_viewport.h"
#include "Vfxr_viewport_lanes1.h"
#include "Vfxr_viewport_lanes7.h"
#include "model/stages/setup.hpp"
#include "model/stages/viewport.hpp"
#include "txn/draw_state_ports.hpp"
#include "txn_harness.hpp"

namespace {

using fxr::SceneStageVectors;
using fxr::tb::TxnHook;
using fxr::tb::TxnOptions;
using fxr::tb::TxnResult;

const std::string kCommitted = std::string(FXR_SOURCE_DIR) + "/vectors/scenes/transactions";
const std::string kDefault = std::string(FXR_BINARY_DIR) + "/vectors/scene_default";

TxnOptions opts(const std::string& run, uint64_t seed, unsigned gap, unsigned stall) {
  return fxr::tb::txn_options("viewport", run, seed, gap, stall);
}

// The draw state fxr_viewport reads, and its range pulses.
template <class Dut>
struct Drive {
  fxr::DrawState st;
  int wib = 0;
  uint64_t rejected = 0;
  TxnHook<Dut> hook() {
    TxnHook<Dut> h;
    h.reset = [this] { rejected = 0; };
    h.drive = [this](Dut& d) {
      d.viewport_x_i = fxr::tb::state_bits(st.viewport_x, wib);
      d.viewport_y_i = fxr::tb::state_bits(st.viewport_y, wib);
      d.viewport_w_i = fxr::tb::state_bits(st.viewport_w, wib + 1);
      d.viewport_h_i = fxr::tb::state_bits(st.viewport_h, wib + 1);
      d.interp_i = (uint8_t)st.interp;
    };
    h.observe = [this](Dut& d) { rejected += d.rej_range_o; };
    return h;
  }
};

template <class Dut = Vfxr_viewport>
// all_handshakes: no gaps, 25 % / 25 % and 60 % / 70 %; else no gaps and 60 % / 70 % only.
// lanes: the DUT's Lanes. Without gaps or stalls, and when every triangle is emitted, the stream
// is busy for exactly (rows − 1)·ii + latency + 1 clocks with ii and latency from
// ViewportStage::cost (model/stages/viewport.hpp: the model's cost is the RTL's).
void run_dump(const std::string& dir, const std::string& name, uint64_t min_rows, bool all_handshakes = true,
              int lanes = fxr::kViewportLanes) {
  const SceneStageVectors v = fxr::load_scene_stage(dir, "viewport");
  ASSERT_GE(v.out.rows, min_rows);
  uint64_t dropped = 0;  // inputs with no output: the model's RejectedRange
  for (uint64_t r = 0; r < v.in.rows; ++r) dropped += v.in.row(r)[1] == 0;
  for (auto [seed, gap, stall] : {std::tuple{1u, 0u, 0u}, {2u, 25u, 25u}, {3u, 60u, 70u}}) {
    if (!all_handshakes && seed == 2) continue;
    Drive<Dut> dr;
    dr.st = fxr::tb::read_dump_draw_state(dir);
    dr.wib = v.cfg.raster.window_int_bits;
    const TxnHook<Dut> h = dr.hook();
    const TxnResult r = fxr::tb::run_txn<Dut>(v, nullptr, opts(name + std::to_string(seed), seed, gap, stall), &h);
    EXPECT_TRUE(r.passed()) << "seed " << seed;
    EXPECT_EQ(r.outputs, v.out.rows);
    EXPECT_EQ(r.inputs, v.in.rows);
    EXPECT_EQ(dr.rejected, dropped);
    if (seed == 1 && r.inputs > 0 && dropped == 0) {
      const fxr::StageCost c = fxr::ViewportStage::cost(v.cfg, fxr::kRecordPackageVaryings, lanes);
      EXPECT_EQ(r.busy_cycles, (v.in.rows - 1) * (uint64_t)c.ii + (uint64_t)c.latency + 1)
          << "ViewportStage::cost: ii " << c.ii << ", latency " << c.latency << " at " << lanes << " lanes";
    }
    if (seed == 1 && r.inputs > 0)
      std::printf("viewport %s: %llu triangles, %llu busy cycles (%.3f cycles/triangle), first in %llu, last out %llu\n",
                  name.c_str(), (unsigned long long)v.in.rows, (unsigned long long)r.busy_cycles,
                  (double)r.busy_cycles / (double)v.in.rows, (unsigned long long)r.first_in_cycle,
                  (unsigned long long)r.last_out_cycle);
  }
}

TEST(ViewportTxn, CommittedDumpMatchesTheModel) { run_dump(kCommitted, "viewport_committed_", 3); }

TEST(ViewportTxn, DefaultSceneMatchesTheModel) { run_dump(kDefault, "viewport_default_", 1000); }

// Other lane counts (tb/txn/fxr_viewport_lanes1.sv, _lanes7.sv): 18 slots with one snap unit; 3
// slots, the last one partly empty, with two snap units.
TEST(ViewportTxn, OneLaneMatchesTheModel) {
  run_dump<Vfxr_viewport_lanes1>(kCommitted, "viewport_lanes1_committed_", 3, true, 1);
  run_dump<Vfxr_viewport_lanes1>(kDefault, "viewport_lanes1_default_", 1000, false, 1);
}
TEST(ViewportTxn, SevenLanesMatchTheModel) {
  run_dump<Vfxr_viewport_lanes7>(kCommitted, "viewport_lanes7_committed_", 3, true, 7);
  run_dump<Vfxr_viewport_lanes7>(kDefault, "viewport_lanes7_default_", 1000, false, 7);
}

// ---- expected values from the definition (GMP) ------------------------------------------------

struct Fx {  // (−1)^neg·sig·2^exp, as the record holds it
  bool neg = false;
  uint64_t sig = 0;
  int exp = 0;
};

mpq_class value(const Fx& f) {
  mpq_class q(mpz_class(std::to_string(f.sig)));
  mpz_class p2 = 1;
  mpz_mul_2exp(p2.get_mpz_t(), p2.get_mpz_t(), (mp_bitcnt_t)std::abs(f.exp));
  if (f.exp >= 0) q *= p2;
  else q /= p2;
  return f.neg ? mpq_class(-q) : q;
}
mpq_class pow2(int e) { return value(Fx{false, 1, e}); }

// Round half to even of a rational.
mpz_class rne(const mpq_class& q) {
  mpz_class fl;
  mpz_fdiv_q(fl.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  const mpq_class frac = q - mpq_class(fl);
  const mpq_class half(1, 2);
  if (frac > half || (frac == half && mpz_odd_p(fl.get_mpz_t()))) fl += 1;
  return fl;
}

// The nearest-even `bits`-bit float of q ≠ 0.
Fx float_of(const mpq_class& q, int bits) {
  Fx f;
  f.neg = q < 0;
  const mpq_class a = abs(q);
  int e = 0;  // a·2^−e ∈ [2^(bits−1), 2^bits)
  while (a * pow2(-e) >= pow2(bits)) ++e;
  while (a * pow2(-e) < pow2(bits - 1)) --e;
  mpz_class s = rne(a * pow2(-e));
  if (s == mpz_class(1) << bits) s >>= 1, ++e;
  f.sig = s.get_ui();
  f.exp = e;
  return f;
}

struct Vtx {
  Fx x, y, z, w, wa, var[4];
  Fx r;  // the reciprocal unit's 1/w (the snap's factor; any value for the stage's contract)
};

struct Expected {
  bool range = false;
  int64_t x = 0, y = 0, ax = 0, ay = 0;
  uint64_t z = 0;
  Fx rw, vw[4];
};

Expected expect(const Vtx& v, const fxr::DrawState& st, const fxr::Config& cfg, int nv) {
  const fxr::RasterConfig& rc = cfg.raster;
  Expected e;
  const int cb = rc.window_int_bits + rc.subpixel_bits, pb = rc.window_int_bits + rc.attr_subpixel_bits;
  auto in_range = [](const mpz_class& c, int bits) { return c >= -(mpz_class(1) << (bits - 1)) && c < (mpz_class(1) << (bits - 1)); };
  auto window = [&](const mpq_class& n, int size, int origin, int frac, int bits, int64_t& out) {
    const mpz_class c = rne(((n + 1) * size / 2 + origin) * pow2(frac));
    if (!in_range(c, bits)) e.range = true;
    else out = c.get_si();
  };
  const mpq_class rq = value(v.r);
  const Fx& aw = v.wa.sig ? v.wa : v.w;
  const mpq_class w = value(aw);
  window(value(v.x) * rq, st.viewport_w, st.viewport_x, rc.subpixel_bits, cb, e.x);
  window(value(v.y) * rq, st.viewport_h, st.viewport_y, rc.subpixel_bits, cb, e.y);
  window(value(v.x) / w, st.viewport_w, st.viewport_x, rc.attr_subpixel_bits, pb, e.ax);
  window(value(v.y) / w, st.viewport_h, st.viewport_y, rc.attr_subpixel_bits, pb, e.ay);
  const mpq_class zn = value(v.z) / w;
  const mpz_class one = mpz_class(1) << rc.z_frac_bits;
  mpz_class z = zn <= 0 ? mpz_class(0) : rne(zn * pow2(rc.z_frac_bits));
  if (z > one) z = one;
  e.z = z.get_ui();
  e.rw = float_of(1 / w, rc.attr_sig_bits);
  for (int k = 0; k < nv; ++k) {
    const Fx& a = v.var[k];
    if (a.sig == 0) e.vw[k] = Fx{a.neg, 0, st.interp == fxr::InterpMode::Affine ? a.exp : 0};
    else e.vw[k] = float_of(st.interp == fxr::InterpMode::Affine ? value(a) : value(a) / w, rc.attr_sig_bits);
  }
  return e;
}

// A value with a `bits`-bit significand (msb set) and the given leading exponent.
Fx fx_lead(bool neg, uint64_t sig, int bits, int lead) { return Fx{neg, sig, lead - (bits - 1)}; }

class Rows {
 public:
  explicit Rows(const SceneStageVectors& base) : v_(base) {
    v_.in.data.clear();
    v_.out.data.clear();
    v_.in.rows = v_.out.rows = 0;
    for (size_t f = 0; f < v_.in.lay.size(); ++f) in_col_[v_.in.lay[f].name] = f;
    for (size_t f = 0; f < v_.out.lay.size(); ++f) out_col_[v_.out.lay[f].name] = f;
  }
  // One triangle; returns whether the expectation is a drop.
  bool add(const Vtx (&t)[3], const fxr::DrawState& st) {
    const uint64_t txn = v_.in.rows;
    fxr::VecRow in(v_.in.lay.size(), 0);
    Expected ex[3];
    bool range = false;
    for (int i = 0; i < 3; ++i) {
      ex[i] = expect(t[i], st, v_.cfg, v_.num_varyings);
      range = range || ex[i].range;
    }
    in[0] = txn;
    in[1] = range ? 0 : 1;
    set(in, true, "prim", 5000 + txn);
    for (int i = 0; i < 3; ++i) {
      const std::string p = "v" + std::to_string(i) + "_";
      put(in, true, p + "x", t[i].x);
      put(in, true, p + "y", t[i].y);
      put(in, true, p + "z", t[i].z);
      put(in, true, p + "w", t[i].w);
      if (in_col_.count(p + "wa_sig")) put(in, true, p + "wa", t[i].wa);
      for (int k = 0; k < v_.num_varyings; ++k) put(in, true, p + "var" + std::to_string(k), t[i].var[k]);
      put(in, true, "r" + std::to_string(i), t[i].r);
    }
    v_.in.data.insert(v_.in.data.end(), in.begin(), in.end());
    ++v_.in.rows;
    if (range) return true;
    fxr::VecRow out(v_.out.lay.size(), 0);
    out[0] = txn;
    out[1] = 0;
    out[2] = 1;
    set(out, false, "prim", 5000 + txn);
    for (int i = 0; i < 3; ++i) {
      const std::string p = "v" + std::to_string(i) + "_";
      set(out, false, p + "x", (uint64_t)ex[i].x);
      set(out, false, p + "y", (uint64_t)ex[i].y);
      set(out, false, p + "ax", (uint64_t)ex[i].ax);
      set(out, false, p + "ay", (uint64_t)ex[i].ay);
      set(out, false, p + "z", ex[i].z);
      put(out, false, p + "rw", ex[i].rw);
      for (int k = 0; k < v_.num_varyings; ++k) put(out, false, p + "vw" + std::to_string(k), ex[i].vw[k]);
    }
    v_.out.data.insert(v_.out.data.end(), out.begin(), out.end());
    ++v_.out.rows;
    return false;
  }
  const SceneStageVectors& vectors() const { return v_; }

 private:
  // A field of the input (in = true) or output row, masked to its width.
  void set(fxr::VecRow& row, bool in, const std::string& name, uint64_t val) {
    const std::map<std::string, size_t>& cols = in ? in_col_ : out_col_;
    const auto it = cols.find(name);
    if (it == cols.end()) throw std::runtime_error("no field " + name);
    const int w = (in ? v_.in.lay : v_.out.lay)[it->second].width;
    row[it->second] = w >= 64 ? val : (val & ((1ull << w) - 1));
  }
  void put(fxr::VecRow& row, bool in, const std::string& name, const Fx& f) {
    set(row, in, name + "_neg", f.neg);
    set(row, in, name + "_sig", f.sig);
    set(row, in, name + "_exp", (uint64_t)(int64_t)f.exp);
  }
  SceneStageVectors v_;
  std::map<std::string, size_t> in_col_, out_col_;
};

// d truncated to a `bits`-bit significand (exact for the dyadic values of the directed cases; the
// expectations are computed from the Fx, never from d). Zero: the exponent of float32's zeros.
Fx fx_of(double d, int bits = 32) {
  Fx f;
  f.neg = std::signbit(d);
  if (d == 0) return Fx{f.neg, 0, -149};
  int e = 0;
  const double m = std::frexp(std::fabs(d), &e);
  f.sig = (uint64_t)std::ldexp(m, bits);
  f.exp = e - bits;
  return f;
}
const int kRecipSig = 24;  // recip.out_sig_bits of the committed dump's configuration (checked below)
Vtx vtx(double x, double y, double z, double w, double r, double v0 = 0.5, double v1 = -3) {
  Vtx t;
  t.x = fx_of(x);
  t.y = fx_of(y);
  t.z = fx_of(z);
  t.w = fx_of(w);
  t.wa = t.w;
  t.r = fx_of(r, kRecipSig);
  t.var[0] = fx_of(v0);
  t.var[1] = fx_of(v1);
  t.var[2] = fx_of(0.25);
  t.var[3] = fx_of(-0.75);
  return t;
}

template <class Dut = Vfxr_viewport>
void run_rows(const Rows& rows, const fxr::DrawState& st, const std::string& name, uint64_t want_drops) {
  for (auto [seed, gap, stall] : {std::tuple{4u, 0u, 0u}, {5u, 40u, 50u}}) {
    Drive<Dut> dr;
    dr.st = st;
    dr.wib = rows.vectors().cfg.raster.window_int_bits;
    const TxnHook<Dut> h = dr.hook();
    const TxnResult r = fxr::tb::run_txn<Dut>(rows.vectors(), nullptr, opts(name + std::to_string(seed), seed, gap, stall), &h);
    EXPECT_TRUE(r.passed()) << name << " seed " << seed;
    EXPECT_EQ(r.outputs, rows.vectors().out.rows);
    EXPECT_EQ(dr.rejected, want_drops);
  }
}

fxr::DrawState state(int w, int h, int x0, int y0, fxr::InterpMode m = fxr::InterpMode::Perspective) {
  fxr::DrawState st;
  st.viewport_w = w;
  st.viewport_h = h;
  st.viewport_x = x0;
  st.viewport_y = y0;
  st.interp = m;
  st.num_varyings = 2;
  return st;
}

TEST(ViewportTxn, DirectedRowsMatchExactArithmetic) {
  const SceneStageVectors base = fxr::load_scene_stage(kCommitted, "viewport");
  ASSERT_TRUE(fxr::attr_planes(base.cfg.raster)) << "the RTL builds the attribute-position path only";
  ASSERT_EQ(base.cfg.raster.subpixel_bits, 8);
  ASSERT_EQ(base.cfg.raster.window_int_bits, 16);
  ASSERT_EQ(base.cfg.raster.clip_sig_bits, 32);
  ASSERT_EQ(base.cfg.recip.out_sig_bits, kRecipSig);
  // Viewport 32 x 32 at the origin: window x = (n + 1)·16, subpixel code (n + 1)·4096.
  const fxr::DrawState st = state(32, 32, 0, 0);
  Rows rows(base);
  uint64_t drops = 0;
  const Vtx plain = vtx(0.25, -0.5, 0.5, 1, 1);
  auto tri = [&](const Vtx& a) {
    const Vtx t[3] = {a, plain, vtx(-0.75, 0.125, 0.25, 2, 0.5)};
    drops += rows.add(t, st);
  };
  // Snap ties at ½ subpixel: code (n + 1)·4096 = m + ½, both parities of m, both signs.
  for (int m : {5, 6, 4095, 4096, 100, 101}) {
    const double n = (m + 0.5) / 4096 - 1;
    tri(vtx(n, -n, 0.5, 1, 1));
  }
  for (int m : {1, 2, 7, 8}) {  // negative window coordinates: n + 1 = −(m + ½)/4096
    const double n = -(m + 0.5) / 4096 - 1;
    tri(vtx(n, n, 0.5, 1, 1));
  }
  // Ties of the attribute positions: (q + 1)·2^28 = m + ½ needs q to 2^−29: 1 ± 2^−29 (w = 1).
  tri(vtx(1 - std::ldexp(1.0, -29), -1 + std::ldexp(3.0, -29), 0.5, 1, 0.5));
  tri(vtx(-1 + std::ldexp(1.0, -29), 1 - std::ldexp(3.0, -29), 0.5, 1, 0.5));
  // r ≠ 1/w: the snap follows r, the attribute positions w (the stage's contract).
  tri(vtx(0.75, -0.25, 0.5, 4, 0.125));
  // w at the w_min plane (2^−160): x, y, z fractions of it; 1/w = 2^160, v/w enormous.
  {
    const double wm = std::ldexp(1.0, -160);
    tri(vtx(0.5 * wm, -0.375 * wm, 0.25 * wm, wm, std::ldexp(1.0, 160), 3, -std::ldexp(1.0, -100)));
  }
  // Very large and very small w (and odd significands: inexact quotients).
  tri(vtx(std::ldexp(-0.7, 100) * 1, std::ldexp(0.3, 100), std::ldexp(0.9, 100), std::ldexp(1.0, 100),
          std::ldexp(1.0, -100), std::ldexp(1.0, -120), 7));
  tri(vtx(std::ldexp(3.0, -140), std::ldexp(-5.0, -141), std::ldexp(1.0, -139), std::ldexp(3.0, -139),
          std::ldexp(11184811.0, 115), 1, 1));
  tri(vtx(1.0 / 3, -2.0 / 3, 1.0 / 3, 0.75, 4.0 / 3, 1.0 / 7, -1.0 / 9));
  // Depth: z = w (2^32), z slightly above w (saturates), z < 0 (0), z = 0, a tiny z, z = w·(1 − 2^−33).
  tri(vtx(0, 0, 3, 3, 1.0 / 4));
  tri(vtx(0, 0, 3 * (1 + std::ldexp(1.0, -20)), 3, 1.0 / 4));
  tri(vtx(0, 0, -0.25, 1, 1));
  tri(vtx(0, 0, 0, 1, 1));
  tri(vtx(0, 0, std::ldexp(1.0, -34), 1, 1));
  tri(vtx(0, 0, 1 - std::ldexp(1.0, -33), 1, 1));
  tri(vtx(0, 0, 1 - std::ldexp(3.0, -34), 1, 1));
  // Zero varyings (+0 and −0): exponent 0 on the perspective path.
  tri(vtx(0.5, 0.5, 0.5, 1, 1, 0.0, -0.0));
  const uint64_t no_drops = drops;
  EXPECT_EQ(no_drops, 0u);
  // Range: codes at both ends. Viewport 32 x 32 at origin (32767, −32768): x code
  // (n + 1)·4096 + 2^23 − 256, y code (n + 1)·4096 − 2^23.
  const fxr::DrawState edge = state(32, 32, 32767, -32768);
  Rows er(base);
  uint64_t edrops = 0;
  auto etri = [&](const Vtx& a) {
    const Vtx t[3] = {a, vtx(-1, 0, 0.5, 1, 1), vtx(-1, 0.5, 0.5, 1, 1)};
    edrops += er.add(t, edge);
  };
  for (double m : {255.0, 255.5, 256.0, 254.5}) etri(vtx(m / 4096 - 1, 0, 0.5, 1, 1));        // x: 2^23 − 1 … 2^23
  for (double m : {0.0, -0.5, -1.0, 0.5, -1.5}) etri(vtx(-1, m / 4096 - 1, 0.5, 1, 1));        // y: −2^23 … −2^23 − 1
  // ax = (q + 1)·2^28 + 2^39 − 2^24 (w = 1): q + 1 = 2^−4 − 2^−28 gives 2^39 − 1, 2^−4 gives 2^39;
  // r = ½ keeps the snap in range.
  etri(vtx(-1 + std::ldexp(1.0, -4) - std::ldexp(1.0, -28), 0, 0.5, 1, 0.5));
  etri(vtx(-1 + std::ldexp(1.0, -4), 0, 0.5, 1, 0.5));
  etri(vtx(-1 + std::ldexp(1.0, -4) - std::ldexp(1.0, -29), 0, 0.5, 1, 0.5));  // tie: to 2^39 (even)
  etri(vtx(-1 + std::ldexp(1.0, -4) - std::ldexp(3.0, -30), 0, 0.5, 1, 0.5));  // below the tie
  // Huge quotients: x / w with w at w_min, x = 1 (far beyond every code).
  etri(vtx(1, 0, 0.5, std::ldexp(1.0, -160), std::ldexp(1.0, -150)));
  etri(vtx(std::ldexp(1.0, 100), 0, 0.5, 1, std::ldexp(1.0, -130)));  // the snap's product alone in range
  ASSERT_GE(edrops, 5u);
  ASSERT_LT(edrops, er.vectors().in.rows);
  run_rows(rows, st, "viewport_directed_", 0);
  run_rows(er, edge, "viewport_edges_", edrops);
  run_rows<Vfxr_viewport_lanes1>(er, edge, "viewport_edges_lanes1_", edrops);
  // The affine mode: v_k itself rounded to attr_sig_bits (zero keeps its exponent).
  const fxr::DrawState aff = state(32, 32, 0, 0, fxr::InterpMode::Affine);
  Rows ar(base);
  {
    const Vtx t[3] = {vtx(0.5, 0.5, 0.5, 2, 0.5, 0.0, -0.0), vtx(0.25, -0.5, 0.5, 1, 1, 3, 1.0 / 3),
                      vtx(-0.75, 0.125, 0.25, 2, 0.5, -7, 1e-20)};
    ar.add(t, aff);
  }
  run_rows(ar, aff, "viewport_affine_", 0);
}

// Random triangles: 32-bit significands (clipper-made values), exponents around w's, w_a ≠ w
// sometimes, several viewports: expected values from GMP.
TEST(ViewportTxn, RandomRowsMatchExactArithmetic) {
  const SceneStageVectors base = fxr::load_scene_stage(kCommitted, "viewport");
  const int sb = base.cfg.raster.clip_sig_bits;
  std::mt19937_64 rng(23);
  auto sig = [&](int bits) { return (rng() & ((1ull << bits) - 1)) | (1ull << (bits - 1)); };
  for (const fxr::DrawState& st : {state(24, 16, 0, 0), state(65535, 65535, -32768, -32768), state(1000, 3, 100, -7),
                                   state(640, 480, 0, 0, fxr::InterpMode::Affine)}) {
    Rows rows(base);
    uint64_t drops = 0;
    for (int n = 0; n < 400; ++n) {
      Vtx t[3];
      for (auto& v : t) {
        const int we = (int)(rng() % 200) - 100;  // w's leading exponent
        v.w = fx_lead(false, sig(24), 24, we);
        v.wa = rng() % 3 ? fx_lead(false, sig(sb), sb, we) : v.w;
        // 1/w to 24 bits, perturbed by up to an ulp (the reciprocal unit's rounding)
        v.r = float_of(1 / value(v.w), 24);
        v.r.sig = std::min<uint64_t>((1ull << 24) - 1, std::max<uint64_t>(1ull << 23, v.r.sig + rng() % 3 - 1));
        auto coord = [&](int spread) { return fx_lead(rng() & 1, sig(sb), sb, we - (int)(rng() % spread)); };
        v.x = coord(4);
        v.y = coord(30);
        v.z = rng() % 8 ? fx_lead(rng() % 6 == 0, sig(sb), sb, we - (int)(rng() % 3)) : Fx{false, 0, 0};
        for (auto& a : v.var) a = rng() % 10 ? fx_lead(rng() & 1, sig(sb), sb, (int)(rng() % 80) - 40) : Fx{(bool)(rng() & 1), 0, -7};
      }
      drops += rows.add(t, st);
    }
    EXPECT_LT(drops, 400u);
    run_rows(rows, st, "viewport_random_" + std::to_string(st.viewport_w) + "_", drops);
    run_rows<Vfxr_viewport_lanes7>(rows, st, "viewport_random_lanes7_" + std::to_string(st.viewport_w) + "_", drops);
  }
}

// The checker can fail: one bit of an attribute position in the committed expectation flipped ->
// exactly that row and field reported.
TEST(ViewportTxn, CorruptedExpectedRowIsReported) {
  SceneStageVectors v = fxr::load_scene_stage(kCommitted, "viewport");
  size_t col = 0;
  for (size_t f = 0; f < v.out.lay.size(); ++f)
    if (v.out.lay[f].name == "v1_ay") col = f;
  ASSERT_GT(col, 0u);
  v.out.data[2 * v.out.lay.size() + col] ^= 1;
  Drive<Vfxr_viewport> dr;
  dr.st = fxr::tb::read_dump_draw_state(kCommitted);
  dr.wib = v.cfg.raster.window_int_bits;
  const TxnHook<Vfxr_viewport> h = dr.hook();
  TxnOptions o = opts("viewport_corrupt", 2, 25, 25);
  o.write_wave = false;
  const TxnResult r = fxr::tb::run_txn<Vfxr_viewport>(v, nullptr, o, &h);
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.errors, 1u);
  ASSERT_EQ(r.mismatches.size(), 1u);
  EXPECT_EQ(r.mismatches[0].out_row, 2u);
  EXPECT_EQ(r.mismatches[0].cls, "v1_ay");
}

}  // namespace

// fxraster-cosim — the user's co-simulation run behind `fxraster cosim` (app/cmd_cosim.cpp;
// docs/rtl.md, "fxraster cosim"): a scene through the model's chain and through the verilated RTL,
// every stage boundary compared record by record, and a report.
//
//   fxraster-cosim SCENE|--default --out DIR [--wave] [--seed S] [--gaps PCT] [--stalls PCT]
//                  [--mem-latency MAX] [--inject-model STAGE:ROW] [--inject-rtl ROW]
//
// DUT: rtl/fxr_raster_backend.sv (stages 5–9), driven with the model's setup.in records (the
// snapped triangles of the scene, tb/backend/backend_draw.hpp), the draw state on its register
// inputs and the depth buffer behind its memory port (tb/depth_mem.hpp). The stage taps are the
// back end's internal handshakes at every boundary (setup → traverse → interp → depth → divide),
// made readable by tb/cosim/backend_taps.vlt (Verilator public_flat_rd, no debug ports in the RTL),
// compared in order with the model's taps (model/unit/chain.hpp). The first boundary, in pipeline
// order, whose stream differs is where the streams first diverge.
//
// Writes DIR/report.md and DIR/report.json (deterministic: the same scene and options give the
// same bytes), DIR/speed.md and DIR/speed.json (wall-clock figures, not deterministic), and on a
// mismatch DIR/mismatches.csv and DIR/first_mismatch.fst (the window around the first
// mismatch); --wave writes DIR/wave.fst of the whole run. Exit status 0: every boundary, the
// fragment stream, the counters and the depth buffer equal the model's; 1: a mismatch; 2: bad
// input (the error names the file / option).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "backend/backend_draw.hpp"
#include "frontend/scene.hpp"
#ifdef FXR_COSIM_UNIT
#include "Vfxr_raster_unit__cosim.h"
#include "Vfxr_raster_unit__cosim___024root.h"
#include "unit/unit_run.hpp"
#else
#include "Vfxr_raster_backend__cosim.h"
#include "Vfxr_raster_backend__cosim___024root.h"
#endif

namespace {

#ifdef FXR_COSIM_UNIT
// The whole unit (rtl/fxr_raster_unit.sv): every boundary from stage 1's output on.
using Dut = Vfxr_raster_unit__cosim;
constexpr int kFirstTap = 0;
constexpr const char* kDutText = "fxr_raster_unit (stages 1-9), driven with the model's convert.in records";
#define FXR_BE(sig) (d.rootp->fxr_raster_unit__DOT__u_backend__DOT__##sig)
#define FXR_UNIT(sig) (d.rootp->fxr_raster_unit__DOT__##sig)
#else
// The back end alone (rtl/fxr_raster_backend.sv), until stages 2 and 4 are in RTL.
using Dut = Vfxr_raster_backend__cosim;
constexpr int kFirstTap = fxr::tb::kTapSetup;
constexpr const char* kDutText = "fxr_raster_backend (stages 5-9), driven with the model's setup.in records";
#define FXR_BE(sig) (d.rootp->fxr_raster_backend__DOT__##sig)
#endif
using fxr::VecRow;
using fxr::tb::Draw;
using fxr::tb::kTapNames;
using fxr::tb::kTaps;
using fxr::tb::RecordBinding;


struct TapMismatch {
  int tap = 0;
  uint64_t seq = 0, cycle = 0;
  std::string field, got, exp;
};

// Per boundary: the RTL's transfers compared in order with the model's records, and the
// handshake's clocks (busy: a transfer; stalled: valid, not ready; starved: not valid).
struct TapState {
  uint64_t n = 0, matched = 0, mismatched = 0, extra = 0;
  uint64_t busy = 0, stalled = 0, starved = 0;
  std::vector<TapMismatch> first;  // up to kMaxListed
  uint64_t first_cycle = UINT64_MAX;
};
constexpr size_t kMaxListed = 20;

// A boundary's busy / stalled / starved clocks at one moment of the run.
using TapClocks = std::array<std::array<uint64_t, 3>, kTaps>;

struct TapChecker {
  const Draw* draw = nullptr;
  std::array<RecordBinding, kTaps> bind;
  std::array<TapState, kTaps> st;
  uint64_t cycle = 0;
  VecRow got;
  // The clocks before the first input transfer (reset, the register writes) and up to the last
  // output transfer: utilisation is reported over the clocks between the two, the same window
  // as the cycle figure; what follows the last output is the harness's drain (it waits for the
  // unit to settle before reading the counters) and is reported apart.
  bool started = false;
  TapClocks at_first{}, at_last{};
  TapClocks clocks() const {
    TapClocks c{};
    for (int k = 0; k < kTaps; ++k) c[(size_t)k] = {st[(size_t)k].busy, st[(size_t)k].stalled, st[(size_t)k].starved};
    return c;
  }

  explicit TapChecker(const Draw& d) : draw(&d) {
    for (int k = kFirstTap; k < kTaps; ++k) bind[(size_t)k] = RecordBinding(d.taps[(size_t)k].lay, fxr::tb::kTapHeaderFields);
  }
  void reset() {
    st = {};
    cycle = 0;
    started = false;
    at_first = at_last = TapClocks{};
  }
  template <class P>
  void check(int k, bool valid, bool ready, const P& port) {
    TapState& s = st[(size_t)k];
    if (!valid) ++s.starved;
    else if (!ready) ++s.stalled;
    else {
      ++s.busy;
      const fxr::tb::TapStream& t = draw->taps[(size_t)k];
      got.assign(t.lay.size(), 0);
      bind[(size_t)k].sample(port, got);
      if (s.n >= t.rows) {
        ++s.extra;
        ++s.mismatched;
        if (s.first.size() < kMaxListed) s.first.push_back({k, s.n, cycle, "extra", "", ""});
        s.first_cycle = std::min(s.first_cycle, cycle);
      } else {
        const fxr::vec_word* want = t.data.data() + s.n * t.lay.size();
        size_t bad = 0;
        for (size_t f = fxr::tb::kTapHeaderFields; f < t.lay.size() && !bad; ++f)
          if (got[f] != want[f]) bad = f;
        if (bad) {
          ++s.mismatched;
          if (s.first.size() < kMaxListed)
            s.first.push_back({k, s.n, cycle, t.lay[bad].name, fxr::vec_field_hex(t.lay[bad], got[bad]),
                               fxr::vec_field_hex(t.lay[bad], want[bad])});
          s.first_cycle = std::min(s.first_cycle, cycle);
        } else {
          ++s.matched;
        }
      }
      ++s.n;
    }
  }
  void observe(Dut& d) {
    if (!started && d.in_valid_i && d.in_ready_o) {
      started = true;
      at_first = clocks();
    }
#ifdef FXR_COSIM_UNIT
    check(0, FXR_UNIT(s1_valid), FXR_UNIT(s1_ready), FXR_UNIT(s1_out));
    check(1, FXR_UNIT(s2_valid), FXR_UNIT(s2_ready), FXR_UNIT(s2_out));
    check(2, FXR_UNIT(s3_valid), FXR_UNIT(s3_ready), FXR_UNIT(s3_out));
    check(3, FXR_UNIT(s4_valid), FXR_UNIT(s4_ready), FXR_UNIT(s4_out));
#endif
    check(4, FXR_BE(su_valid), FXR_BE(su_ready), FXR_BE(su_out));
    check(5, FXR_BE(ip_in_valid), FXR_BE(ip_in_ready), FXR_BE(ip_in));
    check(6, FXR_BE(ip_out_valid), FXR_BE(ip_out_ready), FXR_BE(ip_out));
    check(7, FXR_BE(dp_out_valid), FXR_BE(dp_out_ready), FXR_BE(dp_out));
    check(8, d.out_valid_o, d.out_ready_i, d.out_o);
    if (d.out_valid_o && d.out_ready_i) at_last = clocks();
    ++cycle;
  }
  // Records the model has and the RTL never produced.
  uint64_t missing(int k) const {
    const uint64_t rows = draw->taps[(size_t)k].rows;
    return st[(size_t)k].n < rows ? rows - st[(size_t)k].n : 0;
  }
  bool equal(int k) const { return st[(size_t)k].mismatched == 0 && missing(k) == 0; }
};

struct Options {
  std::string scene, out;
  bool def = false, wave = false, no_bunny = false;
  int width = 0, height = 0;  // 0: the scene's viewport
  uint64_t seed = 1;
  unsigned gaps = 0, stalls = 0, mem_latency = 1;
  std::string inject_model;
  int64_t inject_rtl = -1;
};

struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double pct(uint64_t a, uint64_t b) { return b ? 100.0 * (double)a / (double)b : 0.0; }

std::string fmt(const char* f, double x) {
  char b[64];
  std::snprintf(b, sizeof b, f, x);
  return b;
}

int run(const Options& o) {
  namespace fs = std::filesystem;
  // ---- the scene and the model -----------------------------------------------------------
  fxr::SceneOptions so;  // fxraster render's --width / --height / --no-bunny
  so.width = o.width;
  so.height = o.height;
  so.no_optional = o.no_bunny;
  const fxr::Scene sc = o.def ? fxr::default_scene(so) : fxr::load_scene(o.scene, so);
  // The configuration the RTL was verilated at: the default's raster, recip and div units (the
  // texture address unit and the line rules are not in this RTL).
  std::string field;
  {
    const nlohmann::json a = fxr::config_to_json(sc.config), b = fxr::config_to_json(fxr::Config{});
    for (const char* unit : {"raster", "recip", "div"})
      for (auto& [k, val] : a.at(unit).items())
        if (field.empty() && (!b.at(unit).contains(k) || b.at(unit).at(k) != val)) field = std::string(unit) + "." + k;
  }
  if (!field.empty()) {
    throw BadInput(sc.source + ": field 'config." + field +
                   "': the RTL was verilated at the default configuration; co-simulate this scene with RTL built "
                   "from its configuration (docs/rtl.md, \"fxraster cosim\")");
  }
  if (sc.tris.empty()) throw BadInput(sc.source + ": the scene has no triangles (line segments are not in the RTL yet)");
  const auto tm0 = std::chrono::steady_clock::now();
  Draw d = fxr::tb::model_draw(sc.name, sc.config, sc.state, sc.tris, -1, kFirstTap == 0);
  const double model_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tm0).count();

  // ---- test hooks: a corrupted model value or RTL input ----------------------------------
  std::string injected;
  if (!o.inject_model.empty()) {
    const size_t colon = o.inject_model.find(':');
    const std::string stage = o.inject_model.substr(0, colon);
    int k = -1;
    std::string names;
    for (int i = kFirstTap; i < kTaps; ++i) {
      if (stage == kTapNames[i]) k = i;
      names += std::string(i > kFirstTap ? ", " : "") + kTapNames[i];
    }
    if (k < 0 || colon == std::string::npos)
      throw BadInput("--inject-model " + o.inject_model + ": expected STAGE:ROW, STAGE one of " + names);
    uint64_t row = 0;
    try {
      row = std::stoull(o.inject_model.substr(colon + 1));
    } catch (const std::exception&) {
      throw BadInput("--inject-model " + o.inject_model + ": ROW is not a number");
    }
    fxr::tb::TapStream& t = d.taps[(size_t)k];
    if (row >= t.rows) throw BadInput("--inject-model " + o.inject_model + ": the model has " + std::to_string(t.rows) + " " + stage + " records");
    const size_t f = t.lay.size() - 1;  // the record's last field, lsb flipped
    t.data[row * t.lay.size() + f] ^= 1;
    if (k == kTaps - 1) {  // the divider's records are also the fragment stream
      for (fxr::SceneStageVectors* sv : {&d.v, &d.u}) {
        const size_t n = sv->out.lay.size();
        sv->out.data[row * n + n - 1] ^= 1;
      }
    }
    injected = "model " + stage + " record " + std::to_string(row) + ", field '" + t.lay[f].name + "' lsb flipped";
  }
  // The DUT's streams: the unit's from convert.in, the back end's from setup.in.
  fxr::SceneStageVectors drive = kFirstTap == 0 ? d.u : d.v;
  const std::string in_name = kFirstTap == 0 ? "convert.in" : "setup.in";
  if (o.inject_rtl >= 0) {
    if ((uint64_t)o.inject_rtl >= drive.in.rows)
      throw BadInput("--inject-rtl " + std::to_string(o.inject_rtl) + ": the draw has " + std::to_string(drive.in.rows) + " " +
                     in_name + " rows");
    const size_t f = drive.in.header + 1;  // the field after prim
    drive.in.data[(size_t)o.inject_rtl * drive.in.lay.size() + f] ^= 1;
    injected = "RTL input " + in_name + " row " + std::to_string(o.inject_rtl) + ", field '" + drive.in.lay[f].name + "' lsb flipped";
  }

  // ---- the RTL run --------------------------------------------------------------------------
  fs::create_directories(o.out);
  for (const char* stale : {"mismatches.csv", "first_mismatch.fst", "wave.fst"}) fs::remove(fs::path(o.out) / stale);
  TapChecker taps(d);
  fxr::tb::Handshake h{o.seed, o.gaps, o.stalls, 1, std::max(1u, o.mem_latency), 0};
  fxr::tb::RtlRunOptions<Dut> ro;
  ro.run = "cosim";
  ro.reset = [&] { taps.reset(); };
  ro.observe = [&](Dut& dut) { taps.observe(dut); };
  const std::string wave_all = (fs::path(o.out) / "wave.fst").string();
  ro.simulate = [&](const fxr::SceneStageVectors& v, const fxr::tb::TxnOptions& to, const fxr::tb::TxnHook<Dut>& hook) {
    fxr::tb::TxnOptions q = to;
    q.print = false;
    return fxr::tb::detail::txn_simulate<Dut>(v, nullptr, q, o.wave, 0, UINT64_MAX, wave_all, &hook);
  };
  const auto tr0 = std::chrono::steady_clock::now();
  const double trc0 = fxr::tb::cpu_seconds_now();
#ifdef FXR_COSIM_UNIT
  fxr::tb::UnitRun ur = fxr::tb::run_unit<Dut>(d, drive, h, ro);
  fxr::tb::RtlRun& k = ur.k;
  const fxr::tb::GeomStats geom_want = fxr::tb::model_geom_stats(d);
  auto rerun = [&](const fxr::tb::RtlRunOptions<Dut>& r) { (void)fxr::tb::run_unit<Dut>(d, drive, h, r); };
#else
  fxr::tb::RtlRun k = fxr::tb::run_rtl<Dut>(d, drive, h, ro);
  auto rerun = [&](const fxr::tb::RtlRunOptions<Dut>& r) { (void)fxr::tb::run_rtl<Dut>(d, drive, h, r); };
#endif
  const double rtl_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tr0).count();
  const double rtl_cpu = fxr::tb::cpu_seconds_now() - trc0;
  // The harness compared the fragment stream with the model's divide.out (d.v.out: the expected
  // stream is the model's, drive.in the possibly corrupted input).

  // ---- verdict ---------------------------------------------------------------------------------
  int diverge = -1;
  for (int t = kFirstTap; t < kTaps && diverge < 0; ++t)
    if (!taps.equal(t)) diverge = t;
  uint64_t depth_diff = 0;
  for (size_t i = 0; i < d.depth.size() && i < k.depth.size(); ++i) depth_diff += d.depth[i] != k.depth[i];
  depth_diff += d.depth.size() > k.depth.size() ? d.depth.size() - k.depth.size() : k.depth.size() - d.depth.size();
  uint64_t counters_diff = 0;
  for (int i = 0; i < fxr::tb::kStats; ++i) counters_diff += d.want[(size_t)i] != k.stats[(size_t)i];
#ifdef FXR_COSIM_UNIT
  for (int i = 0; i < fxr::tb::kGeomStats; ++i) counters_diff += geom_want[(size_t)i] != ur.geom[(size_t)i];
#endif
  const bool match = k.r.passed() && diverge < 0 && depth_diff == 0 && counters_diff == 0 && k.bad_addresses == 0;

  // The first mismatch in time (a tap's or the fragment stream's) centres the waveform window.
  uint64_t first_cycle = UINT64_MAX;
  for (const auto& s : taps.st) first_cycle = std::min(first_cycle, s.first_cycle);
  if (!k.r.mismatches.empty()) first_cycle = std::min(first_cycle, k.r.mismatches.front().cycle);
  if (!match && first_cycle == UINT64_MAX) first_cycle = k.r.cycles;  // counters / buffer only: the end
  std::string fst;
  if (!match) {
    fst = (fs::path(o.out) / "first_mismatch.fst").string();
    fxr::tb::RtlRunOptions<Dut> rw = ro;
    rw.simulate = [&](const fxr::SceneStageVectors& v, const fxr::tb::TxnOptions& to, const fxr::tb::TxnHook<Dut>& hook) {
      fxr::tb::TxnOptions q = to;
      q.print = false;
      const uint64_t before = 200, after = 20;
      return fxr::tb::detail::txn_simulate<Dut>(v, nullptr, q, true, first_cycle > before ? first_cycle - before : 0,
                                                first_cycle + after, fst, &hook);
    };
    TapChecker keep = taps;
#ifdef FXR_COSIM_UNIT
    const fxr::tb::UnitRun keep_u = ur;
    rerun(rw);
    ur = keep_u;
#else
    const fxr::tb::RtlRun keep_k = k;
    rerun(rw);
    k = keep_k;
#endif
    taps = keep;  // the replay stops after the window: the full run's figures stay
    std::ofstream csv(fs::path(o.out) / "mismatches.csv");
    csv << "boundary,seq,cycle,field,rtl,model\n";
    for (int t = kFirstTap; t < kTaps; ++t)
      for (const TapMismatch& m : taps.st[(size_t)t].first)
        csv << kTapNames[t] << "," << m.seq << "," << m.cycle << "," << m.field << "," << m.got << "," << m.exp << "\n";
    for (const fxr::tb::TxnMismatch& m : k.r.mismatches) {
      if (&m - &k.r.mismatches.front() >= (ptrdiff_t)kMaxListed) break;
      csv << "fragments," << m.out_row << "," << m.cycle << "," << m.cls << ",\"" << m.text << "\",\n";
    }
  }

  // ---- figures -----------------------------------------------------------------------------
  const uint64_t cyc = k.r.last_out_cycle > k.r.first_in_cycle ? k.r.last_out_cycle - k.r.first_in_cycle + 1 : 0;
  const uint64_t gen = d.want[7], passed = d.want[8];
  // Utilisation window: the first input transfer to the last output transfer (TapChecker).
  const TapClocks total = taps.clocks();
  const TapClocks& t_first = taps.at_first;
  const TapClocks& t_last = taps.at_last[kTaps - 1][0] >= t_first[kTaps - 1][0] && taps.started ? taps.at_last : total;
  auto win = [&](int t, int i) { return t_last[(size_t)t][(size_t)i] - t_first[(size_t)t][(size_t)i]; };
  auto sum3 = [](const std::array<uint64_t, 3>& a) { return a[0] + a[1] + a[2]; };
  const uint64_t lead_clocks = sum3(t_first[kTaps - 1]);
  const uint64_t window_clocks = sum3(t_last[kTaps - 1]) - lead_clocks;
  const uint64_t drain_clocks = sum3(total[kTaps - 1]) - sum3(t_last[kTaps - 1]);
  nlohmann::json j;
  j["result"] = match ? "match" : "mismatch";
  j["scene"] = {{"name", sc.name}, {"source", sc.source}, {"viewport", {sc.state.viewport_w, sc.state.viewport_h}},
                {"triangles", sc.tris.size()}, {"line_segments_not_simulated", sc.lines.size()},
                {"varyings_scene", sc.state.num_varyings}, {"varyings_rtl", fxr::tb::kRtlVaryings}};
  j["dut"] = kDutText;
  j["handshake"] = {{"seed", o.seed}, {"input_gap_pct", o.gaps}, {"output_stall_pct", o.stalls},
                    {"memory_latency_max", h.lat_max}};
  if (!injected.empty()) j["injected"] = injected;
  nlohmann::json jt = nlohmann::json::array();
  for (int t = kFirstTap; t < kTaps; ++t) {
    const TapState& s = taps.st[(size_t)t];
    nlohmann::json e{{"boundary", std::string(kTapNames[t]) + ".out"}, {"model_records", d.taps[(size_t)t].rows},
                     {"rtl_records", s.n}, {"matched", s.matched}, {"mismatched", s.mismatched},
                     {"missing", taps.missing(t)}, {"busy_clocks", win(t, 0)}, {"stalled_clocks", win(t, 1)},
                     {"starved_clocks", win(t, 2)}};
    if (!s.first.empty())
      e["first_mismatch"] = {{"seq", s.first[0].seq}, {"cycle", s.first[0].cycle}, {"field", s.first[0].field},
                             {"rtl", s.first[0].got}, {"model", s.first[0].exp}};
    jt.push_back(e);
  }
  j["boundaries"] = jt;
  j["first_divergence"] = diverge < 0 ? nlohmann::json(nullptr) : nlohmann::json(kTapNames[diverge]);
  j["fragments"] = {{"model", d.v.out.rows}, {"rtl", k.r.outputs}, {"mismatched", k.r.errors},
                    {"matched", k.r.outputs >= k.r.errors ? k.r.outputs - k.r.errors : 0}};
  nlohmann::json jc = nlohmann::json::object();
  for (int i = 0; i < fxr::tb::kStats; ++i)
    jc[fxr::tb::kStatNames[i]] = {{"model", d.want[(size_t)i]}, {"rtl", k.stats[(size_t)i]}};
#ifdef FXR_COSIM_UNIT
  for (int i = 0; i < fxr::tb::kGeomStats; ++i)
    jc[fxr::tb::kGeomStatNames[i]] = {{"model", geom_want[(size_t)i]}, {"rtl", ur.geom[(size_t)i]}};
#endif
  j["counters"] = jc;
  j["counters_mismatched"] = counters_diff;
  j["depth_buffer_words_differing"] = depth_diff;
  j["cycles"] = {{"first_input_to_last_output", cyc}, {"simulated", k.r.cycles},
                {"utilisation_window", window_clocks}, {"before_first_input", lead_clocks},
                {"drain_after_last_output", drain_clocks}};
  j["fragments_per_clock"] = {{"generated", cyc ? (double)gen / (double)cyc : 0.0},
                              {"passed", cyc ? (double)passed / (double)cyc : 0.0}};
  nlohmann::json jp = nlohmann::json::object();
  for (int i = 0; i < fxr::tb::kPerf; ++i) jp[fxr::tb::kPerfNames[i]] = k.perf[(size_t)i];
  j["rtl_stall_counters"] = jp;
  j["timeout"] = k.r.timeout;
  if (!fst.empty()) j["files"] = {{"csv", "mismatches.csv"}, {"fst", "first_mismatch.fst"}};
  if (o.wave) j["wave"] = "wave.fst";
  std::ofstream(fs::path(o.out) / "report.json") << j.dump(2) << "\n";

  std::ostringstream md;
  md << "# fxraster cosim: " << sc.name << "\n\n";
  md << "**Result: " << (match ? "MATCH" : "MISMATCH") << "**";
  if (diverge >= 0) md << " — the streams first diverge at **" << kTapNames[diverge] << ".out**";
  md << "\n\n";
  md << "- scene: `" << sc.source << "`, viewport " << sc.state.viewport_w << " x " << sc.state.viewport_h << ", "
     << sc.tris.size() << " triangles";
  if (!sc.lines.empty()) md << " (" << sc.lines.size() << " line segments not simulated: no line path in the RTL yet)";
  md << "\n- DUT: `" << kDutText << "` (" << drive.in.rows << " records)\n";
  if (sc.state.num_varyings != fxr::tb::kRtlVaryings)
    md << "- varyings: the scene has " << sc.state.num_varyings << ", the RTL " << fxr::tb::kRtlVaryings
       << " (both sides run with " << fxr::tb::kRtlVaryings << ")\n";
  md << "- handshake: seed " << o.seed << ", input gaps " << o.gaps << " %, output stalls " << o.stalls
     << " %, depth-memory latency 1.." << h.lat_max << "\n";
  if (!injected.empty()) md << "- injected (test hook): " << injected << "\n";
  md << "\n## Stage boundaries\n\n| boundary | model | RTL | matched | mismatched | missing | first mismatch |\n|---|---|---|---|---|---|---|\n";
  for (int t = kFirstTap; t < kTaps; ++t) {
    const TapState& s = taps.st[(size_t)t];
    md << "| " << kTapNames[t] << ".out | " << d.taps[(size_t)t].rows << " | " << s.n << " | " << s.matched << " | "
       << s.mismatched << " | " << taps.missing(t) << " | ";
    if (!s.first.empty())
      md << "record " << s.first[0].seq << ", cycle " << s.first[0].cycle << ", `" << s.first[0].field << "`: RTL "
         << s.first[0].got << ", model " << s.first[0].exp;
    md << " |\n";
  }
  md << "\n## Fragments and counters\n\n";
  md << "Fragments (divide.out): model " << d.v.out.rows << ", RTL " << k.r.outputs << ", mismatched " << k.r.errors
     << (k.r.timeout ? " (the RTL stopped producing: timeout)" : "") << ".\n\n";
  md << "| counter | model | RTL |\n|---|---|---|\n";
  for (int i = 0; i < fxr::tb::kStats; ++i)
    md << "| " << fxr::tb::kStatNames[i] << " | " << d.want[(size_t)i] << " | " << k.stats[(size_t)i]
       << (d.want[(size_t)i] != k.stats[(size_t)i] ? " **≠**" : "") << " |\n";
#ifdef FXR_COSIM_UNIT
  for (int i = 0; i < fxr::tb::kGeomStats; ++i)
    md << "| " << fxr::tb::kGeomStatNames[i] << " | " << geom_want[(size_t)i] << " | " << ur.geom[(size_t)i]
       << (geom_want[(size_t)i] != ur.geom[(size_t)i] ? " **≠**" : "") << " |\n";
#endif
  md << "\nDepth buffer: " << depth_diff << " words differ.\n";
  md << "\n## Performance\n\n";
  md << "- cycles, first input to last output: " << cyc << " (" << k.r.cycles << " simulated)\n";
  md << "- fragments per clock: " << fmt("%.4f", cyc ? (double)gen / (double)cyc : 0.0) << " generated, "
     << fmt("%.4f", cyc ? (double)passed / (double)cyc : 0.0) << " passed\n\n";
  md << "Per-stage utilisation, from the handshake at each stage's output (busy: a record leaves; stalled: "
        "one waits for the next stage; starved: none ready), over the "
     << window_clocks << " clocks from the first input to the last output (of " << k.r.cycles
     << " simulated: " << lead_clocks << " before the first input — reset, register writes — and "
     << drain_clocks << " of drain after the last output, while the harness waits for the unit to settle before "
        "reading the counters):\n\n| stage | busy | stalled | starved |\n|---|---|---|---|\n";
  for (int t = kFirstTap; t < kTaps; ++t) {
    const uint64_t all = win(t, 0) + win(t, 1) + win(t, 2);
    md << "| " << kTapNames[t] << " | " << fmt("%.1f %%", pct(win(t, 0), all)) << " | " << fmt("%.1f %%", pct(win(t, 1), all))
       << " | " << fmt("%.1f %%", pct(win(t, 2), all)) << " |\n";
  }
  md << "\nThe back end's stall counters (rtl/fxr_raster_backend.sv perf_*_o):";
  for (int i = 0; i < fxr::tb::kPerf; ++i) md << (i ? ", " : " ") << fxr::tb::kPerfNames[i] << " " << k.perf[(size_t)i];
  md << ".\n";
  if (!match) {
    md << "\n## First mismatches\n\n";
    for (int t = kFirstTap; t < kTaps; ++t)
      for (const TapMismatch& m : taps.st[(size_t)t].first)
        md << "- " << kTapNames[t] << ".out record " << m.seq << ", cycle " << m.cycle << ": `" << m.field << "` RTL "
           << m.got << ", model " << m.exp << "\n";
    for (size_t i = 0; i < k.r.mismatches.size() && i < kMaxListed; ++i)
      md << "- fragments: " << k.r.mismatches[i].text << "\n";
    md << "\nFiles: `mismatches.csv`, `first_mismatch.fst` (cycles " << (first_cycle > 200 ? first_cycle - 200 : 0)
       << " to " << first_cycle + 20 << ").\n";
  }
  md << "\nWall-clock figures (Verilator speed): `speed.md`, `speed.json`.\n";
  std::ofstream(fs::path(o.out) / "report.md") << md.str();

  nlohmann::json sj{{"model_seconds", model_s},
                    {"rtl_seconds", rtl_s},
                    {"simulated_cycles", k.r.cycles},
                    {"cycles_per_second", rtl_s > 0 ? (double)k.r.cycles / rtl_s : 0.0},
                    {"generated_fragments_per_second", rtl_s > 0 ? (double)gen / rtl_s : 0.0},
                    {"rtl_cpu_seconds", rtl_cpu},
                    {"cycles_per_cpu_second", rtl_cpu > 0 ? (double)k.r.cycles / rtl_cpu : 0.0},
                    {"generated_fragments_per_cpu_second", rtl_cpu > 0 ? (double)gen / rtl_cpu : 0.0}};
  std::ofstream(fs::path(o.out) / "speed.json") << sj.dump(2) << "\n";
  std::ofstream(fs::path(o.out) / "speed.md")
      << "# fxraster cosim: wall-clock figures (not deterministic)\n\n- model: " << fmt("%.3f s", model_s)
      << "\n- RTL (Verilator, one thread): " << fmt("%.3f s", rtl_s) << ", " << k.r.cycles << " cycles, "
      << fmt("%.0f cycles/s", rtl_s > 0 ? (double)k.r.cycles / rtl_s : 0.0) << ", "
      << fmt("%.0f generated fragments/s", rtl_s > 0 ? (double)gen / rtl_s : 0.0) << "\n- RTL, CPU time: "
      << fmt("%.3f s", rtl_cpu) << ", " << fmt("%.0f cycles", rtl_cpu > 0 ? (double)k.r.cycles / rtl_cpu : 0.0) << " and "
      << fmt("%.0f generated fragments per CPU second", rtl_cpu > 0 ? (double)gen / rtl_cpu : 0.0)
      << " (the wall clock of a loaded machine aside)\n";

  std::printf("%s: %s", sc.name.c_str(), match ? "MATCH" : "MISMATCH");
  if (diverge >= 0) std::printf(", first divergence at %s.out", kTapNames[diverge]);
  std::printf(" (%llu fragments, %llu cycles); report: %s\n", (unsigned long long)k.r.outputs, (unsigned long long)cyc,
              (fs::path(o.out) / "report.md").c_str());
  return match ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fxraster cosim — a scene through the model and the verilated RTL, every stage boundary compared "
               "(docs/rtl.md, \"fxraster cosim\"). Exit 0: match, 1: mismatch, 2: bad input."};
  app.name("fxraster cosim");
  Options o;
  app.add_option("scene", o.scene, "scene file (docs/scene-format.md)");
  app.add_flag("--default", o.def, "the built-in default scene");
  app.add_option("--out", o.out, "output folder (report.md, report.json, speed.*, on mismatch mismatches.csv, first_mismatch.fst)")
      ->required();
  app.add_flag("--wave", o.wave, "dump the whole run to OUT/wave.fst");
  app.add_flag("--no-bunny", o.no_bunny, "leave out optional meshes (the default scene's bunny), as fxraster render");
  app.add_option("--width", o.width, "override the viewport width (pixels), as fxraster render")->check(CLI::Range(1, 16384));
  app.add_option("--height", o.height, "override the viewport height (pixels), as fxraster render")->check(CLI::Range(1, 16384));
  app.add_option("--seed", o.seed, "handshake randomness (gaps, stalls, memory latency)");
  app.add_option("--gaps", o.gaps, "input gaps, percent of clocks (default 0)")->check(CLI::Range(0u, 95u));
  app.add_option("--stalls", o.stalls, "output back-pressure, percent of clocks (default 0)")->check(CLI::Range(0u, 95u));
  app.add_option("--mem-latency", o.mem_latency, "depth-memory latency: random in 1..N clocks (default 1)")
      ->check(CLI::Range(1u, 64u));
  app.add_option("--inject-model", o.inject_model,
                 "test hook: flip the lsb of the last field of record ROW of the model's STAGE.out (STAGE:ROW)");
  app.add_option("--inject-rtl", o.inject_rtl, "test hook: flip the lsb of the first field after prim of the RTL's setup input ROW");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  if (o.def == !o.scene.empty()) {
    std::cerr << "fxraster cosim: error: give exactly one of SCENE and --default\n";
    return 2;
  }
  try {
    return run(o);
  } catch (const BadInput& e) {
    std::cerr << "fxraster cosim: error: " << e.what() << "\n";
    return 2;
  } catch (const fxr::ConfigError& e) {
    std::cerr << "fxraster cosim: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fxraster cosim: error: " << e.what() << "\n";
    return 1;
  }
}

// The error budget of a scene (analysis/budget.hpp).
#include "analysis/budget.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <chrono>
#include <thread>

#include "analysis/error_stats.hpp"
#include "analysis/ideal.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/geometry.hpp"
#include "reference/reference.hpp"

namespace fxr {

double SignedStat::max() const { return all.empty() ? 0 : *std::max_element(all.begin(), all.end()); }
double SignedStat::mean() const {
  double s = 0;
  for (double v : all) s += v;
  return all.empty() ? 0 : s / (double)all.size();
}
double SignedStat::pct(double q) const {
  if (all.empty()) return 0;
  std::vector<double> v = all;
  const size_t k = std::min(v.size() - 1, (size_t)std::ceil(q * (double)v.size()) - (q > 0 ? 1 : 0));
  std::nth_element(v.begin(), v.begin() + (long)k, v.end());
  return v[k];
}
nlohmann::json SignedStat::to_json() const {
  return {{"count", n()}, {"max", max()}, {"p99", pct(0.99)}, {"mean", mean()}};
}

namespace {

struct Picked {
  uint64_t index;
  int32_t x, y;
  uint32_t prim, depth;
  FxFloat var[kMaxVaryings];
};

// Streams the model's fragments; keeps those whose index is in the evenly spaced sample.
struct SampleSink final : FragmentSink {
  uint64_t n = 0, total = 0, want = 0, regular = 0;
  std::vector<Picked>* out = nullptr;
  const std::vector<uint64_t>* extra = nullptr;
  uint64_t next_pick() const { return want == 0 ? 0 : (uint64_t)((unsigned __int128)regular * total / want); }
  void emit(const Fragment& f) override {
    if (out) {
      const bool reg = want == 0 || (regular < want && n == next_pick());
      if (reg || (extra && std::binary_search(extra->begin(), extra->end(), n))) {
        Picked p{n, f.x, f.y, f.prim, f.depth, {}};
        std::copy(f.var, f.var + kMaxVaryings, p.var);
        out->push_back(p);
      }
      regular += reg;
    }
    ++n;
  }
};

void run_model(const Scene& sc, FragmentSink& sink) {
  FrameOutput f;
  frame_begin(sc.config, sc.state, f);
  std::vector<SetupTriangle> pieces;
  for (size_t p = 0; p < sc.tris.size(); ++p) {
    pieces.clear();
    if (geometry(sc.config, sc.state, sc.tris[p], (uint32_t)p, pieces, f.stats) != GeomOutcome::Emitted) continue;
    for (const SetupTriangle& t : pieces) raster_triangle_to(sc.config, sc.state, t, f, &sink);
  }
}

// Error of one output value against the ideal, in the output's unit.
double out_err(const BudgetOutput& o, const mpq_class& got, const mpq_class& ideal_lsb_or_value, int qb) {
  if (o.varying < 0) return std::fabs(mpq_class(got - ideal_lsb_or_value).get_d());
  const double u = ulp_err(got, ideal_lsb_or_value, qb);
  return u < 0 ? std::fabs(mpq_class(got - ideal_lsb_or_value).get_d()) : u;  // ideal 0: absolute
}

}  // namespace

BudgetResult run_budget(const Scene& sc, const BudgetOptions& o) {
  BudgetResult r;
  r.scene = sc.name;
  r.cfg = sc.config;
  BudgetPath probe(sc.config, sc.state, sc.tris);  // throws for configurations the path does not model
  const int nv = sc.state.num_varyings;
  // Outputs.
  {
    BudgetOutput d;
    d.name = "depth";
    d.unit = "LSB";
    r.outputs.push_back(d);
    for (int k = 0; k < nv; ++k) {
      BudgetOutput v;
      v.varying = k;
      v.unit = "ulp";
      v.name = k == sc.u_varying ? "u" : k == sc.v_varying ? "v" : "var" + std::to_string(k);
      if (k == sc.u_varying) v.texels = sc.texture.image.width;
      if (k == sc.v_varying) v.texels = sc.texture.image.height;
      r.outputs.push_back(v);
    }
  }
  // The sample: the model's fragments in output order, evenly spaced.
  std::vector<Picked> picked;
  {
    SampleSink count;
    const auto t0 = std::chrono::steady_clock::now();
    run_model(sc, count);
    r.model_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.fragments = count.n;
    SampleSink s;
    s.total = count.n;
    s.want = o.samples <= 0 || (uint64_t)o.samples >= count.n ? 0 : (uint64_t)o.samples;
    s.out = &picked;
    s.extra = &o.extra;
    run_model(sc, s);
  }
  r.sampled = picked.size();
  const int nout = (int)r.outputs.size();
  const int qb = sc.config.div.quot_bits;
  const int db = sc.config.raster.depth_bits();
  const mpq_class Mc = mpq_class((mpz_class(1) << (unsigned long)db) - 1);

  struct Local {
    bool ok = false, mismatch = false, exact_nonzero = false, covered = true, texel_differs = false;
    std::vector<double> err, share, residual;
  };
  std::vector<Local> loc(picked.size());
  auto work = [&](size_t lo, size_t hi) {
    BudgetPath path(sc.config, sc.state, sc.tris);
    IdealJudge judge(sc.state, sc.tris);
    for (size_t i = lo; i < hi; ++i) {
      const Picked& f = picked[i];
      Local& L = loc[i];
      const IdealValue id = judge.at(f.prim, f.x, f.y);
      if (!id.valid) continue;
      const PathValue all = path.eval(f.prim, f.x, f.y, 0);
      const PathValue ex = o.checks ? path.eval(f.prim, f.x, f.y, kAllExact) : PathValue{};
      if (!all.valid || (o.checks && !ex.valid)) continue;
      L.ok = true;
      L.covered = ex.exact_covered;
      // The all-active path against the model's own fragment.
      L.mismatch = all.depth != mpq_class(f.depth);
      for (int k = 0; k < nv; ++k) L.mismatch |= all.var[k] != to_mpq(f.var[k]);
      // The ideal as the outputs measure it.
      std::vector<mpq_class> ideal(nout);
      ideal[0] = id.z * Mc;
      for (int k = 0; k < nv; ++k) ideal[k + 1] = id.v[k];
      if (o.checks) {
        L.exact_nonzero = ex.depth != ideal[0];
        for (int k = 0; k < nv; ++k) L.exact_nonzero |= ex.var[k] != ideal[k + 1];
      } else {
        L.covered = true;
      }
      // The nearest texel of the model's u, v against the ideal's (the image a user sees).
      for (const BudgetOutput& O : r.outputs)
        if (O.texels > 0) {
          const mpq_class a = all.var[O.varying] * O.texels, b = ideal[O.varying + 1] * O.texels;
          mpz_class fa, fb;
          mpz_fdiv_q(fa.get_mpz_t(), a.get_num_mpz_t(), a.get_den_mpz_t());
          mpz_fdiv_q(fb.get_mpz_t(), b.get_num_mpz_t(), b.get_den_mpz_t());
          L.texel_differs |= fa != fb;
        }
      auto errs = [&](const PathValue& pv) {
        std::vector<double> e(nout);
        e[0] = out_err(r.outputs[0], pv.depth, ideal[0], qb);
        for (int k = 0; k < nv; ++k) e[k + 1] = out_err(r.outputs[k + 1], pv.var[k], ideal[k + 1], qb);
        return e;
      };
      L.err = errs(all);
      L.share.assign((size_t)nout * kNumRoundPoints, 0);
      for (int p = 0; p < kNumRoundPoints && o.shares; ++p) {
        if ((RoundPoint)p == RoundPoint::CoverageSnap) continue;  // no value effect on this path (counted as pixels)
        const PathValue one = path.eval(f.prim, f.x, f.y, exact_bit((RoundPoint)p));
        if (!one.valid) continue;
        const std::vector<double> e = errs(one);
        for (int q = 0; q < nout; ++q) L.share[(size_t)q * kNumRoundPoints + p] = L.err[q] - e[q];
      }
      L.residual.assign(nout, 0);
      for (int q = 0; q < nout; ++q) {
        double s = 0;
        for (int p = 0; p < kNumRoundPoints; ++p) s += L.share[(size_t)q * kNumRoundPoints + p];
        L.residual[q] = L.err[q] - s;
      }
      // Texel-level figures need the absolute error: kept in err via the outputs below.
      for (int k = 0; k < nv; ++k) L.err.push_back(abs_err(all.var[k], ideal[k + 1]));
    }
  };
  const int T = std::max(1, std::min(o.threads, (int)std::max<size_t>(1, picked.size() / 64)));
  std::vector<std::thread> th;
  for (int t = 0; t < T; ++t)
    th.emplace_back(work, picked.size() * (size_t)t / (size_t)T, picked.size() * (size_t)(t + 1) / (size_t)T);
  for (auto& x : th) x.join();

  for (size_t i = 0; i < picked.size(); ++i) {
    const Local& L = loc[i];
    if (!L.ok) {
      ++r.skipped;
      continue;
    }
    r.model_mismatches += L.mismatch;
    r.exact_nonzero += L.exact_nonzero;
    r.not_exactly_covered += !L.covered;
    r.texel_differs += L.texel_differs;
    BudgetFragment bf;
    bf.index = picked[i].index;
    bf.texel_differs = L.texel_differs;
    bf.abs.assign(nout, 0);
    for (int k = 0; k < nv; ++k) bf.abs[k + 1] = L.err[(size_t)nout + k];
    bf.x = picked[i].x;
    bf.y = picked[i].y;
    bf.prim = picked[i].prim;
    bf.exact_covered = L.covered;
    bf.err.assign(L.err.begin(), L.err.begin() + nout);
    bf.share = L.share;
    bf.residual = L.residual;
    for (int q = 0; q < nout; ++q) {
      BudgetOutput& O = r.outputs[q];
      O.err.add(L.err[q]);
      if (O.varying >= 0) {
        const double a = L.err[(size_t)nout + O.varying];
        O.abs_err.add(a);
        if (O.texels > 0) O.texel_err.add(a * O.texels);
      }
      int dom = -1;
      double best = 0;
      for (int p = 0; p < kNumRoundPoints; ++p) {
        const double s = L.share[(size_t)q * kNumRoundPoints + p];
        O.share[p].add(s);
        if (s > best) best = s, dom = p;
      }
      O.residual.add(L.residual[q]);
      if (L.residual[q] > best) dom = kNumRoundPoints;
      if (dom >= 0) ++O.dominant[dom];
    }
    r.frags.push_back(std::move(bf));
  }
  return r;
}

nlohmann::json budget_json(const BudgetResult& r) {
  nlohmann::json j;
  j["scene"] = r.scene;
  j["fragments"] = r.fragments;
  j["sampled"] = r.sampled;
  j["skipped"] = r.skipped;
  j["model_mismatches"] = r.model_mismatches;
  j["all_exact_nonzero"] = r.exact_nonzero;
  j["coverage_snap_not_exactly_covered"] = r.not_exactly_covered;
  j["texel_index_differs"] = r.texel_differs;
  nlohmann::json pts = nlohmann::json::array();
  for (int p = 0; p < kNumRoundPoints; ++p)
    pts.push_back({{"name", round_point_info((RoundPoint)p).name},
                   {"fields", round_point_info((RoundPoint)p).fields},
                   {"width", round_point_width(r.cfg, (RoundPoint)p)}});
  j["rounding_points"] = pts;
  for (const BudgetOutput& o : r.outputs) {
    nlohmann::json oj;
    oj["unit"] = o.unit;
    oj["error"] = o.err.to_json();
    if (o.varying >= 0) oj["abs_error"] = o.abs_err.to_json();
    if (o.texels > 0) oj["texel_error"] = o.texel_err.to_json(), oj["texels"] = o.texels;
    for (int p = 0; p < kNumRoundPoints; ++p) {
      nlohmann::json s = o.share[p].to_json();
      s["dominant_fragments"] = o.dominant[p];
      oj["share"][round_point_info((RoundPoint)p).name] = s;
    }
    oj["residual"] = o.residual.to_json();
    oj["residual"]["dominant_fragments"] = o.dominant[kNumRoundPoints];
    j["outputs"][o.name] = oj;
  }
  return j;
}

std::string budget_markdown(const BudgetResult& r, const std::vector<std::string>& images) {
  std::ostringstream m;
  m << "# Error budget: " << r.scene << "\n\n"
    << "Every sampled fragment the model drew, against the exact value of the unsnapped triangle at the pixel "
       "centre (IdealJudge, GMP). A rounding point's **share** is the error with every point active minus the "
       "error with that one point exact (analysis/budget_path.hpp); the **residual** is the error minus the sum "
       "of the shares (the interaction of the points). How to read it: docs/reports.md, \"Error budget\".\n\n"
    << "| figure | value |\n|---|---|\n"
    << "| fragments drawn (depth test passed) | " << r.fragments << " |\n"
    << "| sampled (evenly spaced in output order) | " << r.sampled << " |\n"
    << "| skipped (ideal undefined: edge-on; or zero-area attribute triangle) | " << r.skipped << " |\n"
    << "| all points active ≠ the model's fragment | " << r.model_mismatches << " |\n"
    << "| all points exact ≠ the ideal | " << r.exact_nonzero << " |\n"
    << "| coverage_snap: drawn pixels whose centre is outside the exact triangle | " << r.not_exactly_covered
    << " |\n| nearest texel (⌊u·W⌋, ⌊v·H⌋) differs from the ideal's | " << r.texel_differs << " |\n\n";
  m << "## Rounding points\n\n| point | stage | configuration | width here |\n|---|---|---|---|\n";
  for (int p = 0; p < kNumRoundPoints; ++p) {
    const RoundPointInfo& i = round_point_info((RoundPoint)p);
    m << "| `" << i.name << "` | " << i.stage << " | `" << i.fields << "` | " << round_point_width(r.cfg, (RoundPoint)p)
      << " |\n";
  }
  for (const BudgetOutput& o : r.outputs) {
    m << "\n## " << o.name << " (" << o.unit << ")\n\n"
      << "Error (every point active): max " << fmt_num(o.err.max()) << ", p99 " << fmt_num(o.err.pct(0.99)) << ", mean "
      << fmt_num(o.err.mean()) << " " << o.unit << " over " << o.err.n() << " fragments";
    if (o.varying >= 0)
      m << "; absolute max " << fmt_num(o.abs_err.max()) << ", p99 " << fmt_num(o.abs_err.pct(0.99));
    if (o.texels > 0)
      m << "; in texels (" << o.texels << " texels) max " << fmt_num(o.texel_err.max()) << ", p99 "
        << fmt_num(o.texel_err.pct(0.99));
    m << ".\n\n| rounding point | share max | share p99 | share mean | dominant on |\n|---|---|---|---|---|\n";
    for (int p = 0; p < kNumRoundPoints; ++p)
      m << "| `" << round_point_info((RoundPoint)p).name << "` | " << fmt_num(o.share[p].max()) << " | "
        << fmt_num(o.share[p].pct(0.99)) << " | " << fmt_num(o.share[p].mean()) << " | " << o.dominant[p] << " |\n";
    m << "| residual (interaction) | " << fmt_num(o.residual.max()) << " | " << fmt_num(o.residual.pct(0.99)) << " | "
      << fmt_num(o.residual.mean()) << " | " << o.dominant[kNumRoundPoints] << " |\n";
  }
  if (!images.empty()) {
    m << "\n## Plots\n\n";
    for (const std::string& im : images) m << "![" << im << "](" << im << ")\n\n";
  }
  return m.str();
}

void write_budget_csv(const BudgetResult& r, const std::string& path) {
  std::ofstream f(path);
  f << "x,y,prim,output,unit,error";
  for (int p = 0; p < kNumRoundPoints; ++p) f << ",share_" << round_point_info((RoundPoint)p).name;
  f << ",residual\n";
  char b[64];
  auto num = [&](double v) {
    std::snprintf(b, sizeof b, "%.9g", v);
    return std::string(b);
  };
  for (const BudgetFragment& bf : r.frags)
    for (size_t q = 0; q < r.outputs.size(); ++q) {
      f << bf.x << "," << bf.y << "," << bf.prim << "," << r.outputs[q].name << "," << r.outputs[q].unit << ","
        << num(bf.err[q]);
      for (int p = 0; p < kNumRoundPoints; ++p) f << "," << num(bf.share[q * kNumRoundPoints + p]);
      f << "," << num(bf.residual[q]) << "\n";
    }
  if (!f) throw ConfigError(path + ": cannot write");
}

}  // namespace fxr

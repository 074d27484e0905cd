// The planner (analysis/plan.hpp). Derivations and the search: docs/reports.md, "Planner".
#include "analysis/plan.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "analysis/budget.hpp"
#include "analysis/error_stats.hpp"
#include "analysis/lut_model.hpp"
#include "analysis/scene_analysis.hpp"
#include "model/config/validate.hpp"
#include "model/stages/attr.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/input.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/recip_stage.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/stages/viewport.hpp"

namespace fxr {

namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\n"), b = s.find_last_not_of(" \t\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

double parse_number(const std::string& t, const std::string& item) {
  try {
    const size_t slash = t.find('/');
    if (slash != std::string::npos) return std::stod(t.substr(0, slash)) / std::stod(t.substr(slash + 1));
    size_t used = 0;
    const double v = std::stod(t, &used);
    if (used != t.size()) throw std::invalid_argument(t);
    return v;
  } catch (const std::exception&) {
    throw ConfigError("--target: item '" + item + "': '" + t + "' is not a number (give e.g. 1, 0.5 or 1/16)");
  }
}

}  // namespace

std::vector<PlanLimit> parse_plan_target(const std::string& spec) {
  std::vector<PlanLimit> out;
  std::stringstream ss(spec);
  for (std::string item; std::getline(ss, item, ';');) {
    item = trim(item);
    if (item.empty()) continue;
    const size_t le = item.find("<=");
    if (le == std::string::npos) throw ConfigError("--target: item '" + item + "': expected 'NAMES <= VALUE UNIT'");
    const std::string lhs = trim(item.substr(0, le));
    std::string rhs = trim(item.substr(le + 2));
    if (lhs.find("pixels") != std::string::npos) {  // "image pixels differing from the exact image <= N"
      out.push_back({"pixels", "pixels", parse_number(rhs, item), item});
      continue;
    }
    const size_t sp = rhs.find(' ');
    if (sp == std::string::npos) throw ConfigError("--target: item '" + item + "': give a unit (texel, LSB or ulp)");
    const double v = parse_number(trim(rhs.substr(0, sp)), item);
    std::string unit = trim(rhs.substr(sp + 1));
    if (unit == "texels") unit = "texel";
    if (unit == "LSBs" || unit == "lsb") unit = "LSB";
    if (unit == "ulps") unit = "ulp";
    if (unit != "texel" && unit != "LSB" && unit != "ulp")
      throw ConfigError("--target: item '" + item + "': unit '" + unit + "' (expected texel, LSB or ulp)");
    std::stringstream names(lhs);
    for (std::string n; std::getline(names, n, ',');) {
      n = trim(n);
      if (n.empty()) continue;
      if ((n == "depth") != (unit == "LSB"))
        throw ConfigError("--target: item '" + item + "': depth is measured in LSB, varyings in texel or ulp");
      out.push_back({n, unit, v, item});
    }
  }
  if (out.empty()) throw ConfigError("--target: no limit given");
  return out;
}

namespace {
// The widest values the search may start from when the scenes' configuration misses the target
// (each dimension's ladder reaches them): within the i128 rules of validate() for
// attr_coord_bits 36 and interp_block_bits 48 (2·36 + 48 + 5 = 125 ≤ 127).
struct Wide {
  int attr_coord_bits = 36, attr_sig_bits = 40, interp_block_bits = 48, div_bits = 40, varying_out_sig_bits = 32,
      clip_sig_bits = 48;
} const kWide;
}  // namespace

std::vector<PlanDimension> plan_dimensions(const Config& c, int min_depth_bits) {
  std::vector<PlanDimension> d;
  auto ladder = [](int lo, int hi) {
    std::vector<int> v;
    for (int i = lo; i <= hi; ++i) v.push_back(i);
    return v;
  };
  const RasterConfig& r = c.raster;
  d.push_back({"raster.attr_subpixel_bits", ladder(r.subpixel_bits + 1, std::max(r.attr_subpixel_bits, r.subpixel_bits + 1)),
               [](const Config& k) { return k.raster.attr_subpixel_bits; }, [](Config& k, int v) { k.raster.attr_subpixel_bits = v; }});
  d.push_back({"raster.attr_coord_bits", ladder(r.window_int_bits + 3, std::max({r.attr_coord_bits, r.window_int_bits + 3, kWide.attr_coord_bits})),
               [](const Config& k) { return k.raster.attr_coord_bits; }, [](Config& k, int v) { k.raster.attr_coord_bits = v; }});
  d.push_back({"raster.attr_sig_bits", ladder(8, std::max(r.attr_sig_bits, kWide.attr_sig_bits)), [](const Config& k) { return k.raster.attr_sig_bits; },
               [](Config& k, int v) { k.raster.attr_sig_bits = v; }});
  d.push_back({"raster.interp_block_bits", ladder(16, std::max(r.interp_block_bits, kWide.interp_block_bits)),
               [](const Config& k) { return k.raster.interp_block_bits; }, [](Config& k, int v) { k.raster.interp_block_bits = v; }});
  d.push_back({"raster.z_frac_bits", ladder(16, r.z_frac_bits), [](const Config& k) { return k.raster.z_frac_bits; },
               [](Config& k, int v) { k.raster.z_frac_bits = v; }});
  d.push_back({"div.num_bits=den_bits", ladder(8, std::max({c.div.num_bits, c.div.den_bits, kWide.div_bits})),
               [](const Config& k) { return std::max(k.div.num_bits, k.div.den_bits); },
               [](Config& k, int v) { k.div.num_bits = k.div.den_bits = v; }});
  d.push_back({"raster.varying_out_sig_bits", ladder(8, std::max(r.varying_out_sig_bits, kWide.varying_out_sig_bits)),
               [](const Config& k) { return k.raster.varying_out_sig_bits; },
               [](Config& k, int v) { k.raster.varying_out_sig_bits = v; }});
  d.push_back({"raster.clip_sig_bits", ladder(16, std::max(r.clip_sig_bits, kWide.clip_sig_bits)), [](const Config& k) { return k.raster.clip_sig_bits; },
               [](Config& k, int v) { k.raster.clip_sig_bits = v; }});
  d.push_back({"raster.depth_format (bits)", min_depth_bits > 16 ? std::vector<int>{24} : std::vector<int>{16, 24}, [](const Config& k) { return k.raster.depth_bits(); },
               [](Config& k, int v) { k.raster.depth_format = v == 16 ? DepthFormat::D16 : DepthFormat::D24; }});
  d.push_back({"div.algorithm (0 radix2, 1 shared_recip)", {1, 0},
               [](const Config& k) { return k.div.algorithm == DivAlgorithm::SharedRecip ? 1 : 0; },
               [](Config& k, int v) { k.div.algorithm = v ? DivAlgorithm::SharedRecip : DivAlgorithm::Radix2; }});
  return d;
}

const char* plan_cost_name(PlanCost k) {
  return k == PlanCost::Area ? "area_proxy+ff_bits" : k == PlanCost::Luts ? "lut4_model" : "clocks_per_frame";
}

int64_t plan_cost(const Config& c, int nv, PlanCost k, const LutModel* luts) {
  if (k == PlanCost::Cycles) throw ConfigError("plan_cost: clocks per frame need the scenes (PlanOptions::frame_clocks)");
  if (k == PlanCost::Luts) {
    if (!luts) throw ConfigError("plan_cost: --cost luts needs the LUT4 model (analysis/lut_table.json)");
    return lut_model_total(*luts, c, nv);
  }
  // Area: the stages' logic (tables, partial products, adders) and their registers. Registers
  // count because the depth format is mostly register and memory width: without them D16 came
  // out dearer than D24 (docs/reports.md, "Planner").
  int64_t t = 0;
  for (const StageCost& x : unit_stage_costs(c, nv)) t += x.area_proxy() + x.ff_bits;
  return t;
}

namespace {

std::string label_of(const std::vector<PlanDimension>& dims, const Config& c) {
  std::string s;
  for (const PlanDimension& d : dims) s += (s.empty() ? "" : " ") + std::to_string(d.get(c));
  return s;
}

using Extras = std::vector<std::vector<uint64_t>>;  // per scene: output indices sampled in addition

// Clocks per frame, cached per configuration label and scene (the cycle model is deterministic:
// the same configuration gives the same clocks, so a cache hit never changes a result).
struct ClockCache {
  std::mutex m;
  std::map<std::pair<std::string, size_t>, uint64_t> clocks;
};

int64_t eval_cost(const std::vector<Scene>& scenes, const Config& c, const std::string& label, int nv,
                  const PlanOptions& o, ClockCache* cache) {
  if (o.cost != PlanCost::Cycles) return plan_cost(c, nv, o.cost, o.luts);
  if (!o.frame_clocks) throw ConfigError("--cost cycles: no cycle model was given to the planner");
  int64_t t = 0;
  for (size_t i = 0; i < scenes.size(); ++i) {
    const auto key = std::make_pair(label, i);
    {
      std::lock_guard<std::mutex> g(cache->m);
      if (auto it = cache->clocks.find(key); it != cache->clocks.end()) {
        t += (int64_t)it->second;
        continue;
      }
    }
    const uint64_t k = o.frame_clocks(c, scenes[i]);
    {
      std::lock_guard<std::mutex> g(cache->m);
      cache->clocks[key] = k;
    }
    t += (int64_t)k;
  }
  return t;
}

PlanEval evaluate(const std::vector<Scene>& scenes, const Config& c, const std::vector<PlanDimension>& dims,
                  const PlanOptions& o, const Extras& extras, ClockCache* cache,
                  std::vector<std::vector<uint64_t>>* violating = nullptr) {
  PlanEval e;
  e.cfg = c;
  e.label = label_of(dims, c);
  e.figure.assign(o.target.size(), 0);
  int nv = 0;
  for (const Scene& s : scenes) nv = std::max(nv, s.state.num_varyings);
  try {
    derive_widths(e.cfg);
    validate(e.cfg, "plan");
    check_attr_widths(e.cfg);  // the attribute path's own rules (frame_begin checks them too)
    BudgetPath probe(e.cfg, scenes.front().state, scenes.front().tris);
  } catch (const ConfigError&) {
    e.valid = false;
    return e;
  }
  e.cost = eval_cost(scenes, e.cfg, e.label, nv, o, cache);
  double frags = 0, secs = 0;
  for (const Scene& s0 : scenes) {
    Scene s = s0;
    s.config = e.cfg;
    BudgetOptions bo;
    bo.samples = o.samples;
    bo.threads = 1;
    bo.shares = false;
    bo.checks = false;
    const size_t si = (size_t)(&s0 - &scenes.front());
    if (violating) bo.samples = 0, bo.threads = o.threads;  // verification: every fragment
    else bo.extra = extras[si];
    const BudgetResult r = run_budget(s, bo);
    if (violating) {
      std::vector<uint64_t>& v = (*violating)[si];
      for (const BudgetFragment& f : r.frags) {
        bool bad = false;
        for (const PlanLimit& L : o.target) {
          if (L.output == "pixels") {
            bad |= L.max < 1 && f.texel_differs;  // a per-fragment count: only a limit of 0 names fragments
            continue;
          }
          for (size_t q = 0; q < r.outputs.size(); ++q)
            if (r.outputs[q].name == L.output)
              bad |= (L.unit == "texel" ? f.abs[q] * r.outputs[q].texels : f.err[q]) > L.max;
        }
        if (bad) v.push_back(f.index);
      }
    }
    frags += (double)r.fragments;
    secs += r.model_seconds;
    for (size_t i = 0; i < o.target.size(); ++i) {
      const PlanLimit& L = o.target[i];
      double f = 0;
      if (L.output == "pixels") {
        f = (double)r.texel_differs;
      } else {
        for (const BudgetOutput& b : r.outputs) {
          if (b.name != L.output) continue;
          if (L.unit == "texel") {
            if (b.texels == 0) throw ConfigError("--target: '" + L.output + "' is not a texture coordinate of " + s.name);
            f = b.texel_err.max();
          } else {
            f = b.err.max();
          }
        }
      }
      e.figure[i] = std::max(e.figure[i], f);
    }
  }
  e.mfrags_per_s = secs > 0 ? frags / secs / 1e6 : 0;
  e.ratio = 0;
  for (size_t i = 0; i < o.target.size(); ++i) {
    const double m = o.target[i].max;
    e.ratio = std::max(e.ratio, m > 0 ? e.figure[i] / m : (e.figure[i] > 0 ? INFINITY : 0));
  }
  e.meets = e.ratio <= 1;
  return e;
}

// Fixed batch size: which configurations are evaluated never depends on the thread count.
constexpr size_t kBatch = 4;
// Search rounds at most, and failing fragments added to the sample per scene and round.
constexpr int kMaxRounds = 4;
constexpr size_t kMaxExtraPerRound = 2000;

}  // namespace

PlanResult run_plan(const std::vector<Scene>& scenes, const PlanOptions& o) {
  PlanResult R;
  for (const Scene& s : scenes) R.scenes.push_back(s.name), R.num_varyings = std::max(R.num_varyings, s.state.num_varyings);
  // The depth-format floor: the narrowest format that still separates the overlapping surfaces
  // of every scene (fxraster analyze; −1, coplanar or intersecting surfaces: no format separates
  // them, counted as the widest).
  if (o.depth_floor_from_analysis) {
    for (const Scene& s : scenes)
      for (const MinWidth& w : analyze_scene(s).widths)
        if (w.field == "raster.depth_format") R.min_depth_bits = std::max(R.min_depth_bits, w.min < 0 ? 24 : w.min);
  }
  const std::vector<PlanDimension> dims = plan_dimensions(scenes.front().config, R.min_depth_bits);
  ClockCache cache;
  std::map<std::string, size_t> seen;  // label → index in R.evaluated
  Extras extras(scenes.size());
  auto eval_batch = [&](const std::vector<Config>& cs) {
    std::vector<size_t> idx(cs.size());
    std::vector<size_t> todo;
    std::vector<PlanEval> fresh(cs.size());
    for (size_t i = 0; i < cs.size(); ++i) {
      const std::string l = label_of(dims, cs[i]);
      if (auto it = seen.find(l); it != seen.end()) idx[i] = it->second;
      else todo.push_back(i), idx[i] = SIZE_MAX;
    }
    std::vector<std::thread> th;
    const size_t T = (size_t)std::max(1, o.threads);
    std::vector<std::string> errors(T);
    for (size_t t = 0; t < T; ++t)
      th.emplace_back([&, t] {
        try {
          for (size_t j = t; j < todo.size(); j += T) fresh[todo[j]] = evaluate(scenes, cs[todo[j]], dims, o, extras, &cache);
        } catch (const std::exception& e) {
          errors[t] = e.what();
        }
      });
    for (auto& x : th) x.join();
    for (const std::string& e : errors)
      if (!e.empty()) throw ConfigError(e);
    for (size_t i : todo) {
      const std::string l = fresh[i].label;
      if (auto it = seen.find(l); it != seen.end()) idx[i] = it->second;  // a duplicate inside the batch
      else seen[l] = R.evaluated.size(), idx[i] = R.evaluated.size(), R.evaluated.push_back(fresh[i]);
      if (o.progress)
        o.progress("evaluated " + std::to_string(R.evaluated.size()) + ": " + fresh[i].label + " cost " +
                   std::to_string(fresh[i].cost) + (fresh[i].valid ? (fresh[i].meets ? " meets" : " misses") : " invalid"));
    }
    std::vector<PlanEval> out;
    for (size_t i : idx) out.push_back(R.evaluated[i]);
    return out;
  };
  // Whether some value of `d` narrower than index `at` costs less than `b` (the values up to the
  // first configuration validate() refuses, where the narrowing would stop).
  auto cost_falls = [&](const PlanDimension& d, const PlanEval& b, long at) {
    std::vector<Config> cs;
    for (long i = at - 1; i >= 0; --i) {
      Config c = b.cfg;
      d.set(c, d.values[(size_t)i]);
      derive_widths(c);
      try {
        validate(c, "plan");
        check_attr_widths(c);
      } catch (const ConfigError&) {
        break;
      }
      cs.push_back(c);
    }
    std::vector<int64_t> cost(cs.size(), 0);
    const size_t T = (size_t)std::max(1, o.threads);
    std::vector<std::string> errors(T);
    std::vector<std::thread> th;
    for (size_t t = 0; t < T; ++t)
      th.emplace_back([&, t] {
        try {
          for (size_t j = t; j < cs.size(); j += T) cost[j] = eval_cost(scenes, cs[j], label_of(dims, cs[j]), R.num_varyings, o, &cache);
        } catch (const std::exception& e) {
          errors[t] = e.what();
        }
      });
    for (auto& x : th) x.join();
    for (const std::string& e : errors)
      if (!e.empty()) throw ConfigError(e);
    for (int64_t k : cost)
      if (k < b.cost) return true;
    return false;
  };
  Config cur = scenes.front().config;
  derive_widths(cur);
  PlanEval best;
  // Rounds: search on the sample (plus the fragments earlier rounds found failing), then verify
  // the choice on every fragment; failing fragments join the sample of the next round.
  for (int round = 1; round <= kMaxRounds; ++round) {
  R.rounds = round;
  seen.clear();
  R.evaluated.clear();
  R.start = eval_batch({cur}).front();
  best = R.start;
  R.widened = false;
  if (!R.start.meets) {
    // Start from the widest configuration instead (every dimension at the top of its ladder,
    // keeping depth format and algorithm), then narrow from there.
    Config wide = cur;
    wide.raster.attr_coord_bits = std::max(kWide.attr_coord_bits, cur.raster.window_int_bits + 3);
    wide.raster.attr_sig_bits = kWide.attr_sig_bits;
    wide.raster.interp_block_bits = kWide.interp_block_bits;
    wide.div.num_bits = wide.div.den_bits = kWide.div_bits;
    wide.raster.varying_out_sig_bits = kWide.varying_out_sig_bits;
    wide.raster.clip_sig_bits = kWide.clip_sig_bits;
    const PlanEval w = eval_batch({wide}).front();
    if (w.valid && w.meets) best = w;
    R.widened = true;
  }
  for (int pass = 0; pass < 4; ++pass) {
    bool changed = false;
    for (const PlanDimension& d : dims) {
      const int v = d.get(best.cfg);
      const auto pos = std::find(d.values.begin(), d.values.end(), v);
      if (pos == d.values.end()) continue;
      // Skip the dimension when no narrower value (down to the first invalid one) costs less than
      // the current choice: the search below could not change it. Only the cost is computed —
      // for --cost cycles a cycle-model run per value, in parallel — not the error.
      if (!cost_falls(d, best, pos - d.values.begin())) continue;
      // Narrower values from the current one down, in fixed batches, until one misses.
      PlanEval pick = best;
      for (long i = (long)(pos - d.values.begin()) - 1; i >= 0;) {
        std::vector<Config> batch;
        for (long j = i; j >= 0 && batch.size() < kBatch; --j) {
          Config c = best.cfg;
          d.set(c, d.values[(size_t)j]);
          batch.push_back(c);
        }
        const std::vector<PlanEval> ev = eval_batch(batch);
        bool stop = false;
        for (const PlanEval& e : ev) {
          if (!e.valid || !e.meets) {
            stop = true;
            break;
          }
          if (e.cost <= pick.cost) pick = e;  // the narrowest that meets (ties: narrower)
        }
        if (stop) break;
        i -= (long)batch.size();
      }
      if (pick.cost < best.cost && pick.meets) best = pick, changed = true;
    }
    if (!changed) break;
  }
  // Verification on every fragment of every scene.
  std::vector<std::vector<uint64_t>> bad(scenes.size());
  R.verified = evaluate(scenes, best.cfg, dims, o, extras, &cache, &bad);
  size_t nbad = 0;
  for (size_t i = 0; i < scenes.size(); ++i) {
    nbad += bad[i].size();
    if (bad[i].size() > kMaxExtraPerRound) bad[i].resize(kMaxExtraPerRound);  // the first in output order
    std::vector<uint64_t> u = extras[i];
    u.insert(u.end(), bad[i].begin(), bad[i].end());
    std::sort(u.begin(), u.end());
    u.erase(std::unique(u.begin(), u.end()), u.end());
    extras[i] = u;
  }
  R.total_evaluated += R.evaluated.size();
  if (o.progress)
    o.progress("round " + std::to_string(round) + ": chosen " + best.label + ", every fragment: " +
               (R.verified.meets ? "meets" : std::to_string(nbad) + " fragments miss"));
  if (R.verified.meets || !best.meets) break;
  }
  R.chosen = best;
  // Minimality: each dimension one step cheaper.
  for (const PlanDimension& d : dims) {
    MinimalityRow m;
    m.dimension = d.name;
    m.chosen = d.get(best.cfg);
    const auto pos = std::find(d.values.begin(), d.values.end(), m.chosen);
    if (pos == d.values.begin() || pos == d.values.end()) {
      m.verdict = "range minimum of the search";
      R.minimality.push_back(m);
      continue;
    }
    m.cheaper = *(pos - 1);
    Config c = best.cfg;
    d.set(c, m.cheaper);
    const PlanEval e = eval_batch({c}).front();
    if (!e.valid) m.verdict = "invalid configuration (validate() refuses it)";
    else if (e.cost >= best.cost) m.verdict = "cost does not fall (" + std::to_string(e.cost) + "): kept";
    else if (!e.meets) {
      m.verdict = "misses the target:";
      for (size_t i = 0; i < o.target.size(); ++i)
        if (e.figure[i] > o.target[i].max)
          m.verdict += " " + o.target[i].output + " " + fmt_num(e.figure[i]) + " " + o.target[i].unit;
    }
    else m.verdict = "still meets the target at lower cost", m.holds = false;
    R.minimality.push_back(m);
  }
  return R;
}

namespace {

// Pareto front of (cost, ratio) over the valid evaluations, by increasing cost.
std::vector<size_t> pareto(const PlanResult& r) {
  std::vector<size_t> idx;
  for (size_t i = 0; i < r.evaluated.size(); ++i)
    if (r.evaluated[i].valid) idx.push_back(i);
  std::stable_sort(idx.begin(), idx.end(), [&](size_t a, size_t b) {
    const PlanEval &x = r.evaluated[a], &y = r.evaluated[b];
    return x.cost != y.cost ? x.cost < y.cost : x.ratio < y.ratio;
  });
  std::vector<size_t> f;
  double best = INFINITY;
  for (size_t i : idx)
    if (r.evaluated[i].ratio < best) f.push_back(i), best = r.evaluated[i].ratio;
  return f;
}

}  // namespace

nlohmann::json plan_json(const PlanResult& r, const PlanOptions& o) {
  nlohmann::json j;
  j["scenes"] = r.scenes;
  j["cost"] = plan_cost_name(o.cost);
  j["min_depth_bits"] = r.min_depth_bits;
  for (const PlanLimit& L : o.target) j["target"].push_back({{"output", L.output}, {"unit", L.unit}, {"max", L.max}});
  auto ev = [&](const PlanEval& e) {
    nlohmann::json x = {{"label", e.label}, {"cost", e.cost}, {"meets", e.meets}, {"ratio", e.ratio}};
    for (size_t i = 0; i < o.target.size(); ++i) x["figures"][o.target[i].output] = e.figure[i];
    return x;
  };
  j["start"] = ev(r.start);
  j["verified_every_fragment"] = ev(r.verified);
  j["rounds"] = r.rounds;
  j["widened"] = r.widened;
  j["chosen"] = ev(r.chosen);
  j["chosen"]["config"] = config_to_json(r.chosen.cfg);
  j["evaluated"] = r.evaluated.size();
  for (const MinimalityRow& m : r.minimality)
    j["minimality"].push_back({{"dimension", m.dimension}, {"chosen", m.chosen}, {"cheaper", m.cheaper},
                               {"verdict", m.verdict}, {"holds", m.holds}});
  return j;
}

std::string plan_markdown(const PlanResult& r, const PlanOptions& o, const std::vector<std::string>& images) {
  std::ostringstream m;
  const std::vector<PlanDimension> dims = plan_dimensions(r.start.cfg, r.min_depth_bits);
  m << "# Plan\n\nScenes: ";
  for (size_t i = 0; i < r.scenes.size(); ++i) m << (i ? ", " : "") << r.scenes[i];
  m << ". Target: ";
  for (size_t i = 0; i < o.target.size(); ++i) m << (i ? "; " : "") << o.target[i].output << " ≤ " << fmt_num(o.target[i].max) << " " << o.target[i].unit;
  m << " (against the exact unsnapped value; " << o.samples << " sampled fragments per scene and configuration). Cost: `"
    << plan_cost_name(o.cost) << "` ("
    << (o.cost == PlanCost::Area   ? "Σ of the stages' cost() functions: logic bits and register bits"
        : o.cost == PlanCost::Luts ? "the LUT4 model calibrated to the Yosys figures, analysis/lut_table.json"
                                   : "clocks per frame of the cycle model, summed over the scenes")
    << "). Depth formats searched: D" << r.min_depth_bits << " and wider (the scenes' overlapping surfaces, fxraster analyze). "
    << "How to read it: docs/reports.md, \"Planner\".\n\n";
  m << "| | cost | ratio to target | meets |";
  for (const PlanLimit& L : o.target) m << " " << L.output << " (" << L.unit << ") |";
  m << " model M frag/s |\n|---|---|---|---|";
  for (size_t i = 0; i < o.target.size(); ++i) m << "---|";
  m << "---|\n";
  auto row = [&](const char* what, const PlanEval& e) {
    m << "| " << what << " | " << e.cost << " | " << fmt_num(e.ratio) << " | " << (e.meets ? "yes" : "**no**") << " |";
    for (double f : e.figure) m << " " << fmt_num(f) << " |";
    m << " " << fmt_num(e.mfrags_per_s) << " |\n";
  };
  row("starting configuration", r.start);
  row("**plan**", r.chosen);
  row("plan, every fragment of every scene", r.verified);
  if (r.widened)
    m << "\nThe starting configuration misses the target: the search began at the widest configuration (attr_coord_bits 36, "
         "attr_sig_bits 40, interp_block_bits 48, div operands 40, varying_out_sig_bits 32, clip_sig_bits 48) "
      << (r.chosen.meets ? "and narrowed from there." : "which misses it too: no configuration of the search meets it.") << "\n";
  m << "\nCost " << fmt_num(r.start.cost > 0 ? 100.0 * (double)r.chosen.cost / (double)r.start.cost : 0, 1)
    << " % of the start. " << r.total_evaluated << " configurations evaluated in " << r.rounds
    << " round(s) (a round's fragments that miss the target on the full check join the next round's sample).\n\n## Chosen configuration\n\n| dimension | start | plan |\n|---|---|---|\n";
  for (const PlanDimension& d : dims) m << "| `" << d.name << "` | " << d.get(r.start.cfg) << " | " << d.get(r.chosen.cfg) << " |\n";
  m << "\nFile: `plan_config.json` (`fxraster config --config plan_config.json --emit-sv F`).\n\n## Minimality\n\n"
       "| dimension | plan | one step cheaper | verdict |\n|---|---|---|---|\n";
  for (const MinimalityRow& x : r.minimality)
    m << "| `" << x.dimension << "` | " << x.chosen << " | " << (x.verdict.rfind("range", 0) == 0 ? std::string("—") : std::to_string(x.cheaper))
      << " | " << x.verdict << " |\n";
  m << "\n## Pareto front (ratio to target against cost)\n\n| configuration (dimensions in the order above) | cost | ratio | meets | M frag/s |\n|---|---|---|---|---|\n";
  for (size_t i : pareto(r)) {
    const PlanEval& e = r.evaluated[i];
    m << "| " << e.label << " | " << e.cost << " | " << fmt_num(e.ratio) << " | " << (e.meets ? "yes" : "no") << " | "
      << fmt_num(e.mfrags_per_s) << " |\n";
  }
  m << "\nModel speed is measured in this run (the only column that is not reproducible; never in plan.json / pareto.csv).\n";
  if (o.cost == PlanCost::Luts && o.luts) m << lut_model_markdown(*o.luts, r.start.cfg, r.chosen.cfg, r.num_varyings);
  if (!images.empty()) {
    m << "\n## Plots\n\n";
    for (const std::string& im : images) m << "![" << im << "](" << im << ")\n\n";
  }
  return m.str();
}

void write_pareto_csv(const PlanResult& r, const PlanOptions& o, const std::string& path, bool with_speed) {
  std::ofstream f(path);
  f << "label,cost,ratio,meets,pareto";
  for (const PlanLimit& L : o.target) f << "," << L.output;
  if (with_speed) f << ",mfrags_per_s";
  f << "\n";
  const std::vector<size_t> front = pareto(r);
  char b[64];
  for (size_t i = 0; i < r.evaluated.size(); ++i) {
    const PlanEval& e = r.evaluated[i];
    if (!e.valid) continue;
    std::snprintf(b, sizeof b, "%.9g", e.ratio);
    f << e.label << "," << e.cost << "," << b << "," << (e.meets ? 1 : 0) << ","
      << (std::find(front.begin(), front.end(), i) != front.end() ? 1 : 0);
    for (double x : e.figure) std::snprintf(b, sizeof b, "%.9g", x), f << "," << b;
    if (with_speed) std::snprintf(b, sizeof b, "%.4g", e.mfrags_per_s), f << "," << b;
    f << "\n";
  }
  if (!f) throw ConfigError(path + ": cannot write");
}

}  // namespace fxr

// The LUT4 cost model (analysis/lut_model.hpp; docs/reports.md, "LUT4 cost model").
#include "analysis/lut_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "model/config/arch_config.hpp"
#include "model/config/json_input.hpp"
#include "model/config/validate.hpp"
#include "model/stages/clip.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/input.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/recip_stage.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/stages/viewport.hpp"
#include "model/vectors/codegen.hpp"

namespace fxr {

const UnitStage kUnitStages[9] = {{"input", "fxr_input"},   {"clip", "fxr_clip"},         {"recip", "fxr_recip_stage"},
                                  {"viewport", "fxr_viewport"}, {"setup", "fxr_setup"},   {"traverse", "fxr_traverse"},
                                  {"interp", "fxr_interp"}, {"depth", "fxr_depth"},       {"divide", "fxr_divide"}};

std::vector<StageCost> unit_stage_costs(const Config& c, int nv) {
  nv = std::max(nv, 1);
  // fxr_interp as the back end instantiates it (ArchConfig::interp_div_steps quotient bits per clock).
  return {ConvertStage::cost(c), ClipStage::cost(c),  RecipStage::cost(c),
          ViewportStage::cost(c), SetupStage::cost(c), TraverseStage::cost(c),
          InterpStage::cost(c, ArchConfig{}.interp_div_steps), DepthStage::cost(c), divide_cost(c, nv, nv)};
}

namespace {

// A LUT4 holds 16 bits of table.
constexpr double kTableBitsPerLut = 16;

double proxy(const StageCost& s, double k_add, double k_ff) {
  return (double)s.mult_bits + k_add * (double)s.adder_bits + k_ff * (double)s.ff_bits + (double)s.table_bits / kTableBitsPerLut;
}

Config config_over_default(const nlohmann::json& fields, const std::string& where) {
  nlohmann::json merged = config_to_json(Config{});
  merged.merge_patch(fields);
  Config c = config_from_json(merged, where);
  derive_widths(c);
  return c;
}

// The cost function standing for a checkpoint's module.
StageCost proxy_cost(const std::string& name, const Config& c, const std::string& where) {
  if (name == "div_lane") return div_cost(c.div);
  if (name == "depth") return DepthStage::cost(c);
  if (name == "viewport") return ViewportStage::cost(c);
  if (name == "setup") return SetupStage::cost(c);
  if (name == "setup_plane") {
    // One fxr_setup_plane as SetupStage::cost counts a plane of the attribute path: a_k·q_k,
    // b_k·q_k (6 products, ab × qb) and C_k·q_k (3, cwb × qb), the three-term sums of c, dx, dy,
    // and its two register stages of the three sums.
    const RasterConfig& r = c.raster;
    const int W = r.attr_coord_bits, ab = std::max(W + 2, edge_coef_bits(r)), cwb = std::max(2 * W + 2, edge_value_bits(r));
    const int qb = r.interp_block_bits + 2, ipb = interp_plane_bits(r);
    StageCost k;
    for (int i = 0; i < 6; ++i) k.add_mult(ab, qb);
    for (int i = 0; i < 3; ++i) k.add_mult(cwb, qb);
    k.adder_bits = 3 * 2 * (int64_t)ipb;
    k.ff_bits = 2 * 3 * (int64_t)ipb;
    return k;
  }
  if (name == "interp") return InterpStage::cost(c, ArchConfig{}.interp_div_steps);
  throw ConfigError(where + ": proxy '" + name + "' (expected div_lane, depth, viewport, setup, setup_plane or interp)");
}

struct Row {
  double lut4;
  StageCost cost;
  std::string group;
};

// Σ over pairs (i, j) of one group, neither `skip`, of log(P_i / P_j) − log(L_i / L_j), squared.
double pair_error(const std::vector<Row>& rows, double ka, double kf, size_t skip, size_t* pairs) {
  double e = 0;
  size_t n = 0;
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = i + 1; j < rows.size(); ++j) {
      if (i == skip || j == skip || rows[i].group != rows[j].group) continue;
      const double d = std::log(proxy(rows[i].cost, ka, kf) / proxy(rows[j].cost, ka, kf)) - std::log(rows[i].lut4 / rows[j].lut4);
      e += d * d, ++n;
    }
  if (pairs) *pairs = n;
  return e;
}

// Grid search (deterministic): k_add in [0, 8], k_ff in [0, 4], steps of 1/20.
std::pair<double, double> fit(const std::vector<Row>& rows, size_t skip) {
  double best = INFINITY, ka = 1, kf = 0;
  for (int a = 0; a <= 160; ++a)
    for (int f = 0; f <= 80; ++f) {
      const double e = pair_error(rows, a / 20.0, f / 20.0, skip, nullptr);
      if (e < best - 1e-12) best = e, ka = a / 20.0, kf = f / 20.0;
    }
  return {ka, kf};
}

}  // namespace

LutModel load_lut_model(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "LUT4 table");
  LutModel m;
  m.stage_lut4.assign(9, 0);
  m.stage_source.assign(9, "not measured");
  try {
    for (const auto& x : j.at("modules")) {
      const std::string st = x.at("stage").get<std::string>();
      const std::string algo = x.value("algorithm", "");
      bool found = false;
      for (size_t i = 0; i < 9; ++i) {
        if (st != kUnitStages[i].stage) continue;
        found = true;
        if (x.at("lut4").is_null()) continue;
        if (st == "divide" && algo == "shared_recip") {
          m.divide_shared_lut4 = x.at("lut4").get<double>();
          continue;
        }
        m.stage_lut4[i] = x.at("lut4").get<double>();
        m.stage_source[i] = x.at("source").get<std::string>();
      }
      if (!found) throw ConfigError(path + ": modules: unknown stage '" + st + "'");
    }
    std::vector<Row> rows;
    for (const auto& x : j.at("checkpoints")) {
      LutCheckpoint k;
      k.name = x.at("name").get<std::string>();
      k.top = x.at("top").get<std::string>();
      k.group = x.at("group").get<std::string>();
      k.proxy = x.at("proxy").get<std::string>();
      k.config = x.at("proxy_config");
      if (x.at("lut4").is_null()) continue;  // Yosys did not finish: kept in the table, not used
      k.lut4 = x.at("lut4").get<double>();
      const std::string where = path + ": checkpoint '" + k.name + "'";
      rows.push_back({k.lut4, proxy_cost(k.proxy, config_over_default(k.config, where), where), k.group});
      m.checkpoints.push_back(k);
    }
    const auto [ka, kf] = fit(rows, SIZE_MAX);
    m.k_add = ka, m.k_ff = kf;
    size_t n = 0;
    const double e = pair_error(rows, ka, kf, SIZE_MAX, &n);
    m.fit_rms_log = n ? std::sqrt(e / (double)n) : 0;
    // Leave one out: refit without the row, predict it from each other row of its group.
    for (size_t i = 0; i < rows.size(); ++i) {
      const auto [a, f] = fit(rows, i);
      double lsum = 0;
      int cnt = 0;
      for (size_t q = 0; q < rows.size(); ++q)
        if (q != i && rows[q].group == rows[i].group)
          lsum += std::log(rows[q].lut4 * proxy(rows[i].cost, a, f) / proxy(rows[q].cost, a, f)), ++cnt;
      if (cnt == 0) continue;
      m.checkpoints[i].loo_predicted = std::exp(lsum / cnt);
      m.checkpoints[i].loo_error = m.checkpoints[i].loo_predicted / rows[i].lut4 - 1;
    }
  } catch (const nlohmann::json::exception& e) {
    throw ConfigError(path + ": " + e.what());
  }
  // Modules without a figure: the measured modules' LUT4 per proxy unit at the default.
  const Config c0 = config_over_default(nlohmann::json::object(), path);
  const std::vector<StageCost> s0 = unit_stage_costs(c0, kRecordPackageVaryings);
  double lm = 0, pm = 0;
  for (size_t i = 0; i < 9; ++i)
    if (m.stage_lut4[i] > 0) lm += m.stage_lut4[i], pm += proxy(s0[i], m.k_add, m.k_ff);
  m.unmeasured_lut_per_proxy = pm > 0 ? lm / pm : 0;
  return m;
}

std::vector<double> lut_model_stages(const LutModel& m, const Config& c, int nv) {
  Config c0;  // the default, with c's divider algorithm (each algorithm has its own figure)
  c0.div.algorithm = c.div.algorithm;
  derive_widths(c0);
  const std::vector<StageCost> s = unit_stage_costs(c, nv), s0 = unit_stage_costs(c0, kRecordPackageVaryings);
  std::vector<double> out(9, 0);
  for (size_t i = 0; i < 9; ++i) {
    double M = m.stage_lut4[i];
    if (i == 8 && c.div.algorithm == DivAlgorithm::SharedRecip) M = m.divide_shared_lut4;
    const double p = proxy(s[i], m.k_add, m.k_ff);
    out[i] = M > 0 ? M * p / proxy(s0[i], m.k_add, m.k_ff) : m.unmeasured_lut_per_proxy * p;
  }
  return out;
}

int64_t lut_model_total(const LutModel& m, const Config& c, int nv) {
  double t = 0;
  for (double x : lut_model_stages(m, c, nv)) t += x;
  return (int64_t)std::llround(t);
}

std::string lut_model_markdown(const LutModel& m, const Config& a, const Config& b, int nv) {
  std::ostringstream o;
  char buf[160];
  o << "\n## LUT4 model\n\nPer module M · P(c) / P(c0), P = mult_bits + " << m.k_add << " · adder_bits + " << m.k_ff
    << " · ff_bits + table_bits / 16 (k fitted to the checkpoints: rms of log ratio " << m.fit_rms_log
    << "; docs/reports.md, \"LUT4 cost model\").\n\n| module | M at the default (source) | start | plan |\n|---|---|---|---|\n";
  const std::vector<double> x = lut_model_stages(m, a, nv), y = lut_model_stages(m, b, nv);
  double tx = 0, ty = 0;
  for (size_t i = 0; i < 9; ++i) {
    std::snprintf(buf, sizeof buf, "%.0f | %.0f", x[i], y[i]);
    o << "| " << kUnitStages[i].module << " | " << (m.stage_lut4[i] > 0 ? std::to_string((int64_t)m.stage_lut4[i]) : std::string("—"))
      << " (" << m.stage_source[i] << ") | " << buf << " |\n";
    tx += x[i], ty += y[i];
  }
  std::snprintf(buf, sizeof buf, "| **unit** | | **%.0f** | **%.0f** |\n", tx, ty);
  o << buf << "\n| checkpoint | module | group | measured LUT4 | leave-one-out prediction | error |\n|---|---|---|---|---|---|\n";
  for (const LutCheckpoint& k : m.checkpoints) {
    if (k.loo_predicted > 0) std::snprintf(buf, sizeof buf, "%.0f | %.0f | %+.1f %%", k.lut4, k.loo_predicted, 100 * k.loo_error);
    else std::snprintf(buf, sizeof buf, "%.0f | — | —", k.lut4);
    o << "| " << k.name << " | " << k.top << " | " << k.group << " | " << buf << " |\n";
  }
  return o.str();
}

}  // namespace fxr

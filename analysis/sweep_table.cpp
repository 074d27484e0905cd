// analysis/sweep_table.cpp — CSV / Markdown writers and the Pareto front of a sweep table.
#include "analysis/sweep_table.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace fxr::app {

int SweepTable::metric_index(const std::string& name) const {
  for (size_t i = 0; i < metrics.size(); ++i)
    if (metrics[i].name == name) return (int)i;
  return -1;
}

int SweepTable::add_metric(const MetricCol& col) {
  metrics.push_back(col);
  for (auto& r : rows) r.metrics.resize(metrics.size(), NAN);
  return (int)metrics.size() - 1;
}

std::string config_id(const std::string& unit, const nlohmann::json& params) {
  const std::string s = unit + ":" + params.dump();  // nlohmann::json objects dump keys sorted
  uint64_t h = 1469598103934665603ull;                // FNV-1a 64 offset basis
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;  // FNV-1a 64 prime
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)h);
  return buf;
}

std::vector<bool> pareto_front(const SweepTable& t, int cost_col, bool cost_higher_is_better, int err_col) {
  const size_t n = t.rows.size();
  std::vector<bool> on(n, false);
  if (cost_col < 0 || err_col < 0) return on;
  const double sign = cost_higher_is_better ? -1.0 : 1.0;
  for (size_t i = 0; i < n; ++i) {
    const double ci = sign * t.rows[i].metrics[cost_col], ei = t.rows[i].metrics[err_col];
    if (std::isnan(ci) || std::isnan(ei)) continue;
    bool dominated = false;
    for (size_t j = 0; j < n && !dominated; ++j) {
      const double cj = sign * t.rows[j].metrics[cost_col], ej = t.rows[j].metrics[err_col];
      if (j == i || std::isnan(cj) || std::isnan(ej)) continue;
      dominated = cj <= ci && ej <= ei && (cj < ci || ej < ei);
    }
    on[i] = !dominated;
  }
  return on;
}

namespace {

std::string fmt_metric(const MetricCol& c, double v) {
  if (std::isnan(v)) return "";
  char buf[64];
  if (c.integer) std::snprintf(buf, sizeof buf, "%.0f", v);
  else std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::ofstream open_out(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw ConfigError(path + ": cannot write");
  return f;
}

}  // namespace

void write_csv(const SweepTable& t, const std::string& error_col, const std::vector<FrontSpec>& fronts,
               const std::string& path) {
  auto f = open_out(path);
  const int err = t.metric_index(error_col);
  std::vector<std::vector<bool>> on;
  f << "id,label,is_default";
  if (!t.rows.empty())
    for (const auto& p : t.rows[0].params) f << "," << p.name;
  for (const auto& m : t.metrics) f << "," << m.name;
  for (const auto& m : t.text_cols) f << "," << m.name;
  for (const auto& fr : fronts) {
    f << ",pareto_" << fr.cost;
    on.push_back(pareto_front(t, t.metric_index(fr.cost), fr.higher_is_better, err));
  }
  f << "\n";
  for (size_t i = 0; i < t.rows.size(); ++i) {
    const auto& r = t.rows[i];
    f << r.id << "," << r.label << "," << (r.is_default ? 1 : 0);
    for (const auto& p : r.params) f << "," << p.text;
    for (size_t m = 0; m < t.metrics.size(); ++m) f << "," << fmt_metric(t.metrics[m], r.metrics[m]);
    for (const auto& x : r.texts) f << "," << x;
    for (const auto& o : on) f << "," << (o[i] ? 1 : 0);
    f << "\n";
  }
  if (!f) throw ConfigError(path + ": write failed");
}

void write_markdown(const SweepTable& t, const std::string& title, const std::string& intro,
                    const std::string& error_col, const std::vector<FrontSpec>& fronts,
                    const std::vector<std::string>& images, const std::string& path) {
  auto f = open_out(path);
  const int err = t.metric_index(error_col);
  f << "# " << title << "\n\n" << intro << "\n\n";

  // Parameters that never change are listed once; the tables show the ones that vary.
  std::vector<size_t> varying;
  std::vector<size_t> fixed;
  if (!t.rows.empty()) {
    for (size_t p = 0; p < t.rows[0].params.size(); ++p) {
      bool same = true;
      for (const auto& r : t.rows) same = same && r.params[p].text == t.rows[0].params[p].text;
      (same ? fixed : varying).push_back(p);
    }
  }
  // Metric columns that were measured for at least one row.
  std::vector<size_t> shown;
  for (size_t m = 0; m < t.metrics.size(); ++m) {
    bool any = false;
    for (const auto& r : t.rows) any = any || !std::isnan(r.metrics[m]);
    if (any) shown.push_back(m);
  }
  auto header = [&](std::ostream& os) {
    os << "| configuration |";
    for (size_t p : varying) os << " " << t.rows[0].params[p].name << " |";
    for (size_t m : shown) os << " " << t.metrics[m].name << " |";
    for (const auto& x : t.text_cols) os << " " << x.name << " |";
    os << "\n|---|";
    for (size_t i = 0; i < varying.size() + shown.size(); ++i) os << "---:|";
    for (size_t i = 0; i < t.text_cols.size(); ++i) os << "---|";
    os << "\n";
  };
  auto row = [&](std::ostream& os, const SweepRow& r) {
    os << "| " << (r.is_default ? "**" + r.label + "** (default)" : r.label) << " |";
    for (size_t p : varying) os << " " << r.params[p].text << " |";
    for (size_t m : shown) os << " " << fmt_metric(t.metrics[m], r.metrics[m]) << " |";
    for (const auto& x : r.texts) os << " " << x << " |";
    os << "\n";
  };

  f << "## Default configuration\n\n";
  header(f);
  for (const auto& r : t.rows)
    if (r.is_default) row(f, r);
  f << "\n";

  for (const auto& fr : fronts) {
    const int c = t.metric_index(fr.cost);
    if (c < 0) continue;
    const auto on = pareto_front(t, c, fr.higher_is_better, err);
    f << "## Pareto front: " << error_col << " against " << fr.cost
      << (fr.higher_is_better ? " (higher is better)" : "") << "\n\n"
      << "No other configuration is at least as good in both and better in one.\n\n";
    header(f);
    // In order of cost (cheapest first); NaN rows are never on the front.
    std::vector<size_t> idx;
    for (size_t i = 0; i < t.rows.size(); ++i)
      if (on[i]) idx.push_back(i);
    std::stable_sort(idx.begin(), idx.end(), [&](size_t a, size_t b) {
      const double ca = t.rows[a].metrics[c], cb = t.rows[b].metrics[c];
      return fr.higher_is_better ? ca > cb : ca < cb;
    });
    for (size_t i : idx) row(f, t.rows[i]);
    f << "\n";
  }

  if (!images.empty()) {
    f << "## Plots\n\n";
    for (const auto& img : images) f << "![" << img << "](" << img << ")\n\n";
  }

  f << "## All configurations\n\n";
  if (!fixed.empty()) {
    f << "Same in every row:";
    for (size_t p : fixed) f << " " << t.rows[0].params[p].name << " = " << t.rows[0].params[p].text << ";";
    f << "\n\n";
  }
  header(f);
  for (const auto& r : t.rows) row(f, r);
  f << "\n## Columns\n\n";
  for (size_t p : varying) f << "- `" << t.rows[0].params[p].name << "`: " << t.rows[0].params[p].doc << "\n";
  for (size_t m : shown) f << "- `" << t.metrics[m].name << "`: " << t.metrics[m].doc << "\n";
  for (const auto& x : t.text_cols) f << "- `" << x.name << "`: " << x.doc << "\n";
  if (!f) throw ConfigError(path + ": write failed");
}

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw ConfigError(path + ": cannot read");
  std::vector<std::vector<std::string>> out;
  std::string line;
  size_t fields = 0;
  for (int lineno = 1; std::getline(f, line); ++lineno) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    if (line.back() == ',') cells.emplace_back();
    if (out.empty()) fields = cells.size();
    else if (cells.size() != fields)
      throw ConfigError(path + ":" + std::to_string(lineno) + ": expected " + std::to_string(fields) +
                        " fields, got " + std::to_string(cells.size()));
    out.push_back(std::move(cells));
  }
  if (out.empty()) throw ConfigError(path + ": empty (no header line)");
  return out;
}

}  // namespace fxr::app

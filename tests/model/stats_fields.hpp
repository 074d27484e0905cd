// Every counter of a RasterStats as (name, value) pairs, the line and per-triangle counters
// included: two runs compare equal field by field (threads_test.cpp, shortcut_test.cpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "model/unit/io.hpp"

namespace fxr {

inline std::vector<std::pair<std::string, uint64_t>> stats_fields(RasterStats s) {
  std::vector<std::pair<std::string, uint64_t>> v;
  auto add = [&](const char* n, uint64_t& x) { v.emplace_back(n, x); };
  s.visit(add);
  auto add_line = [&](const char* n, uint64_t& x) { v.emplace_back(std::string("lines.") + n, x); };
  s.lines.visit(add_line);
  const TriStats& t = s.tris;
  for (auto [n, x] : {std::pair<const char*, uint64_t>{"tris.geom_rejected_range", t.geom_rejected_range},
                      {"tris.in", t.in}, {"tris.drawn", t.drawn}, {"tris.zero_area", t.zero_area},
                      {"tris.backface", t.backface}, {"tris.no_samples", t.no_samples}, {"tris.range", t.range}})
    v.emplace_back(n, x);
  return v;
}

}  // namespace fxr

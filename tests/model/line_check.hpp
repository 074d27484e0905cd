// tests/model/line_check.hpp — runs the model against the exact references of line_ref.hpp over
// every segment class (shared by line_test.cpp and line_slow_test.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>

#include "line_ref.hpp"
#include "model/stages/line.hpp"

namespace fxr::line_check {

struct Counts {
  uint64_t segments = 0, pixels = 0, mismatched_segments = 0, reverse_mismatches = 0;
  std::string first;  // the first mismatching segment, described
};

inline std::string describe(const LineIn& s) {
  std::ostringstream o;
  o << "(" << s.x0 << "," << s.y0 << ")-(" << s.x1 << "," << s.y1 << ")";
  return o.str();
}

// n segments per class; midpoint also checks that the reversed segment gives the same stream.
inline Counts check(const RasterConfig& r, const LineConfig& c, uint64_t seed, int n_per_class) {
  Counts k;
  line_ref::SegmentGen gen(r, seed);
  for (int cls = 0; cls < (int)line_ref::SegClass::kCount; ++cls) {
    // Long segments cost ~10^4 pixels each: a tenth as many.
    const int n = cls == (int)line_ref::SegClass::GuardBandLong ? std::max(1, n_per_class / 10) : n_per_class;
    for (int t = 0; t < n; ++t) {
      const LineIn s = gen.next((line_ref::SegClass)cls);
      std::vector<LinePixel> got = line_pixels(r, c, s);
      const std::vector<LinePixel> stream = got;
      std::sort(got.begin(), got.end());
      const std::vector<LinePixel> exp = line_ref::reference(r, c, s);
      ++k.segments;
      k.pixels += exp.size();
      if (got != exp) {
        if (k.mismatched_segments++ == 0)
          k.first = describe(s) + " got " + std::to_string(got.size()) + " pixels, exact " + std::to_string(exp.size());
      }
      if (c.rule == LineRule::Midpoint) {
        const LineIn rev{s.x1, s.y1, s.x0, s.y0};
        if (line_pixels(r, c, rev) != stream) ++k.reverse_mismatches;
      }
    }
  }
  return k;
}

}  // namespace fxr::line_check

#include "model/arith/fixed.hpp"

namespace fxr {

const char* to_string(Round r) {
  switch (r) {
    case Round::Trunc: return "trunc";
    case Round::TruncZero: return "trunc_zero";
    case Round::HalfUp: return "half_up";
    case Round::HalfEven: return "half_even";
    case Round::HalfAway: return "half_away";
  }
  return "?";
}

const char* to_string(Overflow o) { return o == Overflow::Wrap ? "wrap" : "saturate"; }

std::string FxFormat::describe() const {
  return std::string(is_signed ? "s" : "u") + std::to_string(int_bits()) + "." + std::to_string(frac) +
         " " + to_string(round) + " " + to_string(overflow);
}

}  // namespace fxr

// PixelDivide (model/stages/pixel_divide.hpp) against normalize_den + divide_varying (the staged
// divider's functions, model/stages/divide.hpp) on 10^8 pixels with two varyings at the default
// widths, every case family of tests/model/pixel_divide_cases.hpp, and 10^7 at each of three
// other shapes (label slow: about a minute of one core).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "model/stages/pixel_divide.hpp"
#include "tests/model/pixel_divide_cases.hpp"

using namespace fxr;
using namespace fxr::pixel_divide_cases;

namespace {

uint64_t count_mismatches(const DivConfig& dc, int nv, uint64_t pixels, uint64_t seed) {
  Config cfg;
  cfg.div = dc;
  PixelDivide pd(dc, nv);
  const size_t bytes = fragment_record_bytes(kMaxVaryings);
  std::vector<uint8_t> want(bytes), got(bytes);
  constexpr size_t kChunk = 100000;
  uint64_t bad = 0, done = 0;
  for (uint64_t chunk = 0; done < pixels; ++chunk) {
    const Family f = kAllFamilies[chunk % (sizeof kAllFamilies / sizeof kAllFamilies[0])];
    for (const PixelCase& p : random_cases(dc, nv, kChunk, seed + chunk, f)) {
      std::memset(want.data(), 0xA5, bytes);
      std::memset(got.data(), 0xA5, bytes);
      reference_words(cfg, p, nv, want.data());
      pd.begin(p.tri(nv));
      pd.write(got.data(), p.sums);
      if (want != got && ++bad <= 5)
        ADD_FAILURE() << family_name(f) << " " << p.describe(nv) << ": want " << words(want.data(), nv) << " got "
                      << words(got.data(), nv);
    }
    done += kChunk;
  }
  return bad;
}

}  // namespace

TEST(PixelDivideSlow, EqualsTheStagedDividerOnHundredMillionPixelsAtDefaultWidths) {
  EXPECT_EQ(count_mismatches(DivConfig{}, 2, 100'000'000, 1001), 0u);
}

TEST(PixelDivideSlow, EqualsTheStagedDividerAtOtherWidths) {
  for (const DivConfig& dc : {div_shape(39, 39, 24), div_shape(20, 39, 24), div_shape(12, 12, 12)})
    EXPECT_EQ(count_mismatches(dc, 3, 10'000'000, 2002), 0u) << shape_name(dc);
}

// The render report's analysis component (analysis/): statistics, ulps, coverage sets, exact
// spot checks and the report files. Expected values come from arithmetic done here by hand
// (percentiles of 1..100, powers of two) or from the documented bounds of the model judged by
// exact GMP arithmetic (docs/pipeline.md: ≤ 0.5 LSB depth and ≤ ½ ulp + ε varyings on the
// snapped triangle).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "analysis/error_stats.hpp"
#include "analysis/render_analysis.hpp"
#include "analysis/render_report.hpp"
#include "analysis/texel_errors.hpp"
#include "frontend/scene.hpp"
#include "model/unit/raster_unit.hpp"
#include "reference/reference.hpp"

namespace {

fxr::Scene small_default_scene() {
  fxr::SceneOptions so;
  so.width = 96;
  so.height = 64;
  so.no_optional = true;  // no bunny: fast
  return fxr::default_scene(so);
}

TEST(ErrorStats, NearestRankPercentilesMeanAndRmsOfOneToHundred) {
  fxr::ErrStat e;
  for (int i = 100; i >= 1; --i) e.add(i);
  e.add(NAN);  // ignored
  e.add(INFINITY);
  EXPECT_EQ(e.n, 100u);
  EXPECT_EQ(e.max, 100);
  EXPECT_DOUBLE_EQ(e.mean(), 50.5);
  EXPECT_DOUBLE_EQ(e.rms(), std::sqrt(338350.0 / 100));  // Σ i² = 100·101·201/6
  EXPECT_EQ(e.pct(0.5), 50);
  EXPECT_EQ(e.pct(0.99), 99);
  EXPECT_EQ(e.pct(1.0), 100);
}

TEST(ErrorStats, UlpIsThePowerOfTwoOfTheValuesBinade) {
  EXPECT_EQ(fxr::ulp_of(1.0, 24), std::ldexp(1.0, -23));
  EXPECT_EQ(fxr::ulp_of(1.999, 24), std::ldexp(1.0, -23));
  EXPECT_EQ(fxr::ulp_of(0.75, 24), std::ldexp(1.0, -24));
  EXPECT_EQ(fxr::ulp_of(-3.0, 8), std::ldexp(1.0, -6));
  EXPECT_EQ(fxr::ulp_of(0.0, 24), 0.0);
  fxr::FxFloat f;
  f.sig = 3;
  f.exp = -2;
  f.neg = true;
  EXPECT_EQ(fxr::fx_to_double(f), -0.75);
}

TEST(RenderAnalysis, CoverageDiffCountsTheSymmetricDifference) {
  fxr::FragmentStore m(0);
  std::vector<fxr::RefFragment> r(3);
  for (int i = 0; i < 3; ++i) {
    fxr::Fragment f;
    f.x = r[i].x = i;
    f.y = r[i].y = 7;
    f.prim = r[i].prim = 1;
    m.push_back(f);
  }
  fxr::CoverageDiff same = fxr::compare_coverage(m, r);
  EXPECT_EQ(same.common, 3u);
  EXPECT_EQ(same.model_only + same.ref_only, 0u);
  r[2].x = 5;  // model has (1, 2, 7), reference has (1, 5, 7)
  fxr::CoverageDiff d = fxr::compare_coverage(m, r);
  EXPECT_EQ(d.common, 2u);
  EXPECT_EQ(d.model_only, 1u);
  EXPECT_EQ(d.ref_only, 1u);
  ASSERT_EQ(d.examples.size(), 2u);
  EXPECT_EQ(d.examples[0]["x"], 2);
  EXPECT_EQ(d.examples[0]["only_in"], "model");
  EXPECT_EQ(d.examples[1]["x"], 5);
}

TEST(RenderAnalysis, ExactSpotChecksStayWithinTheModelsRoundingBounds) {
  const fxr::Scene sc = small_default_scene();
  const fxr::FrameOutput fo = fxr::run_raster_unit(sc.config, sc.state, sc.tris);
  ASSERT_GT(fo.fragments.size(), 1000u);
  const fxr::SpotChecks s = fxr::exact_spot_checks(sc, fo, 500);
  EXPECT_GE(s.checked, 500u);
  EXPECT_EQ(s.not_covered_exactly, 0u);
  EXPECT_LE(s.depth_lsb.max, 0.5);  // one correct rounding of the exact plane value
  for (const auto& v : s.var_ulp) EXPECT_LT(v.max, 0.51) << "½ ulp of the divider + the operand pre-rounding";
}

TEST(RenderAnalysis, ReferenceComparisonCoversEveryFragmentAndMapsTheHeat) {
  const fxr::Scene sc = small_default_scene();
  const fxr::FrameOutput fo = fxr::run_raster_unit(sc.config, sc.state, sc.tris);
  const fxr::RenderErrors e = fxr::compare_to_reference(sc, fo);
  EXPECT_EQ(e.depth_lsb.n + e.ref_invalid, fo.fragments.size());
  ASSERT_EQ(e.heat.size(), (size_t)sc.state.viewport_w * sc.state.viewport_h);
  size_t painted = 0;
  for (double h : e.heat) painted += h >= 0;
  EXPECT_GT(painted, 0u);
  EXPECT_LE(painted, fo.fragments.size());
}

// The texel report (analysis/texel_errors.hpp) for every wrap mode and two weight widths: on the
// model's own coordinates the unit is exact (same texels everywhere, weight error ≤ ½ LSB, colour
// error ≤ ½ level of the final rounding + 255 · 2^−F of the weight rounding: Σ|ŵ − w| over the
// four weights ≤ 2 · 2^−F and the weights' errors sum to zero); against the ideal the weight error
// is at most ½ LSB + the coordinate's own error |u − u_ideal| · size · 2^F (measured here).
TEST(TexelErrors, TheUnitIsExactOnItsOwnCoordinatesAndWithinTheCoordinateErrorOfTheIdeal) {
  for (fxr::TexWrap wrap : {fxr::TexWrap::Repeat, fxr::TexWrap::MirroredRepeat, fxr::TexWrap::ClampToEdge,
                            fxr::TexWrap::ClampToBorder})
    for (int f : {4, 8}) {
      fxr::Scene sc = small_default_scene();
      sc.config.tex_addr.wrap = wrap;
      sc.config.tex_addr.weight_frac_bits = f;
      const fxr::FrameOutput fo = fxr::run_raster_unit(sc.config, sc.state, sc.tris);
      const fxr::SpotChecks spot = fxr::exact_spot_checks(sc, fo, 300);
      ASSERT_GT(spot.ideal_uv.size(), 250u);
      const fxr::TexelErrors te = fxr::texel_errors(sc, fo, spot);
      ASSERT_TRUE(te.textured);
      ASSERT_EQ(te.filters.size(), 2u);
      EXPECT_EQ(te.coords_exp_outside, 0u);
      double du = 0;  // largest |u − u_ideal| · size over the sample, in texels
      for (const auto& p : spot.ideal_uv) {
        const fxr::Fragment& fr = fo.fragments[p.fragment];
        du = std::max(du, std::abs(mpq_class(fxr::to_mpq(fr.var[sc.u_varying]) - p.u).get_d()) * sc.texture.image.width);
        du = std::max(du, std::abs(mpq_class(fxr::to_mpq(fr.var[sc.v_varying]) - p.v).get_d()) * sc.texture.image.height);
      }
      for (const fxr::TexelFilterErrors& e : te.filters) {
        const std::string what = e.filter + " wrap " + std::to_string((int)wrap) + " F " + std::to_string(f);
        EXPECT_EQ(e.own.checked, fo.fragments.size()) << what;
        EXPECT_EQ(e.own.same_texels, e.own.checked) << what;
        EXPECT_EQ(e.ideal.checked, spot.ideal_uv.size()) << what;
        if (e.filter == "nearest") {
          EXPECT_EQ(e.own.colour.max, 0.0) << what;
          EXPECT_EQ(e.own.weight_lsb.n, 0u) << what;
        } else {
          EXPECT_EQ(e.own.weight_lsb.n, 2 * e.own.checked) << what;
          EXPECT_LE(e.own.weight_lsb.max, 0.5) << what;
          EXPECT_GT(e.own.weight_lsb.max, 0.5 - std::ldexp(1.0, -10)) << what << ": the rounding is measured";
          EXPECT_LE(e.own.colour.max, 0.5 + 255 * std::ldexp(1.0, -f)) << what;
          EXPECT_LE(e.ideal.weight_lsb.max, 0.5 + du * std::ldexp(1.0, f) + 1e-9) << what;
        }
      }
    }
}

TEST(RenderReport, WritesEveryFileAndTheDumpHasOneLinePerFragment) {
  const fxr::Scene sc = small_default_scene();
  fxr::RenderOptions o;
  o.out = (std::filesystem::temp_directory_path() / ("fxr_render_report_test_" + std::to_string(::getpid()))).string();
  std::filesystem::remove_all(o.out);
  o.spot_checks = 100;
  const fxr::RenderSummary r = fxr::render_with_report(sc, o);
  EXPECT_TRUE(r.all_accounted);
  for (const char* f : {"image.png", "reference.png", "depth.png", "image_affine.png", "side_by_side.png",
                        "fragments.csv", "fragments.json", "stats.json", "report.md", "report.json"})
    EXPECT_TRUE(std::filesystem::file_size(std::filesystem::path(o.out) / f) > 0) << f;
  std::ifstream csv(std::filesystem::path(o.out) / "fragments.csv");
  size_t rows = 0, comments = 0;
  for (std::string line; std::getline(csv, line);) (line.rfind("#", 0) == 0 ? comments : rows) += 1;
  EXPECT_GT(comments, 0u);
  EXPECT_EQ(rows, r.fragments + 1);  // + the header row
  std::filesystem::remove_all(o.out);
}

}  // namespace

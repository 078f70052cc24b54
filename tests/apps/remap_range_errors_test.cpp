// `coopmap remap --range-errors`: radial-map ranges against the true surfaces.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "sim/runner/remap.h"
#include "tests/support/radial_reading.h"

namespace coopmap {
namespace {

// A wall filling x in [2, 2.2) m on a 1 cm grid.
GridU8 wallAtTwoMetres() {
  GridU8 g(MapLimits::covering({-2.0, -1.0}, {3.0, 1.0}, 0.01), 0);
  for (int iy = 0; iy < g.limits.height; ++iy)
    for (int ix = g.limits.cellX(2.005); ix < g.limits.cellX(2.195); ++ix) g.at(ix, iy) = 1;
  return g;
}

TEST(RemapRangeErrorsTest, ErrorsAgainstTheTrueSurfaceWithTheirSpreadAndTheSigmaCheck) {
  const GridU8 truth = wallAtTwoMetres();
  RadialMap near;  // the wall 2 m ahead: errors -2..+2 cm, modelled sigma 1.5 cm
  for (double e : {-0.02, -0.01, 0.0, 0.01, 0.02})
    near.readings.push_back(hit(0.0, 2.0 + e, 0.015));
  near.readings.push_back(hit(0.0, 1.2, 0.015));  // nothing within 0.5 m of it: an outlier
  RadialReading beyond;
  beyond.kind = RadialKind::kBeyond;
  beyond.range = 4.0;
  near.readings.push_back(beyond);  // not a return: not counted
  const std::vector<RangeErrorBin> bins = rangeErrors({{&near, Pose2()}}, truth);
  ASSERT_EQ(bins.size(), 2u);
  const RangeErrorBin& a = bins[0];  // 2.0 - 0.02 and 2.0 - 0.01 and the outlier at 1.2
  EXPECT_DOUBLE_EQ(a.from_m, 1.0);
  EXPECT_DOUBLE_EQ(a.to_m, 2.0);
  const RangeErrorBin& b = bins[1];
  EXPECT_DOUBLE_EQ(b.from_m, 2.0);
  EXPECT_EQ(a.returns + b.returns, 6u);
  EXPECT_EQ(a.returns, 3u);
  EXPECT_EQ(a.outliers, 1u);
  EXPECT_EQ(b.outliers, 0u);
  // The ray walk finds the surface to a quarter cell (2.5 mm).
  EXPECT_NEAR(a.median_m, -0.01, 0.003);  // of -0.02 and -0.01: the upper middle
  EXPECT_NEAR(b.median_m, 0.01, 0.003);   // of 0, 0.01, 0.02
  EXPECT_NEAR(b.robust_sd_m, 1.4826 * 0.01, 1e-9);
  EXPECT_NEAR(b.rms_m, std::sqrt((0.0 + 1e-4 + 4e-4) / 3), 0.003);
  EXPECT_NEAR(b.mean_sigma_m, 0.015, 1e-12);
  EXPECT_NEAR(b.within_sigma, 2.0 / 3.0, 1e-12);  // 0 and 0.01, not 0.02
  EXPECT_NEAR(a.within_sigma, 0.5, 1e-12);        // -0.01, not -0.02
}

TEST(RemapRangeErrorsTest, AFarReturnIsBinnedByItsRangeAndJudgedByItsOwnSigma) {
  const GridU8 truth = wallAtTwoMetres();
  // The sensor 0.1 m ahead of a robot turned by 0.3 rad sits at (-1.5, 0) and looks along
  // the x axis: the wall is 3.5 m ahead.
  RadialMap far;
  far.sensor_origin = {0.1, 0.0};
  far.readings.push_back(hit(-0.3, 3.5 + 0.05, 0.1));
  far.readings.push_back(hit(-0.3, 3.5 - 0.15, 0.1));
  const Pose2 robot(-1.5 - 0.1 * std::cos(0.3), -0.1 * std::sin(0.3), 0.3);
  const std::vector<RangeErrorBin> bins = rangeErrors({{&far, robot}}, truth);
  ASSERT_EQ(bins.size(), 1u);
  EXPECT_DOUBLE_EQ(bins[0].from_m, 3.0);
  EXPECT_EQ(bins[0].returns, 2u);
  EXPECT_EQ(bins[0].outliers, 0u);
  EXPECT_NEAR(bins[0].rms_m, std::sqrt((0.05 * 0.05 + 0.15 * 0.15) / 2), 0.003);
  EXPECT_NEAR(bins[0].within_sigma, 0.5, 1e-12);
}

TEST(RemapRangeErrorsTest, BadBinsAreRefused) {
  EXPECT_THROW(rangeErrors({}, wallAtTwoMetres(), 0.0), std::invalid_argument);
  EXPECT_THROW(rangeErrors({}, wallAtTwoMetres(), 1.0, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap

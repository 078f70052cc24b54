#include "core/localization/manhattan.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace coopmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

// What stereo sees of a corridor's stretch: its two walls (y = 0 and y = 2, x in [0, 3]) and
// a cross wall at x = 3.5, 1 cm apart with 1.5 cm of noise across each wall, turned by `turn`
// about (7, -3) and, with `clutter` > 0, that share of points more scattered anywhere near
// (people, furniture at any angle).
std::vector<Eigen::Vector2d> corridorPoints(double turn, double clutter, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.015);
  std::uniform_real_distribution<double> anywhere(-0.5, 3.5);
  std::vector<Eigen::Vector2d> p;
  for (double x = 0.0; x <= 3.0; x += 0.01) {
    p.emplace_back(x, noise(rng));
    p.emplace_back(x, 2.0 + noise(rng));
  }
  for (double y = 0.0; y <= 2.0; y += 0.01) p.emplace_back(3.5 + noise(rng), y);
  const size_t walls = p.size();
  for (size_t i = 0; i < static_cast<size_t>(clutter * walls); ++i)
    p.emplace_back(anywhere(rng), anywhere(rng) * 0.6);
  const Eigen::Vector2d pivot(7.0, -3.0);
  const Eigen::Rotation2Dd r(turn);
  for (Eigen::Vector2d& q : p) q = pivot + r * (q - pivot);
  return p;
}

TEST(ManhattanTest, FindsHowFarTheWallsAreTurnedFromTheAxes) {
  for (const double deg : {-2.5, -1.2, -0.3, 0.0, 0.15, 0.7, 2.0}) {
    const std::optional<ManhattanFit> fit = manhattanTurn(corridorPoints(deg * kDeg, 0.0, 1));
    ASSERT_TRUE(fit.has_value()) << deg;
    EXPECT_NEAR(fit->turn_rad / kDeg, deg, 0.05) << deg;
    EXPECT_GT(fit->gain, 1.1);
  }
}

TEST(ManhattanTest, ClutterAtAnyAngleDoesNotMoveTheWallsTurn) {
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    const std::optional<ManhattanFit> fit = manhattanTurn(corridorPoints(0.8 * kDeg, 0.4, seed));
    ASSERT_TRUE(fit.has_value()) << seed;
    EXPECT_NEAR(fit->turn_rad / kDeg, 0.8, 0.1) << seed;
  }
}

TEST(ManhattanTest, AxesOfTheBuildingMayBeTurnedInTheMapFrame) {
  ManhattanConfig c;
  c.axes_rad = 30.0 * kDeg;
  const std::optional<ManhattanFit> fit = manhattanTurn(corridorPoints(31.0 * kDeg, 0.0, 2), c);
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR(fit->turn_rad / kDeg, 1.0, 0.05);
  // The same walls read on the map's own axes are 31 degrees off: outside the window.
  EXPECT_FALSE(manhattanTurn(corridorPoints(31.0 * kDeg, 0.0, 2)).has_value());
}

TEST(ManhattanTest, NoEstimateWithoutStraightWallsNearTheAxes) {
  // Too few points.
  std::vector<Eigen::Vector2d> few = corridorPoints(0.0, 0.0, 3);
  few.resize(100);
  EXPECT_FALSE(manhattanTurn(few).has_value());
  // A round pillar's points: no direction sharper than another.
  std::vector<Eigen::Vector2d> round;
  for (int i = 0; i < 600; ++i)
    round.emplace_back(std::cos(i * 2.0 * M_PI / 600.0), std::sin(i * 2.0 * M_PI / 600.0));
  EXPECT_FALSE(manhattanTurn(round).has_value());
  // Walls turned beyond the window (a wing of the building at another angle).
  EXPECT_FALSE(manhattanTurn(corridorPoints(12.0 * kDeg, 0.0, 4)).has_value());
}

TEST(ManhattanTest, BadConfigurationNamesTheField) {
  auto refusal = [](const ManhattanConfig& c) {
    try {
      c.validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  ManhattanConfig c;
  c.search_rad = 0.0;
  EXPECT_NE(refusal(c).find("search_rad"), std::string::npos) << refusal(c);
  c = {};
  c.step_rad = 1.0;
  EXPECT_NE(refusal(c).find("step_rad"), std::string::npos) << refusal(c);
  c = {};
  c.bin_m = -0.05;
  EXPECT_NE(refusal(c).find("bin_m"), std::string::npos) << refusal(c);
  c = {};
  c.min_sharpness_gain = 0.5;
  EXPECT_NE(refusal(c).find("min_sharpness_gain"), std::string::npos) << refusal(c);
  EXPECT_THROW(manhattanTurn(corridorPoints(0.0, 0.0, 1), c), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap

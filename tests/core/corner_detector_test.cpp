// Corner detection and fitting on synthetic occupancy grids whose true corners are known:
// random sub-cell positions and angles, wall noise and missing cells.
#include "core/landmarks/corner_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/localization/home_base.h"

namespace coopmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct TrueCorner {
  Eigen::Vector2d vertex;  // cells
  double heading;          // rad, into the free wedge
};

// Paints what a robot would map of a corner seen from inside: the free wedge between the
// arms (radius `reach` cells), walls `thick` cells deep behind both arms, unknown elsewhere.
void paintCorner(GridU8& g, const TrueCorner& c, double arm, double thick, double reach) {
  const Eigen::Vector2d a1(std::cos(c.heading + M_PI / 4), std::sin(c.heading + M_PI / 4));
  const Eigen::Vector2d a2(std::cos(c.heading - M_PI / 4), std::sin(c.heading - M_PI / 4));
  const Eigen::Vector2d n1(-a1.y(), a1.x()), n2(a2.y(), -a2.x());  // away from the wedge
  for (int iy = 0; iy < g.limits.height; ++iy)
    for (int ix = 0; ix < g.limits.width; ++ix) {
      const Eigen::Vector2d r = Eigen::Vector2d(ix + 0.5, iy + 0.5) - c.vertex;
      const double s1 = r.dot(a1), q1 = r.dot(n1), s2 = r.dot(a2), q2 = r.dot(n2);
      const bool wall1 = s1 >= -thick && s1 <= arm && q1 >= 0 && q1 <= thick;
      const bool wall2 = s2 >= -thick && s2 <= arm && q2 >= 0 && q2 <= thick;
      const bool wedge = q1 < 0 && q2 < 0 && r.norm() < reach;
      if (wall1 || wall2)
        g.at(ix, iy) = static_cast<uint8_t>(CellClass::kOccupied);
      else if (wedge)
        g.at(ix, iy) = static_cast<uint8_t>(CellClass::kFree);
    }
}

// Flips a fraction of the seen cells to uncertain or the other class, and forgets some.
void addNoise(GridU8& g, std::mt19937& rng, double flip, double missing) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (uint8_t& c : g.cells) {
    if (c == static_cast<uint8_t>(CellClass::kUnknown)) continue;
    const double p = u(rng);
    if (p < missing)
      c = static_cast<uint8_t>(CellClass::kUnknown);
    else if (p < missing + flip)
      c = static_cast<uint8_t>(CellClass::kUncertain);
  }
}

MapLimits limits(int w, int h) {
  MapLimits l;
  l.resolution = 0.05;
  l.origin = {-1.0, 2.0};
  l.width = w;
  l.height = h;
  return l;
}

Eigen::Vector2d toCells(const MapLimits& l, const Eigen::Vector2d& m) {
  return (m - l.origin) / l.resolution;
}

TEST(CornerDetectorTest, SubCellAccuracyOverRandomCorners) {
  std::mt19937 rng(20261121);
  std::uniform_real_distribution<double> pos(25.0, 35.0), ang(-M_PI, M_PI);
  double sq_sum = 0.0;
  int found = 0;
  std::vector<int> iterations;
  const int cases = 200;
  for (int i = 0; i < cases; ++i) {
    GridU8 g(limits(60, 60), 0);
    const TrueCorner truth{{pos(rng), pos(rng)}, ang(rng)};
    paintCorner(g, truth, 18.0, 2.0, 16.0);
    addNoise(g, rng, 0.03, 0.05);
    const CornerDetector det(g);
    const Eigen::Vector2d predicted = g.limits.origin + truth.vertex * g.limits.resolution;
    const CornerSearch s = det.findNear(predicted, 0.5);
    ASSERT_EQ(s.status, CornerStatus::kOk) << "case " << i << ": " << toString(s.status);
    const Corner& c = s.corners.front();
    const double err = (toCells(g.limits, c.position) - truth.vertex).norm();
    sq_sum += err * err;
    ++found;
    iterations.push_back(c.iterations);
    EXPECT_LE(c.rms, 1.5);
    // One corner's own angle is rough (the paper's finding); two corners give the heading.
    EXPECT_NEAR(std::remainder(c.heading - truth.heading, 2 * M_PI), 0.0, 6.0 * kDeg)
        << "case " << i;
  }
  std::sort(iterations.begin(), iterations.end());
  const double rms = std::sqrt(sq_sum / found);
  std::printf("corner position error RMS %.3f cells over %d cases; median iterations %d\n", rms,
              found, iterations[iterations.size() / 2]);
  EXPECT_EQ(found, cases);
  EXPECT_LE(rms, 0.25);
  EXPECT_LE(iterations[iterations.size() / 2], 10);
}

TEST(CornerDetectorTest, HeadingFromTwoCornersIsAccurate) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5), ang(-M_PI, M_PI);
  double worst = 0.0, sq = 0.0;
  const int cases = 50;
  for (int i = 0; i < cases; ++i) {
    // Two corners 30 cells (1.5 m at 5 cm) apart, both opening the same way, like the home
    // base of worlds/lab.yaml. Heading error scales with 1 / separation.
    GridU8 g(limits(90, 90), 0);
    const double base = ang(rng);
    const Eigen::Vector2d along(std::cos(base + M_PI / 2), std::sin(base + M_PI / 2));
    const Eigen::Vector2d centre(45 + jitter(rng), 45 + jitter(rng));
    const TrueCorner a{centre - 15 * along, base}, b{centre + 15 * along, base};
    paintCorner(g, a, 12.0, 1.0, 12.0);
    paintCorner(g, b, 12.0, 1.0, 12.0);
    addNoise(g, rng, 0.02, 0.03);
    CornerConfig cfg;
    cfg.arm_cells = 12.0;
    const CornerDetector det(g, cfg);
    const auto m = [&](const TrueCorner& c) {
      return g.limits.origin + c.vertex * g.limits.resolution;
    };
    const CornerSearch sa = det.findNear(m(a), 0.4, a.heading),
                       sb = det.findNear(m(b), 0.4, b.heading);
    ASSERT_EQ(sa.status, CornerStatus::kOk) << i;
    ASSERT_EQ(sb.status, CornerStatus::kOk) << i;
    const Eigen::Vector2d obs = sb.corners.front().position - sa.corners.front().position;
    const double err =
        std::abs(std::remainder(std::atan2(obs.y(), obs.x()) - std::atan2(along.y(), along.x()),
                                2 * M_PI)) /
        kDeg;
    worst = std::max(worst, err);
    sq += err * err;
  }
  std::printf("heading from two corners: RMS %.3f deg, worst %.3f deg over %d cases\n",
              std::sqrt(sq / cases), worst, cases);
  EXPECT_LE(std::sqrt(sq / cases), 0.3);
}

TEST(CornerDetectorTest, StraightWallHasNoCorner) {
  GridU8 g(limits(40, 40), static_cast<uint8_t>(CellClass::kUnknown));
  for (int iy = 0; iy < 40; ++iy)
    for (int ix = 0; ix < 40; ++ix)
      g.at(ix, iy) = static_cast<uint8_t>(iy < 20   ? CellClass::kFree
                                          : iy < 22 ? CellClass::kOccupied
                                                    : CellClass::kUnknown);
  const CornerDetector det(g);
  const CornerSearch s = det.findAll();
  EXPECT_NE(s.status, CornerStatus::kOk);
  EXPECT_TRUE(s.corners.empty());
}

TEST(CornerDetectorTest, EmptyMapReportsWhyNothingWasFound) {
  GridU8 g(limits(30, 30), static_cast<uint8_t>(CellClass::kFree));
  const CornerDetector det(g);
  const CornerSearch all = det.findAll();
  EXPECT_EQ(all.status, CornerStatus::kNoCandidates);
  EXPECT_STREQ(toString(all.status), "no corner candidates");
  // Near a prediction the fits seeded there find no edges to fit.
  const CornerSearch near = det.findNear({-0.5, 2.5}, 0.3);
  EXPECT_NE(near.status, CornerStatus::kOk);
  EXPECT_TRUE(near.corners.empty());
}

TEST(HomeBaseTest, RecoversAKnownDrift) {
  // The home base painted at its true place (registration) and again as a drifted robot
  // sees it: the map frame rotated by 4 degrees and shifted; the fix must undo it.
  const TrueCorner a{{30.3, 20.6}, M_PI}, b{{30.3, 50.6}, M_PI};
  GridU8 start(limits(70, 70), 0);
  paintCorner(start, a, 12.0, 1.0, 14.0);
  paintCorner(start, b, 12.0, 1.0, 14.0);
  const MapLimits& l = start.limits;
  const auto m = [&](const Eigen::Vector2d& cells) { return l.origin + cells * l.resolution; };
  CornerConfig cfg;
  cfg.arm_cells = 12.0;
  const auto reg = registerHomeBase(CornerDetector(start, cfg), m(a.vertex), m(b.vertex), 0.3);
  ASSERT_TRUE(reg.home.has_value()) << toString(reg.status);

  const Pose2 X_OM(0.12, -0.07, 4.0 * kDeg);  // how the drifted odometry frame sees the map
  auto drifted = [&](const TrueCorner& c) {
    const Eigen::Vector2d p = (X_OM * m(c.vertex) - l.origin) / l.resolution;
    return TrueCorner{p, c.heading + X_OM.theta};
  };
  GridU8 back(limits(70, 70), 0);
  paintCorner(back, drifted(a), 12.0, 1.0, 14.0);
  paintCorner(back, drifted(b), 12.0, 1.0, 14.0);
  const Pose2 true_pose(0.5, 3.3, 0.3);
  const Pose2 odometry = X_OM * true_pose;
  const HomeBaseFix fix = localizeAtHomeBase(CornerDetector(back, cfg), *reg.home, odometry, 0.4);
  ASSERT_EQ(fix.status, HomeBaseStatus::kOk);
  // The simulator's acceptance figures: 2 cm and 0.5 degrees.
  EXPECT_NEAR(fix.pose.x, true_pose.x, 0.02);
  EXPECT_NEAR(fix.pose.y, true_pose.y, 0.02);
  EXPECT_NEAR(fix.pose.theta, true_pose.theta, 0.5 * kDeg);
  EXPECT_GT(fix.sigma_xy, 0.0);
}

}  // namespace
}  // namespace coopmap

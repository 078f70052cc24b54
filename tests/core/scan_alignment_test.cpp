// Alignment of radial maps to a reference grid, and what an alignment pins down: a
// straight corridor's walls fix the offset across the corridor and the heading, not the
// offset along it; a corner fixes both.
#include "core/localization/scan_alignment.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "tests/core/segment_world.h"

namespace coopmap {
namespace {

using test::castRay;
using test::Segment;

// The walls as a reference grid (three inserts of dense exact rays, hits within max_range m,
// from each of a few poses).
OccupancyGrid referenceOf(const std::vector<Segment>& walls, const std::vector<Pose2>& from,
                          double max_range = 8.0) {
  OccupancyGrid grid(MapLimits::covering({-6, -4}, {6, 4}, 0.05), OccupancyConfig{});
  for (const Pose2& p : from) {
    RadialMap scan;
    scan.odometry = p;
    for (int i = 0; i < 720; ++i) {
      RadialReading r;
      r.bearing = -M_PI + i * M_PI / 360.0;
      const double a = p.theta + r.bearing;
      r.range = castRay(walls, p.translation(), {std::cos(a), std::sin(a)}, max_range);
      if (r.range < 0.0) continue;
      r.kind = RadialKind::kHit;
      r.sigma = 0.005;
      scan.readings.push_back(r);
    }
    for (int k = 0; k < 3; ++k) grid.insert(scan, p);
  }
  return grid;
}

// A stereo-like view from `pose`: 160 columns over 90 degrees, hits within 3.5 m, ranges
// with 2 cm of noise (seeded).
RadialMap viewOf(const std::vector<Segment>& walls, const Pose2& pose, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.02);
  RadialMap scan;
  scan.odometry = pose;
  for (int i = 0; i < 160; ++i) {
    RadialReading r;
    r.bearing = M_PI / 4 - i * (M_PI / 2) / 159.0;
    const double a = pose.theta + r.bearing;
    r.range = castRay(walls, pose.translation(), {std::cos(a), std::sin(a)}, 3.5);
    if (r.range < 0.0) continue;
    r.range += noise(rng);
    r.kind = RadialKind::kHit;
    r.sigma = 0.02;
    scan.readings.push_back(r);
  }
  return scan;
}

// Eigenvalues (ascending) and the weak direction of the position information at `at`.
struct Pinned {
  double weak, strong;
  Eigen::Vector2d weak_dir;
};
Pinned pinned(const AlignmentResult& a, const Eigen::Vector2d& at) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(positionInformation(a, at));
  return {eig.eigenvalues()(0), eig.eigenvalues()(1), eig.eigenvectors().col(0)};
}

TEST(ScanAlignmentTest, ACorridorPinsTheOffsetAcrossItNotAlongIt) {
  // Walls on cell centres (the grid's cells are 5 cm): one cell thick in the reference.
  const std::vector<Segment> corridor = {{{-6, -0.975}, {6, -0.975}}, {{-6, 1.025}, {6, 1.025}}};
  std::vector<Pose2> along;
  for (double x = -5.5; x <= 5.5; x += 0.5) along.emplace_back(x, 0.0, 0.0);
  const OccupancyGrid ref = referenceOf(corridor, along);
  const std::vector<RadialMap> views = {viewOf(corridor, {0, 0, 0.3}, 1),
                                        viewOf(corridor, {0.5, 0, -0.3}, 2)};
  const std::vector<const RadialMap*> scans = {&views[0], &views[1]};
  // Off across the corridor and in heading: both come back.
  const AlignmentResult a = alignScans(scans, ref, Pose2(0.0, 0.08, 0.02));
  ASSERT_TRUE(a.ok) << a.message;
  EXPECT_NEAR(a.correction.y, 0.0, 0.02);
  EXPECT_NEAR(a.correction.theta, 0.0, 0.01);
  const Pinned p = pinned(a, {0.25, 0.0});
  EXPECT_LT(p.weak, 0.05 * p.strong) << p.weak << " vs " << p.strong;
  EXPECT_GT(std::abs(p.weak_dir.x()), 0.98) << p.weak_dir.transpose();  // along the walls
}

TEST(ScanAlignmentTest, ACornerPinsBothOffsets) {
  const std::vector<Segment> corner = {{{-6, -0.975}, {2.025, -0.975}},
                                       {{-6, 1.025}, {2.025, 1.025}},
                                       {{2.025, -0.975}, {2.025, 1.025}}};
  const OccupancyGrid ref = referenceOf(corner, {{-3, 0, 0}, {0, 0, 0}, {1.5, 0, 0}});
  const std::vector<RadialMap> views = {viewOf(corner, {0, 0, 0.3}, 3),
                                        viewOf(corner, {0.5, 0, -0.3}, 4)};
  const std::vector<const RadialMap*> scans = {&views[0], &views[1]};
  const AlignmentResult a = alignScans(scans, ref, Pose2(0.06, 0.05, 0.02));
  ASSERT_TRUE(a.ok) << a.message;
  EXPECT_NEAR(a.correction.x, 0.0, 0.02);
  EXPECT_NEAR(a.correction.y, 0.0, 0.02);
  const Pinned p = pinned(a, {0.25, 0.0});
  EXPECT_GT(p.weak, 0.05 * p.strong) << p.weak << " vs " << p.strong;
}

// The seen-points tests' corridor (a door in its north wall at x = -0.8..0), a reference of
// it from x = -5.5 to -1 with hits within 2.5 m (so mapped up to x = 1.4), and two views from
// x = -1.5 and -1 that see 3.5 m ahead.
std::vector<Pose2> doorCorridorReferencePoses() {
  std::vector<Pose2> along;
  for (double x = -5.5; x <= -0.9; x += 0.5) along.emplace_back(x, 0.0, 0.0);
  return along;
}
struct DoorCorridor {
  std::vector<Segment> walls = {
      {{-6, -0.975}, {6, -0.975}}, {{-6, 1.025}, {-0.8, 1.025}}, {{0, 1.025}, {6, 1.025}}};
  OccupancyGrid ref = referenceOf(walls, doorCorridorReferencePoses(), 2.5);
  std::vector<RadialMap> views = {viewOf(walls, {-1.5, 0, 0.3}, 5),
                                  viewOf(walls, {-1.0, 0, -0.3}, 6)};
  std::vector<const RadialMap*> scans() const { return {&views[0], &views[1]}; }
};

TEST(ScanAlignmentTest, WithSeenPointsOnlyWallsGoingOnPastTheMappedPartAreNotPulledBack) {
  // The reference saw the corridor (a door in its north wall at x = -0.8..0) only up to
  // x = 1.4 (poses up to x = -1, hits within 2.5 m); the views see it from x = -1.5 on,
  // 3.5 m ahead. The door's jambs pin the offset along the corridor; the walls past the
  // mapped part say nothing about it. An aligner that counted those points against the
  // last mapped wall cells pulled every stretch going on into new ground back (a sortie
  // into new ground was shrunk toward home, about 1 % in the building).
  const DoorCorridor c;
  const OccupancyGrid& ref = c.ref;
  const std::vector<const RadialMap*> scans = c.scans();
  AlignmentConfig config;
  config.seen_points_only = true;
  const AlignmentResult a = alignScans(scans, ref, Pose2(), config);
  ASSERT_TRUE(a.ok) << a.message;
  EXPECT_NEAR(a.correction.x, 0.0, 0.01);
  EXPECT_NEAR(a.correction.y, 0.0, 0.01);
  // Counting every point within robust_scale of the map's obstacles, it is pulled back.
  const AlignmentResult near = alignScans(scans, ref, Pose2());
  ASSERT_TRUE(near.ok) << near.message;
  EXPECT_LT(near.correction.x, -0.05);
}

TEST(ScanAlignmentTest, WithSeenPointsOnlyWallsSeenOnlyWeaklyFartherOnDoNotPullTheStretchBack) {
  // The reference mapped the corridor (the door in its north wall pins the offset along it)
  // for sure only up to x = 1.4; one far look from x = -1 saw the walls on to x = 4 with
  // the spread of far stereo: evidence too weak to make them occupied, but the cells are
  // seen. Judged against the distance to the sure cells, the views' points on that far
  // stretch of wall pulled them back toward x = 1.4 (in the building the later of two radial
  // maps 1-1.5 m apart came out 4-8 % too near the earlier).
  DoorCorridor c;
  OccupancyGrid& ref = c.ref;
  RadialMap far;
  far.odometry = Pose2(-1.0, 0.0, 0.0);
  for (int i = 0; i < 720; ++i) {
    RadialReading r;
    r.bearing = -M_PI / 2 + i * M_PI / 719.0;
    r.range = castRay(c.walls, far.odometry.translation(),
                      {std::cos(r.bearing), std::sin(r.bearing)}, 5.0);
    if (r.range < 2.5) continue;
    r.kind = RadialKind::kHit;
    r.sigma = 0.15;  // 0.15 m: a third of the occupied evidence of a sharp return per cell
    far.readings.push_back(r);
  }
  ref.insert(far, far.odometry);
  ASSERT_EQ(ref.state(ref.limits().cellX(3.0), ref.limits().cellY(1.025)), CellState::kUnknown);
  ASSERT_GT(ref.logOdds(ref.limits().cellX(3.0), ref.limits().cellY(1.025)), 0);
  ASSERT_TRUE(ref.seen(ref.limits().cellX(3.0), ref.limits().cellY(1.0)));
  const std::vector<const RadialMap*> scans = c.scans();
  AlignmentConfig config;
  config.seen_points_only = true;
  const AlignmentResult seen = alignScans(scans, ref, Pose2(), config);
  ASSERT_TRUE(seen.ok) << seen.message;
  EXPECT_LT(seen.correction.x, -0.05);  // 0.106 m back
  config.decided_points_only = true;
  const AlignmentResult a = alignScans(scans, ref, Pose2(), config);
  ASSERT_TRUE(a.ok) << a.message;
  EXPECT_NEAR(a.correction.x, 0.0, 0.03);  // 0.025 m: within the cell the jambs leave loose
  EXPECT_NEAR(a.correction.y, 0.0, 0.01);
}

}  // namespace
}  // namespace coopmap

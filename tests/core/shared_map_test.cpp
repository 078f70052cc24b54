#include "core/sharing/shared_map.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/io/atomic_file.h"

namespace coopmap {
namespace {

const MapLimits kLimits = MapLimits::covering({0.0, 0.0}, {6.0, 4.0}, 0.05);

// A scan seeing a wall 2 m ahead across a 60 degree fan.
RadialMap wallScan() {
  RadialMap m;
  m.max_range = 4.0;
  for (int k = 0; k < 31; ++k) {
    RadialReading r;
    r.bearing = (15 - k) * M_PI / 90.0;
    r.range = 2.0 / std::cos(r.bearing);
    r.sigma = 0.02;
    r.kind = RadialKind::kHit;
    m.readings.push_back(r);
  }
  return m;
}

MapPost postOf(const std::string& robot, uint64_t id, int scans, const Pose2& pose) {
  MapPost p;
  p.robot = robot;
  p.post_id = id;
  for (int i = 0; i < scans; ++i) p.scans.push_back({wallScan(), pose});
  return p;
}

int occupiedCells(const OccupancyGrid& g) {
  int n = 0;
  for (int iy = 0; iy < g.limits().height; ++iy)
    for (int ix = 0; ix < g.limits().width; ++ix) n += g.state(ix, iy) == CellState::kOccupied;
  return n;
}

std::string freshFolder(const std::string& name) {
  const std::string dir = testing::TempDir() + "/shared_map_test_" + name;
  std::filesystem::remove_all(dir);
  return dir;
}

TEST(SharedMapTest, PostsAreAppliedAndVersioned) {
  LocalSharedMap map(kLimits, {});
  EXPECT_EQ(map.version(), 0u);
  const PostResult r = map.post(postOf("jose", 1, 3, Pose2(1.0, 2.0, 0.0)));
  EXPECT_EQ(r.status, PostStatus::kAccepted);
  EXPECT_EQ(r.version, 1u);
  // The wall at x = 3 m is in the shared map, and the space before it is free.
  const OccupancyGrid g = map.grid();
  auto state = [&](double x, double y) { return g.state(kLimits.cellX(x), kLimits.cellY(y)); };
  EXPECT_TRUE(state(2.975, 2.0) == CellState::kOccupied ||
              state(3.025, 2.0) == CellState::kOccupied);
  EXPECT_EQ(state(2.0, 2.0), CellState::kFree);
  EXPECT_EQ(map.snapshot().version, 1u);
  EXPECT_EQ(map.post(postOf("eric", 1, 1, Pose2(1.0, 2.0, 0.0))).version, 2u);
}

TEST(SharedMapTest, AFaultyPostChangesNothing) {
  LocalSharedMap map(kLimits, {});
  map.post(postOf("jose", 1, 2, Pose2(1.0, 2.0, 0.0)));
  const SharedMapSnapshot before = map.snapshot();
  MapPost bad = postOf("jose", 2, 3, Pose2(1.0, 1.0, 0.5));
  bad.scans[2].pose.theta = std::numeric_limits<double>::quiet_NaN();
  const PostResult r = map.post(bad);
  EXPECT_EQ(r.status, PostStatus::kRejected);
  EXPECT_EQ(r.reason, "scan 2: pose is not finite");
  MapPost outside = postOf("jose", 2, 1, Pose2(9.0, 1.0, 0.0));
  EXPECT_EQ(map.post(outside).reason,
            "scan 0: pose (9.000000, 1.000000) is outside the shared map");
  const SharedMapSnapshot after = map.snapshot();
  EXPECT_EQ(after.version, before.version);
  EXPECT_EQ(after.log_odds, before.log_odds);
  EXPECT_EQ(after.seen, before.seen);
}

TEST(SharedMapTest, RetriedPostsAreNotAppliedTwice) {
  LocalSharedMap map(kLimits, {});
  ASSERT_EQ(map.post(postOf("jose", 5, 1, Pose2(1.0, 2.0, 0.0))).status, PostStatus::kAccepted);
  const SharedMapSnapshot once = map.snapshot();
  const PostResult again = map.post(postOf("jose", 5, 1, Pose2(1.0, 2.0, 0.0)));
  EXPECT_EQ(again.status, PostStatus::kDuplicate);
  EXPECT_EQ(map.snapshot().log_odds, once.log_odds);
  EXPECT_EQ(map.post(postOf("jose", 6, 1, Pose2(1.0, 2.0, 0.0))).status, PostStatus::kAccepted);
}

TEST(SharedMapTest, AcknowledgedPostsSurviveARestart) {
  const std::string dir = freshFolder("restart");
  SharedMapSnapshot acknowledged;
  {
    LocalSharedMap map(kLimits, {}, dir);
    map.post(postOf("jose", 1, 2, Pose2(1.0, 2.0, 0.0)));
    map.post(postOf("eric", 1, 1, Pose2(1.0, 1.5, 0.3)));
    acknowledged = map.snapshot();
  }
  LocalSharedMap restarted(kLimits, {}, dir);
  const SharedMapSnapshot s = restarted.snapshot();
  EXPECT_EQ(s.version, 2u);
  EXPECT_EQ(s.log_odds, acknowledged.log_odds);
  EXPECT_EQ(s.seen, acknowledged.seen);
  EXPECT_GT(occupiedCells(restarted.grid()), 10);
  // Retries across the restart are still recognised.
  EXPECT_EQ(restarted.post(postOf("eric", 1, 1, Pose2(1.0, 1.5, 0.3))).status,
            PostStatus::kDuplicate);
}

TEST(SharedMapTest, CorruptOrForeignSnapshotsAreReported) {
  const std::string dir = freshFolder("corrupt");
  {
    LocalSharedMap map(kLimits, {}, dir);
    map.post(postOf("jose", 1, 1, Pose2(1.0, 2.0, 0.0)));
  }
  const std::string file = dir + "/shared_map.bin";
  std::string bytes = readFile(file);
  bytes[bytes.size() / 2] ^= 0x10;
  writeFileAtomic(file, bytes);
  try {
    LocalSharedMap map(kLimits, {}, dir);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              file + ": checksum mismatch (the file is corrupt or truncated)");
  }
  writeFileAtomic(file, LocalSharedMap::encodeSnapshot(OccupancyGrid(kLimits, {}), 3, {}));
  const MapLimits other = MapLimits::covering({0.0, 0.0}, {6.0, 4.0}, 0.1);
  try {
    LocalSharedMap map(other, {}, dir);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              file + ": made for other map limits (120 x 80 cells of 0.050000 m)");
  }
}

TEST(SharedMapTest, CorrectedAndNaivePosts) {
  TraverseLog log;
  log.robot = "jose";
  for (int i = 0; i < 3; ++i) {
    TraverseEntry e;
    e.scan = wallScan();
    e.scan.odometry = Pose2(1.0 + 0.1 * i, 2.0, 0.0);
    log.entries.push_back(e);
  }
  const MapPost naive = naivePost(log, 1, PostThinning{0.0, 0.0});
  ASSERT_EQ(naive.scans.size(), 3u);
  EXPECT_EQ(naive.scans[2].pose.x, log.entries[2].scan.odometry.x);
  const std::vector<Pose2> corrected(3, Pose2(1.5, 2.5, 0.1));
  const MapPost fixed = correctedPost(log, corrected, 2, PostThinning{0.0, 0.0});
  EXPECT_EQ(fixed.robot, "jose");
  EXPECT_EQ(fixed.scans[1].pose.y, 2.5);
  EXPECT_THROW(correctedPost(log, {Pose2()}, 3), std::invalid_argument);
}

TEST(SharedMapTest, PostsAreThinnedToOneScanPerViewpoint) {
  // A robot that stands still, then drives in 6 cm steps, then turns on the spot.
  TraverseLog log;
  log.robot = "eric";
  auto add = [&](double x, double theta) {
    TraverseEntry e;
    e.scan = wallScan();
    e.scan.odometry = Pose2(x, 2.0, theta);
    log.entries.push_back(e);
  };
  for (int i = 0; i < 10; ++i) add(1.0, 0.0);             // still: one view
  for (int i = 1; i <= 6; ++i) add(1.0 + 0.06 * i, 0.0);  // 0.36 m: every other scan
  for (int i = 1; i <= 4; ++i) add(1.36, 0.07 * i);       // 0.28 rad: every other scan
  const MapPost thinned = naivePost(log, 1);
  ASSERT_EQ(thinned.scans.size(), 1u + 3u + 2u);
  EXPECT_NEAR(thinned.scans[1].pose.x, 1.12, 1e-9);
  EXPECT_NEAR(thinned.scans[5].pose.theta, 0.28, 1e-9);
  const std::vector<Pose2> corrected(log.entries.size(), Pose2(1.5, 2.5, 0.1));
  EXPECT_EQ(correctedPost(log, corrected, 2).scans.size(), 1u);  // all at one corrected pose
  EXPECT_EQ(naivePost(log, 3, PostThinning{0.0, 0.0}).scans.size(), log.entries.size());
  EXPECT_THROW(naivePost(log, 4, PostThinning{-1.0, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap

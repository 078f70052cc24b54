#include "core/sharing/shared_map.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <random>
#include <thread>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/binary_io.h"

namespace coopmap {
namespace {

const MapLimits kLimits = MapLimits::covering({0.0, 0.0}, {6.0, 4.0}, 0.05);

// A scan seeing a wall 2 m ahead across a 60 degree fan, each return of range sigma `sigma`.
RadialMap wallScan(double sigma = 0.02) {
  RadialMap m;
  m.max_range = 4.0;
  for (int k = 0; k < 31; ++k) {
    RadialReading r;
    r.bearing = (15 - k) * M_PI / 90.0;
    r.range = 2.0 / std::cos(r.bearing);
    r.sigma = sigma;
    r.kind = RadialKind::kHit;
    m.readings.push_back(r);
  }
  return m;
}

MapPost postOf(const std::string& robot, uint64_t id, int scans, const Pose2& pose,
               double sigma = 0.02) {
  MapPost p;
  p.robot = robot;
  p.post_id = id;
  for (int i = 0; i < scans; ++i) p.scans.push_back({wallScan(sigma), pose});
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
  writeFileAtomic(file, LocalSharedMap::encodeSnapshot(OccupancyGrid(kLimits, {}),
                                                       OccupancyGrid(kLimits, {}), 3, {}));
  const MapLimits other = MapLimits::covering({0.0, 0.0}, {6.0, 4.0}, 0.1);
  try {
    LocalSharedMap map(other, {}, dir);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              file + ": made for other map limits (120 x 80 cells of 0.050000 m)");
  }
}

// Occupied cells of `g` in the rows of the posts' fan (y 2.0 +- 0.5 m) whose centre is more
// than a cell from the true wall at x = 3 m (posts from (1, 2) facing +x).
int offWallCells(const OccupancyGrid& g) {
  int n = 0;
  const MapLimits& l = g.limits();
  for (int iy = l.cellY(1.5); iy <= l.cellY(2.5); ++iy)
    for (int ix = 0; ix < l.width; ++ix)
      n += g.state(ix, iy) == CellState::kOccupied &&
           std::abs(l.origin.x() + (ix + 0.5) * l.resolution - 3.0) > l.resolution;
  return n;
}

TEST(SharedMapTest, ThePublishedGridDrawsTheSamePostsOverItsOwnBand) {
  OccupancyConfig narrow;
  narrow.sigma_scale = 0.5;
  LocalSharedMap map(kLimits, {}, "", narrow);
  EXPECT_EQ(map.publishedConfig().sigma_scale, 0.5);
  EXPECT_EQ(map.config().sigma_scale, 1.0);
  // Returns of 10 cm sigma at 2 m, all on the wall: the shared grid draws them +-10 cm, the
  // published one +-5 cm.
  ASSERT_EQ(map.post(postOf("jose", 1, 10, Pose2(1.0, 2.0, 0.0), 0.1)).status,
            PostStatus::kAccepted);
  const OccupancyGrid shared = map.grid(), published = map.publishedGrid();
  for (const OccupancyGrid* g : {&shared, &published})
    EXPECT_TRUE(g->state(kLimits.cellX(2.975), kLimits.cellY(2.0)) == CellState::kOccupied ||
                g->state(kLimits.cellX(3.025), kLimits.cellY(2.0)) == CellState::kOccupied);
  const int shared_off = offWallCells(shared), published_off = offWallCells(published);
  EXPECT_GT(shared_off, 10);
  EXPECT_LT(published_off, shared_off / 2) << "shared " << shared_off;
  // What the robots import is the shared grid.
  EXPECT_EQ(map.snapshot().log_odds, shared.logOddsGrid().cells);
  // Without a published rule of its own, the published grid is the shared one.
  LocalSharedMap one(kLimits, {});
  one.post(postOf("jose", 1, 10, Pose2(1.0, 2.0, 0.0), 0.1));
  EXPECT_EQ(one.publishedGrid().logOddsGrid().cells, one.grid().logOddsGrid().cells);
  EXPECT_EQ(one.grid().logOddsGrid().cells, shared.logOddsGrid().cells);
}

TEST(SharedMapTest, BothGridsSurviveARestartAndVersionOneSnapshotsAreRead) {
  const std::string dir = freshFolder("published");
  OccupancyConfig narrow;
  narrow.sigma_scale = 0.5;
  OccupancyGrid shared(kLimits, {}), published(kLimits, narrow);
  {
    LocalSharedMap map(kLimits, {}, dir, narrow);
    map.post(postOf("jose", 1, 10, Pose2(1.0, 2.0, 0.0), 0.1));
    shared = map.grid();
    published = map.publishedGrid();
  }
  ASSERT_NE(shared.logOddsGrid().cells, published.logOddsGrid().cells);
  LocalSharedMap restarted(kLimits, {}, dir, narrow);
  EXPECT_EQ(restarted.version(), 1u);
  EXPECT_EQ(restarted.grid().logOddsGrid().cells, shared.logOddsGrid().cells);
  EXPECT_EQ(restarted.publishedGrid().logOddsGrid().cells, published.logOddsGrid().cells);
  EXPECT_EQ(restarted.publishedGrid().seenGrid().cells, published.seenGrid().cells);
  // A version 1 file (one grid): the same bytes without the published layers, its
  // published grid a copy of the shared one.
  const std::string file = dir + "/shared_map.bin";
  std::string bytes = readFile(file);
  const size_t layers = kLimits.size() * 3;
  bytes.resize(bytes.size() - 4 - layers);
  const uint32_t v1 = 1;
  std::memcpy(bytes.data() + 8, &v1, 4);
  ByteWriter crc;
  crc.put<uint32_t>(crc32Of(bytes.data(), bytes.size()));
  writeFileAtomic(file, bytes + crc.out);
  LocalSharedMap old(kLimits, {}, dir, narrow);
  EXPECT_EQ(old.version(), 1u);
  EXPECT_EQ(old.grid().logOddsGrid().cells, shared.logOddsGrid().cells);
  EXPECT_EQ(old.publishedGrid().logOddsGrid().cells, shared.logOddsGrid().cells);
  // A file of another format version is refused, naming it.
  const uint32_t v7 = 7;
  std::memcpy(bytes.data() + 8, &v7, 4);
  ByteWriter crc7;
  crc7.put<uint32_t>(crc32Of(bytes.data(), bytes.size()));
  writeFileAtomic(file, bytes + crc7.out);
  try {
    LocalSharedMap map(kLimits, {}, dir);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              file + ": shared map format version 7 (this build reads 1 and 2)");
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

// A post of its own for each id: `id` scans somewhere on the map, so that a snapshot tells
// which posts it holds.
MapPost numberedPost(uint64_t id) {
  return postOf("jose", id, 1 + static_cast<int>(id % 3),
                Pose2(0.5 + 0.1 * static_cast<double>(id % 20), 1.0 + 0.05 * (id % 7), 0.1 * id));
}

// The service in a child process posts as fast as it can and tells the parent each post it
// acknowledged; once the first is acknowledged (a slow start, as under a sanitizer, must not
// leave a round without posts) the parent kills it with SIGKILL at a random moment (most fall
// inside a post, which is almost all of the child's time), 20 times. On restart the folder holds
// every acknowledged post, in order, and nothing else: at most the one in flight, whole, when the
// kill came after it was durable but before it was acknowledged; no temporary files stay.
TEST(SharedMapTest, EveryAcknowledgedPostSurvivesAKillMidPost) {
  const std::string dir = freshFolder("kill");
  std::mt19937_64 rng(20261206);
  uint64_t posts = 0;
  for (int round = 0; round < 20; ++round) {
    int ack[2];
    ASSERT_EQ(::pipe(ack), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(ack[0]);
      LocalSharedMap map(kLimits, {}, dir);
      for (uint64_t id = map.lastPost("jose") + 1;; ++id) {
        if (map.post(numberedPost(id)).status != PostStatus::kAccepted) ::_exit(3);
        if (::write(ack[1], &id, sizeof id) != sizeof id) ::_exit(4);
      }
    }
    ::close(ack[1]);
    uint64_t acknowledged = posts, id = 0;
    const bool first_acknowledged = ::read(ack[0], &id, sizeof id) == sizeof id;
    if (first_acknowledged) {
      acknowledged = id;
      std::this_thread::sleep_for(
          std::chrono::microseconds(std::uniform_int_distribution<int>(2000, 40000)(rng)));
    }
    ASSERT_EQ(::kill(child, SIGKILL), 0);  // an unreaped child that ended is killed too
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(first_acknowledged)
        << "round " << round << ": the child never posted, status " << status;
    ASSERT_TRUE(WIFSIGNALED(status)) << "the posting child ended by itself: status " << status;
    while (::read(ack[0], &id, sizeof id) == sizeof id) acknowledged = id;
    ::close(ack[0]);

    const LocalSharedMap restored(kLimits, {}, dir);
    const uint64_t kept = restored.lastPost("jose");
    EXPECT_GE(kept, acknowledged) << "round " << round << ": an acknowledged post was lost";
    EXPECT_LE(kept, acknowledged + 1) << "round " << round << ": posts nobody made";
    EXPECT_EQ(restored.version(), kept) << "round " << round;
    // The grid is the posts 1..kept applied in order, bit for bit.
    LocalSharedMap expected(kLimits, {});
    for (uint64_t k = 1; k <= kept; ++k) expected.post(numberedPost(k));
    const SharedMapSnapshot a = restored.snapshot(), b = expected.snapshot();
    EXPECT_TRUE(a.log_odds == b.log_odds && a.seen == b.seen) << "round " << round;
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      files.push_back(e.path().filename().string());
    EXPECT_EQ(files, std::vector<std::string>{"shared_map.bin"}) << "round " << round;
    posts = kept;
  }
  EXPECT_GT(posts, 20u) << "the child posted too little for the kills to fall inside posts";
}

}  // namespace
}  // namespace coopmap

// `coopmap stereo-scale`: the odometry's distance scale measured by stereo over runs' logs.
#include "sim/runner/stereo_scale_logs.h"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/tum.h"
#include "tests/core/pilaster_corridor.h"

namespace coopmap {
namespace {

namespace fs = std::filesystem;

// A run folder as `coopmap run` writes it for robot "r" driving the pilaster corridor on
// odometry that over-counts 2 %: the traverse log at the live estimate's poses (here the
// truth, as if the live corrections were perfect: a measurement on them finds no scale), the
// raw odometry and the ground truth.
std::string writeRun(const std::string& name, uint32_t seed) {
  const fs::path dir = fs::path(testing::TempDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  TraverseLog log = test::driveAlong(test::corridorWithPilasters(), 0.02, seed);
  std::vector<StampedPose2> odometry, truth;
  for (size_t i = 0; i < log.entries.size(); ++i) {
    TraverseEntry& e = log.entries[i];
    odometry.push_back({e.scan.stamp, e.scan.odometry});
    truth.push_back({e.scan.stamp, test::alongTheMiddle(static_cast<int>(i))});
    e.scan.odometry = truth.back().pose;
  }
  saveTraverseLog((dir / "traverse_r.traverse").string(), log);
  writeTum((dir / "trajectory_r_odometry.tum").string(), odometry, "odometry");
  writeTum((dir / "trajectory_r_groundtruth.tum").string(), truth, "ground truth");
  return dir.string();
}

TEST(StereoScaleCommandTest, MeasuresEachLogAtItsRawOdometryAndPoolsThem) {
  StereoScaleOptions o;
  o.run_dirs = {writeRun("coopmap_scale_a", 21), writeRun("coopmap_scale_b", 22)};
  const StereoScaleSummary s = runStereoScale(o);
  ASSERT_EQ(s.logs.size(), 2u);
  int pairs = 0;
  for (const StereoScaleLog& l : s.logs) {
    EXPECT_EQ(l.robot, "r");
    EXPECT_GT(l.pairs, 20);
    EXPECT_NEAR(l.scale, 0.02, 0.002);
    EXPECT_NEAR(l.truth, 0.02, 0.001);  // from the ground truth's path
    pairs += l.pairs;
  }
  EXPECT_EQ(s.pairs, pairs);
  EXPECT_EQ(s.logs_with_pairs, 2);
  EXPECT_NEAR(s.pooled, 0.02, 0.0015);
  EXPECT_NEAR(s.mean, 0.5 * (s.logs[0].scale + s.logs[1].scale), 1e-12);
  EXPECT_GT(s.standard_error, 0.0);
  EXPECT_LT(s.standard_error, 0.002);
}

TEST(StereoScaleCommandTest, AFolderWithoutLogsOrOdometryIsNamed) {
  StereoScaleOptions o;
  const std::string run = writeRun("coopmap_scale_missing", 23);
  o.run_dirs = {run};
  o.robot = "eric";
  try {
    runStereoScale(o);
    FAIL() << "a folder without eric's log was measured";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(run + ": no traverse_eric.traverse"), std::string::npos)
        << e.what();
  }
  o.robot = "";
  fs::remove(fs::path(run) / "trajectory_r_odometry.tum");
  try {
    runStereoScale(o);
    FAIL() << "a log without its raw odometry was measured";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("trajectory_r_odometry.tum"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace coopmap

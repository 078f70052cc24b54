// Scenario: the lab world end to end (rendered trinocular frames -> stereo -> radial
// maps -> occupancy grid), scored against the world's true occupancy.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "sim/runner/world_run.h"
#include "sim/runner/world_run_outputs.h"

namespace coopmap {
namespace {

const std::string kLab = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(LabScenarioTest, OneRobotPerfectOdometryMapsTheLab) {
  const std::string out =
      (std::filesystem::temp_directory_path() / "coopmap_lab_scenario").string();
  std::filesystem::remove_all(out);
  RunOptions o;
  o.world_file = kLab;
  o.seed = 1;
  o.robots = 1;
  o.odometry = "perfect";
  const RunResult r = runWorld(o);
  writeRunOutputs(out, r);
  ASSERT_EQ(r.robots.size(), 1u);
  const RobotRunResult& jose = r.robots[0];
  EXPECT_EQ(jose.name, "jose");
  EXPECT_TRUE(jose.route_complete);
  EXPECT_EQ(jose.collisions, 0);
  EXPECT_GT(jose.path_length_m, 15.0);
  EXPECT_GE(jose.map.wall_recall, 0.90);
  EXPECT_LE(jose.map.false_occupied_rate, 0.02);
  EXPECT_GE(jose.map.coverage, 0.70);
  EXPECT_GT(jose.map.wall_cells, 300);  // the score rests on many wall cells, not a few
  std::printf(
      "lab, perfect odometry, seed 1: wall_recall %.3f false_occupied_rate %.4f "
      "coverage %.3f path %.1f m\n",
      jose.map.wall_recall, jose.map.false_occupied_rate, jose.map.coverage, jose.path_length_m);

  for (const char* f : {"map_jose.pgm", "map_jose.yaml", "map_jose.png", "metrics.json",
                        "trajectory_jose_groundtruth.tum", "trajectory_jose_odometry.tum"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  const std::string metrics = slurp(out + "/metrics.json");
  for (const char* key : {"\"robots\"", "\"jose\"", "\"path_length_m\"", "\"collisions\"",
                          "\"map\"", "\"wall_recall\"", "\"false_occupied_rate\"", "\"coverage\"",
                          "\"sim_time_s\"", "\"wall_time_s\"", "\"real_time_factor\""})
    EXPECT_NE(metrics.find(key), std::string::npos) << key;
  const std::string yaml = slurp(out + "/map_jose.yaml");
  EXPECT_NE(yaml.find("image: map_jose.pgm"), std::string::npos);
  EXPECT_NE(yaml.find("resolution: 0.050000"), std::string::npos);
  EXPECT_EQ(slurp(out + "/map_jose.pgm").rfind("P5\n", 0), 0u);
  // The odometry starts at the origin, as encoders do; the map frame is the home base's.
  EXPECT_EQ(jose.odometry.front().pose.x, 0.0);
  EXPECT_EQ(jose.odometry.front().pose.y, 0.0);
  EXPECT_EQ(jose.odometry.front().pose.theta, 0.0);
  std::istringstream tum(slurp(out + "/trajectory_jose_odometry.tum"));
  std::string line;
  while (std::getline(tum, line) && line.rfind("#", 0) == 0) {
  }
  double stamp = -1, x = -1, y = -1, z = -1;
  std::istringstream(line) >> stamp >> x >> y >> z;
  EXPECT_EQ(x, 0.0) << line;
  EXPECT_EQ(y, 0.0) << line;
  EXPECT_TRUE(jose.placed) << "its first look at the home base placed it in the map frame";
  // No temp files left behind.
  for (const auto& e : std::filesystem::directory_iterator(out))
    EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
}

TEST(LabScenarioTest, SameSeedSameRunDifferentSeedDifferentDrift) {
  auto run = [](uint64_t seed) {
    RunOptions o;
    o.world_file = kLab;
    o.seed = seed;
    o.robots = 1;
    o.duration = 60.0;
    o.odometry = "drifting";
    return runWorld(o);
  };
  const RunResult a = run(5), b = run(5), c = run(6);
  const auto &ta = a.robots[0], &tb = b.robots[0], &tc = c.robots[0];
  ASSERT_EQ(ta.odometry.size(), tb.odometry.size());
  for (size_t i = 0; i < ta.odometry.size(); ++i) {
    ASSERT_EQ(ta.odometry[i].pose.x, tb.odometry[i].pose.x) << i;
    ASSERT_EQ(ta.groundtruth[i].pose.y, tb.groundtruth[i].pose.y) << i;
  }
  EXPECT_EQ(ta.map.wall_recall, tb.map.wall_recall);
  EXPECT_EQ(ta.map.false_occupied_rate, tb.map.false_occupied_rate);
  // Another seed draws other odometry noise.
  EXPECT_NE(ta.odometry.back().pose.x, tc.odometry.back().pose.x);
  // Drifting odometry really drifts from the truth.
  EXPECT_GT(ta.odometry_error_m + ta.odometry_error_deg, 0.0);
}

}  // namespace
}  // namespace coopmap

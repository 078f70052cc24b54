// Two robots against one (`coopmap bench speedup`): two benchmark outputs read world by
// world, who reached 90 % coverage first, the median speed-up, and the inputs it refuses.
#include "sim/runner/team_speedup.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/yaml_reader.h"

namespace coopmap {
namespace {

namespace fs = std::filesystem;

std::string freshDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("coopmap_speedup_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "runs");
  return dir.string();
}

// runs/<seed>/metrics.json of a run of `robots` robots in world `world` that reached 90 %
// coverage after `t90` s (-1: never), cut to the keys the comparison reads.
void writeRun(const std::string& dir, int seed, const std::string& world, int robots, double t90) {
  const fs::path run = fs::path(dir) / "runs" / std::to_string(seed);
  fs::create_directories(run);
  std::string robot_entries = R"("jose": {"phase": "done", "map": {"wall_recall": 0.9,
      "false_occupied_rate": 0.01, "coverage": 0.9}})";
  if (robots == 2)
    robot_entries += R"(, "eric": {"phase": "done", "map": {"wall_recall": 0.9,
      "false_occupied_rate": 0.01, "coverage": 0.9}})";
  std::ofstream(run / "metrics.json")
      << "{\"world\": \"" << world << "\", \"cooperative\": " << (robots == 2 ? "true" : "false")
      << ", \"shared_map\": {\"wall_recall\": 0.95, \"false_occupied_rate\": 0.005, "
         "\"coverage\": 0.95}, \"collisions\": 0, \"time_to_50_percent_coverage_s\": 100, "
         "\"time_to_90_percent_coverage_s\": "
      << t90 << ", \"robots\": {" << robot_entries << "}}\n";
}

TEST(TeamSpeedupTest, CountsTheWorldsTwoRobotsCoveredSoonerAndTheMedianSpeedup) {
  const std::string two = freshDir("two"), one = freshDir("one");
  writeRun(two, 1, "a", 2, 500.0);  // both reach it: 2x
  writeRun(one, 1, "a", 1, 1000.0);
  writeRun(two, 2, "b", 2, 900.0);  // one robot sooner: 0.5x
  writeRun(one, 2, "b", 1, 450.0);
  writeRun(two, 3, "c", 2, 1200.0);  // one robot never: two sooner, no ratio
  writeRun(one, 3, "c", 1, -1.0);
  writeRun(two, 4, "d", 2, -1.0);  // neither
  writeRun(one, 4, "d", 1, -1.0);
  writeRun(two, 5, "e", 2, 300.0);  // both: 4x
  writeRun(one, 5, "e", 1, 1200.0);
  writeRun(two, 6, "f", 2, 300.0);  // a one-robot run that failed: no metrics.json
  fs::create_directories(fs::path(one) / "runs" / "6");
  writeRun(one, 7, "g", 1, 300.0);  // in the one-robot output only
  const TeamSpeedup c = compareTeams(two, one);
  ASSERT_EQ(c.worlds.size(), 5u);
  EXPECT_EQ(c.twoSooner(), 3);  // worlds 1, 3 and 5
  ASSERT_TRUE(c.medianSpeedup().has_value());
  EXPECT_DOUBLE_EQ(*c.medianSpeedup(), 2.0);  // of 2, 0.5 and 4
  EXPECT_EQ(c.unmatched, (std::vector<uint64_t>{6, 7}));
  const std::string md = formatTeamSpeedup(c, two, one);
  EXPECT_NE(md.find("sooner in 3 of 5 worlds (60 %)"), std::string::npos) << md;
  EXPECT_NE(md.find("Median speed-up (one robot's time over two robots') 2.00, over the 3 "
                    "worlds"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 3 | c | 1200 | never | - |"), std::string::npos) << md;
  EXPECT_NE(md.find("Not compared (in one output only, or a run that failed): 6 7."),
            std::string::npos)
      << md;
}

TEST(TeamSpeedupTest, RefusesOutputsOfTheWrongTeamOrOfOtherWorlds) {
  const std::string two = freshDir("two_bad"), one = freshDir("one_bad");
  writeRun(two, 1, "a", 2, 500.0);
  writeRun(one, 1, "a", 2, 900.0);  // --one given a two-robot run
  try {
    compareTeams(two, one);
    FAIL() << "a two-robot run was taken for a one-robot run";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("runs/1/metrics.json: expected a run of 1 robot, got 2"),
              std::string::npos)
        << e.what();
  }
  writeRun(one, 1, "other", 1, 900.0);
  try {
    compareTeams(two, one);
    FAIL() << "runs of different worlds were compared";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("world 'other', but"), std::string::npos) << e.what();
  }
  EXPECT_THROW(compareTeams(two, fs::path(one).parent_path().string() + "/nowhere"), ConfigError);
}

}  // namespace
}  // namespace coopmap

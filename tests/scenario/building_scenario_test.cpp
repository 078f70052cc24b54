// Scenario: issue 7's acceptance in the dynamic building (worlds/lab_corridor.yaml: people
// walking its corridors, slippery tiles and dust, a changing lab). Two B-14s with drifting
// odometry explore it autonomously under its mission settings; per run: no contact with
// walls or people, the shared map covers at least 0.90 of the reachable floor, its
// wall_recall is at least 0.95 and its false_occupied_rate at most 0.01, and the home-base
// protocol beats naive sharing on both.
//
// The seeds are the first three (a rule fixed before their results; the runs take the
// issue's 1800 s). Over seeds 1-24 at 1800 s with the agent of core/agent/robot_agent.h
// (`coopmap run worlds/lab_corridor.yaml --robots 2 --duration 1800 --seed S`): both map bars
// in 23, coverage >= 0.90 in 23, one contact in all.
#include <cstdint>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "sim/runner/world_run.h"
#include "tests/scenario/run_summary.h"

namespace coopmap {
namespace {

class BuildingScenarioTest : public testing::TestWithParam<uint64_t> {};

TEST_P(BuildingScenarioTest, TwoRobotsMeetTheIssuesBars) {
  RunOptions o;
  o.world_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab_corridor.yaml";
  o.explore = true;
  o.robots = 2;
  o.seed = GetParam();
  o.duration = 1800.0;
  const RunResult r = runWorld(o);
  ASSERT_TRUE(r.cooperative);
  const SharedMapResult& s = r.shared_map;
  ASSERT_TRUE(s.computed);
  scenario_test::printSharedMap(o.seed, r);
  for (const RobotRunResult& robot : r.robots) {
    EXPECT_EQ(robot.collisions, 0) << robot.name << " touched something";
    EXPECT_GE(robot.sorties_posted, 3) << robot.name;
    for (const std::string& line : robot.log)
      std::printf("  %s %s\n", robot.name.c_str(), line.substr(0, 150).c_str());
  }
  EXPECT_GE(s.protocol.coverage, 0.90);
  EXPECT_GE(s.protocol.wall_recall, 0.95);
  EXPECT_LE(s.protocol.false_occupied_rate, 0.01);
  EXPECT_GT(s.protocol.wall_recall, s.naive.wall_recall);
  EXPECT_LT(s.protocol.false_occupied_rate, s.naive.false_occupied_rate);
}

INSTANTIATE_TEST_SUITE_P(Seeds, BuildingScenarioTest, testing::Values(1u, 2u, 3u),
                         [](const testing::TestParamInfo<uint64_t>& info) {
                           return "seed" + std::to_string(info.param);
                         });

}  // namespace
}  // namespace coopmap

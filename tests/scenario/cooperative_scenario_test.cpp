// Scenario: the paper's whole cooperation, autonomous. Two B-14s with drifting odometry
// explore worlds/lab.yaml in sorties on coopmap's default settings; after each a robot comes
// home, localizes at the home base (driving to its start by a first fix and looking again),
// corrects the sortie (heading-drift model fitted to the fix, headings from the walls),
// posts it, imports the shared map and goes again. The same radial maps are also shared
// naively (every one at its odometry pose).
//
// Beyond the paper: the robots coordinate (frontiers near a teammate's goals are worth
// less, and a robot whose own part is explored goes home to share it), what a robot sees of
// a teammate is not posted, and odometry is calibrated online from the fixes.
//
// The seeds are the first two (a rule fixed before their results). Over seeds 1-8
// (`coopmap run worlds/lab.yaml --explore --seed N`) seven meet the bars asserted here; in
// seed 7 a robot is still out at 900 s, going after the lab's last frontiers.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "sim/runner/world_run.h"
#include "tests/scenario/run_summary.h"

namespace coopmap {
namespace {

TEST(CooperativeScenarioTest, TwoRobotsShareOnlyCorrectedSortiesAndBeatNaiveSharing) {
  for (uint64_t seed : {1, 2}) {
    RunOptions o;
    o.world_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml";
    o.seed = seed;
    o.odometry = "drifting";
    o.explore = true;
    o.duration = 900;
    const RunResult r = runWorld(o);
    ASSERT_TRUE(r.cooperative);
    const SharedMapResult& s = r.shared_map;
    ASSERT_TRUE(s.computed);
    scenario_test::printSharedMap(seed, r);
    for (const RobotRunResult& robot : r.robots) {
      for (const std::string& line : robot.log)
        std::printf("  %s %s\n", robot.name.c_str(), line.c_str());
      EXPECT_GE(robot.sorties_posted, 2) << robot.name << ", seed " << seed;
      EXPECT_EQ(robot.phase, "done") << robot.name << ", seed " << seed;
      EXPECT_EQ(robot.collisions, 0) << robot.name << ", seed " << seed;
      // Every fix is measured against the truth; the posted ones must be good.
      EXPECT_EQ(robot.fix_errors.size(), static_cast<size_t>(robot.sorties_fixed));
      for (const FixError& e : robot.fix_errors) {
        EXPECT_LE(e.error_m, 0.03) << robot.name << ", seed " << seed;
        EXPECT_LE(e.error_deg, 0.75) << robot.name << ", seed " << seed;
      }
    }
    EXPECT_GE(s.protocol.coverage, 0.9) << "seed " << seed;
    EXPECT_GT(s.protocol.wall_recall, s.naive.wall_recall + 0.2) << "seed " << seed;
    EXPECT_LT(s.protocol.false_occupied_rate, s.naive.false_occupied_rate) << "seed " << seed;
    EXPECT_GE(s.protocol.wall_recall, 0.95) << "seed " << seed;
    EXPECT_LE(s.protocol.false_occupied_rate, 0.01) << "seed " << seed;
    // The timeline ends with the run, and the shared map it shows is the final one.
    ASSERT_FALSE(r.timeline.empty());
    EXPECT_NEAR(r.timeline.back().shared_coverage, s.protocol.coverage, 1e-9);
  }
}

}  // namespace
}  // namespace coopmap

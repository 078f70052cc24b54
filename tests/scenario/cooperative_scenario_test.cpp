// Scenario: the paper's whole cooperation, autonomous (issue 7). Two B-14s with drifting
// odometry explore worlds/lab.yaml in sorties of 25 m; after each a robot comes home,
// localizes at the home base (driving to its start by a first fix and looking again),
// corrects the sortie (heading-drift model, then a pose graph with closures to the shared
// map), posts it, imports the shared map and goes again. The same radial maps are also
// shared naively (every one at its odometry pose).
//
// Measured (`coopmap run worlds/lab.yaml --explore --seed N`, seeds 1-5): shared map
// wall_recall 0.973 / 0.973 / 0.947 / 0.958 / 0.957 against naive 0.519 / 0.384 / 0.520 /
// 0.546 / 0.560; false_occupied_rate 0.0146 / 0.0176 / 0.0175 / 0.0133 / 0.0213 against
// 0.0534 / 0.0546 / 0.0496 / 0.0435 / 0.0456; coverage >= 0.993. Fixes that were posted:
// 0.3-1.6 cm, <= 0.51 deg. Not yet met: false_occupied_rate <= 0.01 and 0 collisions
// (0-6 per run, mostly a drifting robot coming home into a teammate standing there).
#include <cstdio>

#include <gtest/gtest.h>

#include "apps/run_world.h"

namespace coopmap {
namespace {

TEST(CooperativeScenarioTest, TwoRobotsShareOnlyCorrectedSortiesAndBeatNaiveSharing) {
  for (uint64_t seed : {3, 4}) {
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
    std::printf(
        "seed %llu: shared wall_recall %.3f FOR %.4f coverage %.3f (%d posts); naive "
        "%.3f %.4f; 90 %% coverage after %.0f s\n",
        static_cast<unsigned long long>(seed), s.protocol.wall_recall,
        s.protocol.false_occupied_rate, s.protocol.coverage, s.posts_accepted, s.naive.wall_recall,
        s.naive.false_occupied_rate, r.time_to_90_s);
    for (const RobotRunResult& robot : r.robots) {
      for (const std::string& line : robot.sortie_log)
        std::printf("  %s %s\n", robot.name.c_str(), line.c_str());
      EXPECT_GE(robot.sorties_posted, 1) << robot.name << ", seed " << seed;
      EXPECT_EQ(robot.mission_phase, "done") << robot.name << ", seed " << seed;
      // Every fix is measured against the truth; the posted ones must be good.
      EXPECT_EQ(robot.fix_errors.size(), static_cast<size_t>(robot.sorties_fixed));
      for (const auto& [m, deg] : robot.fix_errors) {
        EXPECT_LE(m, 0.03) << robot.name << ", seed " << seed;
        EXPECT_LE(deg, 0.75) << robot.name << ", seed " << seed;
      }
    }
    EXPECT_GE(s.protocol.coverage, 0.9) << "seed " << seed;
    EXPECT_GT(s.protocol.wall_recall, s.naive.wall_recall + 0.2) << "seed " << seed;
    EXPECT_LT(s.protocol.false_occupied_rate, s.naive.false_occupied_rate) << "seed " << seed;
    EXPECT_GE(s.protocol.wall_recall, 0.9) << "seed " << seed;
    EXPECT_LE(s.protocol.false_occupied_rate, 0.025) << "seed " << seed;
    // The timeline ends with the run, and the shared map it shows is the final one.
    ASSERT_FALSE(r.timeline.empty());
    EXPECT_NEAR(r.timeline.back().shared_coverage, s.protocol.coverage, 1e-9);
  }
}

}  // namespace
}  // namespace coopmap

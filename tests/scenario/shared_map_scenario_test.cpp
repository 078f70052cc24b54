// Scenario: the paper's two ways of sharing, on worlds/lab.yaml's two scripted robots with
// drifting odometry: every radial map posted at its odometry pose ("naive"), or each
// robot's traverse corrected at the home base first (the protocol). The protocol's shared
// map has more of the walls where they are.
//
// Measured (seeds 1-2): wall_recall protocol 0.967 / 0.942 against naive 0.586 / 0.657;
// false_occupied_rate 0.0115 / 0.0179 against 0.0396 / 0.0337. Both traverses go through
// the autonomous runs' protocol (core/agent/cooperation.h): eric's, fixed, is shared when
// its return look matches the home jose shared. Until session 26 only jose's was shared
// here (eric's fix was not trusted after jose's route drove into it at home).
#include <cstdio>

#include <gtest/gtest.h>

#include "sim/runner/world_run.h"

namespace coopmap {
namespace {

TEST(SharedMapScenarioTest, HomeBaseProtocolBeatsNaiveSharingOnWalls) {
  for (uint64_t seed : {1, 2}) {
    RunOptions o;
    o.world_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml";
    o.seed = seed;
    o.odometry = "drifting";
    o.share_maps = true;
    const RunResult r = runWorld(o);
    const SharedMapResult& s = r.shared_map;
    ASSERT_TRUE(s.computed);
    std::printf("seed %llu: protocol wall_recall %.3f FOR %.4f (%d posts), naive %.3f %.4f\n",
                static_cast<unsigned long long>(seed), s.protocol.wall_recall,
                s.protocol.false_occupied_rate, s.posts_accepted, s.naive.wall_recall,
                s.naive.false_occupied_rate);
    EXPECT_EQ(s.posts_accepted, 2) << "seed " << seed;
    // The scripted routes keep the robots apart (until session 26 jose drove into eric, back
    // at its start, on every seed).
    for (const RobotRunResult& robot : r.robots)
      EXPECT_EQ(robot.collisions, 0) << "seed " << seed << ": " << robot.name;
    EXPECT_GT(s.protocol.wall_recall, s.naive.wall_recall + 0.05) << "seed " << seed;
    EXPECT_LT(s.protocol.false_occupied_rate, s.naive.false_occupied_rate) << "seed " << seed;
    EXPECT_GT(s.protocol.coverage, 0.9) << "seed " << seed;
  }
}

}  // namespace
}  // namespace coopmap

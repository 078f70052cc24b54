// Scenario: the paper's two ways of sharing, on worlds/lab.yaml's two scripted robots with
// drifting odometry: every radial map posted at its odometry pose ("naive"), or each
// robot's traverse corrected at the home base first (the protocol). The protocol's shared
// map has more of the walls where they are.
//
// Measured (seeds 1-2): wall_recall protocol 0.969 / 0.882 against naive 0.598 / 0.642;
// false_occupied_rate 0.0086 / 0.0245 against 0.0408 / 0.0348. Only jose's traverse is
// shared: eric's scripted tour brings it back ~0.5 m north of its start, where its return
// turn does not match its narrow first view, and an unfixed traverse is never shared
// (autonomous runs drive back to the start by a first fix and look again:
// cooperative_scenario_test.cpp).
#include <cstdio>

#include <gtest/gtest.h>

#include "apps/run_world.h"

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
    EXPECT_GE(s.posts_accepted, 1) << "seed " << seed;
    EXPECT_GT(s.protocol.wall_recall, s.naive.wall_recall + 0.05) << "seed " << seed;
    EXPECT_LT(s.protocol.false_occupied_rate, s.naive.false_occupied_rate) << "seed " << seed;
    EXPECT_GT(s.protocol.coverage, 0.9) << "seed " << seed;
  }
}

}  // namespace
}  // namespace coopmap

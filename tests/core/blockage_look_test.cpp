#include "core/planning/blockage_look.h"

#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "tests/core/mission_test_maps.h"

namespace coopmap {
namespace {

using mission_test::gridOf;
using mission_test::roomAndCorridor;

TEST(BlockageLookTest, APersonMappedInTheDoorwayIsLookedAtFromInTheRoom) {
  const OccupancyGrid g = roomAndCorridor(true);
  const PlanningMap p(g, PlanningMapConfig{});
  const Eigen::Vector2d robot(1.0, 1.0);
  const std::vector<Frontier> frontiers = findFrontiers(g, p, robot, FrontierConfig{});
  ASSERT_FALSE(frontiers.empty());
  for (const Frontier& f : frontiers) ASSERT_FALSE(f.has_goal);  // the doorway is shut
  const std::optional<BlockageLook> look = findBlockageLook(g, p, robot, frontiers, {}, 0.5);
  ASSERT_TRUE(look.has_value());
  // The blockage is the doorway, the look from in the room, facing it, from about 1.2 m.
  EXPECT_NEAR(look->at.x(), 3.0, 0.35);
  EXPECT_NEAR(look->at.y(), 2.0, 0.5);
  EXPECT_LT(look->from.x(), 2.95);
  EXPECT_TRUE(p.connected(robot, look->from));
  EXPECT_NEAR((look->at - look->from).norm(), kBlockageLookDistance, 0.15);
  const Eigen::Vector2d toward = look->at - look->from;
  EXPECT_NEAR(look->heading, std::atan2(toward.y(), toward.x()), 1e-9);
  EXPECT_GT(look->frontier.x(), 4.0);
  // Looked at once: not again.
  EXPECT_FALSE(findBlockageLook(g, p, robot, frontiers, {look->at}, 0.5).has_value());
}

TEST(BlockageLookTest, AFrontierLookedAtFromItsGoalBeyondTheBlockageIsLookedAtAgain) {
  // The corridor seen only 0.6 m beyond the doorway: its frontier has a goal in the room,
  // reached and looked from, and it is still there; the explorer is done, with the frontier
  // out of reach, and what closes the way to it is the doorway.
  const OccupancyGrid g = roomAndCorridor(true, 3.6);
  const PlanningMap p(g, PlanningMapConfig{});
  const Pose2 robot(1.0, 1.0, 0.0);
  FrontierExplorer explorer({}, PlannerConfig{});
  const ExploreStep first = explorer.next(g, p, robot);
  ASSERT_EQ(first.status, ExploreStatus::kGoal) << first.reason;
  EXPECT_LT(first.frontier.goal.x(), 2.95);  // on the room's side
  explorer.markReached(first.frontier.goal);
  const ExploreStep step = explorer.next(g, p, robot);
  ASSERT_EQ(step.status, ExploreStatus::kDone);
  ASSERT_EQ(step.out_of_reach.size(), 1u) << step.reason;
  const std::optional<BlockageLook> look =
      findBlockageLook(g, p, robot.translation(), step.out_of_reach, {}, 0.5);
  ASSERT_TRUE(look.has_value());
  EXPECT_NEAR(look->at.x(), 3.0, 0.35);
  EXPECT_NEAR(look->at.y(), 2.0, 0.5);
  EXPECT_LT(look->from.x(), 2.95);
}

TEST(BlockageLookTest, NothingToLookAtWhenTheFrontierCanBeReached) {
  const OccupancyGrid g = roomAndCorridor(false);
  const PlanningMap p(g, PlanningMapConfig{});
  const Eigen::Vector2d robot(1.0, 1.0);
  const std::vector<Frontier> frontiers = findFrontiers(g, p, robot, FrontierConfig{});
  ASSERT_FALSE(frontiers.empty());
  EXPECT_FALSE(findBlockageLook(g, p, robot, frontiers, {}, 0.5).has_value());
}

TEST(BlockageLookTest, NothingToLookAtFromABlockedCell) {
  const OccupancyGrid g = roomAndCorridor(true);
  const PlanningMap p(g, PlanningMapConfig{});
  const Eigen::Vector2d in_room(1.0, 1.0), on_wall(3.0, 1.0);
  const std::vector<Frontier> frontiers = findFrontiers(g, p, in_room, FrontierConfig{});
  EXPECT_FALSE(findBlockageLook(g, p, on_wall, frontiers, {}, 0.5).has_value());
}

TEST(BlockageLookTest, AFrontierBeyondNeverSeenCellsOnlyIsNotLookedAt) {
  // A pocket the robot stands in and a patch seen free far off, never-observed cells between
  // them: no way to the patch's frontier through known cells, so no blockage to look at.
  const MapLimits lim = MapLimits::covering({0.0, 0.0}, {6.0, 4.0}, 0.05);
  const OccupancyGrid g = gridOf(lim, [](const Eigen::Vector2d& c) -> std::optional<int16_t> {
    const bool pocket = c.x() < 1.5 && c.y() < 1.5;
    const bool far_patch = c.x() > 4.0 && c.x() < 4.5 && c.y() > 2.0 && c.y() < 3.0;
    if (!pocket && !far_patch) return std::nullopt;
    return -1000;
  });
  const PlanningMap p(g, PlanningMapConfig{});
  const Eigen::Vector2d robot(0.7, 0.7);
  std::vector<Frontier> frontiers = findFrontiers(g, p, robot, FrontierConfig{});
  bool goalless = false;
  for (const Frontier& f : frontiers) goalless = goalless || (!f.has_goal && f.gain > 0);
  ASSERT_TRUE(goalless);  // the far patch's
  EXPECT_FALSE(findBlockageLook(g, p, robot, frontiers, {}, 0.5).has_value());
}

}  // namespace
}  // namespace coopmap

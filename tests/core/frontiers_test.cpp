#include "core/planning/frontiers.h"

#include <optional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "tests/core/mission_test_maps.h"

namespace coopmap {
namespace {

// A 6 m x 4 m map at 5 cm: a walled room x in [0, 3] m seen whole, with doorways in its east
// wall (y intervals, m); east of the wall nothing has been seen.
OccupancyGrid roomWithDoors(const std::vector<std::pair<double, double>>& doors) {
  const MapLimits lim = MapLimits::covering({0.0, 0.0}, {6.0, 4.0}, 0.05);
  return mission_test::gridOf(lim, [&](const Eigen::Vector2d& c) -> std::optional<int16_t> {
    if (c.x() > 3.05) return std::nullopt;  // unknown
    bool wall = c.x() < 0.1 || c.y() < 0.1 || c.y() > 3.9 || c.x() > 2.95;
    for (const auto& [y0, y1] : doors)
      if (c.x() > 2.95 && c.y() > y0 && c.y() < y1) wall = false;
    return wall ? 500 : -500;
  });
}

PlanningMap planningOf(const OccupancyGrid& g) { return PlanningMap(g, PlanningMapConfig{}); }

// `g` with the cells whose centres satisfy `where` observed, at log-odds `lo`.
template <typename Where>
OccupancyGrid observedWeakly(OccupancyGrid g, Where where, int16_t lo) {
  const MapLimits& lim = g.limits();
  std::vector<int16_t> log_odds(lim.size());
  std::vector<uint8_t> seen(lim.size());
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      const size_t i = lim.index(ix, iy);
      const bool here = where(lim.cellCenter(ix, iy));
      log_odds[i] = here ? lo : g.logOdds(ix, iy);
      seen[i] = here || g.seen(ix, iy);
    }
  g.assign(log_odds, seen);
  return g;
}

TEST(FrontiersTest, TheDoorwayIsTheFrontierAndItsGoalIsReachable) {
  const OccupancyGrid g = roomWithDoors({{1.5, 2.5}});
  const PlanningMap p = planningOf(g);
  const std::vector<Frontier> f = findFrontiers(g, p, {1.0, 2.0}, FrontierConfig{});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_NEAR(f[0].centroid.x(), 3.025, 0.06);
  EXPECT_NEAR(f[0].centroid.y(), 2.0, 0.1);
  EXPECT_GT(f[0].gain, 100);
  ASSERT_TRUE(f[0].has_goal);
  EXPECT_TRUE(p.freeAt(f[0].goal));
  EXPECT_LT((f[0].goal - f[0].centroid).norm(), 1.5);
}

TEST(FrontiersTest, ExplorerPlansToTheBestFrontierAndBlacklistsFailures) {
  // Two doorways: a near one and a far one with the same unknown space behind.
  const OccupancyGrid g = roomWithDoors({{0.4, 1.2}, {2.8, 3.6}});
  const PlanningMap p = planningOf(g);
  FrontierExplorer explorer({}, PlannerConfig{});
  const Pose2 robot(1.5, 0.8, 0.0);
  const ExploreStep step = explorer.next(g, p, robot);
  ASSERT_EQ(step.status, ExploreStatus::kGoal) << step.reason;
  EXPECT_EQ(step.frontiers, 2);
  EXPECT_LT(step.frontier.centroid.y(), 2.0);  // the near doorway
  ASSERT_TRUE(step.plan.solved());
  for (const Eigen::Vector2d& w : step.plan.path.waypoints) EXPECT_TRUE(p.freeAt(w));
  // Could not get there after all: the other doorway is next.
  explorer.blacklist(step.frontier.goal);
  const ExploreStep second = explorer.next(g, p, robot);
  ASSERT_EQ(second.status, ExploreStatus::kGoal);
  EXPECT_GT(second.frontier.centroid.y(), 2.0);
  explorer.blacklist(second.frontier.goal);
  const ExploreStep none = explorer.next(g, p, robot);
  EXPECT_EQ(none.status, ExploreStatus::kDone);
  EXPECT_EQ(none.reason,
            "2 frontiers, none with a reachable goal not blacklisted: (3.0, 0.8) goal "
            "blacklisted; (3.0, 3.2) goal blacklisted");
}

TEST(FrontiersTest, AFrontierATeammateClaimedIsLeftToIt) {
  // The near doorway is the best alone; a teammate driving to it makes the far one best, and
  // the step says how much the chosen frontier is claimed.
  const OccupancyGrid g = roomWithDoors({{0.4, 1.2}, {2.8, 3.6}});
  const PlanningMap p = planningOf(g);
  FrontierExplorer explorer({}, PlannerConfig{});
  const Pose2 robot(1.5, 0.8, 0.0);
  const ExploreStep alone = explorer.next(g, p, robot);
  ASSERT_EQ(alone.status, ExploreStatus::kGoal);
  EXPECT_LT(alone.frontier.centroid.y(), 2.0);
  EXPECT_DOUBLE_EQ(alone.claim_factor, 1.0);
  const ExploreStep shared = explorer.next(g, p, robot, {alone.frontier.goal});
  ASSERT_EQ(shared.status, ExploreStatus::kGoal);
  EXPECT_GT(shared.frontier.centroid.y(), 2.0);
  EXPECT_GT(shared.claim_factor, 0.9);  // the doorways' goals are ~2.4 m apart
  // Both claimed: the less claimed one is chosen, and its factor says it is a teammate's.
  const ExploreStep both = explorer.next(g, p, robot, {alone.frontier.goal, shared.frontier.goal});
  ASSERT_EQ(both.status, ExploreStatus::kGoal);
  EXPECT_LT(both.claim_factor, 0.1);
  // Coordination off: claims change nothing.
  FrontierConfig off;
  off.claim_radius = 0.0;
  FrontierExplorer independent(off, PlannerConfig{});
  const ExploreStep ignored = independent.next(g, p, robot, {alone.frontier.goal});
  EXPECT_LT(ignored.frontier.centroid.y(), 2.0);
  EXPECT_DOUBLE_EQ(ignored.claim_factor, 1.0);
}

// A frontier whose goal was reached is not chosen again: what the robot did not see from
// there it will not see from there again.
TEST(FrontiersTest, AFrontierLookedAtFromItsGoalIsNotChosenAgain) {
  const OccupancyGrid g = roomWithDoors({{1.5, 2.5}});
  const PlanningMap p = planningOf(g);
  const Pose2 robot(1.0, 1.0, 0.0);
  FrontierExplorer plain({}, PlannerConfig{});
  const ExploreStep first = plain.next(g, p, robot);
  ASSERT_EQ(first.status, ExploreStatus::kGoal) << first.reason;
  plain.markReached(first.frontier.goal);
  const ExploreStep done = plain.next(g, p, robot);
  EXPECT_EQ(done.status, ExploreStatus::kDone);
  EXPECT_EQ(done.reason,
            "1 frontiers, none with a reachable goal not blacklisted: (3.0, 2.0) looked from its "
            "goal before");
}

TEST(FrontiersTest, AClosedRoomIsExplored) {
  const OccupancyGrid g = roomWithDoors({});
  FrontierExplorer explorer({}, PlannerConfig{});
  const ExploreStep step = explorer.next(g, planningOf(g), Pose2(1.5, 2.0, 0.0));
  EXPECT_EQ(step.status, ExploreStatus::kDone);
  EXPECT_EQ(step.reason, "no frontier left");
}

TEST(FrontiersTest, AFringeObservedTooLittleToTellDoesNotHideTheUnknownBeyond) {
  // Through the doorway, a stretch seen once from afar (the far ends of long stereo rays):
  // observed, its log-odds too weak for free. Beyond it nothing has been seen. The explorer
  // once found no frontier here (no free cell touched a never-observed one) and called the
  // exploration complete with a whole corridor unseen.
  const OccupancyGrid g = observedWeakly(
      roomWithDoors({{1.5, 2.5}}),
      [](const Eigen::Vector2d& c) {
        return c.x() > 3.05 && c.x() < 3.6 && c.y() > 1.5 && c.y() < 2.5;
      },
      -20);  // weakly free: state unknown
  const MapLimits& lim = g.limits();
  ASSERT_EQ(g.state(lim.cellX(3.3), lim.cellY(2.0)), CellState::kUnknown);
  ASSERT_TRUE(g.seen(lim.cellX(3.3), lim.cellY(2.0)));
  const PlanningMap p = planningOf(g);
  EXPECT_TRUE(findFrontiers(g, p, {1.0, 2.0}, FrontierConfig{}).empty());  // off by default
  FrontierConfig fc;
  fc.fringe_clearance = 0.3;
  const std::vector<Frontier> f = findFrontiers(g, p, {1.0, 2.0}, fc);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_NEAR(f[0].centroid.x(), 3.025, 0.06);  // the free cells before the fringe
  EXPECT_GT(f[0].gain, 50);                     // never-observed cells within reach
  ASSERT_TRUE(f[0].has_goal);
  FrontierExplorer explorer(fc, PlannerConfig{});
  EXPECT_EQ(explorer.next(g, p, Pose2(1.0, 2.0, 0.0)).status, ExploreStatus::kGoal);
}

TEST(FrontiersTest, AnUncertainDoorwayBetweenTwoJambsIsAFrontierWithADoorwayWidth) {
  // A door 0.5 m wide seen only obliquely: its opening observed but left uncertain, every
  // cell of it within fringe_clearance of a jamb; beyond it nothing has been seen. With the
  // fringe alone no frontier leads through it (the building's lab back door, seeds 5 and 8).
  const OccupancyGrid g = observedWeakly(
      roomWithDoors({{1.75, 2.25}}),
      [](const Eigen::Vector2d& c) {
        return c.x() > 2.95 && c.x() < 3.05 && c.y() > 1.75 && c.y() < 2.25;
      },
      -20);  // weakly free: state unknown
  const MapLimits& lim = g.limits();
  ASSERT_EQ(g.state(lim.cellX(3.0), lim.cellY(2.0)), CellState::kUnknown);
  const PlanningMap p = planningOf(g);
  FrontierConfig fc;
  fc.fringe_clearance = 0.3;
  EXPECT_TRUE(findFrontiers(g, p, {1.0, 2.0}, fc).empty());
  fc.doorway_width = 1.2;
  const std::vector<Frontier> f = findFrontiers(g, p, {1.0, 2.0}, fc);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_NEAR(f[0].centroid.x(), 2.925, 0.06);  // the room's free cells before the opening
  EXPECT_NEAR(f[0].centroid.y(), 2.0, 0.1);
  EXPECT_GT(f[0].gain, 100);
  ASSERT_TRUE(f[0].has_goal);
  FrontierExplorer explorer(fc, PlannerConfig{});
  EXPECT_EQ(explorer.next(g, p, Pose2(1.0, 2.0, 0.0)).status, ExploreStatus::kGoal);
  fc.doorway_width = 0.4;  // the gap is wider
  EXPECT_TRUE(findFrontiers(g, p, {1.0, 2.0}, fc).empty());
  fc.doorway_width = 1.2;
  fc.doorway_min_width = 0.6;  // the gap is narrower
  EXPECT_TRUE(findFrontiers(g, p, {1.0, 2.0}, fc).empty());
  fc.doorway_min_width = -0.1;
  EXPECT_THROW(fc.validate(), std::invalid_argument);
}

TEST(FrontiersTest, UncertainCellsClosedInByKnownOnesAreNoFrontier) {
  // In the closed room, a patch seen but left uncertain (stereo's band beside a table): with
  // nothing unobserved behind it, driving up to it shows nothing new.
  const OccupancyGrid g = observedWeakly(
      roomWithDoors({}),
      [](const Eigen::Vector2d& c) {
        return c.x() > 1.2 && c.x() < 1.8 && c.y() > 1.2 && c.y() < 1.8;
      },
      30);  // weakly occupied: state unknown
  const MapLimits& lim = g.limits();
  ASSERT_EQ(g.state(lim.cellX(1.5), lim.cellY(1.5)), CellState::kUnknown);
  FrontierConfig fc;
  fc.fringe_clearance = 0.3;
  EXPECT_TRUE(findFrontiers(g, planningOf(g), {1.0, 3.0}, fc).empty());
}

TEST(FrontiersTest, ARobotOnABlockedCellIsBlockedNotDone) {
  // Against the west wall (inside its inflation) nothing can be planned: that is not the
  // end of exploration, the doorway is still there.
  const OccupancyGrid g = roomWithDoors({{1.5, 2.5}});
  FrontierExplorer explorer({}, PlannerConfig{});
  const ExploreStep step = explorer.next(g, planningOf(g), Pose2(0.15, 2.0, 0.0));
  EXPECT_EQ(step.status, ExploreStatus::kBlocked);
  EXPECT_EQ(step.reason, "the robot stands on a blocked cell");
  EXPECT_EQ(explorer.next(g, planningOf(g), Pose2(1.0, 2.0, 0.0)).status, ExploreStatus::kGoal);
}

TEST(FrontiersTest, ADoorwayTooNarrowForTheRobotHasNoGoalBeyondIt) {
  // 20 cm is too narrow for the B-14 (35.6 cm wide): the frontier is seen, its goal lies
  // inside the room, and the explorer goes there (to look), not through.
  const OccupancyGrid g = roomWithDoors({{1.9, 2.1}});
  const PlanningMap p = planningOf(g);
  const std::vector<Frontier> f = findFrontiers(g, p, {1.0, 2.0}, FrontierConfig{});
  ASSERT_EQ(f.size(), 1u);
  ASSERT_TRUE(f[0].has_goal);
  EXPECT_LT(f[0].goal.x(), 2.95);
}

TEST(FrontiersTest, BadConfigNamesTheField) {
  FrontierConfig c;
  c.gain_radius = -1.0;
  try {
    c.validate();
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "frontier config: field 'gain_radius': expected a positive number, got "
                 "-1.000000");
  }
}

}  // namespace
}  // namespace coopmap

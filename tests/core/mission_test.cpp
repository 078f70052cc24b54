// The mission's bump rule, driven by a kinematic robot on a map with frontiers all around:
// every bump backs the robot off; bumped max_sortie_bumps times in a sortie, the robot
// stops for good (its wheels slipped, its odometry cannot be trusted).
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/agent/mission.h"

namespace coopmap {
namespace {

// Free space 3.5 m ahead of `at` over +-60 degrees (a look that way); unknown beyond.
OccupancyGrid lookedAround(const Pose2& at) {
  OccupancyGrid map(MapLimits::covering({0.0, 0.0}, {8.0, 6.0}, 0.05), OccupancyConfig{});
  for (int k = -3; k <= 3; ++k) {
    RadialMap scan;
    scan.max_range = 3.5;
    for (int c = 0; c < 40; ++c) {
      RadialReading r;
      r.bearing = (c - 19.5) / 39.0 * (M_PI / 3.0);
      r.range = 3.5;
      r.kind = RadialKind::kBeyond;
      scan.readings.push_back(r);
    }
    for (int i = 0; i < 3; ++i) map.insert(scan, Pose2(at.x, at.y, at.theta + k * M_PI / 18.0));
  }
  return map;
}

TEST(MissionTest, StopsForGoodAfterTooManyBumpsInASortie) {
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));  // the robot 1 m into it
  MissionConfig c;
  c.look_wait_s = 0.5;
  c.look_turn_rate = 1.5;
  c.max_sortie_bumps = 2;
  c.planner.seed = 7;
  MissionAgent mission(home, c);
  Pose2 pose = home;
  const double dt = 0.05;
  int bumps = 0;
  bool was_exploring = false;
  double driving_since = -1.0;
  for (int step = 0; step < 20000 && !mission.done(); ++step) {
    const double now = step * dt;
    // Something the map does not show touches the robot whenever it drives forward, 2 s
    // into each drive.
    const bool bump = driving_since >= 0.0 && now - driving_since > 2.0;
    const MotionCommand cmd = mission.update(now, pose, map, nullptr, bump);
    if (bump) {
      ++bumps;
      driving_since = -1.0;
      EXPECT_LT(cmd.linear, 0.0) << "backs off";
    } else if (cmd.linear > 0.0 && driving_since < 0.0) {
      driving_since = now;
    } else if (cmd.linear <= 0.0) {
      driving_since = -1.0;
    }
    was_exploring = was_exploring || mission.phase() == MissionPhase::kExplore;
    if (bumps < c.max_sortie_bumps) {
      EXPECT_FALSE(mission.done()) << mission.lastEvent();
    }
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
  }
  EXPECT_TRUE(was_exploring) << mission.lastEvent();
  ASSERT_TRUE(mission.done());
  EXPECT_EQ(bumps, c.max_sortie_bumps);
  EXPECT_NE(mission.lastEvent().find("bumped 2 times"), std::string::npos) << mission.lastEvent();
  EXPECT_EQ(mission.safetyStops(), 2);
}

TEST(MissionTest, GoesHomeToShareWhenTheFrontiersLeftAreTeammates) {
  // A robot with sorties explores; once it has driven min_sortie_m, a teammate claims every
  // frontier (its goals all over the map): the robot goes home to share its part, not
  // before, and forgets the claims when it has imported the shared map.
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  MissionConfig c;
  c.look_wait_s = 0.5;
  c.look_turn_rate = 1.5;
  c.max_sorties = 2;
  c.min_sortie_m = 1.0;
  c.planner.seed = 3;
  MissionAgent mission(home, c);
  std::vector<Eigen::Vector2d> everywhere;
  for (double x = 0.25; x < 8.0; x += 0.5)
    for (double y = 0.25; y < 6.0; y += 0.5) everywhere.push_back({x, y});
  Pose2 pose = home;
  const double dt = 0.05;
  double driven = 0.0;
  bool claimed = false;
  for (int step = 0; step < 20000 && mission.phase() != MissionPhase::kAtHome; ++step) {
    const MotionCommand cmd = mission.update(step * dt, pose, map, nullptr);
    if (mission.phase() == MissionPhase::kExplore) {
      const std::optional<Eigen::Vector2d> goal = mission.explorationGoal();
      if (driven < c.min_sortie_m) {
        // Its own goal claimed by a teammate changes nothing yet: it has not driven enough.
        if (goal) mission.setTeammateGoals({*goal});
        EXPECT_EQ(mission.earlyReturns(), 0);
      } else if (!claimed) {
        mission.setTeammateGoals(everywhere);
        claimed = true;
      }
    }
    driven += std::abs(cmd.linear) * dt;
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
  }
  ASSERT_EQ(mission.phase(), MissionPhase::kAtHome) << mission.lastEvent();
  EXPECT_TRUE(claimed) << mission.lastEvent();
  EXPECT_EQ(mission.earlyReturns(), 1);
  EXPECT_FALSE(mission.explorationComplete());
  EXPECT_LT((pose.translation() - home.translation()).norm(), 0.3);
  EXPECT_FALSE(mission.claimed().empty());
  mission.continueAfterFix(1000.0);
  EXPECT_EQ(mission.phase(), MissionPhase::kExplore);
  EXPECT_TRUE(mission.claimed().empty());
}

TEST(MissionTest, BadBumpSettingsNameTheField) {
  MissionConfig c;
  c.max_sortie_bumps = 0;
  try {
    c.validate();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'max_sortie_bumps'"), std::string::npos) << e.what();
  }
  c = MissionConfig{};
  c.bump_radius = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = MissionConfig{};
  c.claimed_return_factor = 1.5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = MissionConfig{};
  c.bump_width = -0.1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = MissionConfig{};
  c.team_close = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap

// The mission's bump rule, driven by a kinematic robot on a map with frontiers all around:
// every bump backs the robot off; bumped max_sortie_bumps times in a sortie, the robot
// stops for good (its wheels slipped, its odometry cannot be trusted).
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/agent/mission.h"

namespace coopmap {
namespace {

// A radial map of 40 columns over +-60 degrees, free up to `range` (m) in every one.
RadialMap freeAhead(double range) {
  RadialMap scan;
  scan.max_range = range;
  for (int c = 0; c < 40; ++c) {
    RadialReading r;
    r.bearing = (c - 19.5) / 39.0 * (M_PI / 3.0);
    r.range = range;
    r.kind = RadialKind::kBeyond;
    scan.readings.push_back(r);
  }
  return scan;
}

// Free space 3.5 m ahead of `at` over +-60 degrees (a look that way); unknown beyond.
OccupancyGrid lookedAround(const Pose2& at) {
  OccupancyGrid map(MapLimits::covering({0.0, 0.0}, {8.0, 6.0}, 0.05), OccupancyConfig{});
  const RadialMap scan = freeAhead(3.5);
  for (int k = -3; k <= 3; ++k)
    for (int i = 0; i < 3; ++i) map.insert(scan, Pose2(at.x, at.y, at.theta + k * M_PI / 18.0));
  return map;
}

TEST(MissionTest, ItsPlannerIsBoundedByIterationsNotByTheClock) {
  // The same seed must give the same run however busy the machine: every query the planner
  // gets ends at its solution or at the iteration cap, long before the time backstop (a
  // RRTConnect iteration takes about 3.5 us on the CI machine).
  const MissionConfig c;
  EXPECT_GT(c.planner.max_iterations, 0u);
  EXPECT_GE(c.planner.time_budget, 10.0 * 3.5e-6 * static_cast<double>(c.planner.max_iterations))
      << "the time backstop would bind before the iteration cap on a machine 10x slower";
}

// With no way home in the map (a wall across it, as a person standing in a corridor makes),
// a robot away from home stops and plans again later; it used to drive straight at home,
// through what the map showed. When the way opens, it goes.
TEST(MissionTest, WithNoWayHomeItWaitsAndPlansAgainRatherThanDriveStraight) {
  const Pose2 home(1.0, 3.0, 0.0);
  const OccupancyGrid open = lookedAround(home);
  OccupancyGrid walled = open;
  {
    std::vector<int16_t> log_odds = walled.logOddsGrid().cells;
    std::vector<uint8_t> seen = walled.seenGrid().cells;
    const MapLimits& l = walled.limits();
    for (int iy = 0; iy < l.height; ++iy)
      for (int ix = l.cellX(2.5); ix <= l.cellX(2.6); ++ix) {
        log_odds[l.index(ix, iy)] = 400;
        seen[l.index(ix, iy)] = 1;
      }
    walled.assign(log_odds, seen);
  }
  MissionConfig c;
  c.look_wait_s = 0.5;
  c.look_turn_rate = 1.5;
  c.budget_m = 1.0;
  c.look_from_m = 1.0;
  c.planner.seed = 3;
  MissionAgent mission(home, c);
  Pose2 pose = home;
  const double dt = 0.05;
  double t = 0.0;
  for (; t < 60.0 && mission.phase() != MissionPhase::kExplore; t += dt) {
    const MotionCommand cmd = mission.update(t, pose, open, nullptr);
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
  }
  ASSERT_EQ(mission.phase(), MissionPhase::kExplore);
  // Just beyond the wall, 1.95 m from home (more than look_from_m), nowhere 0.5 m nearer home
  // to go to: the budget is spent.
  pose = Pose2(2.95, 3.0, 0.0);
  for (const double until = t + 1.5; t < until; t += dt) {
    const MotionCommand cmd = mission.update(t, pose, walled, nullptr);
    if (mission.phase() != MissionPhase::kReturn) continue;
    EXPECT_EQ(cmd.linear, 0.0) << "at " << t << " s: " << mission.lastEvent();
    EXPECT_EQ(cmd.angular, 0.0) << "at " << t << " s: " << mission.lastEvent();
  }
  ASSERT_EQ(mission.phase(), MissionPhase::kReturn);
  EXPECT_NE(mission.lastEvent().find("no way home"), std::string::npos) << mission.lastEvent();
  // The wall goes: within a few seconds the robot is on its way.
  bool moving = false;
  for (const double until = t + 5.0; t < until && !moving; t += dt) {
    const MotionCommand cmd = mission.update(t, pose, open, nullptr);
    moving = cmd.linear != 0.0 || cmd.angular != 0.0;
  }
  EXPECT_TRUE(moving) << mission.lastEvent();
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
  // Its odometry slipped: it does not know where it stands, and says so (teammates then see
  // it as an obstacle rather than keep clear of where it reports itself).
  EXPECT_TRUE(mission.lost());
}

TEST(MissionTest, AMissionFinishedWhereItKnowsItIsIsNotLost) {
  MissionAgent mission(Pose2(2.0, 3.0, 0.0), MissionConfig{});
  EXPECT_FALSE(mission.lost());
  mission.finish("exploration complete");
  EXPECT_TRUE(mission.done());
  EXPECT_FALSE(mission.lost());
  MissionAgent unsure(Pose2(2.0, 3.0, 0.0), MissionConfig{});
  unsure.finish("no trusted home-base fix", false);
  EXPECT_TRUE(unsure.done());
  EXPECT_TRUE(unsure.lost());
}

// With bump_away and a bearing from the base, the robot backs off away from the touch: a
// touch behind while driving forward (something walked into it) sends it forwards. Without
// either, it backs off against its command.
TEST(MissionTest, BacksOffAwayFromWhereTheBaseWasTouched) {
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  // bump_away, the bearing reported, whether the back-off is forwards
  const struct {
    bool away;
    std::optional<double> bearing;
    bool forwards;
  } cases[] = {{true, M_PI, true},  {true, -2.5, true},          {true, 0.3, false},
               {true, -1.2, false}, {true, std::nullopt, false}, {false, M_PI, false}};
  for (const auto& k : cases) {
    MissionConfig c;
    c.look_wait_s = 0.5;
    c.look_turn_rate = 1.5;
    c.bump_away = k.away;
    c.planner.seed = 7;
    MissionAgent mission(home, c);
    Pose2 pose = home;
    const double dt = 0.05;
    bool bumped = false;
    for (int step = 0; step < 4000 && !bumped; ++step) {
      const double now = step * dt;
      MotionCommand cmd = mission.update(now, pose, map, nullptr);
      if (mission.phase() == MissionPhase::kExplore && cmd.linear > 0.0) {
        bumped = true;
        const double t = now + dt;
        cmd = mission.update(t, pose, map, nullptr, true, k.bearing);
        EXPECT_EQ(cmd.linear > 0.0, k.forwards)
            << "away " << k.away << ", bearing " << k.bearing.value_or(99) << ": " << cmd.linear;
        EXPECT_NEAR(std::abs(cmd.linear), 0.1, 1e-9);
        // It keeps backing off the same way while the back-off lasts.
        const MotionCommand later = mission.update(t + 0.5, pose, map, nullptr);
        EXPECT_EQ(later.linear, cmd.linear);
      }
      pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
    }
    EXPECT_TRUE(bumped) << "never drove forward to explore";
  }
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

// The map never changes (the test's robot has no cameras): every frontier's goal, once
// reached, leaves its frontier unseen. Without look_again_gain exploration ends there; with
// it the robot goes back to such a goal once and turns a full circle in place before ending.
TEST(MissionTest, TurnsAFullCircleAtAGoalWhoseFrontierItDidNotSee) {
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  auto longestTurnInPlace = [&](int look_again_gain, std::string* reason) {
    MissionConfig c;
    c.look_wait_s = 0.2;
    c.look_turn_rate = 3.0;
    c.retry_frontiers = true;  // reached goals are remembered (FrontierExplorer::markReached)
    c.planner.seed = 3;
    c.frontiers.look_again_gain = look_again_gain;
    MissionAgent mission(home, c);
    Pose2 pose = home;
    const double dt = 0.05;
    double turned = 0.0, longest = 0.0;
    for (int step = 0; step < 40000 && !mission.explorationComplete(); ++step) {
      const MotionCommand cmd = mission.update(step * dt, pose, map, nullptr);
      if (mission.phase() == MissionPhase::kExplore) {
        turned = cmd.linear == 0.0 ? turned + std::abs(cmd.angular) * dt : 0.0;
        longest = std::max(longest, turned);
      }
      pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
    }
    *reason = mission.lastEvent();
    return longest;
  };
  std::string reason;
  EXPECT_LT(longestTurnInPlace(0, &reason), 1.1 * M_PI);
  EXPECT_NE(reason.find("exploration complete"), std::string::npos) << reason;
  EXPECT_NE(reason.find("looked from its goal before"), std::string::npos) << reason;
  EXPECT_GT(longestTurnInPlace(20, &reason), 1.9 * M_PI);
  EXPECT_NE(reason.find("exploration complete"), std::string::npos) << reason;
  EXPECT_NE(reason.find("looked around from its goal before"), std::string::npos) << reason;
}

// Seen free everywhere south of y = 6 m but for a wall x in [2.5, 2.6] m from the south edge
// to y = 6; nothing seen north of y = 6. The only way round the wall is through the unknown.
OccupancyGrid wallWithTheWayRoundUnknown() {
  const MapLimits lim = MapLimits::covering({0.0, 0.0}, {8.0, 8.0}, 0.05);
  OccupancyGrid map(lim, OccupancyConfig{});
  std::vector<int16_t> lo(lim.size(), 0);
  std::vector<uint8_t> seen(lim.size(), 0);
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      const Eigen::Vector2d c = lim.cellCenter(ix, iy);
      if (c.y() > 6.0) continue;
      seen[lim.index(ix, iy)] = 1;
      lo[lim.index(ix, iy)] = c.x() > 2.5 && c.x() < 2.6 ? 500 : -500;
    }
  map.assign(lo, seen);
  return map;
}

// Quick looks at home and a first sortie that ends after 0.5 m, of two sorties: the tests
// below carry the robot elsewhere as it sets off, and watch its way home.
MissionConfig quickFirstSortie() {
  MissionConfig c;
  c.look_wait_s = 0.2;
  c.look_turn_rate = 3.0;
  c.first_budget_m = 0.5;
  c.max_sorties = 2;
  c.planner.seed = 5;
  return c;
}

// Runs a mission whose first sortie ends at once, carried to (3.5, 3) east of the wall, home
// at (2, 3) west of it. Returns, for its way home east of the wall: the farthest north it
// went, and the nearest it came to home.
std::pair<double, double> wayHome(double max_home_detour) {
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = wallWithTheWayRoundUnknown();
  MissionConfig c = quickFirstSortie();
  c.max_home_detour = max_home_detour;
  MissionAgent mission(home, c);
  Pose2 pose = home;
  const double dt = 0.05;
  double north = 0.0, nearest = 1e9;
  for (int step = 0; step < 40000 && mission.phase() != MissionPhase::kAtHome; ++step) {
    const MissionPhase before = mission.phase();
    const MotionCommand cmd = mission.update(step * dt, pose, map, nullptr);
    if (before == MissionPhase::kLookAtHome && mission.phase() == MissionPhase::kExplore)
      pose = Pose2(3.5, 3.0, 0.0);  // carried east of the wall
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
    if (mission.phase() == MissionPhase::kReturn && pose.x > 2.6) {
      north = std::max(north, pose.y);
      nearest = std::min(nearest, (pose.translation() - home.translation()).norm());
    }
  }
  return {north, nearest};
}

TEST(MissionTest, DoesNotGoHomeTheLongWayRoundThroughTheUnknown) {
  // Home is 1.5 m away behind a wall; round it through the unknown is some 8 m. A drifting
  // robot must not drive that far through places it has never seen (round a corridor loop a
  // robot drove 60 m so and came home 6.7 m off): it goes as near home as the free space goes.
  const auto [north, nearest] = wayHome(2.0);
  EXPECT_LT(north, 5.0) << "went round through the unknown";
  EXPECT_LT(nearest, 1.0) << "did not come to the wall by home";
  // Allowed any detour, it does go round: the bound is what keeps it out.
  EXPECT_GT(wayHome(100.0).first, 6.0);
}

// A wall at x 2.5-2.6 with a door 0.9 m wide at y 2.55-3.45; everything seen and free else.
OccupancyGrid wallWithADoor() {
  const MapLimits lim = MapLimits::covering({0.0, 0.0}, {8.0, 6.0}, 0.05);
  OccupancyGrid map(lim, OccupancyConfig{});
  std::vector<int16_t> lo(lim.size(), -500);
  std::vector<uint8_t> seen(lim.size(), 1);
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      const Eigen::Vector2d c = lim.cellCenter(ix, iy);
      if (c.x() > 2.5 && c.x() < 2.6 && (c.y() < 2.55 || c.y() > 3.45)) lo[lim.index(ix, iy)] = 500;
    }
  map.assign(lo, seen);
  return map;
}

// A robot on its way home west through the door, a teammate standing just beyond it
// (nearer the door) for the first `hold_s` of the way home. Returns the robot's least x
// while the teammate stands there, and its least x by the end.
std::pair<double, double> throughTheDoor(double passage_width, double hold_s,
                                         int* waits = nullptr) {
  const Pose2 home(1.0, 3.0, 0.0);
  const OccupancyGrid map = wallWithADoor();
  MissionConfig c = quickFirstSortie();
  c.passage_width = passage_width;
  MissionAgent mission(home, c);
  Pose2 pose = home;
  const double dt = 0.05;
  double held = 1e9, least = 1e9, return_start = -1.0;
  for (int step = 0; step < 20000 && mission.phase() != MissionPhase::kAtHome; ++step) {
    const double now = step * dt;
    const MissionPhase before = mission.phase();
    if (before == MissionPhase::kReturn && return_start < 0.0) return_start = now;
    const bool holding = return_start >= 0.0 && now - return_start < hold_s;
    // 1.05 m from the door's middle, 0.9 m off the way along y = 3: no teammate-ahead stop.
    mission.setTeammates({holding ? Eigen::Vector2d(2.0, 3.9) : Eigen::Vector2d(7.5, 5.5)}, false);
    const MotionCommand cmd = mission.update(now, pose, map, nullptr);
    if (before == MissionPhase::kLookAtHome && mission.phase() == MissionPhase::kExplore)
      pose = Pose2(4.5, 3.0, 0.0);  // carried east of the wall
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
    if (return_start >= 0.0) {
      least = std::min(least, pose.x);
      if (holding) held = std::min(held, pose.x);
    }
  }
  if (waits) *waits = mission.passageWaits();
  return {held, least};
}

TEST(MissionTest, WaitsAtADoorWhileATeammateNearerToItGoesThrough) {
  int waits = 0;
  const auto [held, least] = throughTheDoor(1.2, 15.0, &waits);
  EXPECT_GT(held, 2.6 + 0.178) << "entered the door while the teammate stood at it";
  EXPECT_LT(least, 1.5) << "did not go through once the teammate had gone";
  EXPECT_GE(waits, 1);
  // Off, the same robot goes through with the teammate there.
  const auto [held_off, least_off] = throughTheDoor(0.0, 15.0);
  EXPECT_LT(held_off, 2.4);
  EXPECT_LT(least_off, 1.5);
  // It waits at most passage_wait_s (20 s) for a teammate that stays.
  EXPECT_LT(throughTheDoor(1.2, 1e9).second, 1.5) << "waited for good";
}

TEST(MissionTest, FrontiersLeftButOutOfReachThisSortieAreTriedAgainNextSortie) {
  // Something the map does not show stops every drive 2 s in (a bump: the goal is given up).
  // Once every frontier's goal has failed, frontiers are still left: that is the end of the
  // sortie, not of exploration. Home, and after the import (failed goals forgotten) they
  // are goals again. Goals reached and looked from are not: the robot saw what it could.
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  MissionConfig c;
  c.look_wait_s = 0.2;
  c.look_turn_rate = 3.0;
  c.budget_m = 1000.0;
  c.budget_s = 1e5;
  c.max_sorties = 2;
  c.max_sortie_bumps = 1000;
  c.min_sortie_m = 1.0;
  c.retry_frontiers = true;
  c.planner.seed = 9;
  MissionAgent mission(home, c);
  Pose2 pose = home;
  const double dt = 0.05;
  double driving_since = -1.0;
  int step = 0;
  for (; step < 200000 && mission.phase() != MissionPhase::kAtHome; ++step) {
    const double now = step * dt;
    const bool bump = mission.phase() == MissionPhase::kExplore && driving_since >= 0.0 &&
                      now - driving_since > 2.0;
    const MotionCommand cmd = mission.update(now, pose, map, nullptr, bump);
    if (bump || cmd.linear <= 0.0)
      driving_since = -1.0;
    else if (driving_since < 0.0)
      driving_since = now;
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
  }
  ASSERT_EQ(mission.phase(), MissionPhase::kAtHome) << mission.lastEvent();
  EXPECT_GT(mission.goalsFailed(), 1);
  EXPECT_FALSE(mission.explorationComplete()) << mission.lastEvent();
  EXPECT_NE(mission.lastEvent().find("no reachable frontier for now"), std::string::npos)
      << mission.lastEvent();
  mission.continueAfterFix(step * dt);
  ASSERT_EQ(mission.phase(), MissionPhase::kExplore);
  mission.update(step * dt, pose, map, nullptr);
  EXPECT_TRUE(mission.explorationGoal().has_value()) << mission.lastEvent();
}

// A radial map with one obstacle straight ahead at `range` (m), or none.
RadialMap aheadAt(std::optional<double> range) {
  RadialMap scan = freeAhead(4.0);
  for (RadialReading& r : scan.readings)
    if (range && std::abs(r.bearing) < 0.1) {
      r.range = *range;
      r.kind = RadialKind::kHit;
    }
  return scan;
}

TEST(MissionTest, SlowsDownForWhatIsNearAhead) {
  // Cruise 0.4 m/s; an obstacle 0.65 m ahead, halfway between safety_distance (0.3 m) and
  // slow_distance (1 m), halves the speed; once it is gone, the robot speeds up again.
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  MissionConfig c;
  c.look_wait_s = 0.2;
  c.look_turn_rate = 3.0;
  c.safety_distance = 0.3;
  c.slow_distance = 1.0;
  c.planner.seed = 4;
  MissionAgent mission(home, c);
  Pose2 pose = home;
  const double dt = 0.05;
  double slow_max = 0.0, free_max = 0.0;
  int slow_steps = 0;
  for (int step = 0; step < 4000; ++step) {
    const bool exploring = mission.phase() == MissionPhase::kExplore;
    // Frames at 3 Hz: in the first 20 s of exploring something is near ahead, then nothing.
    const bool frame = step % 7 == 0;
    const bool near = exploring && step * dt < 25.0;
    const RadialMap scan = aheadAt(near ? std::optional<double>(0.65) : std::nullopt);
    const MotionCommand cmd = mission.update(step * dt, pose, map, frame ? &scan : nullptr);
    if (exploring && near && step * dt > 6.0) {
      slow_max = std::max(slow_max, cmd.linear);
      slow_steps += cmd.linear > 0.0;
    }
    if (exploring && !near) free_max = std::max(free_max, cmd.linear);
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
  }
  EXPECT_GT(slow_steps, 20) << mission.lastEvent();
  EXPECT_LE(slow_max, 0.2 + 1e-9);
  EXPECT_GT(free_max, 0.3);
  c.slow_fraction = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

// A map held firmly free everywhere (the shared map, imported), and a wall it does not show
// at x = 4 from y = 0 to 2.5: a textureless wall drift left out of it. The cameras see the
// wall only where the floor ends in front of it, 1.2-1.5 m away (nearer, the floor is out of
// view). A robot carried to (7, 1), going home to (1, 1) straight through the wall. Returns
// the least distance (m) between its body and the wall, and how near it came to home.
std::pair<double, double> pastAnUnmappedWall(double recent_hits_s) {
  const Pose2 home(1.0, 1.0, 0.0);
  const MapLimits lim = MapLimits::covering({0.0, 0.0}, {8.0, 6.0}, 0.05);
  OccupancyGrid map(lim, OccupancyConfig{});
  map.assign(std::vector<int16_t>(lim.size(), -1000), std::vector<uint8_t>(lim.size(), 1));
  MissionConfig c = quickFirstSortie();
  c.max_sorties = 1;
  c.recent_hits_s = recent_hits_s;
  MissionAgent mission(home, c);
  const double wall_x = 4.0, wall_top = 2.5;
  auto toWall = [&](const Eigen::Vector2d& p) {
    return (p - Eigen::Vector2d(wall_x, std::clamp(p.y(), 0.0, wall_top))).norm();
  };
  Pose2 pose = home;
  const double dt = 0.05;
  double least = 1e9, nearest = 1e9;
  for (int step = 0; step < 6000 && !mission.done(); ++step) {
    const MissionPhase before = mission.phase();
    std::optional<RadialMap> scan;
    if (step % 7 == 0) {  // frames at 3 Hz
      scan = freeAhead(4.0);
      scan->sensor_origin = {0.1, 0.0};
      for (RadialReading& r : scan->readings) {
        r.kind = RadialKind::kNone;
        const Eigen::Vector2d o = pose * scan->sensor_origin;
        const double a = pose.theta + r.bearing;
        if (std::abs(std::cos(a)) < 1e-9) continue;
        const double range = (wall_x - o.x()) / std::cos(a);
        const double y = o.y() + range * std::sin(a);
        if (range >= 1.2 && range <= 1.5 && y >= 0.0 && y <= wall_top) {
          r.range = range;
          r.kind = RadialKind::kHit;
        }
      }
    }
    const MotionCommand cmd = mission.update(step * dt, pose, map, scan ? &*scan : nullptr);
    if (before == MissionPhase::kLookAtHome && mission.phase() == MissionPhase::kExplore)
      pose = Pose2(7.0, 1.0, M_PI);  // carried east of the wall
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
    if (mission.phase() != MissionPhase::kLookAtHome) {
      least = std::min(least, toWall(pose.translation()) - c.planning.robot_radius);
      nearest = std::min(nearest, (pose.translation() - home.translation()).norm());
    }
  }
  return {least, nearest};
}

TEST(MissionTest, KeepsClearOfWhatItJustSawWhereItsMapHoldsFree) {
  const auto [least, nearest] = pastAnUnmappedWall(10.0);
  EXPECT_GT(least, 0.02) << "came within 2 cm of the wall";
  EXPECT_LT(nearest, 0.3) << "did not get round the wall home";
  // By its map alone it drives into the wall.
  EXPECT_LT(pastAnUnmappedWall(0.0).first, 0.0);
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
  c = MissionConfig{};
  c.first_budget_m = -1.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = MissionConfig{};
  c.max_home_detour = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = MissionConfig{};
  c.recent_hits_s = -1.0;
  try {
    c.validate();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'recent_hits_s'"), std::string::npos) << e.what();
  }
  c = MissionConfig{};
  c.recent_hits_range = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap

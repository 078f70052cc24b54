// The mission's bump rule, driven by a kinematic robot on a map with frontiers all around:
// every bump backs the robot off; bumped max_sortie_bumps times in a sortie, the robot
// stops for good (its wheels slipped, its odometry cannot be trusted).
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/agent/mission.h"
#include "tests/core/mission_test_maps.h"

namespace coopmap {
namespace {

using mission_test::freeAhead;
using mission_test::lookedAround;
using mission_test::quickFirstSortie;
using mission_test::quickLooks;
using mission_test::roomAndCorridor;

TEST(MissionTest, StopsForGoodAfterTooManyBumpsInASortie) {
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));  // the robot 1 m into it
  MissionConfig c;
  c.look_wait_s = 0.5;
  c.look_turn_rate = 1.5;
  c.max_sortie_bumps = 2;
  c.planner.seed = 7;
  MissionAgent mission(home, c);
  mission.startFrom(home, 0.0);  // the odometry frame is the map frame
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
    mission.startFrom(home, 0.0);  // the odometry frame is the map frame
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
  mission.startFrom(home, 0.0);  // the odometry frame is the map frame
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
// reached, leaves its frontier unseen, and exploration ends there: the frontiers are "looked
// from its goal before", and no full turn is taken at a goal.
TEST(MissionTest, EndsWhenEveryFrontierWasLookedAtFromItsGoal) {
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  MissionConfig c = quickLooks();
  c.retry_frontiers = true;  // reached goals are remembered (FrontierExplorer::markReached)
  c.planner.seed = 3;
  MissionAgent mission(home, c);
  mission.startFrom(home, 0.0);  // the odometry frame is the map frame
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
  EXPECT_TRUE(mission.explorationComplete());
  EXPECT_LT(longest, 1.1 * M_PI);
  const std::string reason = mission.lastEvent();
  EXPECT_NE(reason.find("exploration complete"), std::string::npos) << reason;
  EXPECT_NE(reason.find("looked from its goal before"), std::string::npos) << reason;
}

TEST(MissionTest, FrontiersLeftButOutOfReachThisSortieAreTriedAgainNextSortie) {
  // Something the map does not show stops every drive 2 s in (a bump: the goal is given up).
  // Once every frontier's goal has failed, frontiers are still left: that is the end of the
  // sortie, not of exploration. Home, and after the import (failed goals forgotten) they
  // are goals again. Goals reached and looked from are not: the robot saw what it could.
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  MissionConfig c = quickLooks();
  c.budget_m = 1000.0;
  c.budget_s = 1e5;
  c.max_sorties = 2;
  c.max_sortie_bumps = 1000;
  c.min_sortie_m = 1.0;
  c.retry_frontiers = true;
  c.planner.seed = 9;
  MissionAgent mission(home, c);
  mission.startFrom(home, 0.0);  // the odometry frame is the map frame
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

TEST(MissionTest, LooksAgainAtWhatClosesTheWayToAFrontierOnceAndGoesOnWhenItIsGone) {
  // The map holds the room's doorway shut (a person stood in it); the corridor beyond is seen,
  // its far end a frontier no goal of the room reaches. The robot drives to look at the doorway
  // from in the room and stands facing it. `clears`: the person has gone and the look shows it
  // (here: the map without the person from then on), and the frontier is the next goal; else
  // the blockage is not looked at twice and exploration ends there.
  auto run = [](bool clears) {
    const Pose2 home(1.0, 1.0, 0.0);
    const OccupancyGrid shut = roomAndCorridor(true), open = roomAndCorridor(false);
    MissionConfig c = quickLooks();
    c.planner.seed = 4;
    MissionAgent mission(home, c);
    mission.startFrom(home, 0.0);  // the odometry frame is the map frame
    Pose2 pose = home;
    const double dt = 0.05;
    int looks = 0;
    double standing = 0.0, longest_stand = 0.0;
    Pose2 stood_at = pose;
    bool looked = false;
    std::string last;
    for (int step = 0; step < 20000 && !mission.explorationComplete(); ++step) {
      const MotionCommand cmd =
          mission.update(step * dt, pose, looked && clears ? open : shut, nullptr);
      if (mission.lastEvent() != last) {
        last = mission.lastEvent();
        if (last.find("to look again") != std::string::npos) ++looks;
        if (looked && last.find("to frontier") != std::string::npos) break;
      }
      const bool still = cmd.linear == 0.0 && cmd.angular == 0.0;
      standing = still ? standing + dt : 0.0;
      if (looks > 0 && standing > longest_stand) {
        longest_stand = standing;
        stood_at = pose;
      }
      looked = looked || longest_stand > 5.0;
      pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
    }
    return std::make_tuple(looks, longest_stand, stood_at, last, mission.explorationComplete(),
                           mission.explorationGoal());
  };
  for (const bool clears : {false, true}) {
    SCOPED_TRACE(clears ? "the look clears the doorway" : "the doorway stays shut");
    const auto [looks, stood, at, last, complete, goal] = run(clears);
    EXPECT_EQ(looks, 1) << last;
    EXPECT_GT(stood, 9.0);  // long enough for the grid's evidence to turn
    EXPECT_LT(at.x, 2.95);  // in the room, facing the doorway from about 1.2 m
    EXPECT_NEAR(std::hypot(3.0 - at.x, 2.0 - at.y), 1.2, 0.4);
    EXPECT_LT(std::abs(std::remainder(at.theta - std::atan2(2.0 - at.y, 3.0 - at.x), 2 * M_PI)),
              0.35);
    if (clears) {
      EXPECT_FALSE(complete) << last;
      ASSERT_TRUE(goal.has_value()) << last;
      EXPECT_GT(goal->x(), 3.0);  // through the doorway
    } else {
      EXPECT_TRUE(complete) << last;
      EXPECT_NE(last.find("no reachable goal"), std::string::npos) << last;
    }
  }
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

// The cameras see something at the place the robot drives to look at a blockage from (the
// jamb it looks at, seen nearer; a person stepping by): the place is blocked now, but the look
// is not given up for it. The robot stands at the nearest place still free, facing the
// blockage, for the look's whole wait.
TEST(MissionTest, ALookWhosePlaceIsSeenBlockedIsTakenFromNearby) {
  const Pose2 home(1.0, 1.0, 0.0);
  const OccupancyGrid shut = roomAndCorridor(true);
  MissionConfig c = quickLooks();
  c.planner.seed = 4;
  c.recent_hits_s = 4.0;
  MissionAgent mission(home, c);
  mission.startFrom(home, 0.0);  // the odometry frame is the map frame
  Pose2 pose = home;
  const double dt = 0.05;
  std::optional<Eigen::Vector2d> place;  // the look's place, seen blocked
  int frames_seen = 0;
  double standing = 0.0, longest_stand = 0.0;
  Pose2 stood_at = pose;
  bool looking = false, nearby = false;
  std::string last;
  for (int step = 0; step < 20000 && !mission.explorationComplete(); ++step) {
    std::optional<RadialMap> scan;
    const std::optional<Eigen::Vector2d> goal = mission.explorationGoal();
    if (looking && goal && frames_seen < 3 && !nearby) {
      // Driving straight at the place, 0.6-1.0 m before it: the cameras see it blocked.
      const Eigen::Vector2d to = *goal - pose.translation();
      const double off = std::remainder(std::atan2(to.y(), to.x()) - pose.theta, 2.0 * M_PI);
      if (to.norm() > 0.6 && to.norm() < 1.0 && std::abs(off) < 0.05) {
        scan = aheadAt(to.norm());
        place = *goal;
        ++frames_seen;
      }
    }
    const MotionCommand cmd = mission.update(step * dt, pose, shut, scan ? &*scan : nullptr);
    if (mission.lastEvent() != last) {
      last = mission.lastEvent();
      looking = looking || last.find("to look again") != std::string::npos;
      nearby = nearby || last.find("looking from nearby") != std::string::npos;
    }
    const bool still = cmd.linear == 0.0 && cmd.angular == 0.0;
    standing = still ? standing + dt : 0.0;
    if (frames_seen > 0 && standing > longest_stand) {
      longest_stand = standing;
      stood_at = pose;
    }
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
  }
  ASSERT_TRUE(place.has_value()) << "the robot never drove straight at its look's place";
  EXPECT_TRUE(nearby) << last;
  EXPECT_GT(longest_stand, 9.0) << last;  // the look's whole wait
  const double from_place = (stood_at.translation() - *place).norm();
  EXPECT_GT(from_place, 0.1) << "stood where the cameras saw it blocked";
  EXPECT_LT(from_place, 0.8);
  EXPECT_LT(std::abs(std::remainder(stood_at.theta - std::atan2(2.0 - stood_at.y, 3.0 - stood_at.x),
                                    2 * M_PI)),
            0.35);  // facing the doorway
}

// Two robots converging from the sides see nothing of each other in their cameras: the one
// without priority stops while the teammate, at the speed it reports, would come within its
// disc; the one with priority drives on (here the teammate never yields: they meet).
TEST(MissionTest, WaitsForATeammateConvergingFromTheSide) {
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  auto closest = [&](bool priority, int* stops) {
    MissionConfig c = quickLooks();
    c.planner.seed = 4;
    MissionAgent mission(home, c);
    mission.startFrom(home, 0.0);  // the odometry frame is the map frame
    Pose2 pose = home;
    const double dt = 0.05;
    // Once the robot drives, the teammate sets off 1.2 m to its left, 1.2 m ahead of it, and
    // crosses its way at the robot's speed: both would reach the crossing together.
    std::optional<Eigen::Vector2d> start, velocity;
    double start_t = 0.0, nearest = 1e9;
    for (int step = 0; step < 1200; ++step) {
      const double t = step * dt;
      std::vector<Eigen::Vector2d> teammates;
      if (start) teammates.push_back(*start + (t - start_t) * *velocity);
      mission.setTeammates(teammates, priority);
      const MotionCommand cmd = mission.update(t, pose, map, nullptr);
      if (!start && mission.phase() == MissionPhase::kExplore && cmd.linear > 0.3) {
        const Eigen::Vector2d ahead(std::cos(pose.theta), std::sin(pose.theta));
        const Eigen::Vector2d left(-ahead.y(), ahead.x());
        const Eigen::Vector2d crossing = pose.translation() + 1.2 * ahead;
        start = crossing + 1.2 * left;
        velocity = -cmd.linear * left;
        start_t = t;
      }
      if (start && t - start_t < 8.0)
        nearest =
            std::min(nearest, (*start + (t - start_t) * *velocity - pose.translation()).norm());
      pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
    }
    *stops = mission.teamStops();
    return nearest;
  };
  // Nearer than this, the teammate is inside the disc the planning map draws for it.
  const MissionConfig c;
  const double disc = c.team_radius + c.planning.robot_radius;
  int stops = 0;
  const double yielding = closest(false, &stops);
  EXPECT_GT(yielding, disc);
  EXPECT_GE(stops, 1);
  // With priority only the teammate ahead, seen late, stops it.
  EXPECT_LT(closest(true, &stops), disc);
}

TEST(MissionTest, SlowsDownForWhatIsNearAhead) {
  // Cruise 0.4 m/s; an obstacle 0.65 m ahead, halfway between safety_distance (0.3 m) and
  // slow_distance (1 m), halves the speed; once it is gone, the robot speeds up again.
  const Pose2 home(2.0, 3.0, 0.0);
  const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
  MissionConfig c = quickLooks();
  c.safety_distance = 0.3;
  c.slow_distance = 1.0;
  c.planner.seed = 4;
  MissionAgent mission(home, c);
  mission.startFrom(home, 0.0);  // the odometry frame is the map frame
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

TEST(MissionTest, SpeedsUpNoFasterThanItsAccelerationLimitAndStopsAtOnce) {
  // Exploring open ground at 0.4 m/s; at 25 s something appears 0.2 m ahead (inside
  // safety_distance): the robot stops in one update, however gently it speeds up.
  auto run = [](double accel) {
    const Pose2 home(2.0, 3.0, 0.0);
    const OccupancyGrid map = lookedAround(Pose2(1.0, 3.0, 0.0));
    MissionConfig c = quickLooks();
    c.planner.seed = 4;
    c.max_linear_accel = accel;
    MissionAgent mission(home, c);
    mission.startFrom(home, 0.0);  // the odometry frame is the map frame
    Pose2 pose = home;
    const double dt = 0.05;
    double previous = 0.0, steepest = 0.0, fastest = 0.0, before_stop = 0.0, at_stop = -1.0;
    for (int step = 0; step < 600; ++step) {
      const double t = step * dt;
      const bool blocked = t >= 25.0;
      const RadialMap scan = aheadAt(blocked ? std::optional<double>(0.2) : std::nullopt);
      const MotionCommand cmd =
          mission.update(t, pose, map, step % 7 == 0 || blocked ? &scan : nullptr);
      steepest = std::max(steepest, (cmd.linear - previous) / dt);
      fastest = std::max(fastest, cmd.linear);
      if (!blocked) before_stop = cmd.linear;
      if (blocked && at_stop < 0.0) at_stop = cmd.linear;
      previous = cmd.linear;
      pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
    }
    return std::make_tuple(steepest, fastest, before_stop, at_stop);
  };
  const auto [steepest, fastest, before_stop, at_stop] = run(0.4);
  EXPECT_LE(steepest, 0.4 + 1e-9);
  EXPECT_NEAR(fastest, RouteConfig{}.linear_speed, 1e-9);  // it still gets to its cruise
  EXPECT_GT(before_stop, 0.2);
  EXPECT_EQ(at_stop, 0.0);
  // Without the limit the commands jump to cruise (the base's own profile smooths them).
  EXPECT_GT(std::get<0>(run(0.0)), 1.0);
  MissionConfig c;
  c.max_linear_accel = -0.1;
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
  mission.startFrom(home, 0.0);  // the odometry frame is the map frame
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

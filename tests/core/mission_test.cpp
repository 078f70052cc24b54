// The mission's driving, with a kinematic robot on maps with frontiers all around: the bump
// rule (every bump backs the robot off; bumped max_sortie_bumps times in a sortie, the robot
// stops for good: its wheels slipped, its odometry cannot be trusted), teammates converging
// from the side, speed near what the cameras see, what was just seen kept clear, and the
// settings' checks. Which frontiers it goes to and when it is done: mission_frontiers_test.cpp.
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

using mission_test::aheadAt;
using mission_test::freeAhead;
using mission_test::lookedAround;
using mission_test::quickFirstSortie;
using mission_test::quickLooks;

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

// A sortie that starts on a cell the planner will not start from (an obstacle 0.2 m from the
// robot's cell, the next cell over clear of it): the robot steps onto that free cell, 3 cm
// away (within the route's arrival tolerance), and plans to the frontier from there; it does not
// take itself for arrived where it stood and go home "on a blocked cell".
TEST(MissionTest, StepsOntoAFreeCellNearerThanTheArrivalTolerance) {
  const MapLimits lim = MapLimits::covering({0.0, 0.0}, {8.0, 6.0}, 0.05);
  const Eigen::Vector2d obstacle(1.825, 3.025);
  const OccupancyGrid map =
      mission_test::gridOf(lim, [&](const Eigen::Vector2d& c) -> std::optional<int16_t> {
        if (c.x() > 5.0) return std::nullopt;
        return (c - obstacle).norm() < 0.01 ? 1000 : -1000;
      });
  const Pose2 home(2.045, 3.03, 0.0);
  const Eigen::Vector2d free_cell(2.075, 3.025);
  MissionConfig c = quickLooks();
  c.planner.seed = 6;
  const PlanningMap planning(map, c.planning);
  ASSERT_FALSE(planning.freeAt(home.translation()));
  ASSERT_TRUE(planning.freeAt(free_cell));
  ASSERT_LT((free_cell - home.translation()).norm(), c.route.arrive_tolerance);
  MissionAgent mission(home, c);
  mission.startFrom(home, 0.0);  // the odometry frame is the map frame
  Pose2 pose = home;
  const double dt = 0.05;
  std::vector<std::string> events;
  for (int step = 0; step < 1200; ++step) {  // to the frontier, where the map ends
    const MotionCommand cmd = mission.update(step * dt, pose, map, nullptr);
    if (events.empty() || events.back() != mission.lastEvent())
      events.push_back(mission.lastEvent());
    if (mission.phase() != MissionPhase::kLookAtHome && mission.phase() != MissionPhase::kExplore)
      break;
    pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
  }
  std::string all;
  for (const std::string& e : events) all += e + "; ";
  EXPECT_NE(all.find("stepping off a blocked cell; to frontier"), std::string::npos) << all;
  EXPECT_EQ(all.find("on a blocked cell: going home"), std::string::npos) << all;
  EXPECT_GT((pose.translation() - home.translation()).norm(), 1.0) << all;
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

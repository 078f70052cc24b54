// The mission's frontier goals and the end of exploring, with a kinematic robot on maps
// with frontiers all around or a room shut off from its corridor: home to share when what is
// left is the teammates', done when every frontier was looked at from its goal, frontiers out
// of reach tried again next sortie, and the look at what closes the way to one.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/agent/mission.h"
#include "tests/core/mission_test_maps.h"
#include "tests/core/segment_world.h"

namespace coopmap {
namespace {

using mission_test::aheadAt;
using mission_test::lookedAround;
using mission_test::quickFirstSortie;
using mission_test::quickLooks;
using mission_test::roomAndCorridor;

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

// A teammate's goal is claimed while the teammate drives to it: one it has reached (it saw
// what it could from there) or turned from is no one's, and the frontiers near it are this
// robot's again (stale claims sent a robot home "own part explored" sortie after sortie).
TEST(MissionTest, ATeammatesGoalIsClaimedOnlyWhileItDrivesThere) {
  MissionAgent mission(Pose2(2.0, 3.0, 0.0), MissionConfig{});
  const Eigen::Vector2d first(1.0, 1.0), next(6.0, 5.0);
  mission.setTeammateGoals({first});
  ASSERT_EQ(mission.claimed().size(), 1u);
  mission.setTeammateGoals({next});
  ASSERT_EQ(mission.claimed().size(), 1u);
  EXPECT_EQ(mission.claimed().front(), next);
  mission.setTeammateGoals({});  // on its way home
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

// The map has the doorway open (seen through from many places), and from the room the
// cameras see something in it. What they have just seen closes the only way to the
// frontiers beyond; the map's way is driven all the same, stopping short of what was seen:
//  - seen only from farther than 1.3 m (a doorway's edge smeared into the opening when seen
//    from the side, gone from nearer): the robot goes through. Without driving the map's
//    way, every goal beyond is given up in turn.
//  - a textureless panel standing in the doorway, which the map does not hold, seen only
//    1.2-1.5 m off (where the floor ends before it): the robot stops short of it and never
//    touches it, though nearer the cameras no longer show it.
TEST(MissionTest, AWayClosedOnlyByWhatWasJustSeenIsDrivenByTheMap) {
  using test::Segment;
  const std::vector<Segment> walls = {{{0.0, 0.0}, {0.0, 4.0}},
                                      {{0.0, 0.0}, {3.0, 0.0}},
                                      {{0.0, 4.0}, {3.0, 4.0}},
                                      {{3.0, 0.0}, {3.0, 1.5}},
                                      {{3.0, 2.5}, {3.0, 4.0}}};
  const Segment in_doorway{{3.0, 1.5}, {3.0, 2.5}};
  std::vector<Segment> closed = walls;
  closed.push_back(in_doorway);
  const Eigen::Vector2d doorway(3.0, 2.0);
  for (const bool panel : {false, true}) {
    SCOPED_TRACE(panel ? "a panel in the doorway" : "the doorway seen closed from afar");
    const Pose2 home(1.0, 2.0, 0.0);
    const OccupancyGrid map = roomAndCorridor(false);
    MissionConfig c = quickLooks();
    c.planner.seed = 6;
    c.recent_hits_s = 4.0;
    MissionAgent mission(home, c);
    mission.startFrom(home, 0.0);  // the odometry frame is the map frame
    Pose2 pose = home;
    const double dt = 0.05;
    int closed_frames = 0;
    double farthest = pose.x, nearest_panel = 1e9;
    std::string last, events;
    for (int step = 0; step < 8000 && farthest < 3.6 && !mission.done(); ++step) {
      std::optional<RadialMap> scan;
      if (step % 7 == 0) {  // frames at 3 Hz
        const bool from_afar = (pose.translation() - doorway).norm() > 1.3;
        scan = test::cameraScan(pose, panel || from_afar ? closed : walls);
        if (panel) {
          const RadialMap open = test::cameraScan(pose, walls);
          for (size_t k = 0; k < scan->readings.size(); ++k) {
            RadialReading& r = scan->readings[k];
            const bool on_panel = r.range < open.readings[k].range - 1e-6;
            if (on_panel && (r.range < 1.2 || r.range > 1.5)) r.kind = RadialKind::kNone;
            closed_frames += on_panel && r.kind == RadialKind::kHit;
          }
        } else {
          closed_frames += from_afar;
        }
      }
      const MotionCommand cmd = mission.update(step * dt, pose, map, scan ? &*scan : nullptr);
      if (mission.lastEvent() != last) {
        last = mission.lastEvent();
        events += last + "; ";
      }
      pose = pose * Pose2(cmd.linear * dt, 0.0, cmd.angular * dt);
      farthest = std::max(farthest, pose.x);
      nearest_panel = std::min(nearest_panel, std::abs(3.0 - pose.x));
    }
    EXPECT_GE(closed_frames, 2) << "the doorway was never seen closed: " << events;
    EXPECT_NE(events.find("going on by the map"), std::string::npos) << events;
    if (panel) {
      // The body (its radius 0.178 m) never reaches the panel.
      EXPECT_GT(nearest_panel, c.planning.robot_radius + 0.05) << events;
    } else {
      EXPECT_GT(farthest, 3.6) << "never went through the doorway: " << events;
    }
  }
}

}  // namespace
}  // namespace coopmap

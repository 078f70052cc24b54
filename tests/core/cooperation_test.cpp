// The cooperation layer's guards: bad configuration, a sortie without radial maps, and a
// sortie that cannot be localized are reported and nothing reaches the shared map; the post
// gate finds the stretches of a corrected traverse that the shared map says are misplaced;
// closures to the shared map are found from the live estimate where the correction is far off.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/agent/cooperation.h"
#include "tests/core/segment_world.h"

namespace coopmap {
namespace {

HomeBase homeBase() {
  HomeBase h;
  h.first.position = {2.8, 0.8};
  h.first.heading = M_PI;
  h.second.position = {2.8, 2.2};
  h.second.heading = M_PI;
  return h;
}

MapLimits limits() { return MapLimits::covering({0, 0}, {10, 8}, 0.05); }

TEST(CooperationTest, BadConfigurationNamesTheField) {
  LocalSharedMap shared(limits(), OccupancyConfig{});
  // The message a configuration is refused with ("" when it is accepted).
  auto refusal = [&](const CooperationConfig& c) -> std::string {
    try {
      HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared, c);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  CooperationConfig c;
  c.max_fix_jump_m = 0.0;
  EXPECT_NE(refusal(c).find("max_fix_jump_m"), std::string::npos) << refusal(c);
  c = CooperationConfig{};
  c.post_gate_m = -0.1;
  EXPECT_NE(refusal(c).find("post_gate_m"), std::string::npos) << refusal(c);
  c = CooperationConfig{};
  c.manhattan_sigma_rad = -0.01;
  EXPECT_NE(refusal(c).find("manhattan_sigma_rad"), std::string::npos) << refusal(c);
  c = CooperationConfig{};
  c.manhattan_passes = 0;
  EXPECT_NE(refusal(c).find("'manhattan_passes': expected an integer >= 1, got 0"),
            std::string::npos)
      << refusal(c);
  c = CooperationConfig{};
  c.manhattan.bin_m = 0.0;
  EXPECT_NE(refusal(c).find("bin_m"), std::string::npos) << refusal(c);
  c = CooperationConfig{};
  c.closure_min_inliers = 1.5;
  EXPECT_NE(refusal(c).find("closure_min_inliers"), std::string::npos) << refusal(c);
  EXPECT_EQ(refusal(CooperationConfig{}), "");
  EXPECT_THROW(HomeBaseCooperation("jose", homeBase(), 0.6, nullptr), std::invalid_argument);
}

TEST(CooperationTest, EmptySortieIsReportedAndNothingIsPosted) {
  LocalSharedMap shared(limits(), OccupancyConfig{});
  HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared);
  TraverseLog log;
  log.robot = "jose";
  const SortieReport r = coop.endSortie(log);
  EXPECT_FALSE(r.fixed());
  EXPECT_FALSE(r.posted);
  EXPECT_EQ(r.sortie, 1);
  EXPECT_EQ(r.status, SortieStatus::kNoEntries) << r.method;
  EXPECT_EQ(shared.version(), 0u);
  EXPECT_EQ(coop.reports().size(), 1u);
  EXPECT_TRUE(coop.corrected().empty());
}

TEST(CooperationTest, SortieWithoutAHomeBaseInViewIsNotShared) {
  // A robot that turned in place in an empty world: no corners, no reference obstacles.
  LocalSharedMap shared(limits(), OccupancyConfig{});
  HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared);
  TraverseLog log;
  log.robot = "jose";
  for (int i = 0; i < 40; ++i) {
    TraverseEntry e;
    e.segment = MotionSegment::kTurn;
    e.scan.stamp = i / 3.0;
    e.scan.odometry = Pose2(1.5, 1.5, wrapAngle(i * 0.2));
    RadialReading miss;
    miss.kind = RadialKind::kBeyond;
    miss.range = 3.0;
    e.scan.readings.assign(20, miss);
    log.entries.push_back(e);
  }
  const SortieReport first = coop.locate(log).rep;
  EXPECT_FALSE(first.fixed());
  EXPECT_TRUE(coop.reports().empty()) << "locate records nothing";
  const SortieReport r = coop.endSortie(log);
  EXPECT_FALSE(r.fixed());
  EXPECT_FALSE(r.posted);
  EXPECT_EQ(shared.version(), 0u);
}

// A room with furniture for looks at home: the robot starts at (1.5, 1.5) facing +x.
std::vector<test::Segment> homeRoom() {
  return {{{0, 0}, {6, 0}},         {{6, 0}, {6, 4}},         {{6, 4}, {0, 4}},
          {{0, 4}, {0, 0}},         {{3.0, 0.6}, {3.4, 0.6}}, {{3.4, 0.6}, {3.4, 1.0}},
          {{3.0, 2.4}, {3.6, 2.0}}, {{1.0, 3.0}, {1.8, 3.2}}, {{4.5, 1.5}, {4.8, 1.2}}};
}

// A turn in place of a full circle (and a little more) at `at`, from `heading`.
void lookAround(TraverseLog& log, const Eigen::Vector2d& at, double heading, double& t) {
  for (int i = 0; i <= 66; ++i) {
    TraverseEntry e;
    e.segment = MotionSegment::kTurn;
    e.scan = test::cameraScan(Pose2(at.x(), at.y(), wrapAngle(heading + 0.1 * i)), homeRoom());
    e.scan.stamp = t += 1.0 / 3.0;
    log.entries.push_back(e);
  }
}

TEST(CooperationTest, ASortieThatNeverLeftHomeIsFixedOnItsOwnTurn) {
  // Sortie 1: still at the start, the look, out 1 m and back, the look again. Sortie 2:
  // the robot has nowhere left to go and only looks again where it stands. The scans of
  // the start's look go in front of sortie 2 for its localization; its turn must not reach
  // back into them (it stood where they were taken).
  LocalSharedMap shared(MapLimits::covering({-1, -1}, {7, 5}, 0.05), OccupancyConfig{});
  HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared);
  const Eigen::Vector2d home(1.5, 1.5);
  double t = 0.0;
  TraverseLog first;
  first.robot = "jose";
  for (int i = 0; i < 9; ++i) {
    TraverseEntry e;
    e.segment = MotionSegment::kStop;
    e.scan = test::cameraScan(Pose2(home.x(), home.y(), 0.0), homeRoom());
    e.scan.stamp = t += 1.0 / 3.0;
    first.entries.push_back(e);
  }
  lookAround(first, home, 0.0, t);
  for (int i = 1; i <= 20; ++i) {  // out and back along +x
    const double x = home.x() + (i <= 10 ? i : 20 - i) * 0.1;
    TraverseEntry e;
    e.segment = MotionSegment::kStraight;
    e.scan = test::cameraScan(Pose2(x, home.y(), i <= 10 ? 0.0 : M_PI), homeRoom());
    e.scan.stamp = t += 1.0 / 3.0;
    first.entries.push_back(e);
  }
  lookAround(first, home, M_PI, t);
  const SortieReport one = coop.endSortie(first);
  ASSERT_TRUE(one.fixed()) << one.method;
  TraverseLog second;
  second.robot = "jose";
  lookAround(second, home, wrapAngle(M_PI + 6.6), t);
  const SortieReport two = coop.endSortie(second);
  ASSERT_TRUE(two.fixed()) << two.method;
  EXPECT_GE(two.fix_stamp, second.entries.front().scan.stamp);
  EXPECT_LT((two.fix.translation() - home).norm(), 0.02);
  const Pose2* at = nullptr;
  for (const TraverseEntry& e : second.entries)
    if (e.scan.stamp == two.fix_stamp) at = &e.scan.odometry;
  ASSERT_NE(at, nullptr);
  EXPECT_LT(std::abs(wrapAngle(two.fix.theta - at->theta)), 0.5 * M_PI / 180.0);
}

TEST(CooperationTest, AFixThatOnlyTurnsTheRobotIsNotTakenForAMove) {
  // Sortie 1 registers the home base at (1.5, 1.5), 2.1 m from the map's origin. Sortie 2
  // looks again there on odometry that has the robot's position right and its heading 0.3
  // rad off (slip in turns). The fix turns the robot 0.3 rad and moves it nowhere; as a
  // correction about the map's origin it is a 0.63 m translation, which a 0.5 m bound on the
  // robot's move must not refuse.
  CooperationConfig config;
  config.max_fix_jump_m = 0.5;
  LocalSharedMap shared(MapLimits::covering({-1, -1}, {7, 5}, 0.05), OccupancyConfig{});
  HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared, config);
  const Eigen::Vector2d home(1.5, 1.5);
  double t = 0.0;
  TraverseLog first;
  first.robot = "jose";
  lookAround(first, home, 0.0, t);
  lookAround(first, home, 6.6, t);
  ASSERT_TRUE(coop.endSortie(first).fixed());
  TraverseLog second;
  second.robot = "jose";
  lookAround(second, home, 0.5, t);
  constexpr double kOff = 0.3;
  for (TraverseEntry& e : second.entries)
    e.scan.odometry.theta = wrapAngle(e.scan.odometry.theta + kOff);
  const SortieReport r = coop.locate(second).rep;
  ASSERT_TRUE(r.fixed()) << r.method;
  EXPECT_GT(r.correction.translation().norm(), config.max_fix_jump_m) << "the lever of the turn";
  EXPECT_LT((r.fix.translation() - home).norm(), 0.05);
  const Pose2* at = nullptr;
  for (const TraverseEntry& e : second.entries)
    if (e.scan.stamp == r.fix_stamp) at = &e.scan.odometry;
  ASSERT_NE(at, nullptr);
  EXPECT_NEAR(wrapAngle(r.fix.theta - at->theta), -kOff, 1.0 * M_PI / 180.0);

  // One that does move the robot more than the bound is refused (the home-base search keeps
  // to the bound around where the robot believes it is), and the report says why.
  TraverseLog third;
  third.robot = "jose";
  lookAround(third, home, 0.5, t);
  for (TraverseEntry& e : third.entries) e.scan.odometry.x += 0.7;
  const SortieReport far = coop.locate(third).rep;
  EXPECT_EQ(far.status, SortieStatus::kNotLocalized) << far.method;
  EXPECT_NE(far.method.find("farther than it can be off"), std::string::npos) << far.method;
}

// A 12 m x 2 m corridor with alcoves every 2 m on both sides (so that a stretch's alignment
// is pinned along it too), walls as segments; x along the corridor.
std::vector<test::Segment> corridor() {
  std::vector<test::Segment> w;
  for (int i = 0; i < 6; ++i) {
    const double x = 2.0 * i;
    for (const double y : {0.0, 2.0}) {
      const double out = y == 0.0 ? -0.4 : 2.4;
      w.push_back({{x, y}, {x + 1.4, y}});            // wall
      w.push_back({{x + 1.4, y}, {x + 1.4, out}});    // alcove
      w.push_back({{x + 1.4, out}, {x + 2.0, out}});  //
      w.push_back({{x + 2.0, out}, {x + 2.0, y}});    //
    }
  }
  return w;
}

// The shared map of the corridor, from scans at true poses along it looking four ways.
OccupancyGrid corridorMap(const std::vector<test::Segment>& world) {
  OccupancyGrid map(MapLimits::covering({-1, -1}, {13, 3}, 0.05), OccupancyConfig{});
  for (int i = 0; i <= 70; ++i)
    for (const double heading : {0.0, M_PI, M_PI / 2, -M_PI / 2}) {
      const Pose2 pose(0.5 + 0.1 * i, 1.0, heading);
      map.insert(test::cameraScan(pose, world), pose);
    }
  return map;
}

TEST(CooperationTest, PostGateFlagsTheStretchesTheMapSaysAreMisplaced) {
  // The shared map knows the corridor.
  const std::vector<test::Segment> world = corridor();
  const OccupancyGrid map = corridorMap(world);
  const ScanAligner aligner(map, AlignmentConfig{});
  // A traverse east along the corridor, 0.1 m a scan. Its correction placed entries 30-59
  // (x 3.5 - 6.4 m) 0.25 m too far north, the rest where they were. (Much farther off, a
  // stretch may not fit the map at all, and cannot be judged: it is posted.)
  TraverseLog log;
  log.robot = "jose";
  std::vector<Pose2> poses;
  for (int i = 0; i < 110; ++i) {
    const Pose2 truth(0.5 + 0.1 * i, 1.0, 0.0);
    TraverseEntry e;
    e.scan = test::cameraScan(truth, world);
    e.scan.stamp = i / 3.0;
    log.entries.push_back(e);
    poses.push_back(i >= 30 && i < 60 ? Pose2(truth.x, truth.y + 0.25, truth.theta) : truth);
  }
  const std::vector<bool> flagged = misplacedEntries(log, poses, aligner, 6, 0.7, 0.15, M_PI);
  ASSERT_EQ(flagged.size(), log.entries.size());
  int wrong_kept = 0, right_withheld = 0;
  for (int i = 0; i < 110; ++i) {
    const bool misplaced = i >= 30 && i < 60;
    wrong_kept += misplaced && !flagged[i];
    right_withheld += !misplaced && flagged[i];
  }
  EXPECT_EQ(wrong_kept, 0);
  EXPECT_EQ(right_withheld, 0);

  // A turn error shows as well: entries 60-71 turned 8 degrees about their middle.
  std::vector<Pose2> turned(poses.size());
  for (int i = 0; i < 110; ++i) turned[i] = log.entries[i].scan.odometry;
  const Pose2 pivot = turned[66];
  for (int i = 60; i < 72; ++i)
    turned[i] = pivot * Pose2(0, 0, 8.0 * M_PI / 180.0) * pivot.inverse() * turned[i];
  const std::vector<bool> by_turn = misplacedEntries(log, turned, aligner, 6, 0.7, 0.15, 0.05);
  for (int i = 0; i < 110; ++i) EXPECT_EQ(by_turn[i], i >= 60 && i < 72) << "entry " << i;
  // Off by less than the gate: nothing is withheld.
  std::vector<Pose2> nudged = poses;
  for (int i = 30; i < 60; ++i) nudged[i] = Pose2(poses[i].x, poses[i].y - 0.15, poses[i].theta);
  for (const bool f : misplacedEntries(log, nudged, aligner, 6, 0.7, 0.15, M_PI)) EXPECT_FALSE(f);
  EXPECT_THROW(misplacedEntries(log, {}, aligner, 6, 0.7, 0.15, M_PI), std::invalid_argument);
}

TEST(CooperationTest, ClosuresAlsoTryEachStretchWhereTheLiveEstimateHadIt) {
  // The shared map knows the corridor. A traverse east along it, on an odometry chain of its
  // own frame; the home-base correction left it 0.6 m north of the truth (too far for an
  // alignment to come back from), the live estimate 5 cm and half a degree off.
  const std::vector<test::Segment> world = corridor();
  const OccupancyGrid map = corridorMap(world);
  const ScanAligner aligner(map, AlignmentConfig{});
  const Pose2 chain_frame(3.0, -2.0, 0.7);  // where the odometry chain has the map's origin
  TraverseLog log;
  log.robot = "jose";
  std::vector<Pose2> truth, corrected, estimate;
  for (int i = 0; i < 90; ++i) {
    truth.emplace_back(0.5 + 0.1 * i, 1.0, 0.3 * std::sin(0.2 * i));
    TraverseEntry e;
    e.scan = test::cameraScan(truth.back(), world);
    e.scan.odometry = chain_frame * truth.back();
    e.scan.stamp = i / 3.0;
    log.entries.push_back(e);
    corrected.push_back(Pose2(0.0, 0.6, 0.0) * truth.back());
    estimate.push_back(Pose2(0.05, -0.03, 0.5 * M_PI / 180.0) * truth.back());
  }
  CooperationConfig config;
  EXPECT_TRUE(mapClosures(log, corrected, aligner, config, 0, 90).empty());
  const std::vector<PoseObservation> closures =
      mapClosures(log, corrected, aligner, config, 0, 90, &estimate);
  EXPECT_GE(closures.size(), 8u);
  for (const PoseObservation& o : closures) {
    const Pose2& t = truth[o.entry];
    EXPECT_LT((o.pose.translation() - t.translation()).norm(), 0.08) << "entry " << o.entry;
    EXPECT_LT(std::abs(wrapAngle(o.pose.theta - t.theta)), 1.0 * M_PI / 180.0)
        << "entry " << o.entry;
  }
  // Where the correction is right, the closures stay there (a stretch of six aligns within a
  // few centimetres).
  for (const PoseObservation& o : mapClosures(log, truth, aligner, config, 0, 90, &estimate))
    EXPECT_LT((o.pose.translation() - truth[o.entry].translation()).norm(), 0.08);
  const std::vector<Pose2> short_estimate(estimate.begin(), estimate.end() - 1);
  EXPECT_THROW(mapClosures(log, corrected, aligner, config, 0, 90, &short_estimate),
               std::invalid_argument);
}

TEST(CooperationTest, WallsGiveTheHeadingWhereTheEstimateHasDrifted) {
  // A traverse east along the corridor, looking ahead and 25 degrees to either side in turn,
  // on an estimate whose heading drifts by 0.25 degrees a metre and whose position follows it.
  const std::vector<test::Segment> world = corridor();
  TraverseLog log;
  log.robot = "jose";
  std::vector<Pose2> estimate;
  Pose2 drifted(0.5, 1.0, 0.0);
  for (int i = 0; i < 100; ++i) {
    const double look = (i / 6 % 3 - 1) * 25.0 * M_PI / 180.0;
    const Pose2 truth(0.5 + 0.1 * i, 1.0, look);
    TraverseEntry e;
    e.scan = test::cameraScan(truth, world);
    e.scan.stamp = i / 3.0;
    log.entries.push_back(e);
    const double error = 0.025 * i * M_PI / 180.0;
    if (i > 0)
      drifted = Pose2(drifted.x + 0.1 * std::cos(error), drifted.y + 0.1 * std::sin(error), 0.0);
    estimate.push_back(Pose2(drifted.x, drifted.y, wrapAngle(look + error)));
  }
  const std::vector<PoseObservation> headings = manhattanHeadings(log, estimate, 6, 9, 3.5, 0.01);
  EXPECT_GE(headings.size(), 8u);
  for (const PoseObservation& o : headings) {
    const double truth = log.entries[o.entry].scan.odometry.theta;
    const double drift = wrapAngle(estimate[o.entry].theta - truth);
    EXPECT_LT(std::abs(wrapAngle(o.pose.theta - truth)), 0.1 * M_PI / 180.0)
        << "entry " << o.entry << ", the estimate " << drift * 180.0 / M_PI << " deg off";
    EXPECT_EQ(o.pose.translation(), estimate[o.entry].translation());
    EXPECT_EQ(o.sigma_theta, 0.01);
    ASSERT_TRUE(o.xy_information.has_value());
    EXPECT_LT(o.xy_information->norm(), 1e-6);  // the position is left free
  }
  EXPECT_THROW(manhattanHeadings(log, {}, 6, 9, 3.5, 0.01), std::invalid_argument);
  EXPECT_THROW(manhattanHeadings(log, estimate, 0, 9, 3.5, 0.01), std::invalid_argument);
}

TEST(CooperationTest, RivalPlacementFindsWhereALookAtTwoAlikeCornersBelongs) {
  // A room with two alike bumps on its east wall, 1.4 m apart (the home base's corners):
  // from one of them, the other looks the same; the rest of the room tells them apart.
  std::vector<test::Segment> room = {
      {{0, -1}, {4, -1}}, {{4, -1}, {4, 5}}, {{4, 5}, {0, 5}}, {{0, 5}, {0, -1}}};
  for (const double y : {0.8, 2.2}) {
    room.push_back({{4.0, y - 0.2}, {3.7, y}});
    room.push_back({{3.7, y}, {4.0, y + 0.2}});
  }
  OccupancyGrid map(MapLimits::covering({-1, -2}, {5, 6}, 0.05), OccupancyConfig{});
  for (int i = 0; i < 5; ++i)
    for (int h = 0; h < 8; ++h) {
      const Pose2 pose(0.8 + 0.6 * i, 0.5 + 0.5 * i, h * M_PI / 4);
      map.insert(test::cameraScan(pose, room), pose);
    }
  const ScanAligner aligner(map, AlignmentConfig{});
  // The look: turning in place at (2.0, 1.5), placed 1.4 m too far north by a wrong fix.
  std::vector<RadialMap> look;
  for (int h = 0; h < 12; ++h)
    look.push_back(test::cameraScan(Pose2(2.0, 1.5, h * M_PI / 6), room));
  std::vector<const RadialMap*> pointers;
  for (const RadialMap& m : look) pointers.push_back(&m);
  const std::vector<Eigen::Vector2d> truth = aligner.obstaclePoints(pointers);
  std::vector<Eigen::Vector2d> wrong;
  for (const Eigen::Vector2d& p : truth) wrong.push_back(p + Eigen::Vector2d(0.0, 1.4));
  const Eigen::Vector2d fix(2.0, 2.9);
  const RivalPlacement r = rivalPlacement(aligner, wrong, fix, 2.0, 0.5, 4.0 * M_PI / 180.0);
  EXPECT_GT(r.score, r.here + 0.3) << "here " << r.here << ", there " << r.score;
  EXPECT_NEAR(r.correction.x, 0.0, 0.06);
  EXPECT_NEAR(r.correction.y, -1.4, 0.06);
  EXPECT_NEAR(r.correction.theta, 0.0, 1.01 * M_PI / 180.0);
  // Placed right, nothing else fits as well.
  const RivalPlacement right =
      rivalPlacement(aligner, truth, {2.0, 1.5}, 2.0, 0.5, 4.0 * M_PI / 180.0);
  EXPECT_GT(right.here, 0.9);
  EXPECT_LT(right.score, right.here);
  // The rival check's configuration is checked.
  LocalSharedMap shared(limits(), OccupancyConfig{});
  CooperationConfig c;
  c.rival_min_shift_m = 3.0;
  try {
    HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared, c);
    ADD_FAILURE() << "a minimum shift beyond the search radius was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rival_min_shift_m"), std::string::npos) << e.what();
  }
  c.rival_search_m = 0.0;  // off: the shift does not matter
  EXPECT_NO_THROW(HomeBaseCooperation("jose", homeBase(), 0.6, &shared, c));
}

}  // namespace
}  // namespace coopmap

// People who wait for robots: a person pauses while a robot stands ahead of them and near,
// walks on when it has gone, pushes through only if told never to wait; contacts with people
// are counted apart from contacts with the static world; ground truth shows people where
// they actually stand; runs repeat bit for bit.
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "robots/robot_model.h"
#include "sim/simulator.h"
#include "sim/world/ground_truth.h"

namespace coopmap::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// A person walking +x along y = 0 from x = -6 to x = 6 at 1 m/s from t = 0.
PersonSpec walker(double yield_distance, bool loop = false) {
  PersonSpec p;
  p.name = "ann";
  p.radius = 0.25;
  p.speed = 1.0;
  p.loop = loop;
  p.yield_distance = yield_distance;
  p.path = {{-6.0, 0.0}, {6.0, 0.0}};
  return p;
}

// An open floor (nothing static to touch) with the given people.
World openWorld(std::vector<PersonSpec> people) {
  World w;
  w.floor_min = {-10, -10};
  w.floor_max = {10, 10};
  TextureSpec t;
  t.name = "carpet";
  w.textures["carpet"] = t;
  w.floor_texture = "carpet";
  w.people = std::move(people);
  return w;
}

// A B-14 (perfect odometry) standing at the origin facing +y, across the person's path.
struct Fixture {
  Simulator sim;
  double robot_radius = 0.0;
  double min_gap = 1e9;  // smallest person-robot centre distance seen, m
  Fixture(std::vector<PersonSpec> people, uint64_t seed = 5) : sim(openWorld(people), seed) {
    RobotModel m = loadRobotModel(std::string(COOPMAP_SOURCE_DIR) + "/robots/b14/b14.yaml");
    m.odometry.perfect = true;
    robot_radius = m.description.body_radius;
    RobotSpec spec;
    spec.name = "r";
    spec.start = {0.0, 0.0, M_PI / 2};
    sim.addRobot(spec, {m.description, m.drive, m.odometry, {}});
  }
  // Advances `seconds` in 20 ms steps, keeping the smallest gap to person 0.
  void run(double seconds) {
    for (int i = 0; i < std::lround(seconds / 0.02); ++i) {
      sim.advance(0.02);
      const Eigen::Vector2d robot = sim.truePose(0).translation();
      min_gap = std::min(min_gap, (sim.personPositions().at(0) - robot).norm());
    }
  }
};

TEST(PersonYieldTest, YieldsOnlyToARobotAheadAndNear) {
  const PersonSpec p = walker(1.0);
  const double r = 0.2;
  const double reach = 1.0 + 0.25 + r;
  // At walked 2 s the person is at (-4, 0) walking +x.
  const Eigen::Vector2d at(-4.0, 0.0);
  ASSERT_TRUE(p.positionAtWalked(2.0).isApprox(at));
  const auto robotAt = [&](double dist, double deg) {
    return Eigen::Vector2d(at + dist * Eigen::Vector2d(std::cos(deg * kDeg), std::sin(deg * kDeg)));
  };
  EXPECT_TRUE(p.yieldsTo(2.0, robotAt(reach - 0.01, 0), r));
  EXPECT_FALSE(p.yieldsTo(2.0, robotAt(reach + 0.01, 0), r));
  EXPECT_TRUE(p.yieldsTo(2.0, robotAt(1.0, 74), r));
  EXPECT_TRUE(p.yieldsTo(2.0, robotAt(1.0, -74), r));
  EXPECT_FALSE(p.yieldsTo(2.0, robotAt(1.0, 76), r));
  EXPECT_FALSE(p.yieldsTo(2.0, robotAt(0.5, 180), r));  // behind
  EXPECT_FALSE(walker(0.0).yieldsTo(2.0, robotAt(0.5, 0), r));
  // At the end of a path that does not loop the person stands: nothing to wait for.
  EXPECT_FALSE(p.yieldsTo(20.0, Eigen::Vector2d(6.5, 0.0), r));
}

TEST(PersonYieldTest, WalkingDirectionIsTheCurrentSegments) {
  PersonSpec p;
  p.speed = 1.0;
  p.loop = true;
  p.path = {{1, 1}, {4, 1}, {4, 3}};
  const PersonSpec::Place a = p.placeAtWalked(1.0);
  EXPECT_TRUE(a.position.isApprox(Eigen::Vector2d(2, 1)));
  EXPECT_TRUE(a.direction.isApprox(Eigen::Vector2d(1, 0)));
  const PersonSpec::Place b = p.placeAtWalked(4.0);
  EXPECT_TRUE(b.position.isApprox(Eigen::Vector2d(4, 2)));
  EXPECT_TRUE(b.direction.isApprox(Eigen::Vector2d(0, 1)));
  // On the closing segment back to the start, 1 m past (4, 3).
  const Eigen::Vector2d home = Eigen::Vector2d(-3, -2).normalized();
  const PersonSpec::Place c = p.placeAtWalked(6.0);
  EXPECT_TRUE(c.position.isApprox(Eigen::Vector2d(4, 3) + home));
  EXPECT_TRUE(c.direction.isApprox(home));
  p.loop = false;
  EXPECT_TRUE(p.placeAtWalked(60.0).direction.isZero());
  EXPECT_EQ(p.placeAtWalked(60.0).position, Eigen::Vector2d(4, 3));
}

TEST(PersonYieldTest, WaitsForAStandingRobotThenWalksOnWhenItDrivesOff) {
  Fixture f({walker(1.0)});
  const double reach = 1.0 + 0.25 + f.robot_radius;
  f.run(10.0);
  // Unhindered, the person would be at x = 4 by now; they wait just outside their reach.
  const Eigen::Vector2d waiting = f.sim.personPositions()[0];
  EXPECT_TRUE(f.sim.personYielding(0));
  EXPECT_NEAR(waiting.x(), -reach, 0.02);
  EXPECT_NEAR(waiting.y(), 0.0, 1e-12);
  EXPECT_GE(f.min_gap, reach - 0.02);
  EXPECT_LT(f.sim.truePose(0).translation().norm(), 1e-3);  // nobody pushed the robot
  // Still waiting a few seconds on.
  f.run(3.0);
  EXPECT_EQ(f.sim.personPositions()[0], waiting);

  // The robot drives 2 m off the path (+y); the person walks on to the path's end.
  f.sim.command(0, MotionCommand::straight(2.0));
  f.run(15.0);
  EXPECT_NEAR(f.sim.truePose(0).y, 2.0, 0.05);
  EXPECT_FALSE(f.sim.personYielding(0));
  EXPECT_TRUE(f.sim.personPositions()[0].isApprox(Eigen::Vector2d(6.0, 0.0)));
  EXPECT_GE(f.min_gap, 0.25 + f.robot_radius);
  const ContactCounts c = f.sim.contactCounts(0);
  EXPECT_EQ(c.people, 0);
  EXPECT_EQ(c.static_world, 0);
  EXPECT_EQ(f.sim.status(0).contact_events, 0);
}

TEST(PersonYieldTest, RobotBehindDoesNotStopThePerson) {
  // Starts 0.6 m ahead of the robot and walks away from it: never waits.
  PersonSpec p = walker(1.0);
  p.path = {{0.6, 0.0}, {8.0, 0.0}};
  Fixture f({p});
  for (int i = 0; i < 50; ++i) {
    f.run(0.1);
    EXPECT_EQ(f.sim.personPositions()[0], p.positionAt(f.sim.time()));
  }
}

TEST(PersonYieldTest, PersonWhoNeverYieldsPushesThrough) {
  Fixture f({walker(0.0)});
  f.run(14.0);
  EXPECT_TRUE(f.sim.personPositions()[0].isApprox(Eigen::Vector2d(6.0, 0.0)));
  EXPECT_LT(f.min_gap, 0.25 + f.robot_radius);
  EXPECT_GT(f.sim.truePose(0).translation().norm(), 0.1);  // pushed aside
  const ContactCounts c = f.sim.contactCounts(0);
  EXPECT_GE(c.people, 1);
  EXPECT_EQ(c.static_world, 0);
  EXPECT_EQ(c.robots, 0);
  EXPECT_GE(f.sim.status(0).contact_events, c.people);
}

// No people; one wall along y = 1 from x = -2 to 2.
World wallAcrossAtYOne() {
  World w = openWorld({});
  WallSpec wall;
  wall.from = {-2.0, 1.0};
  wall.to = {2.0, 1.0};
  wall.texture = "carpet";
  w.walls.push_back(wall);
  return w;
}

TEST(PersonYieldTest, WallContactsAreCountedApartFromPeople) {
  const World w = wallAcrossAtYOne();
  const WallSpec& wall = w.walls[0];
  Simulator sim(w, 5);
  RobotModel m = loadRobotModel(std::string(COOPMAP_SOURCE_DIR) + "/robots/b14/b14.yaml");
  RobotSpec spec;
  spec.name = "r";
  spec.start = {0.0, 0.0, M_PI / 2};
  sim.addRobot(spec, {m.description, m.drive, m.odometry, {}});
  sim.command(0, {0.3, 0.0});  // into the wall 0.95 m ahead
  sim.advance(6.0);
  const ContactCounts c = sim.contactCounts(0);
  EXPECT_EQ(c.static_world, 1);
  EXPECT_EQ(c.people, 0);
  EXPECT_EQ(sim.status(0).contact_events, 1);
  // The log says when and where: on the wall's near face (y = 1 - thickness / 2), ahead of
  // the robot, once it has driven the ~0.7 m between its front and the wall.
  const std::vector<ContactEvent>& log = sim.contactLog(0);
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0].kind, ContactEvent::Kind::kStaticWorld);
  EXPECT_STREQ(toString(log[0].kind), "static_world");
  EXPECT_NEAR(log[0].point.y(), 1.0 - 0.5 * wall.thickness, 0.02);
  EXPECT_NEAR(log[0].point.x(), 0.0, 0.1);
  EXPECT_GT(log[0].time, 2.0);
  EXPECT_LT(log[0].time, 6.0);
}

// The bump panels say where the base is touched: a wall met head-on is ahead (bearing 0), one
// backed into is behind (pi), one the robot turns into on its left is on its left front.
TEST(PersonYieldTest, TheBumpPanelSaysWhereTheBaseIsTouched) {
  const World w = wallAcrossAtYOne();
  const RobotModel m = loadRobotModel(std::string(COOPMAP_SOURCE_DIR) + "/robots/b14/b14.yaml");
  const struct {
    Pose2 start;
    MotionCommand cmd;
    double lo, hi;  // rad, robot frame: where the touch must be
  } cases[] = {{{0.0, 0.0, M_PI / 2}, {0.3, 0.0}, -0.2, 0.2},
               {{0.0, 0.0, -M_PI / 2}, {-0.3, 0.0}, M_PI - 0.2, M_PI + 0.2},
               {{0.0, 0.6, 0.0}, {0.2, 0.6}, 0.2, M_PI / 2 + 0.2}};
  for (const auto& c : cases) {
    Simulator sim(w, 5);
    RobotSpec spec;
    spec.name = "r";
    spec.start = c.start;
    sim.addRobot(spec, {m.description, m.drive, m.odometry, {}});
    EXPECT_FALSE(sim.status(0).bump_bearing) << "touching nothing at the start";
    sim.command(0, c.cmd);
    std::optional<double> bearing;
    for (int i = 0; i < 120 && !bearing; ++i) {
      sim.advance(0.05);
      bearing = sim.status(0).bump_bearing;
    }
    ASSERT_TRUE(bearing) << "never touched the wall, command " << c.cmd.linear;
    EXPECT_TRUE(sim.status(0).bumped);
    const double b = *bearing < c.lo ? *bearing + 2.0 * M_PI : *bearing;  // into [lo, lo + 2pi)
    EXPECT_GE(b, c.lo) << "command " << c.cmd.linear << ", " << c.cmd.angular;
    EXPECT_LE(b, c.hi) << "command " << c.cmd.linear << ", " << c.cmd.angular;
  }
}

// Two walkers on a loop cross a robot that drives back and forth across their path; the
// same seed gives the same positions, step for step.
std::vector<Eigen::Vector2d> crossingRun(uint64_t seed, int* waits) {
  PersonSpec a = walker(1.0, true);
  a.path = {{-5.0, 0.0}, {5.0, 0.0}, {5.0, 0.4}, {-5.0, 0.4}};
  PersonSpec b = walker(1.0, true);
  b.name = "bob";
  b.speed = 0.8;
  b.start_time = 2.0;
  b.path = {{4.0, -0.3}, {-4.0, -0.3}};
  Fixture f({a, b}, seed);
  f.sim.command(0, {0.3, 0.5});
  std::vector<Eigen::Vector2d> out;
  *waits = 0;
  for (int i = 0; i < 400; ++i) {
    if (i == 150) f.sim.command(0, {-0.3, -0.4});
    f.sim.advance(0.05);
    for (const Eigen::Vector2d& p : f.sim.personPositions()) out.push_back(p);
    *waits += f.sim.personYielding(0) + f.sim.personYielding(1);
  }
  return out;
}

TEST(PersonYieldTest, SameSeedSamePersonPositions) {
  int waits_a = 0, waits_b = 0;
  const std::vector<Eigen::Vector2d> a = crossingRun(11, &waits_a);
  const std::vector<Eigen::Vector2d> b = crossingRun(11, &waits_b);
  EXPECT_GT(waits_a, 0);  // the run does make people wait
  EXPECT_EQ(waits_a, waits_b);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "sample " << i;
}

TEST(PersonYieldTest, GroundTruthShowsAWaitingPersonWhereTheyStand) {
  Fixture f({walker(1.0)});
  f.run(8.0);
  ASSERT_TRUE(f.sim.personYielding(0));
  const World& w = f.sim.world();
  const MapLimits lim = worldMapLimits(w, 0.0);
  const Eigen::Vector2d stands = f.sim.personPositions()[0];
  const Eigen::Vector2d scheduled = w.people[0].positionAt(f.sim.time());  // (2, 0)
  ASSERT_GT((stands - scheduled).norm(), 3.0);
  const GridU8 g = trueOccupancyAt(w, lim, 1.0, f.sim.time(), f.sim.personPositions());
  EXPECT_EQ(g.at(lim.cellX(stands.x()), lim.cellY(stands.y())), 1);
  EXPECT_EQ(g.at(lim.cellX(stands.x() + 0.2), lim.cellY(stands.y())), 1);
  EXPECT_EQ(g.at(lim.cellX(scheduled.x()), lim.cellY(scheduled.y())), 0);
  // Without positions: the schedule's place (nobody waited).
  const GridU8 s = trueOccupancyAt(w, lim, 1.0, f.sim.time());
  EXPECT_EQ(s.at(lim.cellX(scheduled.x()), lim.cellY(scheduled.y())), 1);
  EXPECT_EQ(s.at(lim.cellX(stands.x()), lim.cellY(stands.y())), 0);
}

TEST(PersonYieldTest, GroundTruthWantsOnePositionPerPerson) {
  const World w = openWorld({walker(1.0)});
  try {
    trueOccupancyAt(w, worldMapLimits(w, 0.0), 1.0, 0.0, std::vector<Eigen::Vector2d>{});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "trueOccupancyAt: 0 person positions for the world's 1 people");
  }
}

}  // namespace
}  // namespace coopmap::sim

// The CARMEN log driver: playback by timestamps, odometry, laser mounts; and the whole range
// path (log -> driver -> radial maps -> occupancy grid -> corners) on a log written here of
// a robot driving around a rectangular room, its ranges ray-cast against the true walls.
#include "robots/carmen/carmen_log_robot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/atomic_file.h"
#include "core/mapping/map_metrics.h"
#include "robots/carmen/carmen_mapping.h"

namespace coopmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(CarmenLogRobotTest, PlaysScansInOrderAndInterpolatesOdometry) {
  const CarmenLog log = parseCarmenLog(
      "ODOM 0 0 0 0 0 0 10.0 h 10.0\n"
      "ODOM 1 0 0.2 0 0 0 11.0 h 11.0\n"
      "RAWLASER1 0 -1.5 3.0 1.5 8.0 0.02 0 3 1 2 9 0 10.5 h 10.5\n"
      "ODOM 2 1 -0.2 0 0 0 12.0 h 12.0\n"
      "RAWLASER1 0 -1.5 3.0 1.5 8.0 0.02 0 3 3 2 1 0 11.75 h 11.75\n",
      "t.log");
  CarmenLogRobot robot(log);
  RobotInterface& r = robot;
  EXPECT_EQ(robot.laser(), 1);
  EXPECT_EQ(robot.scanCount(), 2);
  EXPECT_DOUBLE_EQ(r.now(), 10.0);
  EXPECT_DOUBLE_EQ(r.odometry().x, 0.0);
  EXPECT_FALSE(r.captureFrame().has_value());

  const std::optional<RangeScan> a = r.captureScan();
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(a->stamp, 10.5);
  EXPECT_DOUBLE_EQ(r.now(), 10.5);  // the clock moved to the scan
  EXPECT_NEAR(a->odometry.x, 0.5, 1e-12);
  EXPECT_NEAR(a->odometry.theta, 0.1, 1e-12);
  EXPECT_NEAR(r.odometry().x, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(a->start_angle, -1.5);
  EXPECT_DOUBLE_EQ(a->angular_resolution, 1.5);
  EXPECT_DOUBLE_EQ(a->max_range, 8.0);
  EXPECT_DOUBLE_EQ(a->range_sigma, 0.02);
  EXPECT_EQ(a->ranges, (std::vector<float>{1, 2, 9}));
  EXPECT_EQ(a->sensor_origin, Eigen::Vector2d::Zero());

  r.command(MotionCommand::straight(5.0));  // a log cannot be steered
  EXPECT_NEAR(r.odometry().x, 0.5, 1e-12);
  EXPECT_FALSE(r.status().bumped);

  const std::optional<RangeScan> b = r.captureScan();
  ASSERT_TRUE(b.has_value());
  EXPECT_NEAR(b->odometry.x, 1.75, 1e-12);
  EXPECT_NEAR(b->odometry.y, 0.75, 1e-12);
  EXPECT_NEAR(b->odometry.theta, -0.1, 1e-12);
  EXPECT_FALSE(r.captureScan().has_value());
  EXPECT_EQ(robot.scansLeft(), 0);
  robot.advanceTo(20.0);
  EXPECT_DOUBLE_EQ(r.now(), 20.0);
  EXPECT_DOUBLE_EQ(r.odometry().x, 2.0);  // after the log: its last pose
  robot.advanceTo(15.0);
  EXPECT_DOUBLE_EQ(r.now(), 20.0);  // never back
}

TEST(CarmenLogRobotTest, HeadingInterpolatesAcrossTheWrap) {
  CarmenLogRobot robot(
      parseCarmenLog("ODOM 0 0 3.1 0 0 0 1.0 h 1.0\n"
                     "ODOM 0 0 -3.1 0 0 0 2.0 h 2.0\n"
                     "FLASER 1 1 0 0 0 0 0 0 1.5 h 1.5\n",
                     "t.log"));
  EXPECT_NEAR(std::abs(robot.odometryAt(1.5).theta), M_PI, 1e-9);
}

TEST(CarmenLogRobotTest, LaserMountsFromParamsAndRobotLaser) {
  // FLASER: the robot's odometry pose from the message, the mount from the PARAMs.
  CarmenLogRobot front(parseCarmenLog(
      "PARAM robot_frontlaser_offset 0.2 h 0\n"
      "PARAM robot_frontlaser_side_offset -0.05 h 0\n"
      "FLASER 181" +
          [] {
            std::string s;
            for (int i = 0; i < 181; ++i) s += " 1";
            return s;
          }() +
          " 9 9 9 1 2 0.3 1.0 h 1.0\n",
      "f.log"));
  const RangeScan f = *front.captureScan();
  EXPECT_EQ(f.sensor_origin, Eigen::Vector2d(0.2, -0.05));
  EXPECT_NEAR(f.start_angle, -M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(f.odometry.x, 1.0);
  EXPECT_DOUBLE_EQ(f.odometry.theta, 0.3);
  EXPECT_DOUBLE_EQ(f.max_range, 80.0);

  // ROBOTLASER: the mount from its laser and robot poses (laser 0.3 m ahead, turned 0.1 rad).
  const double c = std::cos(0.5), s = std::sin(0.5);
  char line[256];
  std::snprintf(line, sizeof line,
                "ROBOTLASER1 0 -1.5 3.0 1.5 8.0 0.01 0 3 1 2 3 0 %.9f %.9f 0.6 1.0 2.0 0.5 0 "
                "0 0 0 0 1.0 h 1.0\n",
                1.0 + 0.3 * c, 2.0 + 0.3 * s);
  CarmenLogRobot robot_laser(parseCarmenLog(line, "r.log"));
  const RangeScan rl = *robot_laser.captureScan();
  EXPECT_NEAR(rl.sensor_origin.x(), 0.3, 1e-9);
  EXPECT_NEAR(rl.sensor_origin.y(), 0.0, 1e-9);
  EXPECT_NEAR(rl.start_angle, -1.5 + 0.1, 1e-9);
  EXPECT_DOUBLE_EQ(rl.odometry.theta, 0.5);

  // The rear laser faces backwards; a configured mount overrides the log's.
  CarmenLogRobot rear(parseCarmenLog("RLASER 3 1 1 1 0 0 0 0 0 0 1.0 h 1.0\n", "b.log"));
  EXPECT_NEAR(rear.captureScan()->start_angle, M_PI / 2, 1e-12);
  CarmenRobotConfig config;
  config.mount = Pose2(0.1, 0.0, 0.0);
  config.range_sigma = 0.05;
  CarmenLogRobot mounted(parseCarmenLog("RLASER 3 1 1 1 0 0 0 0 0 0 1.0 h 1.0\n", "b.log"), config);
  const RangeScan m = *mounted.captureScan();
  EXPECT_NEAR(m.start_angle, -M_PI / 2, 1e-12);
  EXPECT_EQ(m.sensor_origin, Eigen::Vector2d(0.1, 0.0));
  EXPECT_DOUBLE_EQ(m.range_sigma, 0.05);
}

TEST(CarmenLogRobotTest, ChoosesTheLaserAndRejectsLogsItCannotPlay) {
  const std::string two =
      "RAWLASER3 0 -1.5 3.0 1.5 8.0 0.01 0 1 1 0 1.0 h 1.0\n"
      "RAWLASER2 0 -1.5 3.0 1.5 8.0 0.01 0 1 1 0 1.0 h 1.0\n"
      "ODOM 0 0 0 0 0 0 1.0 h 1.0\n";
  EXPECT_EQ(CarmenLogRobot(parseCarmenLog(two, "t.log")).laser(), 2);
  CarmenRobotConfig config;
  config.laser = 3;
  EXPECT_EQ(CarmenLogRobot(parseCarmenLog(two, "t.log"), config).laser(), 3);

  auto error = [](const std::string& text, const CarmenRobotConfig& c) -> std::string {
    try {
      CarmenLogRobot robot(parseCarmenLog(text, "t.log"), c);
    } catch (const CarmenLogError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(error("ODOM 0 0 0 0 0 0 1.0 h 1.0\n", {}),
            "t.log: no laser scans (FLASER, RLASER, RAWLASER1-4 or ROBOTLASER1-2 lines)");
  config.laser = 4;
  EXPECT_EQ(error(two, config), "t.log: no scans of laser 4");
  EXPECT_EQ(error("# no odometry\nRAWLASER1 0 -1.5 3.0 1.5 8.0 0.01 0 1 1 0 1.0 h 1.0\n", {}),
            "t.log:2: RAWLASER1 has no odometry and the log has no ODOM lines");
}

// ---- The room: a robot drives a loop inside a 6 m x 4 m room with a front laser. ----

struct RoomLog {
  Eigen::Vector2d origin{0.0, 0.0};  // the room's lower-left inner corner (m)
  double width = 6.0, height = 4.0;  // inner walls at origin + (0 or width, 0 or height)
  std::string text;
  int scans = 0;
};

// Distance from p along heading a to the room's walls.
double castRay(const RoomLog& room, const Eigen::Vector2d& p, double a) {
  const Eigen::Vector2d q = p - room.origin;
  const double dx = std::cos(a), dy = std::sin(a);
  double t = INFINITY;
  if (dx > 1e-12) t = std::min(t, (room.width - q.x()) / dx);
  if (dx < -1e-12) t = std::min(t, -q.x() / dx);
  if (dy > 1e-12) t = std::min(t, (room.height - q.y()) / dy);
  if (dy < -1e-12) t = std::min(t, -q.y() / dy);
  return t;
}

// ODOM at every step; a scan between steps from the pose interpolated there: FLASER (181
// beams, 1 degree) on the first half of the loop, RAWLASER1 (361 beams, 0.5 degree, 5 m
// maximum: farther walls give "no return") on the second. Ranges have 1 cm noise.
RoomLog writeRoomLog(const Eigen::Vector2d& origin) {
  RoomLog room;
  room.origin = origin;
  const double laser_offset = 0.15;
  std::vector<Pose2> poses{Pose2(origin.x() + 1.2, origin.y() + 1.0, 0.0)};
  std::vector<Eigen::Vector2d> corners{{4.8, 1.0}, {4.8, 3.0}, {1.2, 3.0}, {1.2, 1.0}};
  for (Eigen::Vector2d& c : corners) c += origin;
  for (const Eigen::Vector2d& target : corners) {
    const Pose2 start = poses.back();
    const Eigen::Vector2d d = target - start.translation();
    const int steps = static_cast<int>(std::lround(d.norm() / 0.1));
    for (int i = 1; i <= steps; ++i) {
      const Eigen::Vector2d p = start.translation() + d * (static_cast<double>(i) / steps);
      poses.emplace_back(p.x(), p.y(), start.theta);
    }
    for (int k = 1; k <= 9; ++k)  // turn left 90 degrees in place
      poses.emplace_back(target.x(), target.y(), wrapAngle(start.theta + k * 10.0 * kDeg));
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::string& out = room.text;
  out += "# CARMEN Logfile\n# written by carmen_log_robot_test: a loop in a 6 x 4 m room\n";
  out += "PARAM robot_frontlaser_offset 0.15 nohost 0.0\n";
  char buf[64];
  for (size_t i = 0; i < poses.size(); ++i) {
    const double t = 100.0 + 0.2 * static_cast<double>(i);
    const Pose2& p = poses[i];
    std::snprintf(buf, sizeof buf, "ODOM %.6f %.6f %.6f 0.5 0 0 %.3f robot %.3f\n", p.x, p.y,
                  p.theta, t, t + 0.001);
    out += buf;
    if (i + 1 == poses.size()) break;
    const Pose2& q = poses[i + 1];  // the scan halfway to the next pose
    const Pose2 X_WR(0.5 * (p.x + q.x), 0.5 * (p.y + q.y),
                     wrapAngle(p.theta + 0.5 * wrapAngle(q.theta - p.theta)));
    const Eigen::Vector2d origin = X_WR * Eigen::Vector2d(laser_offset, 0.0);
    const bool flaser = i < poses.size() / 2;
    const int beams = flaser ? 181 : 361;
    const double step = flaser ? 1.0 * kDeg : 0.5 * kDeg, max_range = flaser ? 80.0 : 5.0;
    std::string ranges;
    for (int b = 0; b < beams; ++b) {
      double r = castRay(room, origin, X_WR.theta - M_PI / 2 + b * step) + noise(rng);
      if (r >= max_range) r = max_range;
      std::snprintf(buf, sizeof buf, " %.3f", r);
      ranges += buf;
    }
    const double ts = t + 0.1;
    if (flaser) {
      out += "FLASER " + std::to_string(beams) + ranges;
      const Pose2 X_WL = X_WR * Pose2(laser_offset, 0.0, 0.0);
      std::snprintf(buf, sizeof buf, " %.6f %.6f %.6f", X_WL.x, X_WL.y, X_WL.theta);
      out += buf;
      std::snprintf(buf, sizeof buf, " %.6f %.6f %.6f", X_WR.x, X_WR.y, X_WR.theta);
      out += buf;
    } else {
      out += "RAWLASER1 0 -1.570796327 3.141592654 0.008726646 5.0 0.01 0 " +
             std::to_string(beams) + ranges + " 0";
    }
    std::snprintf(buf, sizeof buf, " %.3f robot %.3f\n", ts, ts + 0.001);
    out += buf;
    ++room.scans;
    if (i % 50 == 0) out += "SYNC tag " + std::to_string(ts) + " robot 0\n";
  }
  return room;
}

// Distance from a point to the room's wall rectangle.
double wallDistance(const RoomLog& room, const Eigen::Vector2d& world) {
  const Eigen::Vector2d p = world - room.origin;
  const double dx = std::max({-p.x(), 0.0, p.x() - room.width});
  const double dy = std::max({-p.y(), 0.0, p.y() - room.height});
  if (dx > 0.0 || dy > 0.0) return std::hypot(dx, dy);
  return std::min({p.x(), room.width - p.x(), p.y(), room.height - p.y()});
}

// The room's offset from the map's cell grid (the map's cells align with whole multiples of
// the resolution): walls on cell borders, through cell centres, and in between.
class CarmenRoomTest : public testing::TestWithParam<Eigen::Vector2d> {};

TEST_P(CarmenRoomTest, MapsTheRoomItsWallsAndItsFourCorners) {
  const RoomLog room = writeRoomLog(GetParam());
  const std::filesystem::path dir =
      std::filesystem::path(testing::TempDir()) /
      ("coopmap_carmen_room_" + std::to_string(std::lround(GetParam().x() * 1e4)) + "_" +
       std::to_string(std::lround(GetParam().y() * 1e4)));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  writeFileAtomic((dir / "room.log").string(), room.text);

  CarmenOptions options;
  options.log = (dir / "room.log").string();
  options.out_dir = (dir / "out").string();
  options.resolution = 0.05;
  const CarmenResult r = runCarmen(options);
  ASSERT_TRUE(r.grid.has_value());
  const OccupancyGrid& grid = *r.grid;
  const MapLimits& lim = grid.limits();
  const double res = lim.resolution;
  EXPECT_EQ(r.scans, room.scans);
  EXPECT_EQ(r.laser, 1);
  EXPECT_NEAR(r.path_length_m, 2 * (3.6 + 2.0), 1e-3);

  // Occupied cells lie on the true walls.
  int occupied = 0, on_wall = 0;
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix)
      if (grid.state(ix, iy) == CellState::kOccupied) {
        ++occupied;
        on_wall += wallDistance(room, lim.cellCenter(ix, iy)) <= 1.5 * res;
      }
  ASSERT_GT(occupied, 0);
  const double precision = static_cast<double>(on_wall) / occupied;
  EXPECT_GE(precision, 0.9) << on_wall << " of " << occupied << " occupied cells on a wall";

  // The walls seen are mapped: the map metrics against the true occupancy (outside the room).
  GridU8 truth(lim, 0);
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      const Eigen::Vector2d c = lim.cellCenter(ix, iy) - room.origin;
      truth.at(ix, iy) = c.x() < 0.0 || c.y() < 0.0 || c.x() > room.width || c.y() > room.height;
    }
  const MapMetrics m = computeMapMetrics(grid, truth, room.origin + Eigen::Vector2d(3.0, 2.0));
  EXPECT_GE(m.wall_recall, 0.8) << m.wall_cells << " wall cells";
  EXPECT_GT(m.wall_cells, static_cast<int>(0.8 * 2 * (room.width + room.height) / res));
  EXPECT_LE(m.false_occupied_rate, 0.01);
  std::printf("occupied on walls %.3f, wall recall %.3f, false occupied %.4f, coverage %.3f\n",
              precision, m.wall_recall, m.false_occupied_rate, m.coverage);
  EXPECT_GE(m.coverage, 0.95);

  // The room's four inner corners, each within 1.5 cells, the bisector into the room.
  const std::vector<std::pair<Eigen::Vector2d, double>> truth_corners{
      {{0.0, 0.0}, 45.0 * kDeg},
      {{room.width, 0.0}, 135.0 * kDeg},
      {{room.width, room.height}, -135.0 * kDeg},
      {{0.0, room.height}, -45.0 * kDeg}};
  for (const auto& [corner, heading] : truth_corners) {
    const Eigen::Vector2d vertex = room.origin + corner;
    const Corner* best = nullptr;
    for (const Corner& c : r.corners.search.corners)
      if (!best || (c.position - vertex).norm() < (best->position - vertex).norm()) best = &c;
    ASSERT_NE(best, nullptr);
    std::printf("corner (%.3f, %.3f): found %.2f cells off, heading %.2f deg off\n", vertex.x(),
                vertex.y(), (best->position - vertex).norm() / res,
                wrapAngle(best->heading - heading) / kDeg);
    EXPECT_LE((best->position - vertex).norm(), 1.5 * res)
        << "corner at (" << vertex.x() << ", " << vertex.y() << ") found at (" << best->position.x()
        << ", " << best->position.y() << ")";
    EXPECT_LE(std::abs(wrapAngle(best->heading - heading)), 10.0 * kDeg);
  }

  // The outputs.
  for (const char* f :
       {"map.pgm", "map.yaml", "map.png", "corners.json", "corners.png", "trajectory_odometry.tum"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "trajectory_groundtruth.tum"));
  std::ifstream tum(dir / "out" / "trajectory_odometry.tum");
  int lines = 0;
  for (std::string line; std::getline(tum, line);) lines += !line.empty() && line[0] != '#';
  EXPECT_EQ(lines, static_cast<int>(r.odometry.size()));
  EXPECT_EQ(lines, room.scans + 1);
}

INSTANTIATE_TEST_SUITE_P(Offsets, CarmenRoomTest,
                         testing::Values(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.025, 0.025),
                                         Eigen::Vector2d(0.0125, 0.0375)));

// A corrupt line anywhere: the error names it and nothing is written.
TEST(CarmenLogRobotTest, CorruptLogWritesNothing) {
  std::string text = writeRoomLog(Eigen::Vector2d::Zero()).text;
  const size_t at = text.find("ODOM", text.size() / 2);
  text.replace(text.find(' ', at + 5), 1, " x");  // "ODOM 1.2 x..." -> y is not a number
  const std::filesystem::path dir =
      std::filesystem::path(testing::TempDir()) / "coopmap_carmen_corrupt";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  writeFileAtomic((dir / "room.log").string(), text);
  CarmenOptions options;
  options.log = (dir / "room.log").string();
  options.out_dir = (dir / "out").string();
  const int line = static_cast<int>(std::count(text.begin(), text.begin() + at, '\n')) + 1;
  try {
    runCarmen(options);
    FAIL() << "a corrupt log was mapped";
  } catch (const CarmenLogError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(options.log + ":" + std::to_string(line) +
                                              ": ODOM field 'y': expected a number, got 'x",
                                          0),
              0u)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace coopmap

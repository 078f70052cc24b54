// CARMEN robot logs, the format of the classic public laser data sets: one message per line,
// "NAME fields... ipc_timestamp ipc_hostname logger_timestamp", '#' comments. Read: ODOM,
// the laser messages FLASER, RLASER, RAWLASER1-4 and ROBOTLASER1-2, TRUEPOS (ground truth,
// logged by the CARMEN simulator) and PARAM; every other message is counted and skipped.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/pose2.h"

namespace coopmap {

// A malformed or unreadable log. The message names the file and, for a bad line, the line,
// the message and field, what was expected and what was found:
// "run.log:12: FLASER field 'range[3]': expected a number, got 'abc'".
class CarmenLogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ODOM x y theta tv rv accel.
struct CarmenOdometry {
  double stamp = 0.0;  // s, the message's ipc_timestamp
  Pose2 pose;          // odometry pose (m, rad)
  double tv = 0.0;     // m/s
  double rv = 0.0;     // rad/s
  double accel = 0.0;  // m/s^2
  int line = 0;        // 1-based line in the file
};

// One laser scan, whichever message carried it.
struct CarmenLaser {
  std::string message;              // "FLASER", "RLASER", "RAWLASER1", "ROBOTLASER2", ...
  int laser = 1;                    // 1 front (FLASER, RAWLASER1, ROBOTLASER1), 2 rear, 3, 4
  double stamp = 0.0;               // s, the message's ipc_timestamp
  double start_angle = 0.0;         // rad, beam 0 in the laser's frame (CCW from its +x)
  double field_of_view = 0.0;       // rad
  double angular_resolution = 0.0;  // rad between beams
  double max_range = 0.0;           // m; readings at or beyond it are "no return"
  double accuracy = 0.0;            // m, range resolution of the device
  std::vector<float> ranges;        // m, one per beam
  // FLASER/RLASER: robot odometry pose and the laser's pose in the (localized) world frame;
  // ROBOTLASER: robot pose and laser pose, both in the odometry frame. RAWLASER: neither.
  std::optional<Pose2> robot_pose;
  std::optional<Pose2> laser_pose;
  int line = 0;
};

// TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta.
struct CarmenTruePose {
  double stamp = 0.0;  // s
  Pose2 truth;         // true pose (m, rad)
  Pose2 odometry;      // odometry pose at the same time
  int line = 0;
};

struct CarmenParam {
  std::string value;
  int line = 0;
};

struct CarmenLog {
  std::string file;
  std::vector<CarmenOdometry> odometry;         // in file order; stamps never decrease
  std::vector<CarmenLaser> lasers;              // in file order; per laser, stamps never decrease
  std::vector<CarmenTruePose> truth;            // in file order; stamps never decrease
  std::map<std::string, CarmenParam> params;    // PARAM name -> value (the last one wins)
  std::map<std::string, int> skipped_messages;  // other message names -> count
  int lines = 0;                                // lines in the file

  // A PARAM as a number; nullopt when absent. Throws CarmenLogError naming its line when the
  // value is not a number.
  std::optional<double> numericParam(const std::string& name) const;
};

// Reads a log file; throws CarmenLogError naming the file (and line and field) on any error.
CarmenLog readCarmenLog(const std::string& path);
// Parses log text; `file` is used in messages.
CarmenLog parseCarmenLog(std::string_view text, const std::string& file);

}  // namespace coopmap

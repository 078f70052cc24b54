// `coopmap robot CONFIG.yaml [--dry-run]`: the agent on a real B-14 base over its rFLEX
// controller, on the wall clock, with the same core as in simulation: a route follower
// driving the base through the robot interface. --dry-run checks the configuration and the
// controller (a status report arrives) and moves nothing.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "core/agent/route_follower.h"
#include "core/robot/robot_interface.h"
#include "robots/rflex/rflex_robot.h"

namespace coopmap {

// What a robot config file holds:
//
//   model: ../b14/b14.yaml        # robot model file (relative to this file's folder)
//   serial: {device: /dev/ttyS0, baud: 115200}
//   rflex: {report_period: 0.05, watchdog_timeout: 0.5, ...}   # optional, RflexConfig fields
//   route:                        # optional; needed unless --dry-run
//     waypoints: [[1.0, 0.0], {at: [0.0, 0.0], spin: true}]
//     linear_speed: 0.3           # and the other RouteConfig fields
//     control_rate: 10            # Hz
//     max_duration: 300           # s; 0: no limit
struct RobotRunConfig {
  std::string file;        // the config file
  std::string model_file;  // resolved path of the robot model file
  RobotDescription description;
  RflexConfig rflex;
  std::vector<Waypoint> route;
  RouteConfig route_config;
  double control_rate = 10.0;  // Hz
  double max_duration = 0.0;   // s; 0: no limit
};

// Reads a robot config file; ConfigError names file, line, column and field.
RobotRunConfig loadRobotRunConfig(const std::string& path);

struct RobotCommandOptions {
  std::string config;  // the config file
  bool dry_run = false;
  bool quiet = false;  // no progress lines
};

// Runs the command, printing to `out`; returns the exit code (0 done, 130 interrupted by
// SIGINT/SIGTERM after a safe stop). Throws ConfigError for a bad config, RflexError when
// the controller does not answer or faults during the route (after a safe stop), and
// std::runtime_error when the route times out or the base bumps into something.
int runRobotCommand(const RobotCommandOptions& options, std::FILE* out = stdout);

}  // namespace coopmap

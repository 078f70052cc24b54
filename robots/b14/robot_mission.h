// `coopmap robot CONFIG.yaml [--dry-run] [--out DIR]`: a real B-14 on the wall clock, with the
// same core as in simulation. With cameras and a mission, the robot's agent (core/agent/
// robot_agent.h) runs on the base and the camera head (B14Robot): it looks at the home base to
// find where it stands, explores (or follows a route) in sorties, and at home localizes,
// corrects, posts to its shared map and imports it; DIR receives its map, traverse log and
// odometry. Without them, a route follower drives the base alone, in the odometry frame.
// --dry-run checks the configuration and the controller (a status report arrives) and moves
// nothing.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/agent/agent_config_io.h"
#include "core/agent/route_follower.h"
#include "core/correction/traverse_log.h"
#include "core/io/tum.h"
#include "core/mapping/occupancy_grid.h"
#include "core/robot/robot_interface.h"
#include "robots/camera/trinocular_camera.h"
#include "robots/rflex/rflex_robot.h"

namespace coopmap {

// What a robot config file holds:
//
//   model: ../b14/b14.yaml        # robot model file (relative to this file's folder)
//   serial: {device: /dev/ttyS0, baud: 115200}
//   rflex: {report_period: 0.05, watchdog_timeout: 0.5, ...}   # optional, RflexConfig fields
//   # Either the base alone on a route (odometry frame):
//   route:
//     waypoints: [[1.0, 0.0], {at: [0.0, 0.0], spin: true}]
//     linear_speed: 0.3           # and the other RouteConfig fields
//     control_rate: 10            # Hz
//     max_duration: 300           # s; 0: no limit
//   # Or the mission: the cameras and the agent.
//   cameras:
//     sources: [0, 1, 2]          # reference, horizontal, vertical: devices, videos, sequences
//     calibration: rig.yaml       # `coopmap calibrate`'s file (relative to this file); or
//     rectified: true             # the sources give rectified images of the model's rig
//   mission: {name: jose, mode: explore, map: {...}, settings: {...}}   # agent_config_io.h
//   shared_map: shared/           # optional: the shared map kept on disk there
//   control_rate: 10              # Hz, of the mission
//   max_duration: 0               # s of the mission; 0: until it is done
struct RobotRunConfig {
  std::string file;        // the config file
  std::string model_file;  // resolved path of the robot model file
  RobotDescription description;
  RflexConfig rflex;
  std::vector<Waypoint> route;
  RouteConfig route_config;
  double control_rate = 10.0;  // Hz
  double max_duration = 0.0;   // s; 0: no limit
  // The mission (with cameras): unset for a route.
  std::optional<AgentConfig> mission;
  CameraSources camera_sources;
  std::string camera_calibration;  // resolved path; empty: rectified sources
  std::string shared_map_dir;      // resolved path; empty: in memory
};

// Reads a robot config file; ConfigError names file, line, column and field.
RobotRunConfig loadRobotRunConfig(const std::string& path);

struct RobotCommandOptions {
  std::string config;  // the config file
  bool dry_run = false;
  bool quiet = false;   // no progress lines
  std::string out_dir;  // the mission's outputs (map, traverse, odometry); empty: none
};

// What a mission leaves (the robot's outputs, for `coopmap robot --out`).
struct RobotMissionResult {
  std::string name;
  int frames = 0;
  std::vector<std::string> log;        // the agent's lines
  std::vector<StampedPose2> odometry;  // every control step, odometry frame
  Pose2 odometry_in_map;               // the first look's placement (drawing)
  TraverseLog traverse;                // map frame
  std::optional<OccupancyGrid> grid;
};

// Runs the command, printing to `out`; returns the exit code (0 done, 130 interrupted by
// SIGINT/SIGTERM after a safe stop). Throws ConfigError for a bad config, RflexError when
// the controller does not answer or faults (after a safe stop), and std::runtime_error when
// the route times out or the base bumps into something on a route. A mission's result goes to
// `mission` when given.
int runRobotCommand(const RobotCommandOptions& options, std::FILE* out = stdout,
                    RobotMissionResult* mission = nullptr);

}  // namespace coopmap

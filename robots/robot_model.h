// Robot model files (robots/<model>/<model>.yaml): body, limits, camera rig, and the
// parameters the simulator needs to play the robot.
#pragma once

#include <map>
#include <string>

#include "core/robot/robot_interface.h"
#include "sim/simulator.h"

namespace coopmap {

struct RobotModel {
  RobotDescription description;
  sim::DriveConfig drive;
  sim::OdometryConfig odometry;                                 // the default preset
  std::map<std::string, sim::OdometryConfig> odometry_presets;  // "default" and named ones
  sim::CameraNoiseConfig cameras;
  // Per preset ("default" and named ones): the distance scale the robots' operators measured
  // for those encoders (`coopmap stereo-scale` over logs), as a lab calibrates its robots
  // once; the runner gives it to the robots' agents as their odometry_distance_scale.
  std::map<std::string, double> calibrated_distance_scale;
};

// Loads a robot model file; ConfigError messages name the file, line and field.
RobotModel loadRobotModel(const std::string& path);
RobotModel parseRobotModel(const std::string& text, const std::string& file);

}  // namespace coopmap

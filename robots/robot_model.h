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
};

// Loads a robot model file; ConfigError messages name the file, line and field.
RobotModel loadRobotModel(const std::string& path);
RobotModel parseRobotModel(const std::string& text, const std::string& file);

}  // namespace coopmap

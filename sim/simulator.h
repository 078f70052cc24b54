// The simulator: world, Bullet physics, odometry models and the OSMesa trinocular
// renderer on a simulated clock with a fixed physics step.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "core/robot/robot_interface.h"
#include "sim/physics/physics_world.h"
#include "sim/render/renderer.h"
#include "sim/sensors/camera_model.h"
#include "sim/sensors/odometry.h"
#include "sim/world/world.h"

namespace coopmap::sim {

struct SimRobotConfig {
  RobotDescription description;
  DriveConfig drive;
  OdometryConfig odometry;
  CameraNoiseConfig cameras;  // the same imperfections model for all three cameras
};

class Simulator {
 public:
  // `seed` drives every random choice of the run (odometry noise, ...).
  Simulator(World world, uint64_t seed);
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  // Adds a robot at its spec's start pose; returns its index.
  int addRobot(const RobotSpec& spec, const SimRobotConfig& config);

  // Advances the clock by whole physics steps until `dt` seconds more have passed.
  void advance(double dt);
  double time() const;  // s

  // Renders the robot's three cameras now. `truth_depth` (reference camera, metres along
  // the optical axis) is filled if given.
  TrinocularFrame capture(int robot, cv::Mat* truth_depth = nullptr);

  void command(int robot, const MotionCommand& cmd);
  Pose2 truePose(int robot) const;
  Pose2 odometry(int robot) const;
  RobotStatus status(int robot) const;
  const RobotDescription& description(int robot) const;
  const RobotSpec& spec(int robot) const;
  int robotCount() const { return static_cast<int>(robots_.size()); }
  const World& world() const { return world_; }

  // Pose of a robot's camera (0 reference, 1 horizontal, 2 vertical) in the 3D world.
  Eigen::Isometry3d cameraPose(int robot, int camera) const;

  // Where the world's people stand now (m, world), one per World::people in order. People
  // wait for robots (PersonSpec::yieldsTo), so this is not PersonSpec::positionAt(time()).
  std::vector<Eigen::Vector2d> personPositions() const;
  // True if the person stood waiting for a robot in the last step.
  bool personYielding(int person) const;
  // A robot's distinct contacts since start, by what it touched (status().contact_events
  // counts them all as one kind).
  ContactCounts contactCounts(int robot) const;
  const std::vector<ContactEvent>& contactLog(int robot) const;  // each contact: when, what, where

 private:
  struct RobotState {
    RobotSpec spec;
    SimRobotConfig config;
    int physics_index = 0;
    std::unique_ptr<OdometryModel> odometry;
    std::vector<CameraModel> cameras;  // reference, horizontal, vertical
    // The segment under way (kind kVelocity: none), where it started, how far it got.
    MotionCommand segment;
    Pose2 segment_start;
    double segment_done = 0.0;  // rad turned or m driven, by the encoders
    double last_theta = 0.0;
  };
  // A world person's body and walk: walked = max(0, t - start_time - paused).
  struct PersonState {
    int body = 0;         // kinematic body
    double paused = 0.0;  // s spent waiting for robots
    double walked = 0.0;  // s spent walking
    Eigen::Vector2d position{0.0, 0.0};
    bool yielding = false;
  };
  void driveSegment(RobotState& r);
  void walkPeople(double t_next);  // moves the people to where they are at t_next
  World world_;
  uint64_t seed_;
  std::unique_ptr<PhysicsWorld> physics_;
  std::unique_ptr<Renderer> renderer_;  // created with the first robot (needs its intrinsics)
  std::vector<RobotState> robots_;
  std::vector<PersonState> people_;  // one per world person
  std::vector<int> doors_;           // kinematic bodies, one per scheduled door
  int64_t steps_ = 0;
};

}  // namespace coopmap::sim

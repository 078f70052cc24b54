// Bullet physics of the world: static solids, a floor, and robots as cylinders driven by
// velocity commands through traction at the wheel-floor contact.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/pose2.h"
#include "core/robot/robot_interface.h"
#include "sim/world/world.h"

namespace coopmap::sim {

// Body-frame velocity of a robot: forward and lateral speed (m/s), yaw rate (rad/s).
struct BodyVelocity {
  double forward = 0.0;
  double lateral = 0.0;
  double yaw_rate = 0.0;
};

struct DriveConfig {
  double mass = 45.0;                    // kg
  double traction_mu = 0.8;              // wheel-floor friction: limits drive and braking force
  double velocity_time_constant = 0.05;  // s, how hard the base servo tracks the command
};

// Distinct contacts of a robot since start, by what it touched: a contact event of a kind
// starts with a step in which the robot touches something of that kind after a step in which
// it touched nothing of it (as RobotStatus::contact_events, which counts any kind).
struct ContactCounts {
  int static_world = 0;  // walls, furniture, doors, the home base
  int people = 0;        // kinematic cylinders (people)
  int robots = 0;        // other robots
};

// One contact event: when it began, what was touched, and where (the contact point, world).
struct ContactEvent {
  double time = 0.0;  // s
  enum class Kind { kStaticWorld, kPerson, kRobot } kind = Kind::kStaticWorld;
  Eigen::Vector2d point{0.0, 0.0};  // m, world
};
const char* toString(ContactEvent::Kind k);  // "static_world", "person", "robot"

class PhysicsWorld {
 public:
  // Builds the static world. `step` is the fixed physics step (s).
  PhysicsWorld(const World& world, double step);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  // Adds a robot resting on the floor at `start`; returns its index.
  int addRobot(const RobotDescription& robot, const Pose2& start, const DriveConfig& drive);

  // Adds a kinematic vertical cylinder (a person) at `position`; returns its index.
  int addKinematicCylinder(double radius, double height, const Eigen::Vector2d& position);
  // Adds a kinematic box (a door that opens and closes); returns its index.
  int addKinematicBox(const SolidBox& box);
  // Moves a kinematic body (before the next step); `present` false puts it out of the way.
  void moveKinematic(int index, const Eigen::Vector2d& position, bool present = true);

  // Sets a robot's velocity command; the base applies its speed and acceleration limits.
  void command(int robot, const MotionCommand& cmd);
  // Advances by one fixed step.
  void step();

  Pose2 truePose(int robot) const;             // X_WR (m, rad)
  BodyVelocity bodyVelocity(int robot) const;  // in the robot frame
  // What the wheels turn at (robot frame): the body's motion while they grip, the drive's
  // setpoint while they slip (traction saturated). Encoders measure this.
  BodyVelocity wheelVelocity(int robot) const;
  bool inContact(int robot) const;  // touching a solid (not the floor) now
  // Where the robot touches a solid now (a contact point, world), if it does.
  std::optional<Eigen::Vector2d> contactPoint(int robot) const;
  int contactEvents(int robot) const;                            // new contacts since start
  ContactCounts contactCounts(int robot) const;                  // the same, by what was touched
  const std::vector<ContactEvent>& contactLog(int robot) const;  // each kind's events, in order
  double stepSize() const { return step_; }
  double time() const { return time_; }
  int robotCount() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double step_;
  double time_ = 0.0;
};

}  // namespace coopmap::sim

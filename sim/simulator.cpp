#include "sim/simulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/robot/braking.h"

namespace coopmap::sim {

Simulator::Simulator(World world, uint64_t seed) : world_(std::move(world)), seed_(seed) {
  physics_ = std::make_unique<PhysicsWorld>(world_, 1.0 / world_.physics_rate);
  for (const PersonSpec& p : world_.people) {
    PersonState s;
    s.position = p.positionAtWalked(0.0);
    s.body = physics_->addKinematicCylinder(p.radius, p.height, s.position);
    people_.push_back(s);
  }
  for (const DoorSpec& d : world_.doors)
    if (d.scheduled()) doors_.push_back(physics_->addKinematicBox(d.panel()));
}

Simulator::~Simulator() = default;

int Simulator::addRobot(const RobotSpec& spec, const SimRobotConfig& config) {
  const CameraIntrinsics& k = config.description.rig.intrinsics;
  if (!renderer_) {
    renderer_ = std::make_unique<Renderer>(world_, k);
  } else {
    const CameraIntrinsics& r = renderer_->intrinsics();
    if (r.width != k.width || r.height != k.height)
      throw std::invalid_argument("simulator: all robots must share one camera resolution");
  }
  RobotState s;
  s.spec = spec;
  s.config = config;
  s.physics_index = physics_->addRobot(config.description, spec.start, config.drive);
  const uint64_t robot_seed = seed_ * 0x9E3779B97F4A7C15ull + robots_.size() + 1;
  s.odometry = std::make_unique<OdometryModel>(config.odometry, spec.start, robot_seed);
  for (uint64_t c = 0; c < 3; ++c) s.cameras.emplace_back(config.cameras, robot_seed * 31 + c + 7);
  robots_.push_back(std::move(s));
  return static_cast<int>(robots_.size()) - 1;
}

double Simulator::time() const { return steps_ * physics_->stepSize(); }

void Simulator::advance(double dt) {
  const double h = physics_->stepSize();
  const int64_t target = static_cast<int64_t>(std::llround((time() + dt) / h));
  while (steps_ < target) {
    const double t_next = (steps_ + 1) * h;
    walkPeople(t_next);
    size_t door = 0;
    for (const DoorSpec& d : world_.doors)
      if (d.scheduled()) physics_->moveKinematic(doors_[door++], d.center, !d.openAt(t_next));
    for (RobotState& r : robots_)
      if (r.segment.kind != MotionCommand::Kind::kVelocity) driveSegment(r);
    physics_->step();
    ++steps_;
    for (RobotState& r : robots_)
      r.odometry->integrate(physics_->wheelVelocity(r.physics_index),
                            physics_->truePose(r.physics_index), h);
  }
}

// Each person walks on unless a robot, where it stands before this step, makes them wait;
// waiting adds to their paused time, so their walk resumes where it stopped.
void Simulator::walkPeople(double t_next) {
  for (size_t k = 0; k < people_.size(); ++k) {
    const PersonSpec& p = world_.people[k];
    PersonState& s = people_[k];
    const double walked = std::max(0.0, t_next - p.start_time - s.paused);
    s.yielding = false;
    if (walked > s.walked) {
      for (const RobotState& r : robots_)
        if (p.yieldsTo(s.walked, physics_->truePose(r.physics_index).translation(),
                       r.config.description.body_radius)) {
          s.yielding = true;
          break;
        }
    }
    if (s.yielding) {
      s.paused += walked - s.walked;
    } else {
      s.walked = walked;
      s.position = p.positionAtWalked(s.walked);
    }
    physics_->moveKinematic(s.body, s.position);
  }
}

std::vector<Eigen::Vector2d> Simulator::personPositions() const {
  std::vector<Eigen::Vector2d> out;
  out.reserve(people_.size());
  for (const PersonState& s : people_) out.push_back(s.position);
  return out;
}

bool Simulator::personYielding(int person) const { return people_.at(person).yielding; }

ContactCounts Simulator::contactCounts(int robot) const {
  return physics_->contactCounts(robots_.at(robot).physics_index);
}

const std::vector<ContactEvent>& Simulator::contactLog(int robot) const {
  return physics_->contactLog(robots_.at(robot).physics_index);
}

Eigen::Isometry3d Simulator::cameraPose(int robot, int camera) const {
  const RobotState& r = robots_.at(robot);
  const TrinocularRig& rig = r.config.description.rig;
  const Pose2 p = physics_->truePose(r.physics_index);
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.translate(Eigen::Vector3d(p.x, p.y, 0.0));
  X_WR.rotate(Eigen::AngleAxisd(p.theta, Eigen::Vector3d::UnitZ()));
  Eigen::Matrix3d R_RC;  // OpenCV camera axes in the robot frame: x right, y down, z forward
  R_RC.col(0) = Eigen::Vector3d(0, -1, 0);
  R_RC.col(1) = Eigen::Vector3d(0, 0, -1);
  R_RC.col(2) = Eigen::Vector3d(1, 0, 0);
  Eigen::Isometry3d X_RC = Eigen::Isometry3d::Identity();
  X_RC.linear() = R_RC;
  X_RC.translation() = rig.mount_position;
  Eigen::Isometry3d X_WC = X_WR * X_RC;
  if (camera == 1) X_WC.translate(rig.horizontal_offset);
  if (camera == 2) X_WC.translate(rig.vertical_offset);
  return X_WC;
}

TrinocularFrame Simulator::capture(int robot, cv::Mat* truth_depth) {
  std::vector<DynamicCylinder> others;
  for (int k = 0; k < robotCount(); ++k) {
    if (k == robot) continue;
    const RobotDescription& d = robots_[k].config.description;
    const Pose2 p = truePose(k);
    others.push_back({{p.x, p.y}, d.body_radius, d.body_height});
  }
  for (size_t k = 0; k < people_.size(); ++k) {
    const PersonSpec& p = world_.people[k];
    others.push_back({people_[k].position, p.radius, p.height});
  }
  TrinocularFrame f;
  f.stamp = time();
  f.odometry = odometry(robot);
  const std::vector<SolidBox> boxes = world_.doorsClosedAt(time());
  renderer_->renderViews({cameraPose(robot, 0), cameraPose(robot, 1), cameraPose(robot, 2)}, others,
                         boxes, {&f.reference, &f.horizontal, &f.vertical}, truth_depth);
  std::vector<CameraModel>& cams = robots_.at(robot).cameras;
  cams[0].apply(f.reference);
  cams[1].apply(f.horizontal);
  cams[2].apply(f.vertical);
  return f;
}

void Simulator::command(int robot, const MotionCommand& cmd) {
  RobotState& r = robots_.at(robot);
  r.segment = cmd;
  if (cmd.kind == MotionCommand::Kind::kVelocity) {
    physics_->command(r.physics_index, cmd);
    return;
  }
  r.segment_start = r.odometry->pose();
  r.segment_done = 0.0;
  r.last_theta = r.segment_start.theta;
}

// The base's own segment execution: progress by the encoders (odometry), a speed that
// decelerates to stop at the goal (v = sqrt(2 a d)), straight runs holding the encoder
// heading; done within 2 mrad or 2 mm.
void Simulator::driveSegment(RobotState& r) {
  const RobotDescription& d = r.config.description;
  const Pose2 now = r.odometry->pose();
  MotionCommand v;
  if (r.segment.kind == MotionCommand::Kind::kTurn) {
    r.segment_done += wrapAngle(now.theta - r.last_theta);
    r.last_theta = now.theta;
    const double left = r.segment.amount - r.segment_done;
    if (std::abs(left) < 0.002) {
      r.segment = MotionCommand::stop();
    } else {
      const double w = brakingSpeed(left, d.max_angular_accel, d.max_angular_speed);
      v.angular = std::copysign(std::max(0.05, 0.8 * w), left);
    }
  } else {
    const double c = std::cos(r.segment_start.theta), s = std::sin(r.segment_start.theta);
    r.segment_done = c * (now.x - r.segment_start.x) + s * (now.y - r.segment_start.y);
    const double left = r.segment.amount - r.segment_done;
    if (std::abs(left) < 0.002) {
      r.segment = MotionCommand::stop();
    } else {
      const double speed = brakingSpeed(left, d.max_linear_accel, d.max_linear_speed);
      v.linear = std::copysign(std::max(0.02, 0.8 * speed), left);
      v.angular = 2.0 * wrapAngle(r.segment_start.theta - now.theta);
    }
  }
  physics_->command(r.physics_index, v);
}

Pose2 Simulator::truePose(int robot) const {
  return physics_->truePose(robots_.at(robot).physics_index);
}

Pose2 Simulator::odometry(int robot) const { return robots_.at(robot).odometry->pose(); }

RobotStatus Simulator::status(int robot) const {
  const RobotState& r = robots_.at(robot);
  const int i = r.physics_index;
  RobotStatus s{physics_->inContact(i), physics_->contactEvents(i),
                r.segment.kind != MotionCommand::Kind::kVelocity, std::nullopt};
  if (const std::optional<Eigen::Vector2d> p = physics_->contactPoint(i)) {
    // The bump panel pressed: the bearing of the contact point from the base's centre.
    const Eigen::Vector2d local = physics_->truePose(i).inverse() * *p;
    s.bump_bearing = std::atan2(local.y(), local.x());
  }
  return s;
}

const RobotDescription& Simulator::description(int robot) const {
  return robots_.at(robot).config.description;
}

const RobotSpec& Simulator::spec(int robot) const { return robots_.at(robot).spec; }

}  // namespace coopmap::sim

// The B-14 as one robot: its rFLEX base (motion, odometry, bumpers; rflex_robot.h) and its
// trinocular camera head (frames; trinocular_camera.h) behind the one robot interface, so
// that the agent runs on it as on the simulated B-14. Frames are stamped on the base's clock
// as they are grabbed and carry the odometry of that moment, interpolated between the base's
// reports.
#pragma once

#include <memory>
#include <optional>

#include "core/robot/robot_interface.h"
#include "robots/camera/trinocular_camera.h"
#include "robots/rflex/rflex_robot.h"

namespace coopmap {

class B14Robot final : public RobotInterface {
 public:
  // Takes the base and the cameras; `description` is the robot's (its rig's mount position
  // and the body), its rig's intrinsics and offsets the cameras' rectified rig. Throws
  // std::invalid_argument when the cameras' rectified images differ in size from the model's
  // rig.
  B14Robot(std::unique_ptr<RflexRobot> base, std::unique_ptr<TrinocularCamera> cameras,
           const RobotDescription& description);

  const RobotDescription& description() const override { return description_; }
  double now() const override { return base_->now(); }
  // The next frame of the cameras, stamped and placed at the moment it was grabbed; nullopt
  // when the cameras have no more (a recorded sequence ended).
  std::optional<TrinocularFrame> captureFrame() override;
  Pose2 odometry() const override { return base_->odometry(); }
  void command(const MotionCommand& cmd) override { base_->command(cmd); }
  RobotStatus status() const override { return base_->status(); }

  RflexRobot& base() { return *base_; }

 private:
  std::unique_ptr<RflexRobot> base_;
  std::unique_ptr<TrinocularCamera> cameras_;
  RobotDescription description_;
};

}  // namespace coopmap

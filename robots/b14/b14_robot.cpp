#include "robots/b14/b14_robot.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace coopmap {

B14Robot::B14Robot(std::unique_ptr<RflexRobot> base, std::unique_ptr<TrinocularCamera> cameras,
                   const RobotDescription& description)
    : base_(std::move(base)), cameras_(std::move(cameras)), description_(description) {
  const TrinocularRig& rig = cameras_->rig();
  const CameraIntrinsics &k = rig.intrinsics, &m = description_.rig.intrinsics;
  if (k.width != m.width || k.height != m.height)
    throw std::invalid_argument("the cameras' rectified images are " + std::to_string(k.width) +
                                "x" + std::to_string(k.height) + " px, the robot model's rig " +
                                std::to_string(m.width) + "x" + std::to_string(m.height));
  // The rig the frames follow is the cameras'; where it sits on the robot, the model's.
  const Eigen::Vector3d mount = description_.rig.mount_position;
  description_.rig = rig;
  description_.rig.mount_position = mount;
}

std::optional<TrinocularFrame> B14Robot::captureFrame() {
  const double grabbed = base_->now();
  std::optional<TrinocularFrame> frame = cameras_->capture(grabbed);
  if (frame) frame->odometry = base_->odometryAt(grabbed);
  return frame;
}

}  // namespace coopmap

// A robot played back from a coopmap recording (robots/replay/recording.h): the robot
// interface over a recorded run, so the core maps it exactly as it mapped the live robot.
#pragma once

#include <optional>

#include "core/robot/robot_interface.h"
#include "robots/replay/recording.h"

namespace coopmap {

// Plays the frames in order at their stamps. The clock starts at the first recorded stamp
// (odometry or frame). Left to itself, captureFrame() returns the next frame, reading its
// images from disk, and moves the clock forward to its stamp (a recording waits for its next
// frame); nullopt once every frame was returned. Stepped (advanceTo: the replay of a run's
// agents, control step by control step), captureFrame() returns the next frame only if it
// was taken by now. odometry() is the last recorded odometry sample at or before now() (the
// frame's own pose at a frame's stamp); status() the last recorded status (version 2; no
// contact before it, or without). A recording cannot be steered: command() is accepted and
// ignored.
class ReplayRobot final : public RobotInterface {
 public:
  explicit ReplayRobot(RobotRecording recording);

  const RobotDescription& description() const override { return recording_.description; }
  double now() const override { return now_; }
  // Throws std::runtime_error naming the image file and the frame when one is missing,
  // corrupt, truncated or of the wrong size.
  std::optional<TrinocularFrame> captureFrame() override;
  Pose2 odometry() const override;
  void command(const MotionCommand&) override {}  // a recording cannot be steered
  RobotStatus status() const override;

  // Moves the clock to `t` (s, not backwards) and from then on plays stepped (see above).
  void advanceTo(double t);

  // The motion segment recorded with the last frame captureFrame() returned.
  MotionSegment lastSegment() const { return last_segment_; }
  int frameCount() const { return static_cast<int>(recording_.frames.size()); }
  int framesLeft() const { return frameCount() - static_cast<int>(next_); }
  const RobotRecording& recording() const { return recording_; }

 private:
  RobotRecording recording_;
  size_t next_ = 0;
  double now_ = 0.0;
  bool stepped_ = false;
  Pose2 frame_odometry_;  // the pose of the last frame, held until a later odometry sample
  MotionSegment last_segment_ = MotionSegment::kStop;
};

}  // namespace coopmap

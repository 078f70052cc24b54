#include "robots/replay/replay_robot.h"

#include <algorithm>
#include <utility>

namespace coopmap {

ReplayRobot::ReplayRobot(RobotRecording recording) : recording_(std::move(recording)) {
  const auto& odo = recording_.odometry;
  const auto& frames = recording_.frames;
  if (!odo.empty()) now_ = odo.front().stamp;
  if (!frames.empty() && (odo.empty() || frames.front().stamp < now_)) {
    now_ = frames.front().stamp;
    frame_odometry_ = frames.front().odometry;
  }
}

void ReplayRobot::advanceTo(double t) {
  stepped_ = true;
  now_ = std::max(now_, t);
}

RobotStatus ReplayRobot::status() const {
  const auto& rows = recording_.status;
  const auto after =
      std::upper_bound(rows.begin(), rows.end(), now_ + 1e-9,
                       [](double t, const RecordedStatus& r) { return t < r.stamp; });
  return after == rows.begin() ? RobotStatus{} : std::prev(after)->status;
}

std::optional<TrinocularFrame> ReplayRobot::captureFrame() {
  if (next_ >= recording_.frames.size()) return std::nullopt;
  if (stepped_ && recording_.frames[next_].stamp > now_ + 1e-9) return std::nullopt;
  TrinocularFrame frame = readRecordedFrame(recording_, next_);
  const RecordedFrame& f = recording_.frames[next_];
  ++next_;
  now_ = std::max(now_, f.stamp);
  frame_odometry_ = f.odometry;
  last_segment_ = f.segment;
  return frame;
}

Pose2 ReplayRobot::odometry() const {
  const auto& odo = recording_.odometry;
  // The last sample at or before now().
  const auto after = std::upper_bound(odo.begin(), odo.end(), now_,
                                      [](double t, const StampedPose2& p) { return t < p.stamp; });
  const double frame_stamp = next_ > 0 ? recording_.frames[next_ - 1].stamp : now_;
  if (after == odo.begin()) return frame_odometry_;
  const StampedPose2& sample = *std::prev(after);
  // A frame taken after the last odometry sample carries the fresher pose.
  return next_ > 0 && frame_stamp > sample.stamp ? frame_odometry_ : sample.pose;
}

}  // namespace coopmap

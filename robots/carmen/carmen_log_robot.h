// A robot played back from a CARMEN log: the robot interface over a recorded run, so the core
// maps a classic laser data set exactly as it would map the live robot.
#pragma once

#include <optional>
#include <vector>

#include "core/io/carmen_log.h"
#include "core/io/tum.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

struct CarmenRobotConfig {
  int laser = 0;               // laser to play: 1 front, 2 rear, 3, 4; 0: the lowest in the log
  double range_sigma = 0.0;    // m, range noise of the scans; 0: the log's accuracy (>= 1 cm)
  std::optional<Pose2> mount;  // X_RL, the laser in the robot frame; overrides the log's

  void validate() const;  // throws std::invalid_argument naming the field
};

// Plays a log by its timestamps. The clock starts at the log's first ODOM or scan;
// captureScan() returns the scans of the chosen laser one by one, in order, moving the clock
// forward to each scan's stamp (a log waits for its next scan); odometry() is the ODOM pose
// interpolated at now(). A log cannot be steered: command() is ignored, and status() reports
// no contact. captureFrame() has no cameras to offer.
//
// Each scan's odometry is the pose the laser message carries (FLASER, RLASER, ROBOTLASER) or
// else the ODOM pose interpolated at its stamp (RAWLASER). The laser's mount X_RL comes from
// the config, else from ROBOTLASER's laser and robot poses, else from the PARAMs
// robot_{front,rear}laser_{offset,side_offset,angular_offset} (m, m, rad; the rear laser faces
// backwards), else it is the robot's origin.
class CarmenLogRobot final : public RobotInterface {
 public:
  // Throws CarmenLogError naming the file when the log has no scans of the laser, or scans
  // without odometry (RAWLASER and no ODOM lines); std::invalid_argument for a bad config.
  explicit CarmenLogRobot(CarmenLog log, const CarmenRobotConfig& config = {});

  const RobotDescription& description() const override { return description_; }
  double now() const override { return now_; }
  std::optional<TrinocularFrame> captureFrame() override { return std::nullopt; }
  std::optional<RangeScan> captureScan() override;
  Pose2 odometry() const override { return odometryAt(now_); }
  void command(const MotionCommand&) override {}  // a log cannot be steered
  RobotStatus status() const override { return {}; }

  // Moves the clock forward to `stamp` (s); never back. Scans before it are still returned.
  void advanceTo(double stamp);
  // Odometry interpolated at a time (s): linear in x, y and the wrapped heading; the first or
  // last pose outside the log.
  Pose2 odometryAt(double stamp) const;

  int laser() const { return laser_; }  // the laser played
  int scanCount() const { return static_cast<int>(scans_.size()); }
  int scansLeft() const { return static_cast<int>(scans_.size() - next_); }
  // The odometry track: every ODOM message, or the scans' poses when there are none.
  const std::vector<StampedPose2>& odometryTrack() const { return track_; }
  // TRUEPOS ground truth, when the log has it (CARMEN's simulator logs it).
  std::vector<StampedPose2> groundTruth() const;
  const CarmenLog& log() const { return log_; }

 private:
  CarmenLog log_;
  RobotDescription description_;
  int laser_ = 1;
  std::vector<RangeScan> scans_;
  std::vector<StampedPose2> track_;
  size_t next_ = 0;
  double now_ = 0.0;
};

}  // namespace coopmap

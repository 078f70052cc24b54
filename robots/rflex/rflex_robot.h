// The B-14 base driven through its rFLEX controller over a serial port: the robot interface on
// real hardware (motion commands, odometry, bumpers; sonar ignored). The base has no cameras:
// captureFrame() returns nothing, a camera driver supplies the frames.
//
// One I/O thread owns the port: it decodes the controller's reports (rflex_protocol.h),
// integrates odometry from the two axis encoders, runs turn and straight segments on that
// odometry, sends the velocity commands, and keeps a watchdog. Faults latch: a watchdog trip
// (no odometry report within watchdog_timeout), a hang-up or a write error stops the base
// (when the port still takes a stop command), records a message for fault(), and from then on
// command() is ignored. Garbage bytes are skipped and frames with a bad checksum dropped and
// counted (stats()); neither is a fault.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "core/robot/robot_interface.h"
#include "robots/rflex/rflex_protocol.h"
#include "robots/rflex/serial_port.h"

namespace coopmap {

// The controller did not answer, or the port could not be opened.
class RflexError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RflexConfig {
  std::string device;                      // serial device, e.g. /dev/ttyS0
  int baud = 115200;                       // the rFLEX default
  double distance_ticks_per_m = 84157.1;   // translation encoder (CARMEN's B-14r value)
  double angle_ticks_per_rad = 75055.859;  // rotation encoder (CARMEN's B-14r value)
  double report_period = 0.05;             // s between odometry reports asked of the controller
  double watchdog_timeout = 0.5;           // s without an odometry report before a safe stop
  double startup_timeout = 2.0;            // s to wait for the first report when opening
  double write_timeout = 0.2;              // s a command may wait for the port
  double control_period = 0.02;            // s between control steps (segments, watchdog)
  double resend_period = 0.25;             // s: an unchanged velocity command is repeated
  uint32_t translation_torque = 30000;     // torque limit sent with translation commands
  uint32_t rotation_torque = 35000;        // torque limit sent with rotation commands
  bool enable_motion = true;               // false: brake stays on, commands are ignored

  void validate() const;  // throws std::invalid_argument naming the field and value
};

// Counters of what crossed the wire.
struct RflexStats {
  rflex::DecoderStats decoder;  // packets, garbage bytes, bad checksums, malformed frames
  uint64_t odometry_reports = 0;
  uint64_t dio_reports = 0;
  uint64_t ignored_packets = 0;     // sonar, system, joystick, IR and unknown packets
  uint64_t commands_sent = 0;       // MOT_AXIS_SET_DIR packets
  uint32_t controller_time_ms = 0;  // timestamp of the last odometry report
  int32_t translation_ticks = 0;    // last encoder readings
  int32_t rotation_ticks = 0;
};

class RflexRobot final : public RobotInterface {
 public:
  // Opens the port, asks for odometry and digital I/O reports, releases the brake (when
  // motion is enabled) and waits for the first odometry report of both axes. Throws
  // RflexError naming the device when the port cannot be opened or nothing arrives within
  // startup_timeout; std::invalid_argument for a bad config.
  RflexRobot(const RflexConfig& config, const RobotDescription& description);
  // Stops the base, turns the reports off and sets the brake, then closes the port.
  ~RflexRobot() override;

  const RobotDescription& description() const override { return description_; }
  // Seconds since the driver opened the port (wall clock, steady).
  double now() const override;
  std::optional<TrinocularFrame> captureFrame() override { return std::nullopt; }
  // Odometry X_OR integrated from the encoders since opening (starts at the origin).
  Pose2 odometry() const override;
  // The odometry at time `t` (s, now()'s clock) of the last few seconds, interpolated between
  // the reports around it (the latest for a later time, the earliest kept for an earlier one).
  Pose2 odometryAt(double t) const;
  // Velocity (clamped to the description's limits) or a turn/straight segment run on
  // odometry. Ignored after a fault or with motion disabled.
  void command(const MotionCommand& cmd) override;
  RobotStatus status() const override;

  // The latched fault message ("rflex /dev/ttyS0: ..."), if any.
  std::optional<std::string> fault() const;
  RflexStats stats() const;
  const RflexConfig& config() const { return config_; }
  // The velocity last sent to the base (m/s, rad/s).
  MotionCommand lastSentVelocity() const;

 private:
  void run();  // the I/O thread
  void handle(const rflex::Packet& p, double t);
  void controlStep(double t);
  void send(const rflex::Packet& p);      // I/O thread only; throws SerialError
  void sendVelocity(double v, double w);  // I/O thread only
  void latchFault(const std::string& why, bool port_usable);
  void wake();

  RflexConfig config_;
  RobotDescription description_;
  std::unique_ptr<SerialPort> port_;
  std::chrono::steady_clock::time_point start_;
  int wake_pipe_[2] = {-1, -1};

  mutable std::mutex mutex_;
  std::condition_variable first_report_;
  // Guarded by mutex_:
  Pose2 pose_;
  std::deque<std::pair<double, Pose2>> history_;  // (driver clock s, pose) of the last reports
  bool have_translation_ = false, have_rotation_ = false;
  int32_t last_translation_ = 0, last_rotation_ = 0;
  double pending_distance_ = 0.0;       // m reported by translation, not yet integrated
  double last_translation_time_ = 0.0;  // s, driver clock, of the last report per axis
  double last_rotation_time_ = 0.0;
  MotionCommand requested_;  // the command given; segments carry their goal
  bool new_request_ = false;
  bool segment_active_ = false;
  bool bumped_ = false;
  int contact_events_ = 0;
  std::optional<std::string> fault_;
  RflexStats stats_;
  MotionCommand sent_;  // last velocity sent

  // I/O thread state:
  rflex::Decoder decoder_;
  Pose2 segment_start_;
  double segment_done_ = 0.0;
  double segment_last_theta_ = 0.0;
  double last_send_time_ = -1e9;

  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace coopmap

// An emulated rFLEX controller on a pseudo-terminal: it speaks the protocol of
// rflex_protocol.h as the base would (odometry and digital I/O reports at the period asked,
// velocity commands with acceleration limits, brake), and moves a simulated robot (a unicycle
// integrated in small steps on the wall clock). Switches inject serial faults: garbage bytes
// between packets, corrupt checksums, silence, a hang-up. For tests and for trying the driver
// and `coopmap robot` without a robot.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/geometry/pose2.h"
#include "robots/rflex/rflex_protocol.h"

namespace coopmap {

struct RflexEmulatorConfig {
  double distance_ticks_per_m = 84157.1;  // must match the driver's to agree on odometry
  double angle_ticks_per_rad = 75055.859;
  double step = 0.002;                 // s, integration step of the simulated robot
  uint32_t encoder_offset = 0;         // initial encoder readings (ticks), e.g. near 2^31
  double default_linear_accel = 1.0;   // m/s^2 when a command gives none, and for braking
  double default_angular_accel = 3.0;  // rad/s^2
  Pose2 start;                         // the robot's true pose at start
};

struct RflexEmulatorCounters {
  uint64_t packets_received = 0;
  uint64_t axis_commands = 0;    // MOT_AXIS_SET_DIR packets
  uint64_t report_requests = 0;  // MOT_SYSTEM_REPORT_REQ and DIO_REPORTS_REQ packets
  uint64_t reports_sent = 0;     // MOT_SYSTEM_REPORT and DIO_REPORT packets
  uint64_t garbage_bytes_sent = 0;
  uint64_t corrupt_packets_sent = 0;
  rflex::DecoderStats decoder;    // what the emulator's own decoder saw
  uint32_t report_period_us = 0;  // as last asked; 0: no reports
  bool brake_on = true;
};

class RflexEmulator {
 public:
  // Opens a pseudo-terminal and starts the controller thread. Throws std::runtime_error when
  // no pseudo-terminal can be had.
  explicit RflexEmulator(const RflexEmulatorConfig& config = {});
  ~RflexEmulator();
  RflexEmulator(const RflexEmulator&) = delete;
  RflexEmulator& operator=(const RflexEmulator&) = delete;

  // The device the driver opens (the pseudo-terminal's slave, e.g. /dev/pts/3).
  const std::string& device() const { return device_; }

  Pose2 pose() const;              // the simulated robot's true pose (m, rad)
  double linearVelocity() const;   // actual, m/s
  double angularVelocity() const;  // actual, rad/s
  double targetLinear() const;     // as last commanded, m/s
  double targetAngular() const;    // as last commanded, rad/s
  RflexEmulatorCounters counters() const;

  // Fault injection.
  void setGarbage(bool on);       // a burst of garbage bytes before every packet sent
  void corruptNext(int packets);  // the next packets sent carry a wrong checksum
  void setSilent(bool on);        // send nothing (commands are still received and obeyed)
  void hangUp();                  // close the pseudo-terminal: the driver sees a hang-up
  void setBumper(bool pressed);   // the bump panel (DIO address 0x40)

 private:
  void run();
  void handle(const rflex::Packet& p);
  void integrate(double dt);
  void sendPacket(const rflex::Packet& p);
  void writeBytes(const std::vector<uint8_t>& bytes);
  double elapsed() const;

  RflexEmulatorConfig config_;
  std::string device_;
  int master_ = -1;
  int slave_keep_ = -1;  // held open so the master never reads EIO while no driver is attached
  std::chrono::steady_clock::time_point start_;

  mutable std::mutex mutex_;
  std::condition_variable hung_up_cv_;
  // Guarded by mutex_:
  Pose2 pose_;
  double v_ = 0.0, w_ = 0.0;                // actual velocities
  double target_v_ = 0.0, target_w_ = 0.0;  // commanded
  double accel_v_ = 0.0, accel_w_ = 0.0;    // commanded accelerations (m/s^2, rad/s^2)
  double distance_ = 0.0, angle_ = 0.0;     // encoder integrals (m, rad)
  uint32_t dio_period_us_ = 0;
  bool garbage_ = false, silent_ = false, bumper_ = false;
  bool hang_up_request_ = false, hung_up_ = false;
  int corrupt_ = 0;
  uint32_t garbage_seed_ = 12345;
  RflexEmulatorCounters counters_;

  // Emulator thread only:
  rflex::Decoder decoder_;
  double sim_time_ = 0.0;
  double next_report_ = 0.0, next_dio_ = 0.0;
  bool last_bumper_sent_ = false;

  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace coopmap

#include "robots/rflex/rflex_robot.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

#include "core/robot/braking.h"

namespace coopmap {
namespace {

// s of odometry kept for the frames' odometry at capture (odometryAt).
constexpr double kHistorySeconds = 3.0;

constexpr double kTurnTolerance = 0.004;      // rad: a turn segment ends within this
constexpr double kStraightTolerance = 0.003;  // m: a straight segment ends within this
constexpr double kMinSegmentTurnRate = 0.05;  // rad/s, so a turn does not crawl
constexpr double kMinSegmentSpeed = 0.02;     // m/s
constexpr double kProfileMargin = 0.8;        // of the speed that would stop exactly in time

std::string fixed(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

int32_t toTicks(double v, double ticks_per_unit) {
  const double t = std::round(v * ticks_per_unit);
  return static_cast<int32_t>(std::clamp(t, -2.0e9, 2.0e9));
}

uint32_t toUnsignedTicks(double v, double ticks_per_unit) {
  return static_cast<uint32_t>(std::clamp(std::round(v * ticks_per_unit), 0.0, 4.0e9));
}

}  // namespace

void RflexConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& expected, const std::string& got) {
    throw std::invalid_argument("rflex config: field '" + f + "': expected " + expected + ", got " +
                                got);
  };
  auto positive = [&](const std::string& f, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) bad(f, "a positive number", std::to_string(v));
  };
  if (device.empty()) bad("device", "a serial device path", "''");
  if (!SerialPort::supportedBaud(baud))
    bad("baud", "9600, 19200, 38400, 57600, 115200 or 230400", std::to_string(baud));
  positive("distance_ticks_per_m", distance_ticks_per_m);
  positive("angle_ticks_per_rad", angle_ticks_per_rad);
  positive("report_period", report_period);
  positive("watchdog_timeout", watchdog_timeout);
  positive("startup_timeout", startup_timeout);
  positive("write_timeout", write_timeout);
  positive("control_period", control_period);
  positive("resend_period", resend_period);
  if (report_period > 4000.0) bad("report_period", "at most 4000 s", std::to_string(report_period));
  if (watchdog_timeout <= report_period)
    bad("watchdog_timeout", "more than report_period (" + std::to_string(report_period) + " s)",
        std::to_string(watchdog_timeout));
}

RflexRobot::RflexRobot(const RflexConfig& config, const RobotDescription& description)
    : config_(config), description_(description) {
  config_.validate();
  try {
    port_ = std::make_unique<SerialPort>(config_.device, config_.baud);
  } catch (const SerialError& e) {
    throw RflexError(std::string("rflex: ") + e.what());
  }
  if (::pipe2(wake_pipe_, O_NONBLOCK | O_CLOEXEC) != 0)
    throw RflexError(std::string("rflex: cannot create a pipe: ") + std::strerror(errno));
  start_ = std::chrono::steady_clock::now();
  thread_ = std::thread([this] { run(); });

  std::unique_lock lock(mutex_);
  const bool ready = first_report_.wait_for(
      lock, std::chrono::duration<double>(config_.startup_timeout),
      [this] { return (have_translation_ && have_rotation_) || fault_.has_value(); });
  std::string why;
  if (fault_)
    why = *fault_;
  else if (!ready)
    why = "rflex " + config_.device + ": no odometry report from the rFLEX controller within " +
          fixed(config_.startup_timeout, 1) + " s (" + std::to_string(stats_.decoder.packets) +
          " packets, " + std::to_string(stats_.decoder.garbage_bytes) +
          " garbage bytes): is the base powered, and is the baud rate right (" +
          std::to_string(config_.baud) + ")?";
  lock.unlock();
  if (!why.empty()) {
    stop_ = true;
    wake();
    thread_.join();
    ::close(wake_pipe_[0]);
    ::close(wake_pipe_[1]);
    throw RflexError(why);
  }
}

RflexRobot::~RflexRobot() {
  stop_ = true;
  wake();
  if (thread_.joinable()) thread_.join();
  ::close(wake_pipe_[0]);
  ::close(wake_pipe_[1]);
}

double RflexRobot::now() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

Pose2 RflexRobot::odometry() const {
  std::lock_guard lock(mutex_);
  return pose_;
}

Pose2 RflexRobot::odometryAt(double t) const {
  std::lock_guard lock(mutex_);
  if (history_.empty() || t >= history_.back().first) return pose_;
  if (t <= history_.front().first) return history_.front().second;
  auto after = history_.begin();
  while (after->first < t) ++after;
  const auto& [t1, p1] = *after;
  const auto& [t0, p0] = *std::prev(after);
  const double f = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
  return Pose2(p0.x + f * (p1.x - p0.x), p0.y + f * (p1.y - p0.y),
               wrapAngle(p0.theta + f * wrapAngle(p1.theta - p0.theta)));
}

void RflexRobot::command(const MotionCommand& cmd) {
  if (!config_.enable_motion) return;
  MotionCommand c = cmd;
  if (!std::isfinite(c.linear) || !std::isfinite(c.angular) || !std::isfinite(c.amount))
    c = MotionCommand::stop();
  {
    std::lock_guard lock(mutex_);
    if (fault_) return;
    requested_ = c;
    new_request_ = true;
    segment_active_ = c.kind != MotionCommand::Kind::kVelocity;
  }
  wake();
}

RobotStatus RflexRobot::status() const {
  std::lock_guard lock(mutex_);
  return {bumped_, contact_events_, segment_active_, std::nullopt};
}

std::optional<std::string> RflexRobot::fault() const {
  std::lock_guard lock(mutex_);
  return fault_;
}

RflexStats RflexRobot::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

MotionCommand RflexRobot::lastSentVelocity() const {
  std::lock_guard lock(mutex_);
  return sent_;
}

void RflexRobot::wake() {
  const uint8_t b = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_pipe_[1], &b, 1);  // full pipe: already awake
}

void RflexRobot::send(const rflex::Packet& p) {
  const std::vector<uint8_t> bytes = rflex::encode(p);
  port_->write(bytes.data(), bytes.size(), config_.write_timeout);
}

void RflexRobot::sendVelocity(double v, double w) {
  const RobotDescription& d = description_;
  send(rflex::makeAxisSetDir(rflex::kTranslationAxis, toTicks(v, config_.distance_ticks_per_m),
                             toUnsignedTicks(d.max_linear_accel, config_.distance_ticks_per_m),
                             config_.translation_torque));
  send(rflex::makeAxisSetDir(rflex::kRotationAxis, toTicks(w, config_.angle_ticks_per_rad),
                             toUnsignedTicks(d.max_angular_accel, config_.angle_ticks_per_rad),
                             config_.rotation_torque));
  std::lock_guard lock(mutex_);
  stats_.commands_sent += 2;
  sent_ = {v, w, MotionCommand::Kind::kVelocity, 0.0};
}

void RflexRobot::latchFault(const std::string& why, bool port_usable) {
  bool stopped = false;
  if (port_usable && config_.enable_motion) {
    try {
      sendVelocity(0.0, 0.0);
      stopped = true;
    } catch (const SerialError&) {
    }
  }
  std::string message = "rflex " + config_.device + ": " + why;
  if (config_.enable_motion)
    message += stopped ? "; stop sent to the base" : "; no stop could be sent to the base";
  {
    std::lock_guard lock(mutex_);
    if (!fault_) fault_ = message;
    requested_ = MotionCommand::stop();
    segment_active_ = false;
  }
  first_report_.notify_all();
}

void RflexRobot::handle(const rflex::Packet& p, double t) {
  std::lock_guard lock(mutex_);
  if (const auto r = rflex::parseSystemReport(p)) {
    ++stats_.odometry_reports;
    stats_.controller_time_ms = r->timestamp_ms;
    if (r->axis == rflex::kTranslationAxis) {
      if (have_translation_) {
        const auto delta = static_cast<int32_t>(static_cast<uint32_t>(r->position) -
                                                static_cast<uint32_t>(last_translation_));
        pending_distance_ += delta / config_.distance_ticks_per_m;
      }
      have_translation_ = true;
      last_translation_ = r->position;
      stats_.translation_ticks = r->position;
      last_translation_time_ = t;
    } else if (r->axis == rflex::kRotationAxis) {
      double dtheta = 0.0;
      if (have_rotation_) {
        const auto delta = static_cast<int32_t>(static_cast<uint32_t>(r->position) -
                                                static_cast<uint32_t>(last_rotation_));
        dtheta = delta / config_.angle_ticks_per_rad;
      }
      // Midpoint integration of the distance since the last rotation report.
      const double mid = pose_.theta + 0.5 * dtheta;
      pose_.x += pending_distance_ * std::cos(mid);
      pose_.y += pending_distance_ * std::sin(mid);
      pose_.theta = wrapAngle(pose_.theta + dtheta);
      pending_distance_ = 0.0;
      // A few seconds of poses, for the frames' odometry at capture (odometryAt).
      history_.emplace_back(t, pose_);
      while (history_.size() > 1 && t - history_.front().first > kHistorySeconds)
        history_.pop_front();
      have_rotation_ = true;
      last_rotation_ = r->position;
      stats_.rotation_ticks = r->position;
      last_rotation_time_ = t;
    } else {
      ++stats_.ignored_packets;
      return;
    }
    if (have_translation_ && have_rotation_) first_report_.notify_all();
    return;
  }
  if (const auto d = rflex::parseDioReport(p)) {
    ++stats_.dio_reports;
    if (d->address == rflex::kBumperAddress) {
      const bool bumped = d->value != 0;
      if (bumped && !bumped_) ++contact_events_;
      bumped_ = bumped;
    }
    return;
  }
  ++stats_.ignored_packets;
}

void RflexRobot::controlStep(double t) {
  MotionCommand req;
  bool fresh = false;
  Pose2 pose;
  {
    std::unique_lock lock(mutex_);
    if (fault_) return;
    if (have_translation_ && have_rotation_) {
      const double silent = t - std::min(last_translation_time_, last_rotation_time_);
      if (silent > config_.watchdog_timeout) {
        lock.unlock();
        latchFault("no odometry report from the rFLEX controller for " + fixed(silent, 2) +
                       " s (watchdog timeout " + fixed(config_.watchdog_timeout, 2) + " s)",
                   true);
        return;
      }
    }
    if (!config_.enable_motion) return;
    req = requested_;
    fresh = new_request_;
    new_request_ = false;
    pose = pose_;
  }

  const RobotDescription& d = description_;
  double v = 0.0, w = 0.0;
  bool finished = false;
  if (req.kind == MotionCommand::Kind::kVelocity) {
    v = std::clamp(req.linear, -d.max_linear_speed, d.max_linear_speed);
    w = std::clamp(req.angular, -d.max_angular_speed, d.max_angular_speed);
  } else {
    if (fresh) {
      segment_start_ = pose;
      segment_done_ = 0.0;
      segment_last_theta_ = pose.theta;
    }
    if (req.kind == MotionCommand::Kind::kTurn) {
      segment_done_ += wrapAngle(pose.theta - segment_last_theta_);
      segment_last_theta_ = pose.theta;
      const double left = req.amount - segment_done_;
      if (std::abs(left) < kTurnTolerance) {
        finished = true;
      } else {
        const double rate = brakingSpeed(left, d.max_angular_accel, d.max_angular_speed);
        w = std::copysign(std::max(kMinSegmentTurnRate, kProfileMargin * rate), left);
      }
    } else {
      const double c = std::cos(segment_start_.theta), s = std::sin(segment_start_.theta);
      segment_done_ = c * (pose.x - segment_start_.x) + s * (pose.y - segment_start_.y);
      const double left = req.amount - segment_done_;
      if (std::abs(left) < kStraightTolerance) {
        finished = true;
      } else {
        const double speed = brakingSpeed(left, d.max_linear_accel, d.max_linear_speed);
        v = std::copysign(std::max(kMinSegmentSpeed, kProfileMargin * speed), left);
        w = std::clamp(2.0 * wrapAngle(segment_start_.theta - pose.theta), -d.max_angular_speed,
                       d.max_angular_speed);
      }
    }
    if (finished) {
      std::lock_guard lock(mutex_);
      if (!new_request_) {  // not replaced meanwhile
        requested_ = MotionCommand::stop();
        segment_active_ = false;
      }
    }
  }

  MotionCommand sent;
  {
    std::lock_guard lock(mutex_);
    sent = sent_;
  }
  if (v != sent.linear || w != sent.angular || t - last_send_time_ >= config_.resend_period) {
    sendVelocity(v, w);
    last_send_time_ = t;
  }
}

void RflexRobot::run() {
  bool port_ok = true;
  try {
    const auto period_us = static_cast<uint32_t>(std::round(config_.report_period * 1e6));
    send(rflex::makeMotCommand(rflex::kMotSetDefaults));
    send(rflex::makeSystemReportRequest(period_us));
    send(rflex::makeDioReportRequest(period_us));
    if (config_.enable_motion) {
      send(rflex::makeMotCommand(rflex::kMotBrakeRelease));
      sendVelocity(0.0, 0.0);
    }
  } catch (const SerialError& e) {
    latchFault(std::string("cannot start the controller: ") + e.what(), false);
    port_ok = false;
  }

  std::vector<uint8_t> buf(512);
  std::vector<rflex::Packet> packets;
  while (!stop_) {
    if (port_ok) {
      size_t got = 0;
      const SerialPort::ReadResult r =
          port_->read(buf.data(), buf.size(), got, config_.control_period, wake_pipe_[0]);
      if (r == SerialPort::ReadResult::kData) {
        packets.clear();
        decoder_.feed(buf.data(), got, packets);
        const double t = now();
        for (const rflex::Packet& p : packets) handle(p, t);
        std::lock_guard lock(mutex_);
        stats_.decoder = decoder_.stats();
      } else if (r == SerialPort::ReadResult::kHangUp) {
        latchFault("the serial device hung up (end of file or I/O error): controller disconnected",
                   false);
        port_ok = false;
      }
    } else {
      pollfd p{wake_pipe_[0], POLLIN, 0};
      ::poll(&p, 1, static_cast<int>(config_.control_period * 1000.0) + 1);
    }
    uint8_t drain[64];
    while (::read(wake_pipe_[0], drain, sizeof drain) > 0) {
    }
    if (!port_ok || stop_) continue;
    try {
      controlStep(now());
    } catch (const SerialError& e) {
      latchFault(std::string("cannot send a command: ") + e.what(), false);
      port_ok = false;
    }
  }

  if (!port_ok) return;
  try {  // a safe stop on the way out
    if (config_.enable_motion) sendVelocity(0.0, 0.0);
    send(rflex::makeSystemReportRequest(0));
    send(rflex::makeDioReportRequest(0));
    if (config_.enable_motion) send(rflex::makeMotCommand(rflex::kMotBrakeSet));
  } catch (const SerialError&) {
  }
}

}  // namespace coopmap

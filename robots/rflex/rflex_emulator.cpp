#include "robots/rflex/rflex_emulator.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace coopmap {
namespace {

double approach(double current, double target, double accel, double dt) {
  const double step = accel * dt;
  return current + std::clamp(target - current, -step, step);
}

uint32_t encoderTicks(uint32_t offset, double value, double ticks_per_unit) {
  // Converting a signed 64-bit count to uint32 wraps modulo 2^32, as the encoder counter does.
  return offset + static_cast<uint32_t>(std::llround(value * ticks_per_unit));
}

}  // namespace

RflexEmulator::RflexEmulator(const RflexEmulatorConfig& config) : config_(config) {
  pose_ = config_.start;
  counters_.brake_on = true;
  master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master_ < 0)
    throw std::runtime_error(std::string("rflex emulator: no pseudo-terminal: ") +
                             std::strerror(errno));
  char name[256];
  if (::grantpt(master_) != 0 || ::unlockpt(master_) != 0 ||
      ::ptsname_r(master_, name, sizeof name) != 0) {
    const std::string why = std::strerror(errno);
    ::close(master_);
    throw std::runtime_error("rflex emulator: cannot set up the pseudo-terminal: " + why);
  }
  device_ = name;
  slave_keep_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave_keep_ < 0) {
    const std::string why = std::strerror(errno);
    ::close(master_);
    throw std::runtime_error("rflex emulator: cannot open " + device_ + ": " + why);
  }
  termios t{};
  if (::tcgetattr(slave_keep_, &t) == 0) {
    ::cfmakeraw(&t);
    ::tcsetattr(slave_keep_, TCSANOW, &t);
  }
  ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
  start_ = std::chrono::steady_clock::now();
  thread_ = std::thread([this] { run(); });
}

RflexEmulator::~RflexEmulator() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (master_ >= 0) ::close(master_);
  if (slave_keep_ >= 0) ::close(slave_keep_);
}

double RflexEmulator::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

Pose2 RflexEmulator::pose() const {
  std::lock_guard lock(mutex_);
  return pose_;
}
double RflexEmulator::linearVelocity() const {
  std::lock_guard lock(mutex_);
  return v_;
}
double RflexEmulator::angularVelocity() const {
  std::lock_guard lock(mutex_);
  return w_;
}
double RflexEmulator::targetLinear() const {
  std::lock_guard lock(mutex_);
  return target_v_;
}
double RflexEmulator::targetAngular() const {
  std::lock_guard lock(mutex_);
  return target_w_;
}
RflexEmulatorCounters RflexEmulator::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

void RflexEmulator::setGarbage(bool on) {
  std::lock_guard lock(mutex_);
  garbage_ = on;
}
void RflexEmulator::corruptNext(int packets) {
  std::lock_guard lock(mutex_);
  corrupt_ = std::max(0, packets);
}
void RflexEmulator::setSilent(bool on) {
  std::lock_guard lock(mutex_);
  silent_ = on;
}
void RflexEmulator::setBumper(bool pressed) {
  std::lock_guard lock(mutex_);
  bumper_ = pressed;
}

void RflexEmulator::hangUp() {
  std::unique_lock lock(mutex_);
  hang_up_request_ = true;
  hung_up_cv_.wait_for(lock, std::chrono::seconds(5), [this] { return hung_up_; });
}

void RflexEmulator::integrate(double dt) {
  const bool brake = counters_.brake_on;
  const double av = accel_v_ > 0.0 ? accel_v_ : config_.default_linear_accel;
  const double aw = accel_w_ > 0.0 ? accel_w_ : config_.default_angular_accel;
  v_ = approach(v_, brake ? 0.0 : target_v_, brake ? config_.default_linear_accel : av, dt);
  w_ = approach(w_, brake ? 0.0 : target_w_, brake ? config_.default_angular_accel : aw, dt);
  const double mid = pose_.theta + 0.5 * w_ * dt;
  pose_.x += v_ * dt * std::cos(mid);
  pose_.y += v_ * dt * std::sin(mid);
  pose_.theta = wrapAngle(pose_.theta + w_ * dt);
  distance_ += v_ * dt;
  angle_ += w_ * dt;
}

void RflexEmulator::handle(const rflex::Packet& p) {
  std::lock_guard lock(mutex_);
  ++counters_.packets_received;
  if (const auto c = rflex::parseAxisSetDir(p)) {
    ++counters_.axis_commands;
    if (c->axis == rflex::kTranslationAxis) {
      target_v_ = c->velocity / config_.distance_ticks_per_m;
      accel_v_ = c->acceleration / config_.distance_ticks_per_m;
    } else if (c->axis == rflex::kRotationAxis) {
      target_w_ = c->velocity / config_.angle_ticks_per_rad;
      accel_w_ = c->acceleration / config_.angle_ticks_per_rad;
    }
    return;
  }
  if (const auto period = rflex::parsePeriodRequest(p)) {
    ++counters_.report_requests;
    if (p.port == rflex::kMotPort) {
      counters_.report_period_us = *period;
      next_report_ = elapsed();
    } else {
      dio_period_us_ = *period;
      next_dio_ = elapsed();
    }
    return;
  }
  if (p.port == rflex::kMotPort) {
    if (p.opcode == rflex::kMotBrakeSet) counters_.brake_on = true;
    if (p.opcode == rflex::kMotBrakeRelease) counters_.brake_on = false;
    if (p.opcode == rflex::kMotSetDefaults) target_v_ = target_w_ = accel_v_ = accel_w_ = 0.0;
  }
}

void RflexEmulator::writeBytes(const std::vector<uint8_t>& bytes) {
  size_t done = 0;
  int waits = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(master_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) return;  // nobody listening
    if (++waits > 20) return;  // the reader is not draining: drop the rest
    pollfd p{master_, POLLOUT, 0};
    ::poll(&p, 1, 1);
  }
}

void RflexEmulator::sendPacket(const rflex::Packet& p) {
  std::vector<uint8_t> bytes;
  {
    std::lock_guard lock(mutex_);
    if (silent_) return;
    if (garbage_) {
      // A lone ESC that starts no frame, then bytes that are not ESC.
      bytes = {rflex::kEsc, 'G'};
      for (int i = 0; i < 5; ++i) {
        garbage_seed_ = garbage_seed_ * 1103515245u + 12345u;
        uint8_t b = static_cast<uint8_t>(garbage_seed_ >> 16);
        if (b == rflex::kEsc) b = 0x55;
        bytes.push_back(b);
      }
      counters_.garbage_bytes_sent += bytes.size();
    }
    std::vector<uint8_t> frame;
    if (corrupt_ > 0) {
      --corrupt_;
      ++counters_.corrupt_packets_sent;
      frame = rflex::encodeCorrupt(p);
    } else {
      frame = rflex::encode(p);
    }
    bytes.insert(bytes.end(), frame.begin(), frame.end());
    ++counters_.reports_sent;
  }
  writeBytes(bytes);
}

void RflexEmulator::run() {
  std::vector<uint8_t> buf(512);
  std::vector<rflex::Packet> packets;
  while (!stop_) {
    {
      std::lock_guard lock(mutex_);
      if (hang_up_request_ && !hung_up_) {
        ::close(master_);
        ::close(slave_keep_);
        master_ = slave_keep_ = -1;
        hung_up_ = true;
        hung_up_cv_.notify_all();
      }
      if (hung_up_) return;
    }
    pollfd pfd{master_, POLLIN, 0};
    if (::poll(&pfd, 1, std::max(1, static_cast<int>(config_.step * 1000.0))) > 0 &&
        (pfd.revents & POLLIN)) {
      const ssize_t n = ::read(master_, buf.data(), buf.size());
      if (n > 0) {
        packets.clear();
        decoder_.feed(buf.data(), static_cast<size_t>(n), packets);
        for (const rflex::Packet& p : packets) handle(p);
        std::lock_guard lock(mutex_);
        counters_.decoder = decoder_.stats();
      }
    }

    const double t = elapsed();
    std::vector<rflex::Packet> out;
    {
      std::lock_guard lock(mutex_);
      while (sim_time_ + config_.step <= t) {
        integrate(config_.step);
        sim_time_ += config_.step;
      }
      const auto stamp = static_cast<uint32_t>(t * 1000.0);
      const double period = counters_.report_period_us * 1e-6;
      if (period > 0.0 && t >= next_report_) {
        rflex::AxisReport r;
        r.timestamp_ms = stamp;
        r.axis = rflex::kTranslationAxis;
        r.position = static_cast<int32_t>(
            encoderTicks(config_.encoder_offset, distance_, config_.distance_ticks_per_m));
        r.velocity = static_cast<int32_t>(std::lround(v_ * config_.distance_ticks_per_m));
        out.push_back(rflex::makeSystemReport(r));
        r.axis = rflex::kRotationAxis;
        r.position = static_cast<int32_t>(
            encoderTicks(config_.encoder_offset, angle_, config_.angle_ticks_per_rad));
        r.velocity = static_cast<int32_t>(std::lround(w_ * config_.angle_ticks_per_rad));
        out.push_back(rflex::makeSystemReport(r));
        next_report_ += period;
        if (next_report_ < t) next_report_ = t + period;
      }
      const double dio_period = dio_period_us_ * 1e-6;
      if (dio_period > 0.0 && (t >= next_dio_ || bumper_ != last_bumper_sent_)) {
        out.push_back(rflex::makeDioReport(
            {stamp, rflex::kBumperAddress, static_cast<uint16_t>(bumper_ ? 0x0F : 0)}));
        last_bumper_sent_ = bumper_;
        next_dio_ = t + dio_period;
      }
    }
    for (const rflex::Packet& p : out) sendPacket(p);
  }
}

}  // namespace coopmap

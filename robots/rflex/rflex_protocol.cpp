#include "robots/rflex/rflex_protocol.h"

#include <stdexcept>
#include <string>

namespace coopmap::rflex {
namespace {

constexpr size_t kMaxBody = 4 + 255 + 1;  // header, data, checksum

void putStuffed(std::vector<uint8_t>& out, uint8_t b) {
  out.push_back(b);
  if (b == kEsc) out.push_back(kNul);
}

std::vector<uint8_t> frame(const Packet& p, uint8_t check) {
  if (p.data.size() > 255)
    throw std::invalid_argument("rflex packet: data of " + std::to_string(p.data.size()) +
                                " bytes, at most 255 fit");
  std::vector<uint8_t> out;
  out.reserve(p.data.size() + 12);
  out.push_back(kEsc);
  out.push_back(kStx);
  putStuffed(out, p.port);
  putStuffed(out, p.id);
  putStuffed(out, p.opcode);
  putStuffed(out, static_cast<uint8_t>(p.data.size()));
  for (uint8_t b : p.data) putStuffed(out, b);
  putStuffed(out, check);
  out.push_back(kEsc);
  out.push_back(kEtx);
  return out;
}

}  // namespace

uint8_t checksum(const Packet& p) {
  uint8_t c = p.port ^ p.id ^ p.opcode ^ static_cast<uint8_t>(p.data.size());
  for (uint8_t b : p.data) c ^= b;
  return c;
}

std::vector<uint8_t> encode(const Packet& p) { return frame(p, checksum(p)); }

std::vector<uint8_t> encodeCorrupt(const Packet& p) {
  return frame(p, static_cast<uint8_t>(checksum(p) ^ 0x5A));
}

void putU32(std::vector<uint8_t>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<uint8_t>(v >> shift));
}

void putU16(std::vector<uint8_t>& out, uint16_t v) {
  out.push_back(static_cast<uint8_t>(v >> 8));
  out.push_back(static_cast<uint8_t>(v));
}

uint32_t getU32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}

uint16_t getU16(const uint8_t* p) { return static_cast<uint16_t>((p[0] << 8) | p[1]); }

void Decoder::feed(const uint8_t* bytes, size_t n, std::vector<Packet>& out) {
  for (size_t i = 0; i < n; ++i) {
    const uint8_t b = bytes[i];
    switch (state_) {
      case State::kIdle:
        if (b == kEsc)
          state_ = State::kIdleEsc;
        else
          ++stats_.garbage_bytes;
        break;
      case State::kIdleEsc:
        if (b == kStx) {
          body_.clear();
          state_ = State::kBody;
        } else if (b == kEsc) {
          ++stats_.garbage_bytes;  // the first ESC was garbage; this one may start a frame
        } else {
          stats_.garbage_bytes += 2;
          state_ = State::kIdle;
        }
        break;
      case State::kBody:
        if (b == kEsc) {
          state_ = State::kBodyEsc;
        } else if (body_.size() >= kMaxBody) {
          ++stats_.malformed;  // no end in sight: drop and look for the next start
          state_ = State::kIdle;
        } else {
          body_.push_back(b);
        }
        break;
      case State::kBodyEsc:
        if (b == kNul) {
          if (body_.size() >= kMaxBody) {
            ++stats_.malformed;
            state_ = State::kIdle;
          } else {
            body_.push_back(kEsc);
            state_ = State::kBody;
          }
        } else if (b == kEtx) {
          finishFrame(out);
          state_ = State::kIdle;
        } else if (b == kStx) {
          ++stats_.malformed;  // a new frame started before this one ended
          body_.clear();
          state_ = State::kBody;
        } else if (b == kSoh) {
          state_ = State::kBody;
        } else {
          ++stats_.malformed;
          state_ = State::kIdle;
        }
        break;
    }
  }
}

void Decoder::finishFrame(std::vector<Packet>& out) {
  if (body_.size() < 5 || body_.size() != size_t{body_[3]} + 5) {
    ++stats_.malformed;
    return;
  }
  Packet p;
  p.port = body_[0];
  p.id = body_[1];
  p.opcode = body_[2];
  p.data.assign(body_.begin() + 4, body_.end() - 1);
  if (checksum(p) != body_.back()) {
    ++stats_.bad_checksums;
    return;
  }
  ++stats_.packets;
  out.push_back(std::move(p));
}

Packet makeAxisSetDir(uint8_t axis, int32_t velocity, uint32_t acceleration, uint32_t torque) {
  Packet p{kMotPort, 0, kMotAxisSetDir, {}};
  p.data.push_back(axis);
  const int64_t v = velocity;
  putU32(p.data, static_cast<uint32_t>(v < 0 ? -v : v));
  putU32(p.data, acceleration);
  putU32(p.data, torque);
  p.data.push_back(velocity < 0 ? 0 : 1);
  return p;
}

Packet makeSystemReportRequest(uint32_t period_us) {
  Packet p{kMotPort, 0, kMotSystemReportReq, {}};
  putU32(p.data, period_us);
  putU32(p.data, period_us == 0 ? 0 : 3);
  return p;
}

Packet makeDioReportRequest(uint32_t period_us) {
  Packet p{kDioPort, 0, kDioReportsReq, {}};
  putU32(p.data, period_us);
  return p;
}

Packet makeMotCommand(MotOpcode opcode) { return Packet{kMotPort, 0, opcode, {}}; }

std::optional<AxisCommand> parseAxisSetDir(const Packet& p) {
  if (p.port != kMotPort || p.opcode != kMotAxisSetDir || p.data.size() != 14) return std::nullopt;
  AxisCommand c;
  c.axis = p.data[0];
  const int64_t speed = getU32(&p.data[1]);
  if (speed > INT32_MAX) return std::nullopt;
  c.velocity = static_cast<int32_t>(p.data[13] ? speed : -speed);
  c.acceleration = getU32(&p.data[5]);
  c.torque = getU32(&p.data[9]);
  return c;
}

Packet makeSystemReport(const AxisReport& r) {
  Packet p{kMotPort, 0, kMotSystemReport, {}};
  putU32(p.data, r.status);
  putU32(p.data, r.timestamp_ms);
  p.data.push_back(r.axis);
  putU32(p.data, static_cast<uint32_t>(r.position));
  putU32(p.data, static_cast<uint32_t>(r.velocity));
  putU32(p.data, r.acceleration);
  putU32(p.data, r.torque);
  return p;
}

std::optional<AxisReport> parseSystemReport(const Packet& p) {
  if (p.port != kMotPort || p.opcode != kMotSystemReport || p.data.size() < 25) return std::nullopt;
  AxisReport r;
  r.status = getU32(&p.data[0]);
  r.timestamp_ms = getU32(&p.data[4]);
  r.axis = p.data[8];
  r.position = static_cast<int32_t>(getU32(&p.data[9]));
  r.velocity = static_cast<int32_t>(getU32(&p.data[13]));
  r.acceleration = getU32(&p.data[17]);
  r.torque = getU32(&p.data[21]);
  return r;
}

Packet makeDioReport(const DioReport& r) {
  Packet p{kDioPort, 0, kDioReport, {}};
  putU32(p.data, r.timestamp_ms);
  p.data.push_back(r.address);
  putU16(p.data, r.value);
  return p;
}

std::optional<DioReport> parseDioReport(const Packet& p) {
  if (p.port != kDioPort || p.opcode != kDioReport || p.data.size() < 7) return std::nullopt;
  return DioReport{getU32(&p.data[0]), p.data[4], getU16(&p.data[5])};
}

std::optional<uint32_t> parsePeriodRequest(const Packet& p) {
  const bool mot = p.port == kMotPort && p.opcode == kMotSystemReportReq && p.data.size() == 8;
  const bool dio = p.port == kDioPort && p.opcode == kDioReportsReq && p.data.size() == 4;
  if (!mot && !dio) return std::nullopt;
  return getU32(&p.data[0]);
}

}  // namespace coopmap::rflex

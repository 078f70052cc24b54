#include "core/correction/traverse_log.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/io/binary_io.h"

namespace coopmap {

namespace {

constexpr char kMagic[8] = {'C', 'M', 'T', 'R', 'A', 'V', 'L', 'G'};
constexpr uint32_t kRecordMagic = 0x4E414353;  // "SCAN" read as little-endian bytes
constexpr uint32_t kEndMagic = 0x21444E45;     // "END!" read as little-endian bytes
constexpr size_t kReadingBytes = 4 * 8 + 1;
constexpr uint8_t kFloorEdgeBit = 0x80;  // in a reading's kind byte, from version 2
constexpr size_t kFixedPayloadBytes = 4 * 8 + 1 + 3 * 8 + 4;
// Bounds on stored values a reader accepts (beyond them a file is corrupt or not a robot's):
constexpr double kMaxStamp = 1e9;       // s
constexpr double kMaxCoordinate = 1e5;  // m, odometry
constexpr double kMaxAngle = 1e3;       // rad (odometry headings are not wrapped)
constexpr double kMaxOffset = 100.0;    // m, sensor origin on the robot
constexpr double kMaxRange = 1e3;       // m
constexpr double kMaxDisparity = 1e5;   // px

uint32_t crc(const char* data, size_t n) { return crc32Of(data, n); }
using Writer = ByteWriter;
using Reader = ByteReader;

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw std::runtime_error(source + ": " + what);
}

// A stored number a map can be built from: finite and, where a bound is given, within it.
void checkValue(const std::string& source, const std::string& where, const char* field, double v,
                double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi) {
    char b[160];
    std::snprintf(b, sizeof b, ": %s %g, expected a finite number in [%g, %g]", field, v, lo, hi);
    fail(source, where + b);
  }
}

}  // namespace

const char* toString(MotionSegment s) {
  switch (s) {
    case MotionSegment::kStop:
      return "stop";
    case MotionSegment::kTurn:
      return "turn";
    case MotionSegment::kStraight:
      return "straight";
  }
  return "?";
}

MotionSegment segmentOf(const MotionCommand& cmd) {
  switch (cmd.kind) {
    case MotionCommand::Kind::kTurn:
      return cmd.amount != 0.0 ? MotionSegment::kTurn : MotionSegment::kStop;
    case MotionCommand::Kind::kStraight:
      return cmd.amount != 0.0 ? MotionSegment::kStraight : MotionSegment::kStop;
    case MotionCommand::Kind::kVelocity:
      if (cmd.linear != 0.0) return MotionSegment::kStraight;
      return cmd.angular != 0.0 ? MotionSegment::kTurn : MotionSegment::kStop;
  }
  return MotionSegment::kStop;
}

std::string encodeTraverseLog(const TraverseLog& log) {
  Writer h;
  h.out.append(kMagic, sizeof(kMagic));
  h.put<uint32_t>(TraverseLog::kVersion);
  h.put<uint32_t>(static_cast<uint32_t>(log.robot.size()));
  h.out += log.robot;
  h.put<uint32_t>(crc(h.out.data(), h.out.size()));
  std::string out = std::move(h.out);
  for (const TraverseEntry& e : log.entries) {
    Writer p;
    const RadialMap& s = e.scan;
    p.put(s.stamp);
    p.put(s.odometry.x);
    p.put(s.odometry.y);
    p.put(s.odometry.theta);
    p.put(static_cast<uint8_t>(e.segment));
    p.put(s.sensor_origin.x());
    p.put(s.sensor_origin.y());
    p.put(s.max_range);
    p.put<uint32_t>(static_cast<uint32_t>(s.readings.size()));
    for (const RadialReading& r : s.readings) {
      p.put(r.bearing);
      p.put(r.range);
      p.put(r.sigma);
      p.put(r.disparity);
      p.put(static_cast<uint8_t>(static_cast<uint8_t>(r.kind) |
                                 (r.floor_edge && r.kind == RadialKind::kHit ? kFloorEdgeBit : 0)));
    }
    Writer rec;
    rec.put(kRecordMagic);
    rec.put<uint32_t>(static_cast<uint32_t>(p.out.size()));
    out += rec.out;
    out += p.out;
    Writer c;
    c.put(crc(p.out.data(), p.out.size()));
    out += c.out;
  }
  Writer end;
  end.put(kEndMagic);
  end.put<uint32_t>(static_cast<uint32_t>(log.entries.size()));
  end.put<uint32_t>(crc(end.out.data(), end.out.size()));
  out += end.out;
  return out;
}

TraverseLog decodeTraverseLog(const std::string& bytes, const std::string& source) {
  if (bytes.size() < sizeof(kMagic) + 8 || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    fail(source, "not a coopmap traverse log (expected magic 'CMTRAVLG' at byte 0)");
  Reader h(bytes, sizeof(kMagic), bytes.size());
  const uint32_t version = h.get<uint32_t>();
  if (version < 1 || version > TraverseLog::kVersion)
    fail(source, "traverse log version " + std::to_string(version) + " (this build reads 1 to " +
                     std::to_string(TraverseLog::kVersion) + ")");
  const uint32_t name_length = h.get<uint32_t>();
  if (h.left() < static_cast<size_t>(name_length) + 4)
    fail(source, "header truncated (robot name of " + std::to_string(name_length) +
                     " bytes and its checksum expected)");
  TraverseLog log;
  const size_t name_at = sizeof(kMagic) + 8;
  log.robot = bytes.substr(name_at, name_length);
  size_t pos = name_at + name_length;
  {
    Reader c(bytes, pos, bytes.size());
    if (c.get<uint32_t>() != crc(bytes.data(), pos))
      fail(source, "header checksum mismatch (the file is corrupt)");
  }
  pos += 4;
  bool ended = false;
  while (pos < bytes.size()) {
    const size_t index = log.entries.size();
    const std::string where = "record " + std::to_string(index) + " at byte " + std::to_string(pos);
    if (bytes.size() - pos < 8)
      fail(source, where + ": truncated (record header of 8 bytes expected, " +
                       std::to_string(bytes.size() - pos) + " left)");
    Reader rh(bytes, pos, bytes.size());
    const uint32_t magic = rh.get<uint32_t>();
    const uint32_t length = rh.get<uint32_t>();
    if (version >= 3 && magic == kEndMagic) {
      // The end record: u32 magic, u32 record count, u32 CRC-32 of the two.
      if (bytes.size() - pos < 12)
        fail(source, "end record at byte " + std::to_string(pos) +
                         ": truncated (12 bytes expected, " + std::to_string(bytes.size() - pos) +
                         " left)");
      if (rh.get<uint32_t>() != crc(bytes.data() + pos, 8))
        fail(source, "end record at byte " + std::to_string(pos) +
                         ": checksum mismatch (the file is corrupt)");
      if (length != index)
        fail(source, "end record at byte " + std::to_string(pos) + ": it counts " +
                         std::to_string(length) + " records, the file holds " +
                         std::to_string(index));
      if (pos + 12 != bytes.size())
        fail(source, "end record at byte " + std::to_string(pos) + ": " +
                         std::to_string(bytes.size() - pos - 12) + " bytes after it");
      ended = true;
      break;
    }
    if (magic != kRecordMagic) fail(source, where + ": bad record magic (the file is corrupt)");
    if (bytes.size() - pos - 8 < static_cast<size_t>(length) + 4)
      fail(source, where + ": truncated (payload of " + std::to_string(length) +
                       " bytes and its checksum expected, " +
                       std::to_string(bytes.size() - pos - 8) + " left)");
    const size_t payload = pos + 8;
    {
      Reader c(bytes, payload + length, bytes.size());
      if (c.get<uint32_t>() != crc(bytes.data() + payload, length))
        fail(source, where + ": checksum mismatch (the file is corrupt)");
    }
    if (length < kFixedPayloadBytes)
      fail(source, where + ": payload of " + std::to_string(length) + " bytes, expected at least " +
                       std::to_string(kFixedPayloadBytes));
    Reader p(bytes, payload, payload + length);
    TraverseEntry e;
    RadialMap& s = e.scan;
    s.stamp = p.get<double>();
    s.odometry.x = p.get<double>();
    s.odometry.y = p.get<double>();
    s.odometry.theta = p.get<double>();
    checkValue(source, where, "stamp", s.stamp,
               log.entries.empty() ? -kMaxStamp : log.entries.back().scan.stamp, kMaxStamp);
    checkValue(source, where, "odometry x", s.odometry.x, -kMaxCoordinate, kMaxCoordinate);
    checkValue(source, where, "odometry y", s.odometry.y, -kMaxCoordinate, kMaxCoordinate);
    checkValue(source, where, "odometry theta", s.odometry.theta, -kMaxAngle, kMaxAngle);
    const uint8_t segment = p.get<uint8_t>();
    if (segment > 2)
      fail(source, where + ": segment " + std::to_string(segment) + ", expected 0, 1 or 2");
    e.segment = static_cast<MotionSegment>(segment);
    s.sensor_origin.x() = p.get<double>();
    s.sensor_origin.y() = p.get<double>();
    s.max_range = p.get<double>();
    checkValue(source, where, "sensor origin x", s.sensor_origin.x(), -kMaxOffset, kMaxOffset);
    checkValue(source, where, "sensor origin y", s.sensor_origin.y(), -kMaxOffset, kMaxOffset);
    checkValue(source, where, "max_range", s.max_range, 0.0, kMaxRange);
    const uint32_t count = p.get<uint32_t>();
    if (p.left() != static_cast<size_t>(count) * kReadingBytes)
      fail(source, where + ": " + std::to_string(count) + " readings need " +
                       std::to_string(static_cast<size_t>(count) * kReadingBytes) +
                       " bytes, the payload has " + std::to_string(p.left()));
    s.readings.resize(count);
    for (RadialReading& r : s.readings) {
      r.bearing = p.get<double>();
      r.range = p.get<double>();
      r.sigma = p.get<double>();
      r.disparity = p.get<double>();
      const uint8_t byte = p.get<uint8_t>();
      const uint8_t kind = version >= 2 ? static_cast<uint8_t>(byte & ~kFloorEdgeBit) : byte;
      r.floor_edge = version >= 2 && (byte & kFloorEdgeBit) != 0;
      if (kind > 2 || (r.floor_edge && kind != 1))
        fail(source, where + ": reading kind " + std::to_string(byte) +
                         (version >= 2 ? ", expected 0, 1, 2 or 129 (a hit at the floor's end)"
                                       : ", expected 0, 1 or 2"));
      r.kind = static_cast<RadialKind>(kind);
      checkValue(source, where, "reading bearing", r.bearing, -kMaxAngle, kMaxAngle);
      checkValue(source, where, "reading range", r.range, 0.0, kMaxRange);
      checkValue(source, where, "reading sigma", r.sigma, 0.0, kMaxRange);
      checkValue(source, where, "reading disparity", r.disparity, -kMaxDisparity, kMaxDisparity);
    }
    log.entries.push_back(std::move(e));
    pos = payload + length + 4;
  }
  if (version >= 3 && !ended)
    fail(source, "no end record after record " + std::to_string(log.entries.size()) +
                     " (the file was cut short)");
  return log;
}

void saveTraverseLog(const std::string& path, const TraverseLog& log) {
  writeFileAtomic(path, encodeTraverseLog(log));
}

TraverseLog loadTraverseLog(const std::string& path) {
  return decodeTraverseLog(readFile(path), path);
}

}  // namespace coopmap

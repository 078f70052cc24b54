#include "core/correction/traverse_log.h"

#include <cstring>
#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/io/binary_io.h"

namespace coopmap {

namespace {

constexpr char kMagic[8] = {'C', 'M', 'T', 'R', 'A', 'V', 'L', 'G'};
constexpr uint32_t kRecordMagic = 0x4E414353;  // "SCAN" read as little-endian bytes
constexpr size_t kReadingBytes = 4 * 8 + 1;
constexpr uint8_t kFloorEdgeBit = 0x80;  // in a reading's kind byte, from version 2
constexpr size_t kFixedPayloadBytes = 4 * 8 + 1 + 3 * 8 + 4;

uint32_t crc(const char* data, size_t n) { return crc32Of(data, n); }
using Writer = ByteWriter;
using Reader = ByteReader;

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw std::runtime_error(source + ": " + what);
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
  while (pos < bytes.size()) {
    const size_t index = log.entries.size();
    const std::string where = "record " + std::to_string(index) + " at byte " + std::to_string(pos);
    if (bytes.size() - pos < 8)
      fail(source, where + ": truncated (record header of 8 bytes expected, " +
                       std::to_string(bytes.size() - pos) + " left)");
    Reader rh(bytes, pos, bytes.size());
    const uint32_t magic = rh.get<uint32_t>();
    const uint32_t length = rh.get<uint32_t>();
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
    const uint8_t segment = p.get<uint8_t>();
    if (segment > 2)
      fail(source, where + ": segment " + std::to_string(segment) + ", expected 0, 1 or 2");
    e.segment = static_cast<MotionSegment>(segment);
    s.sensor_origin.x() = p.get<double>();
    s.sensor_origin.y() = p.get<double>();
    s.max_range = p.get<double>();
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
    }
    log.entries.push_back(std::move(e));
    pos = payload + length + 4;
  }
  return log;
}

void saveTraverseLog(const std::string& path, const TraverseLog& log) {
  writeFileAtomic(path, encodeTraverseLog(log));
}

TraverseLog loadTraverseLog(const std::string& path) {
  return decodeTraverseLog(readFile(path), path);
}

}  // namespace coopmap

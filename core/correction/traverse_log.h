// The traverse log (section 4.1 of the paper): every sensing cycle a robot appends the
// radial map it made, the odometry pose it was taken at, and the kind of motion segment it
// was executing. Back at the home base the log is corrected and the map rebuilt from it.
//
// File format, version 3 (all numbers little-endian; f64 = IEEE 754 double):
//   header  : 8 bytes magic "CMTRAVLG", u32 version (= 3), u32 name length N, N bytes of
//             robot name (UTF-8), u32 CRC-32 of the header bytes before it
//   records : each u32 record magic 0x4E414353 ("SCAN"), u32 payload length L, L bytes of
//             payload, u32 CRC-32 (zlib) of the payload
//   end     : u32 magic 0x21444E45 ("END!"), u32 number of records, u32 CRC-32 of those 8
//             bytes; the file ends there
//   payload : f64 stamp (s), f64 x, f64 y (m), f64 theta (rad) of the odometry pose X_OR,
//             u8 segment (0 stop, 1 turn, 2 straight), f64 sensor_origin x, y (m, robot frame),
//             f64 max_range (m), u32 reading count R, then R readings of
//             f64 bearing (rad), f64 range (m), f64 sigma (m), f64 disparity (px), u8 kind
//             (0 none, 1 hit, 2 beyond; + 128 for a hit at the floor's end,
//             RadialReading::floor_edge). Version 2 (no end record) and version 1 (no end
//             record, no floor-edge bit) are read too.
// Values are stored exactly, so a loaded log rebuilds a map bit for bit. Readers reject
// unknown versions, bad magic, truncated records, checksum mismatches, a version 3 file
// without its end record (cut at a record boundary), and values no robot logs (not finite,
// out of bounds, stamps going back) with an error naming the file, the record and its byte
// offset.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/perception/radial_map.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

// The kind of motion between the previous sensing cycle and this one.
enum class MotionSegment : uint8_t { kStop = 0, kTurn = 1, kStraight = 2 };
const char* toString(MotionSegment s);

// The segment a motion command belongs to: a turn in place, a straight run (a velocity
// command with forward speed counts, its small steering corrections included), or a stop.
MotionSegment segmentOf(const MotionCommand& cmd);

struct TraverseEntry {
  MotionSegment segment = MotionSegment::kStop;
  RadialMap scan;  // scan.stamp and scan.odometry are the entry's time and odometry pose
};

struct TraverseLog {
  static constexpr uint32_t kVersion = 3;
  std::string robot;
  std::vector<TraverseEntry> entries;
};

// Serialises a log in the format above.
std::string encodeTraverseLog(const TraverseLog& log);
// Parses a log; `source` names it in errors. Throws std::runtime_error.
TraverseLog decodeTraverseLog(const std::string& bytes, const std::string& source);

// Writes a log atomically (temp file + rename); throws std::runtime_error naming the path.
void saveTraverseLog(const std::string& path, const TraverseLog& log);
// Reads a log; throws std::runtime_error naming the path, record and byte offset.
TraverseLog loadTraverseLog(const std::string& path);

}  // namespace coopmap

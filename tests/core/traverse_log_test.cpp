#include "core/correction/traverse_log.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/io/binary_io.h"

namespace coopmap {
namespace {

TraverseLog sampleLog() {
  TraverseLog log;
  log.robot = "jose";
  for (int i = 0; i < 3; ++i) {
    TraverseEntry e;
    e.segment = static_cast<MotionSegment>(i);
    e.scan.stamp = 0.1 + i / 3.0;
    e.scan.odometry = Pose2(1.0 / 3.0 + i, -2.0 / 7.0, 0.1 * i - 1e-9);
    e.scan.sensor_origin = {0.1, -0.05};
    e.scan.max_range = 4.0;
    for (int k = 0; k < 5 + i; ++k) {
      RadialReading r;
      r.bearing = 0.7 - 0.3 * k;
      r.range = 0.5 + k / 9.0;
      r.sigma = 0.01 * k;
      r.disparity = 12.0 / (k + 1);
      r.kind = static_cast<RadialKind>(k % 3);
      r.floor_edge = k == 4;  // a hit (4 % 3 == 1) at the floor's end
      e.scan.readings.push_back(r);
    }
    log.entries.push_back(e);
  }
  return log;
}

// The bytes of a version 1 or 2 log: the same records, no end record, the header's version
// (and its checksum) made again.
std::string asOldVersion(std::string bytes, char version) {
  bytes.resize(bytes.size() - 12);  // the end record
  bytes[8] = version;
  // Header: 8 magic + 4 version + 4 name length + 4 name, then its CRC.
  const uint32_t header_crc = crc32Of(bytes.data(), 20);
  for (int i = 0; i < 4; ++i) bytes[20 + i] = static_cast<char>((header_crc >> (8 * i)) & 0xff);
  return bytes;
}

std::string errorOf(const std::string& bytes) {
  try {
    decodeTraverseLog(bytes, "run/traverse_jose.traverse");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST(TraverseLogTest, RoundTripIsExact) {
  const TraverseLog log = sampleLog();
  const TraverseLog back = decodeTraverseLog(encodeTraverseLog(log), "memory");
  EXPECT_EQ(back.robot, "jose");
  ASSERT_EQ(back.entries.size(), log.entries.size());
  for (size_t i = 0; i < log.entries.size(); ++i) {
    const TraverseEntry &a = log.entries[i], &b = back.entries[i];
    EXPECT_EQ(a.segment, b.segment);
    EXPECT_EQ(a.scan.stamp, b.scan.stamp);
    EXPECT_EQ(a.scan.odometry.x, b.scan.odometry.x);
    EXPECT_EQ(a.scan.odometry.y, b.scan.odometry.y);
    EXPECT_EQ(a.scan.odometry.theta, b.scan.odometry.theta);
    EXPECT_EQ(a.scan.sensor_origin, b.scan.sensor_origin);
    EXPECT_EQ(a.scan.max_range, b.scan.max_range);
    ASSERT_EQ(a.scan.readings.size(), b.scan.readings.size());
    for (size_t k = 0; k < a.scan.readings.size(); ++k) {
      EXPECT_EQ(a.scan.readings[k].bearing, b.scan.readings[k].bearing);
      EXPECT_EQ(a.scan.readings[k].range, b.scan.readings[k].range);
      EXPECT_EQ(a.scan.readings[k].sigma, b.scan.readings[k].sigma);
      EXPECT_EQ(a.scan.readings[k].disparity, b.scan.readings[k].disparity);
      EXPECT_EQ(a.scan.readings[k].kind, b.scan.readings[k].kind);
      EXPECT_EQ(a.scan.readings[k].floor_edge, b.scan.readings[k].floor_edge);
    }
  }
  EXPECT_TRUE(back.entries[0].scan.readings[4].floor_edge);
}

// The floor's-end mark belongs to hits: a reading made something else (a teammate masked
// out, a spike removed) is written without it, so the log reads back (it used to be written
// as kind 128 or 130, which no reader takes).
TEST(TraverseLogTest, OnlyHitsCarryTheFloorEdgeMark) {
  TraverseLog log = sampleLog();
  RadialReading& r = log.entries[0].scan.readings[4];
  r.kind = RadialKind::kBeyond;  // floor_edge left set
  RadialReading& none = log.entries[1].scan.readings[4];
  none.kind = RadialKind::kNone;
  const TraverseLog back = decodeTraverseLog(encodeTraverseLog(log), "memory");
  EXPECT_EQ(back.entries[0].scan.readings[4].kind, RadialKind::kBeyond);
  EXPECT_FALSE(back.entries[0].scan.readings[4].floor_edge);
  EXPECT_EQ(back.entries[1].scan.readings[4].kind, RadialKind::kNone);
  EXPECT_FALSE(back.entries[1].scan.readings[4].floor_edge);
}

TEST(TraverseLogTest, ReadsVersionOneAndTwoLogs) {
  // Version 1 had no floor-edge bit and neither it nor version 2 an end record: the same
  // records read back alike.
  TraverseLog log = sampleLog();
  const TraverseLog two = decodeTraverseLog(asOldVersion(encodeTraverseLog(log), 2), "memory");
  ASSERT_EQ(two.entries.size(), 3u);
  EXPECT_TRUE(two.entries[0].scan.readings[4].floor_edge);
  for (TraverseEntry& e : log.entries)
    for (RadialReading& r : e.scan.readings) r.floor_edge = false;
  const TraverseLog back = decodeTraverseLog(asOldVersion(encodeTraverseLog(log), 1), "memory");
  ASSERT_EQ(back.entries.size(), 3u);
  EXPECT_EQ(back.entries[2].scan.readings[4].kind, RadialKind::kHit);
  EXPECT_FALSE(back.entries[2].scan.readings[4].floor_edge);
  EXPECT_EQ(back.entries[2].scan.readings[5].kind, RadialKind::kBeyond);
}

// A file cut exactly between records is no shorter log: its end record is missing.
TEST(TraverseLogTest, ACutAtARecordBoundaryIsRefused) {
  const std::string bytes = encodeTraverseLog(sampleLog());
  EXPECT_EQ(errorOf(bytes.substr(0, bytes.size() - 12)),
            "run/traverse_jose.traverse: no end record after record 3 (the file was cut short)");
  EXPECT_EQ(errorOf(bytes.substr(0, 262)),
            "run/traverse_jose.traverse: no end record after record 1 (the file was cut short)");
  EXPECT_EQ(errorOf(bytes + "x"), "run/traverse_jose.traverse: end record at byte " +
                                      std::to_string(bytes.size() - 12) + ": 1 bytes after it");
}

// Values no robot logs, under a valid checksum, are refused naming the record and field.
TEST(TraverseLogTest, ValuesNoRobotLogsAreRefused) {
  TraverseLog nan_pose = sampleLog();
  nan_pose.entries[1].scan.odometry.y = std::nan("");
  EXPECT_EQ(errorOf(encodeTraverseLog(nan_pose)),
            "run/traverse_jose.traverse: record 1 at byte 262: odometry y nan, expected a finite "
            "number in [-100000, 100000]");
  TraverseLog far = sampleLog();
  far.entries[2].scan.readings[1].range = 1e300;
  EXPECT_NE(errorOf(encodeTraverseLog(far)).find(": reading range 1e+300, expected a finite"),
            std::string::npos);
  TraverseLog back_in_time = sampleLog();
  back_in_time.entries[2].scan.stamp = 0.2;  // record 1 was taken at 0.433 s
  EXPECT_NE(errorOf(encodeTraverseLog(back_in_time)).find(": stamp 0.2, expected a finite"),
            std::string::npos);
}

TEST(TraverseLogTest, SavesAndLoadsAFile) {
  const std::string dir = testing::TempDir() + "/traverse_log_test";
  std::filesystem::create_directories(dir);
  saveTraverseLog(dir + "/a.traverse", sampleLog());
  EXPECT_EQ(loadTraverseLog(dir + "/a.traverse").entries.size(), 3u);
  EXPECT_THROW(loadTraverseLog(dir + "/missing.traverse"), std::runtime_error);
}

TEST(TraverseLogTest, EmptyLogHasOnlyAHeader) {
  TraverseLog log;
  log.robot = "eric";
  const TraverseLog back = decodeTraverseLog(encodeTraverseLog(log), "memory");
  EXPECT_EQ(back.robot, "eric");
  EXPECT_TRUE(back.entries.empty());
}

TEST(TraverseLogTest, TruncatedFileNamesTheRecordAndOffset) {
  const std::string bytes = encodeTraverseLog(sampleLog());
  // Header: 8 magic + 4 version + 4 name length + 4 name + 4 CRC = 24 bytes; record 0 is
  // 8 + payload (61 + 5 * 33 = 226) + 4 = 238 bytes; record 1 starts at byte 262.
  EXPECT_EQ(errorOf(bytes.substr(0, 280)),
            "run/traverse_jose.traverse: record 1 at byte 262: truncated (payload of 259 bytes "
            "and its checksum expected, 10 left)");
  EXPECT_EQ(errorOf(bytes.substr(0, 266)),
            "run/traverse_jose.traverse: record 1 at byte 262: truncated (record header of 8 "
            "bytes expected, 4 left)");
  EXPECT_EQ(errorOf(bytes.substr(0, 10)),
            "run/traverse_jose.traverse: not a coopmap traverse log (expected magic 'CMTRAVLG' "
            "at byte 0)");
}

TEST(TraverseLogTest, CorruptBytesFailTheChecksum) {
  std::string bytes = encodeTraverseLog(sampleLog());
  bytes[262 + 8 + 20] ^= 0x40;  // inside record 1's payload
  EXPECT_EQ(errorOf(bytes),
            "run/traverse_jose.traverse: record 1 at byte 262: checksum mismatch (the file is "
            "corrupt)");
  std::string header = encodeTraverseLog(sampleLog());
  header[17] = 'X';  // the robot's name
  EXPECT_EQ(errorOf(header),
            "run/traverse_jose.traverse: header checksum mismatch (the file is corrupt)");
}

TEST(TraverseLogTest, RejectsOtherVersions) {
  std::string bytes = encodeTraverseLog(sampleLog());
  bytes[8] = 7;
  EXPECT_EQ(errorOf(bytes),
            "run/traverse_jose.traverse: traverse log version 7 (this build reads 1 to 3)");
}

TEST(TraverseLogTest, SegmentOfCommands) {
  EXPECT_EQ(segmentOf(MotionCommand::turn(0.5)), MotionSegment::kTurn);
  EXPECT_EQ(segmentOf(MotionCommand::straight(2.0)), MotionSegment::kStraight);
  EXPECT_EQ(segmentOf(MotionCommand::stop()), MotionSegment::kStop);
  EXPECT_EQ(segmentOf({0.0, 0.7}), MotionSegment::kTurn);
  EXPECT_EQ(segmentOf({0.4, 0.05}), MotionSegment::kStraight);  // steering while driving
}

}  // namespace
}  // namespace coopmap

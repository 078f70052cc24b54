#include "core/correction/traverse_log.h"

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

TEST(TraverseLogTest, ReadsVersionOneLogs) {
  // Version 1 had no floor-edge bit: the same bytes with version 1 in the header (and its
  // checksum made again) read back alike, every reading off the floor's end.
  TraverseLog log = sampleLog();
  for (TraverseEntry& e : log.entries)
    for (RadialReading& r : e.scan.readings) r.floor_edge = false;
  std::string bytes = encodeTraverseLog(log);
  bytes[8] = 1;
  // Header: 8 magic + 4 version + 4 name length + 4 name, then its CRC.
  const uint32_t header_crc = crc32Of(bytes.data(), 20);
  for (int i = 0; i < 4; ++i) bytes[20 + i] = static_cast<char>((header_crc >> (8 * i)) & 0xff);
  const TraverseLog back = decodeTraverseLog(bytes, "memory");
  ASSERT_EQ(back.entries.size(), 3u);
  EXPECT_EQ(back.entries[2].scan.readings[4].kind, RadialKind::kHit);
  EXPECT_FALSE(back.entries[2].scan.readings[4].floor_edge);
  EXPECT_EQ(back.entries[2].scan.readings[5].kind, RadialKind::kBeyond);
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
            "run/traverse_jose.traverse: traverse log version 7 (this build reads 1 to 2)");
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

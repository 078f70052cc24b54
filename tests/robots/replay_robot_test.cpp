// Record and replay: a simulator recording replays to the live run's maps bit for bit, and a
// missing, corrupt or truncated file is reported naming the file and the frame.
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/io/atomic_file.h"
#include "robots/replay/recording_writer.h"
#include "robots/replay/replay_robot.h"
#include "sim/runner/replay_run.h"
#include "tests/robots/recorded_run.h"

namespace coopmap {
namespace {

namespace fs = std::filesystem;
using test_support::recordedRun;

// A fresh copy of the shared recording to break; returns its folder.
std::string copyOfRecording(const std::string& name) {
  const fs::path dir = test_support::testTempDir() / ("broken_" + name);
  fs::copy(recordedRun().dir, dir, fs::copy_options::recursive);
  return dir.string();
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

// Replays `dir` into an output folder and returns the error message ("" if none); a failed
// replay must not write any output.
std::string replayError(const std::string& dir) {
  ReplayOptions o;
  o.recording = dir;
  o.out_dir = dir + "_out";
  fs::remove_all(o.out_dir);
  try {
    runReplay(o);
  } catch (const std::runtime_error& e) {
    EXPECT_FALSE(fs::exists(o.out_dir)) << "outputs written for a broken recording";
    return e.what();
  }
  return "";
}

// Replaces the `line`-th line (1-based) of a file.
void replaceLine(const std::string& path, int line, const std::string& text) {
  std::string s = readFile(path);
  size_t begin = 0;
  for (int i = 1; i < line; ++i) begin = s.find('\n', begin) + 1;
  const size_t end = s.find('\n', begin);
  s.replace(begin, end - begin, text);
  writeText(path, s);
}

TEST(ReplayTest, ReplayReproducesTheLiveRunBitForBit) {
  const test_support::RecordedRun& rec = recordedRun();
  ASSERT_EQ(rec.live.robots.size(), 1u);
  const RobotRunResult& live = rec.live.robots[0];
  // The run is worth replaying: it drove, turned, and mapped walls.
  ASSERT_GE(live.frames, 20);
  ASSERT_GT(live.path_length_m, 0.5);
  int turns = 0, straights = 0;
  for (const TraverseEntry& e : live.traverse.entries) {
    turns += e.segment == MotionSegment::kTurn;
    straights += e.segment == MotionSegment::kStraight;
  }
  EXPECT_GT(turns, 0);
  EXPECT_GT(straights, 0);
  ASSERT_TRUE(live.grid.has_value());
  ASSERT_GT(live.map.wall_recall, 0.0);

  ReplayOptions o;
  o.recording = rec.dir;
  o.out_dir = rec.dir + "_replayed";
  fs::remove_all(o.out_dir);
  const ReplayResult replay = runReplay(o);
  ASSERT_EQ(replay.robots.size(), 1u);
  const ReplayRobotResult& r = replay.robots[0];
  EXPECT_EQ(r.name, live.name);
  EXPECT_EQ(r.frames, live.frames);
  ASSERT_TRUE(r.grid.has_value());
  const OccupancyGrid &a = *live.grid, &b = *r.grid;
  ASSERT_EQ(a.limits().width, b.limits().width);
  ASSERT_EQ(a.limits().height, b.limits().height);
  EXPECT_EQ(a.limits().origin, b.limits().origin);
  EXPECT_EQ(a.limits().resolution, b.limits().resolution);
  EXPECT_TRUE(a.logOddsGrid().cells == b.logOddsGrid().cells) << "log-odds layers differ";
  EXPECT_TRUE(a.seenGrid().cells == b.seenGrid().cells) << "seen layers differ";
  EXPECT_TRUE(encodeTraverseLog(r.traverse) == encodeTraverseLog(live.traverse))
      << "traverse logs differ";
  // The map metrics from the recorded ground truth are the live ones.
  ASSERT_TRUE(r.map.has_value());
  EXPECT_EQ(r.map->wall_recall, live.map.wall_recall);
  EXPECT_EQ(r.map->coverage, live.map.coverage);
  EXPECT_EQ(*r.odometry_error_m, live.odometry_error_m);
  // The same outputs, byte for byte.
  const std::string n = live.name;
  for (const std::string& f :
       {"map_" + n + ".pgm", "map_" + n + ".yaml", "map_" + n + ".png",
        "map_" + n + "_evaluation.png", "trajectory_" + n + "_groundtruth.tum",
        "trajectory_" + n + "_odometry.tum", "traverse_" + n + ".traverse"})
    EXPECT_TRUE(readFile(o.out_dir + "/" + f) == readFile(rec.live_out + "/" + f))
        << f << " differs";
  EXPECT_TRUE(fs::exists(o.out_dir + "/metrics.json"));
}

TEST(ReplayTest, RecordingHoldsTheExactStream) {
  const test_support::RecordedRun& rec = recordedRun();
  const RecordingInfo info = readRecordingInfo(rec.dir);
  EXPECT_EQ(info.version, kRecordingVersion);
  EXPECT_EQ(info.source, "simulator");
  EXPECT_EQ(info.seed, 7u);
  ASSERT_EQ(info.robots.size(), 1u);
  const RobotRecording robot = readRobotRecording(rec.dir, info, info.robots[0]);
  const RobotRunResult& live = rec.live.robots[0];
  ASSERT_EQ(robot.frames.size(), live.traverse.entries.size());
  for (size_t i = 0; i < robot.frames.size(); ++i) {
    const RadialMap& scan = live.traverse.entries[i].scan;
    EXPECT_EQ(robot.frames[i].stamp, scan.stamp);
    EXPECT_EQ(robot.frames[i].odometry.x, scan.odometry.x);
    EXPECT_EQ(robot.frames[i].odometry.theta, scan.odometry.theta);
    EXPECT_EQ(robot.frames[i].segment, live.traverse.entries[i].segment);
  }
  ASSERT_EQ(robot.odometry.size(), live.odometry.size());
  ASSERT_EQ(robot.groundtruth.size(), live.groundtruth.size());
  EXPECT_EQ(robot.commands.size(), live.odometry.size());
  for (size_t i = 0; i < robot.odometry.size(); ++i) {
    EXPECT_EQ(robot.odometry[i].stamp, live.odometry[i].stamp);
    EXPECT_EQ(robot.odometry[i].pose.y, live.odometry[i].pose.y);
    EXPECT_EQ(robot.groundtruth[i].pose.theta, live.groundtruth[i].pose.theta);
  }
  EXPECT_TRUE(fs::exists(rec.dir + "/README.md"));
  EXPECT_FALSE(fs::exists(rec.dir + ".incomplete"));
}

TEST(ReplayTest, ReplayRobotPlaysFramesInOrderAndIgnoresCommands) {
  const test_support::RecordedRun& rec = recordedRun();
  const RecordingInfo info = readRecordingInfo(rec.dir);
  ReplayRobot robot(readRobotRecording(rec.dir, info, info.robots[0]));
  EXPECT_EQ(robot.now(), 0.0);
  robot.command(MotionCommand::straight(5.0));
  const std::optional<TrinocularFrame> f0 = robot.captureFrame();
  const std::optional<TrinocularFrame> f1 = robot.captureFrame();
  ASSERT_TRUE(f0 && f1);
  EXPECT_EQ(robot.now(), f1->stamp);
  EXPECT_EQ(robot.odometry().x, f1->odometry.x);
  while (robot.captureFrame()) {
  }
  EXPECT_EQ(robot.framesLeft(), 0);
  // After the last frame the odometry is the last recorded sample.
  const RobotRunResult& live = rec.live.robots[0];
  EXPECT_EQ(robot.odometry().x, live.traverse.entries.back().scan.odometry.x);
}

TEST(ReplayTest, ReportsABadNumberWithFileAndLine) {
  const std::string dir = copyOfRecording("number");
  replaceLine(dir + "/r/frames.csv", 3, "1,x,0,0,0,stop");
  EXPECT_EQ(replayError(dir), dir + "/r/frames.csv:3: field 'stamp': expected a number, got 'x'");
}

TEST(ReplayTest, ReportsAFileCutInsideALine) {
  const std::string dir = copyOfRecording("cut");
  const std::string path = dir + "/r/frames.csv";
  const std::string s = readFile(path);
  size_t pos = 0;
  for (int i = 0; i < 5; ++i) pos = s.find('\n', pos) + 1;  // five whole lines, then half
  writeText(path, s.substr(0, pos + 4));
  EXPECT_EQ(replayError(dir), path + ":6: truncated: the file ends inside a line");
}

TEST(ReplayTest, ReportsAFileCutAtALineEnd) {
  const std::string dir = copyOfRecording("short");
  const std::string path = dir + "/r/frames.csv";
  const std::string s = readFile(path);
  size_t pos = 0;
  for (int i = 0; i < 11; ++i) pos = s.find('\n', pos) + 1;  // header and frames 0..9
  writeText(path, s.substr(0, pos));
  const int frames = recordedRun().live.robots[0].frames;
  EXPECT_EQ(replayError(dir),
            path + ": truncated: 10 frames, dataset.yaml says " + std::to_string(frames));
}

TEST(ReplayTest, ReportsAMissingImageWithItsFrame) {
  const std::string dir = copyOfRecording("missing_image");
  const std::string path = dir + "/r/images/000012_vertical.png";
  fs::remove(path);
  EXPECT_EQ(replayError(dir), path + ": frame 12: missing file");
}

TEST(ReplayTest, ReportsACorruptImageWithItsFrame) {
  const std::string dir = copyOfRecording("corrupt_image");
  const std::string path = dir + "/r/images/000007_horizontal.png";
  writeText(path, "this is not a PNG");
  EXPECT_EQ(replayError(dir), path + ": frame 7: expected a PNG image");
}

TEST(ReplayTest, ReportsATruncatedImageWithItsFrame) {
  const std::string dir = copyOfRecording("truncated_image");
  const std::string path = dir + "/r/images/000003_reference.png";
  const std::string png = readFile(path);
  writeText(path, png.substr(0, png.size() / 2));
  const std::string e = replayError(dir);
  EXPECT_EQ(e.rfind(path + ": frame 3: truncated: chunk at byte ", 0), 0u) << e;
}

TEST(ReplayTest, ReportsAnImageOfTheWrongSize) {
  const std::string dir = copyOfRecording("small_image");
  const std::string path = dir + "/r/images/000004_reference.png";
  cv::imwrite(path, cv::Mat(60, 80, CV_8UC1, cv::Scalar(100)));
  EXPECT_EQ(replayError(dir), path +
                                  ": frame 4: expected an 8-bit grey 160x120 image (robot.yaml), "
                                  "got 80x60 with 1 channel(s) of 8 bits");
}

TEST(ReplayTest, ReportsAMissingTable) {
  const std::string dir = copyOfRecording("missing_odometry");
  fs::remove(dir + "/r/odometry.csv");
  EXPECT_EQ(replayError(dir), dir + "/r/odometry.csv: missing file");
}

TEST(ReplayTest, RejectsAnIncompleteRecording) {
  const std::string dir = copyOfRecording("incomplete");
  fs::remove(dir + "/dataset.yaml");
  EXPECT_EQ(replayError(dir),
            dir + "/dataset.yaml: missing file: not a complete coopmap recording");
}

TEST(ReplayTest, RejectsAnUnknownVersion) {
  const std::string dir = copyOfRecording("version");
  replaceLine(dir + "/dataset.yaml", 3, "version: 3");
  EXPECT_EQ(replayError(dir), dir +
                                  "/dataset.yaml:3:10: version: version 3 is not supported (this "
                                  "coopmap reads coopmap-recording versions 1 to 2)");
}

TEST(ReplayTest, ReportsABadRobotDescription) {
  const std::string dir = copyOfRecording("robot_yaml");
  const std::string path = dir + "/r/robot.yaml";
  std::string s = readFile(path);
  const size_t at = s.find("body_radius: ");
  ASSERT_NE(at, std::string::npos);
  s.insert(at + 13, "-");
  writeText(path, s);
  EXPECT_EQ(replayError(dir).rfind(path + ":3:14: body_radius: expected a positive number of "
                                          "metres, got '-0.",
                                   0),
            0u)
      << replayError(dir);
}

TEST(ReplayTest, AnInterruptedRecordingIsNotARecording) {
  const fs::path dir = test_support::testTempDir() / "interrupted";
  {
    RecordingWriter writer(dir.string(), RecordingInfo{});
    writer.addRobot("r", RobotDescription{});
    // Destroyed without finish(): the run was interrupted.
  }
  EXPECT_FALSE(fs::exists(dir));
  EXPECT_TRUE(fs::exists(dir.string() + ".incomplete/r/robot.yaml"));
  EXPECT_FALSE(fs::exists(dir.string() + ".incomplete/dataset.yaml"));
}

TEST(ReplayTest, RecordingRefusesToReplaceOtherFolders) {
  const fs::path dir = test_support::testTempDir() / "not_a_recording";
  fs::create_directories(dir);
  writeText((dir / "precious.txt").string(), "keep me");
  try {
    RecordingWriter writer(dir.string(), RecordingInfo{});
    FAIL() << "a folder that is not a recording would be replaced";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              dir.string() +
                  ": exists and is not a coopmap recording; not replacing it (choose another "
                  "--record folder)");
  }
  EXPECT_TRUE(fs::exists(dir / "precious.txt"));
}

}  // namespace
}  // namespace coopmap

// A coopmap recording: the raw stream of one or more robots on disk (camera images, stamps,
// odometry, commands, rig calibration, robot description, and ground truth when it comes from
// the simulator), in a documented, versioned folder layout that needs no coopmap to read.
//
// Layout, format "coopmap-recording" version 2 (recordingReadme() is the full description,
// written as README.md into every recording; version 1 had no status.csv nor agent.yaml):
//   DIR/README.md                 how to read the folder
//   DIR/dataset.yaml              format, version, source, world, seed, rates, map limits, robots
//   DIR/floor.png                 optional (simulator): 255 where the world has a floor
//   DIR/<robot>/robot.yaml        robot description and rig calibration
//   DIR/<robot>/frames.csv        frame,stamp,x,y,theta,segment (one line per sensing cycle)
//   DIR/<robot>/images/NNNNNN_{reference,horizontal,vertical}.png  8-bit grey, lossless
//   DIR/<robot>/odometry.csv      stamp,x,y,theta at the control rate
//   DIR/<robot>/commands.csv      stamp,kind,linear,angular,amount at the control rate
//   DIR/<robot>/status.csv        stamp,bumped,contact_events,segment_active,bump_bearing at the
//                                 control rate (bump_bearing empty when the base says none)
//   DIR/<robot>/agent.yaml        the robot's agent: setup and settings (agent_config_io.h)
//   DIR/<robot>/groundtruth.csv   optional (simulator): stamp,x,y,theta, the true pose
//   DIR/<robot>/groundtruth_occupancy.png  optional (simulator): 255 occupied, 0 free
// Numbers are written with 17 significant digits, so every double reads back exactly.
// dataset.yaml is written last, and a recording is written into DIR.incomplete and renamed to
// DIR when complete, so an interrupted recording is never mistaken for a complete one.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/agent/agent_config_io.h"
#include "core/correction/traverse_log.h"
#include "core/geometry/pose2.h"
#include "core/io/tum.h"
#include "core/mapping/grid.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

inline constexpr const char* kRecordingFormat = "coopmap-recording";
inline constexpr int kRecordingVersion = 2;
inline constexpr int kOldestRecordingVersion = 1;  // still read (replayed by a mapper alone)

// One robot's entry in dataset.yaml.
struct RecordedRobotInfo {
  std::string name;
  int frames = 0;              // lines of frames.csv (a shorter file is truncated)
  std::optional<Pose2> start;  // true start pose X_WR (simulator recordings)
  // X_WM: the robot's map frame in the world (simulator recordings), to score in the map frame.
  std::optional<Pose2> map_in_world;
};

// dataset.yaml: what the recording holds and what the core needs beside the robot stream.
struct RecordingInfo {
  int version = kRecordingVersion;
  std::string source = "simulator";  // where the stream came from
  std::string world;                 // world name (may be empty)
  std::string world_file;            // world file of a simulator run (may be empty)
  uint64_t seed = 0;                 // seed of a simulator run
  double sensing_rate = 3.0;         // Hz
  double control_rate = 20.0;        // Hz; odometry.csv and commands.csv rows
  MapLimits map;                     // the grid the live run mapped into
  bool shared_map = false;           // the robots' agents shared a map during the run
  std::vector<RecordedRobotInfo> robots;
};

// A sensing cycle of frames.csv; the images are read on demand.
struct RecordedFrame {
  int index = 0;
  double stamp = 0.0;  // s, robot clock
  Pose2 odometry;      // X_OR at capture
  MotionSegment segment = MotionSegment::kStop;
};

struct RecordedCommand {
  double stamp = 0.0;  // s
  MotionCommand command;
};

struct RecordedStatus {
  double stamp = 0.0;  // s
  RobotStatus status;
};

// Everything of one robot in a recording but its images.
struct RobotRecording {
  std::string name;
  std::string dir;  // DIR/<robot>
  RobotDescription description;
  std::vector<RecordedFrame> frames;
  std::vector<StampedPose2> odometry;     // control rate
  std::vector<RecordedCommand> commands;  // control rate
  std::vector<RecordedStatus> status;     // control rate (version 2)
  std::optional<AgentConfig> agent;       // its agent's setup and settings (version 2)
  std::vector<StampedPose2> groundtruth;  // empty unless recorded
  std::optional<GridU8> truth_occupancy;  // 1 occupied, 0 free; over RecordingInfo::map
};

// Paths inside a recording.
std::string recordingImagePath(const std::string& robot_dir, int frame, const char* camera);
// A number as the recording writes it: 17 significant digits, read back as the same double.
std::string formatExact(double v);

// The README.md written into every recording: the layout and how to read it without coopmap.
std::string recordingReadme();

// dataset.yaml and robot.yaml text.
std::string encodeRecordingInfo(const RecordingInfo& info);
std::string encodeRobotDescription(const RobotDescription& description);

// Reads DIR/dataset.yaml. Throws std::runtime_error (ConfigError for malformed YAML) naming
// the file: missing (an incomplete recording), another format, an unknown version.
RecordingInfo readRecordingInfo(const std::string& dir);
// Reads DIR/<robot>/: robot.yaml, frames.csv, odometry.csv, commands.csv, status.csv and
// agent.yaml (version 2) and the optional ground truth. Errors name the file, the line (and
// frame) and the field.
RobotRecording readRobotRecording(const std::string& dir, const RecordingInfo& info,
                                  const RecordedRobotInfo& robot);
// Reads the optional DIR/floor.png over info.map.
std::optional<GridU8> readRecordedFloor(const std::string& dir, const RecordingInfo& info);
// Reads frame i's three images; throws std::runtime_error naming the file and the frame when
// one is missing, cannot be decoded, or is not an 8-bit grey image of the rig's size.
TrinocularFrame readRecordedFrame(const RobotRecording& recording, size_t i);

// A grid of 0/1 cells as an 8-bit PNG (0 or 255), north up (row 0 is the last row of cells).
std::string encodeGridPng(const GridU8& grid);
// Decodes such a PNG over `limits`; throws naming `path` when it does not fit.
GridU8 decodeGridPng(const std::string& bytes, const MapLimits& limits, const std::string& path);

}  // namespace coopmap

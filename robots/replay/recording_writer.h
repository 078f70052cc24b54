// Writes a coopmap recording (layout in recording.h and recordingReadme()) as a robot streams:
// images go to disk as they come, the tables and dataset.yaml at finish().
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "robots/replay/recording.h"

namespace coopmap {

class RecordingWriter {
 public:
  // Starts a recording into `dir`. Everything is written into `dir`.incomplete (a leftover
  // one from an interrupted recording is removed) and renamed to `dir` by finish(). Throws
  // std::runtime_error when `dir` exists and is neither empty nor a coopmap recording (it
  // would be replaced), or cannot be created. info.robots is filled by addRobot().
  RecordingWriter(std::string dir, RecordingInfo info);
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  // Adds a robot; returns its index for the calls below. `start`: true start pose, if known.
  int addRobot(const std::string& name, const RobotDescription& description,
               std::optional<Pose2> start = std::nullopt);
  // Records a sensing cycle: the three images (8-bit grey) and the motion segment since the
  // previous one. Throws std::runtime_error naming the file when it cannot be written.
  void addFrame(int robot, const TrinocularFrame& frame, MotionSegment segment);
  // Records a control step: odometry, the base's status and the command sent at `stamp` (s),
  // and the true pose when known.
  void addControl(int robot, double stamp, const Pose2& odometry, const RobotStatus& status,
                  const MotionCommand& command, const std::optional<Pose2>& truth = std::nullopt);
  // The robot's agent (its setup and settings): a replay runs the same one.
  void setAgent(int robot, const AgentConfig& agent);
  // Where the robot's map frame stands in the world (simulator recordings).
  void setMapInWorld(int robot, const Pose2& X_WM);
  // Optional ground truth: a robot's true occupancy and the world's floor over info.map.
  void setTruthOccupancy(int robot, const GridU8& occupancy);
  void setFloor(const GridU8& floor);

  // Writes the tables, README.md and dataset.yaml, and renames the folder to `dir`
  // (replacing an earlier recording there).
  void finish();

  const std::string& dir() const { return dir_; }

 private:
  struct Robot {
    std::string name;
    std::string frames_csv, odometry_csv, commands_csv, status_csv, groundtruth_csv;
    bool has_truth = false;
  };
  std::string dir_, tmp_;
  RecordingInfo info_;
  std::vector<Robot> robots_;
  bool finished_ = false;
};

}  // namespace coopmap

#include "robots/replay/recording_writer.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/io/atomic_file.h"
#include "robots/replay/recording.h"

namespace fs = std::filesystem;

namespace coopmap {
namespace {

std::string poseRow(double stamp, const Pose2& p) {
  return formatExact(stamp) + "," + formatExact(p.x) + "," + formatExact(p.y) + "," +
         formatExact(p.theta) + "\n";
}

const char* kindName(MotionCommand::Kind k) {
  switch (k) {
    case MotionCommand::Kind::kTurn:
      return "turn";
    case MotionCommand::Kind::kStraight:
      return "straight";
    case MotionCommand::Kind::kVelocity:
      break;
  }
  return "velocity";
}

// True when `dir` may be replaced by a recording: missing, empty, or a recording.
bool replaceable(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return true;
  if (!fs::is_directory(dir, ec)) return false;
  return fs::is_empty(dir, ec) || fs::is_regular_file(dir + "/dataset.yaml", ec);
}

void writePlain(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace

RecordingWriter::RecordingWriter(std::string dir, RecordingInfo info)
    : dir_(std::move(dir)), info_(std::move(info)) {
  while (dir_.size() > 1 && dir_.back() == '/') dir_.pop_back();
  if (dir_.empty()) throw std::invalid_argument("--record: expected a folder");
  if (!replaceable(dir_))
    throw std::runtime_error(dir_ +
                             ": exists and is not a coopmap recording; not replacing it "
                             "(choose another --record folder)");
  info_.robots.clear();
  tmp_ = dir_ + ".incomplete";
  std::error_code ec;
  fs::remove_all(tmp_, ec);
  if (!fs::create_directories(tmp_, ec) || ec)
    throw std::runtime_error("cannot create '" + tmp_ + "': " + ec.message());
}

int RecordingWriter::addRobot(const std::string& name, const RobotDescription& description,
                              std::optional<Pose2> start) {
  std::error_code ec;
  fs::create_directories(tmp_ + "/" + name + "/images", ec);
  if (ec) throw std::runtime_error("cannot create '" + tmp_ + "/" + name + "': " + ec.message());
  writePlain(tmp_ + "/" + name + "/robot.yaml", encodeRobotDescription(description));
  info_.robots.push_back({name, 0, start, std::nullopt});
  Robot r;
  r.name = name;
  r.frames_csv = "frame,stamp,x,y,theta,segment\n";
  r.odometry_csv = r.groundtruth_csv = "stamp,x,y,theta\n";
  r.commands_csv = "stamp,kind,linear,angular,amount\n";
  r.status_csv = "stamp,bumped,contact_events,segment_active,bump_bearing\n";
  robots_.push_back(std::move(r));
  return static_cast<int>(robots_.size()) - 1;
}

void RecordingWriter::addFrame(int robot, const TrinocularFrame& frame, MotionSegment segment) {
  Robot& r = robots_.at(static_cast<size_t>(robot));
  int& index = info_.robots[static_cast<size_t>(robot)].frames;
  const std::string robot_dir = tmp_ + "/" + r.name;
  const char* cameras[3] = {"reference", "horizontal", "vertical"};
  const cv::Mat* images[3] = {&frame.reference, &frame.horizontal, &frame.vertical};
  std::vector<uchar> png;
  for (int c = 0; c < 3; ++c) {
    const std::string path = recordingImagePath(robot_dir, index, cameras[c]);
    if (images[c]->type() != CV_8UC1 || !cv::imencode(".png", *images[c], png))
      throw std::runtime_error(path + ": frame " + std::to_string(index) +
                               ": expected an 8-bit grey image to record");
    writePlain(path, std::string(png.begin(), png.end()));
  }
  r.frames_csv += std::to_string(index) + "," + formatExact(frame.stamp) + "," +
                  formatExact(frame.odometry.x) + "," + formatExact(frame.odometry.y) + "," +
                  formatExact(frame.odometry.theta) + "," + toString(segment) + "\n";
  ++index;
}

void RecordingWriter::addControl(int robot, double stamp, const Pose2& odometry,
                                 const RobotStatus& status, const MotionCommand& command,
                                 const std::optional<Pose2>& truth) {
  Robot& r = robots_.at(static_cast<size_t>(robot));
  r.odometry_csv += poseRow(stamp, odometry);
  r.status_csv += formatExact(stamp) + "," + (status.bumped ? "1" : "0") + "," +
                  std::to_string(status.contact_events) + "," +
                  (status.segment_active ? "1" : "0") + "," +
                  (status.bump_bearing ? formatExact(*status.bump_bearing) : "") + "\n";
  r.commands_csv += formatExact(stamp) + "," + kindName(command.kind) + "," +
                    formatExact(command.linear) + "," + formatExact(command.angular) + "," +
                    formatExact(command.amount) + "\n";
  if (truth) {
    r.groundtruth_csv += poseRow(stamp, *truth);
    r.has_truth = true;
  }
}

void RecordingWriter::setAgent(int robot, const AgentConfig& agent) {
  const Robot& r = robots_.at(static_cast<size_t>(robot));
  writePlain(tmp_ + "/" + r.name + "/agent.yaml",
             "# coopmap agent: setup and settings (see ../README.md)\n" + agentConfigYaml(agent));
}

void RecordingWriter::setMapInWorld(int robot, const Pose2& X_WM) {
  info_.robots.at(static_cast<size_t>(robot)).map_in_world = X_WM;
}

void RecordingWriter::setTruthOccupancy(int robot, const GridU8& occupancy) {
  const Robot& r = robots_.at(static_cast<size_t>(robot));
  writePlain(tmp_ + "/" + r.name + "/groundtruth_occupancy.png", encodeGridPng(occupancy));
}

void RecordingWriter::setFloor(const GridU8& floor) {
  writePlain(tmp_ + "/floor.png", encodeGridPng(floor));
}

void RecordingWriter::finish() {
  if (finished_) return;
  for (const Robot& r : robots_) {
    const std::string d = tmp_ + "/" + r.name;
    writeFileAtomic(d + "/frames.csv", r.frames_csv);
    writeFileAtomic(d + "/odometry.csv", r.odometry_csv);
    writeFileAtomic(d + "/commands.csv", r.commands_csv);
    writeFileAtomic(d + "/status.csv", r.status_csv);
    if (r.has_truth) writeFileAtomic(d + "/groundtruth.csv", r.groundtruth_csv);
  }
  writeFileAtomic(tmp_ + "/README.md", recordingReadme());
  writeFileAtomic(tmp_ + "/dataset.yaml", encodeRecordingInfo(info_));
  if (!replaceable(dir_))
    throw std::runtime_error(dir_ +
                             ": exists and is not a coopmap recording; the recording is "
                             "left in " +
                             tmp_);
  std::error_code ec;
  fs::remove_all(dir_, ec);
  fs::rename(tmp_, dir_, ec);
  if (ec) throw std::runtime_error("cannot move '" + tmp_ + "' to '" + dir_ + "': " + ec.message());
  finished_ = true;
}

}  // namespace coopmap

#include "robots/replay/recording.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/io/atomic_file.h"
#include "core/io/image_file.h"
#include "core/io/json_writer.h"
#include "core/io/yaml_reader.h"

namespace coopmap {
namespace {

std::string vec(const Eigen::Vector3d& v) {
  return "[" + formatExact(v.x()) + ", " + formatExact(v.y()) + ", " + formatExact(v.z()) + "]";
}

bool fileExists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

// Reads a whole file that must exist; `what` is appended to the path in the message.
std::string readExisting(const std::string& path, const std::string& what = "") {
  if (!fileExists(path)) throw std::runtime_error(path + what + ": missing file");
  return readFile(path);
}

// A CSV file with a fixed header line, read row by row with errors naming file, line, field.
class CsvReader {
 public:
  CsvReader(std::string path, std::vector<std::string> columns)
      : path_(std::move(path)), columns_(std::move(columns)), text_(readExisting(path_)) {
    std::string header;
    for (size_t i = 0; i < columns_.size(); ++i) header += (i ? "," : "") + columns_[i];
    if (text_.empty()) throw std::runtime_error(path_ + ": empty file, expected '" + header + "'");
    if (!nextLine() || line_text_ != header)
      throw std::runtime_error(path_ + ":1: expected the header '" + header + "', got '" +
                               line_text_ + "'");
  }

  // Moves to the next row; false at the end of the file.
  bool next() {
    if (!nextLine()) return false;
    fields_.clear();
    size_t start = 0;
    while (true) {
      const size_t comma = line_text_.find(',', start);
      fields_.push_back(line_text_.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    if (fields_.size() != columns_.size())
      throw std::runtime_error(where() + ": expected " + std::to_string(columns_.size()) +
                               " fields, got " + std::to_string(fields_.size()));
    return true;
  }

  const std::string& text(size_t col) const { return fields_[col]; }
  double number(size_t col) const {
    const std::string& s = fields_[col];
    char* end = nullptr;
    errno = 0;
    const double v = s.empty() ? 0.0 : std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v))
      fail(col, "a number");
    return v;
  }
  int integer(size_t col) const {
    const std::string& s = fields_[col];
    char* end = nullptr;
    errno = 0;
    const long v = s.empty() ? 0 : std::strtol(s.c_str(), &end, 10);
    if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || v < 0 || v > 999999)
      fail(col, "an integer in [0, 999999]");
    return static_cast<int>(v);
  }
  [[noreturn]] void fail(size_t col, const std::string& expected) const {
    throw std::runtime_error(where() + ": field '" + columns_[col] + "': expected " + expected +
                             ", got '" + fields_[col] + "'");
  }
  std::string where() const { return path_ + ":" + std::to_string(line_); }
  const std::string& path() const { return path_; }

 private:
  bool nextLine() {
    if (pos_ >= text_.size()) return false;
    ++line_;
    const size_t nl = text_.find('\n', pos_);
    if (nl == std::string::npos)
      throw std::runtime_error(where() + ": truncated: the file ends inside a line");
    line_text_ = text_.substr(pos_, nl - pos_);
    if (!line_text_.empty() && line_text_.back() == '\r') line_text_.pop_back();
    pos_ = nl + 1;
    return true;
  }

  std::string path_;
  std::vector<std::string> columns_;
  std::string text_;
  size_t pos_ = 0;
  int line_ = 0;
  std::string line_text_;
  std::vector<std::string> fields_;
};

// Reads stamp,x,y,theta rows with strictly increasing stamps.
std::vector<StampedPose2> readPoses(const std::string& path) {
  CsvReader csv(path, {"stamp", "x", "y", "theta"});
  std::vector<StampedPose2> poses;
  while (csv.next()) {
    const StampedPose2 p{csv.number(0), {csv.number(1), csv.number(2), csv.number(3)}};
    if (!poses.empty() && !(p.stamp > poses.back().stamp))
      csv.fail(0, "a time after the previous row's " + formatExact(poses.back().stamp));
    poses.push_back(p);
  }
  return poses;
}

std::vector<RecordedFrame> readFrames(const std::string& path) {
  CsvReader csv(path, {"frame", "stamp", "x", "y", "theta", "segment"});
  std::vector<RecordedFrame> frames;
  while (csv.next()) {
    RecordedFrame f;
    f.index = csv.integer(0);
    if (f.index != static_cast<int>(frames.size()))
      csv.fail(0, "frame " + std::to_string(frames.size()));
    f.stamp = csv.number(1);
    if (!frames.empty() && !(f.stamp > frames.back().stamp))
      csv.fail(1, "a time after frame " + std::to_string(frames.size() - 1) + "'s " +
                      formatExact(frames.back().stamp));
    f.odometry = {csv.number(2), csv.number(3), csv.number(4)};
    const std::string& s = csv.text(5);
    if (s == "stop") {
      f.segment = MotionSegment::kStop;
    } else if (s == "turn") {
      f.segment = MotionSegment::kTurn;
    } else if (s == "straight") {
      f.segment = MotionSegment::kStraight;
    } else {
      csv.fail(5, "stop, turn or straight");
    }
    frames.push_back(f);
  }
  return frames;
}

std::vector<RecordedCommand> readCommands(const std::string& path) {
  CsvReader csv(path, {"stamp", "kind", "linear", "angular", "amount"});
  std::vector<RecordedCommand> commands;
  while (csv.next()) {
    RecordedCommand c;
    c.stamp = csv.number(0);
    if (!commands.empty() && !(c.stamp > commands.back().stamp))
      csv.fail(0, "a time after the previous row's " + formatExact(commands.back().stamp));
    const std::string& k = csv.text(1);
    if (k == "velocity") {
      c.command.kind = MotionCommand::Kind::kVelocity;
    } else if (k == "turn") {
      c.command.kind = MotionCommand::Kind::kTurn;
    } else if (k == "straight") {
      c.command.kind = MotionCommand::Kind::kStraight;
    } else {
      csv.fail(1, "velocity, turn or straight");
    }
    c.command.linear = csv.number(2);
    c.command.angular = csv.number(3);
    c.command.amount = csv.number(4);
    commands.push_back(c);
  }
  return commands;
}

std::vector<RecordedStatus> readStatus(const std::string& path) {
  CsvReader csv(path, {"stamp", "bumped", "contact_events", "segment_active", "bump_bearing"});
  std::vector<RecordedStatus> rows;
  while (csv.next()) {
    RecordedStatus r;
    r.stamp = csv.number(0);
    if (!rows.empty() && !(r.stamp > rows.back().stamp))
      csv.fail(0, "a time after the previous row's " + formatExact(rows.back().stamp));
    const int bumped = csv.integer(1), segment = csv.integer(3);
    if (bumped != 0 && bumped != 1) csv.fail(1, "0 or 1");
    if (segment != 0 && segment != 1) csv.fail(3, "0 or 1");
    r.status.bumped = bumped == 1;
    r.status.contact_events = csv.integer(2);
    if (r.status.contact_events < 0) csv.fail(2, "a count >= 0");
    r.status.segment_active = segment == 1;
    if (!csv.text(4).empty()) r.status.bump_bearing = csv.number(4);
    rows.push_back(r);
  }
  return rows;
}

RobotDescription parseRobotDescription(const std::string& path) {
  if (!fileExists(path)) throw std::runtime_error(path + ": missing file");
  const YamlField root = YamlField::loadFile(path);
  root.allowOnly({"model", "body_radius", "body_height", "swept_height", "max_linear_speed",
                  "max_angular_speed", "max_linear_accel", "max_angular_accel", "rig"});
  RobotDescription d;
  d.model = root["model"].asString();
  const double big = 1e6;
  d.body_radius = root["body_radius"].asDouble(1e-6, big, "a positive number of metres");
  d.body_height = root["body_height"].asDouble(1e-6, big, "a positive number of metres");
  d.swept_height = root["swept_height"].asDouble(1e-6, big, "a positive number of metres");
  d.max_linear_speed = root["max_linear_speed"].asDouble(0, big, "a speed >= 0");
  d.max_angular_speed = root["max_angular_speed"].asDouble(0, big, "a speed >= 0");
  d.max_linear_accel = root["max_linear_accel"].asDouble(0, big, "an acceleration >= 0");
  d.max_angular_accel = root["max_angular_accel"].asDouble(0, big, "an acceleration >= 0");
  const YamlField rig = root["rig"];
  rig.allowOnly({"width", "height", "fx", "fy", "cx", "cy", "horizontal_offset", "vertical_offset",
                 "mount_position"});
  CameraIntrinsics& k = d.rig.intrinsics;
  k.width = rig["width"].asInt(16, 4096);  // as robot model files (robots/robot_model.h)
  k.height = rig["height"].asInt(16, 4096);
  k.fx = rig["fx"].asDouble(1e-6, big, "a positive focal length in pixels");
  k.fy = rig["fy"].asDouble(1e-6, big, "a positive focal length in pixels");
  k.cx = rig["cx"].asDouble(-big, big, "a principal point in pixels");
  k.cy = rig["cy"].asDouble(-big, big, "a principal point in pixels");
  d.rig.horizontal_offset = rig["horizontal_offset"].asVector3();
  d.rig.vertical_offset = rig["vertical_offset"].asVector3();
  d.rig.mount_position = rig["mount_position"].asVector3();
  if (!(d.rig.referenceBaseline() > 0.0))
    rig["horizontal_offset"].fail("a partner offset of non-zero length");
  return d;
}

// A robot name is a folder name inside the recording.
bool validName(const std::string& s) {
  if (s.empty() || s == "." || s == "..") return false;
  for (const char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return false;
  return true;
}

std::string trimSlash(std::string dir) {
  while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
  return dir;
}

}  // namespace

std::string recordingImagePath(const std::string& robot_dir, int frame, const char* camera) {
  char name[64];
  std::snprintf(name, sizeof name, "/images/%06d_%s.png", frame, camera);
  return robot_dir + name;
}

std::string encodeRecordingInfo(const RecordingInfo& info) {
  std::string y = "# coopmap recording: see README.md beside this file\n";
  y += "format: " + std::string(kRecordingFormat) + "\n";
  y += "version: " + std::to_string(info.version) + "\n";
  y += "source: " + JsonWriter::quote(info.source) + "\n";
  y += "world: " + JsonWriter::quote(info.world) + "\n";
  y += "world_file: " + JsonWriter::quote(info.world_file) + "\n";
  y += "seed: " + std::to_string(info.seed) + "\n";
  y += "sensing_rate: " + formatExact(info.sensing_rate) + "  # Hz\n";
  y += "control_rate: " + formatExact(info.control_rate) + "  # Hz\n";
  y += "map: {resolution: " + formatExact(info.map.resolution) + ", origin: [" +
       formatExact(info.map.origin.x()) + ", " + formatExact(info.map.origin.y()) +
       "], width: " + std::to_string(info.map.width) +
       ", height: " + std::to_string(info.map.height) + "}\n";
  y += std::string("shared_map: ") + (info.shared_map ? "true" : "false") + "\n";
  y += "robots:\n";
  for (const RecordedRobotInfo& r : info.robots) {
    y += "  - {name: " + JsonWriter::quote(r.name) + ", frames: " + std::to_string(r.frames);
    if (r.start)
      y += ", start: [" + formatExact(r.start->x) + ", " + formatExact(r.start->y) + ", " +
           formatExact(r.start->theta) + "]";
    if (r.map_in_world)
      y += ", map_in_world: [" + formatExact(r.map_in_world->x) + ", " +
           formatExact(r.map_in_world->y) + ", " + formatExact(r.map_in_world->theta) + "]";
    y += "}\n";
  }
  return y;
}

std::string encodeRobotDescription(const RobotDescription& d) {
  const CameraIntrinsics& k = d.rig.intrinsics;
  std::string y = "# coopmap robot description: see ../README.md\n";
  y += "model: " + JsonWriter::quote(d.model) + "\n";
  y += "body_radius: " + formatExact(d.body_radius) + "  # m\n";
  y += "body_height: " + formatExact(d.body_height) + "  # m\n";
  y += "swept_height: " + formatExact(d.swept_height) + "  # m\n";
  y += "max_linear_speed: " + formatExact(d.max_linear_speed) + "  # m/s\n";
  y += "max_angular_speed: " + formatExact(d.max_angular_speed) + "  # rad/s\n";
  y += "max_linear_accel: " + formatExact(d.max_linear_accel) + "  # m/s^2\n";
  y += "max_angular_accel: " + formatExact(d.max_angular_accel) + "  # rad/s^2\n";
  y += "rig:\n";
  y += "  width: " + std::to_string(k.width) + "\n";
  y += "  height: " + std::to_string(k.height) + "\n";
  y += "  fx: " + formatExact(k.fx) + "\n  fy: " + formatExact(k.fy) + "\n";
  y += "  cx: " + formatExact(k.cx) + "\n  cy: " + formatExact(k.cy) + "\n";
  y += "  horizontal_offset: " + vec(d.rig.horizontal_offset) + "\n";
  y += "  vertical_offset: " + vec(d.rig.vertical_offset) + "\n";
  y += "  mount_position: " + vec(d.rig.mount_position) + "\n";
  return y;
}

RecordingInfo readRecordingInfo(const std::string& dir_in) {
  const std::string dir = trimSlash(dir_in);
  const std::string path = dir + "/dataset.yaml";
  if (!fileExists(path))
    throw std::runtime_error(path + ": missing file: not a complete coopmap recording");
  const YamlField root = YamlField::loadFile(path);
  if (root["format"].asString() != kRecordingFormat)
    root["format"].fail("'" + std::string(kRecordingFormat) + "'");
  RecordingInfo info;
  info.version = root["version"].asInt(1, 1000000);
  if (info.version < kOldestRecordingVersion || info.version > kRecordingVersion)
    root["version"].failMessage("version " + std::to_string(info.version) +
                                " is not supported (this coopmap reads " + kRecordingFormat +
                                " versions " + std::to_string(kOldestRecordingVersion) + " to " +
                                std::to_string(kRecordingVersion) + ")");
  root.allowOnly({"format", "version", "source", "world", "world_file", "seed", "sensing_rate",
                  "control_rate", "map", "shared_map", "robots"});
  if (const auto shared = root.get("shared_map")) info.shared_map = shared->asBool();
  info.source = root["source"].asString();
  info.world = root["world"].asString();
  info.world_file = root["world_file"].asString();
  const YamlField seed = root["seed"];
  try {
    info.seed = std::stoull(seed.asString());
  } catch (const std::exception&) {
    seed.fail("an unsigned integer");
  }
  info.sensing_rate = root["sensing_rate"].asDouble(1e-6, 1e6, "a positive rate in Hz");
  info.control_rate = root["control_rate"].asDouble(1e-6, 1e6, "a positive rate in Hz");
  const YamlField map = root["map"];
  map.allowOnly({"resolution", "origin", "width", "height"});
  info.map.resolution = map["resolution"].asDouble(1e-6, 1e6, "a positive number of metres");
  info.map.origin = map["origin"].asVector2();
  info.map.width = map["width"].asInt(1, 100000);
  info.map.height = map["height"].asInt(1, 100000);
  if (const std::string problem = mapSizeProblem(info.map.width, info.map.height); !problem.empty())
    map["height"].fail(problem);
  const std::vector<YamlField> robots = root["robots"].elements();
  if (robots.empty()) root["robots"].fail("a list of at least one robot");
  for (const YamlField& r : robots) {
    r.allowOnly({"name", "frames", "start", "map_in_world"});
    RecordedRobotInfo robot;
    robot.name = r["name"].asString();
    if (!validName(robot.name)) r["name"].fail("a folder name (letters, digits, '_', '-', '.')");
    robot.frames = r["frames"].asInt(0, 999999);
    if (const auto start = r.get("start")) {
      const Eigen::Vector3d s = start->asVector3();
      robot.start = Pose2(s.x(), s.y(), s.z());
    }
    if (const auto frame = r.get("map_in_world")) {
      const Eigen::Vector3d s = frame->asVector3();
      robot.map_in_world = Pose2(s.x(), s.y(), s.z());
    }
    info.robots.push_back(robot);
  }
  return info;
}

RobotRecording readRobotRecording(const std::string& dir_in, const RecordingInfo& info,
                                  const RecordedRobotInfo& robot) {
  RobotRecording rec;
  rec.name = robot.name;
  rec.dir = trimSlash(dir_in) + "/" + robot.name;
  rec.description = parseRobotDescription(rec.dir + "/robot.yaml");
  rec.frames = readFrames(rec.dir + "/frames.csv");
  if (static_cast<int>(rec.frames.size()) != robot.frames)
    throw std::runtime_error(rec.dir +
                             "/frames.csv: truncated: " + std::to_string(rec.frames.size()) +
                             " frames, dataset.yaml says " + std::to_string(robot.frames));
  rec.odometry = readPoses(rec.dir + "/odometry.csv");
  rec.commands = readCommands(rec.dir + "/commands.csv");
  if (info.version >= 2) {
    rec.status = readStatus(rec.dir + "/status.csv");
    const std::string agent = rec.dir + "/agent.yaml";
    if (!fileExists(agent)) throw std::runtime_error(agent + ": missing file");
    rec.agent = readAgentConfig(YamlField::loadFile(agent));
    if (rec.agent->setup.name != rec.name)
      throw std::runtime_error(agent + ": the agent's name '" + rec.agent->setup.name +
                               "' is not the robot's '" + rec.name + "'");
    if (rec.status.size() != rec.odometry.size())
      throw std::runtime_error(rec.dir + "/status.csv: " + std::to_string(rec.status.size()) +
                               " rows for odometry.csv's " + std::to_string(rec.odometry.size()));
  }
  if (fileExists(rec.dir + "/groundtruth.csv"))
    rec.groundtruth = readPoses(rec.dir + "/groundtruth.csv");
  const std::string occupancy = rec.dir + "/groundtruth_occupancy.png";
  if (fileExists(occupancy))
    rec.truth_occupancy = decodeGridPng(readFile(occupancy), info.map, occupancy);
  return rec;
}

std::optional<GridU8> readRecordedFloor(const std::string& dir, const RecordingInfo& info) {
  const std::string path = trimSlash(dir) + "/floor.png";
  if (!fileExists(path)) return std::nullopt;
  return decodeGridPng(readFile(path), info.map, path);
}

TrinocularFrame readRecordedFrame(const RobotRecording& rec, size_t i) {
  const RecordedFrame& f = rec.frames.at(i);
  TrinocularFrame frame;
  frame.stamp = f.stamp;
  frame.odometry = f.odometry;
  const CameraIntrinsics& k = rec.description.rig.intrinsics;
  const char* cameras[3] = {"reference", "horizontal", "vertical"};
  cv::Mat* images[3] = {&frame.reference, &frame.horizontal, &frame.vertical};
  for (int c = 0; c < 3; ++c) {
    const std::string path = recordingImagePath(rec.dir, f.index, cameras[c]);
    const std::string where = ": frame " + std::to_string(f.index);
    const std::string bytes = readExisting(path, where);
    static constexpr char kPngMagic[] = "\x89PNG\r\n\x1a\n";
    if (bytes.compare(0, 8, kPngMagic, 8) != 0)
      throw ConfigError(path + where + ": expected a PNG image");
    const cv::Mat img = decodeImage(bytes, cv::IMREAD_UNCHANGED, path + where, kMaxMapCells);
    if (img.type() != CV_8UC1 || img.cols != k.width || img.rows != k.height)
      throw std::runtime_error(
          path + where + ": expected an 8-bit grey " + std::to_string(k.width) + "x" +
          std::to_string(k.height) + " image (robot.yaml), got " + std::to_string(img.cols) + "x" +
          std::to_string(img.rows) + " with " + std::to_string(img.channels()) + " channel(s) of " +
          std::to_string(8 * img.elemSize1()) + " bits");
    *images[c] = img;
  }
  return frame;
}

std::string encodeGridPng(const GridU8& grid) {
  const MapLimits& l = grid.limits;
  cv::Mat img(l.height, l.width, CV_8UC1);
  for (int iy = 0; iy < l.height; ++iy)
    for (int ix = 0; ix < l.width; ++ix)
      img.at<uint8_t>(l.height - 1 - iy, ix) = grid.at(ix, iy) ? 255 : 0;
  std::vector<uchar> buf;
  if (!cv::imencode(".png", img, buf)) throw std::runtime_error("PNG encoding failed");
  return {buf.begin(), buf.end()};
}

GridU8 decodeGridPng(const std::string& bytes, const MapLimits& limits, const std::string& path) {
  const cv::Mat img = decodeImage(bytes, cv::IMREAD_UNCHANGED, path, kMaxMapCells);
  if (img.type() != CV_8UC1 || img.cols != limits.width || img.rows != limits.height)
    throw std::runtime_error(path + ": expected an 8-bit grey " + std::to_string(limits.width) +
                             "x" + std::to_string(limits.height) +
                             " image (the map of dataset.yaml), got " + std::to_string(img.cols) +
                             "x" + std::to_string(img.rows) + " with " +
                             std::to_string(img.channels()) + " channel(s)");
  GridU8 grid(limits, 0);
  for (int iy = 0; iy < limits.height; ++iy)
    for (int ix = 0; ix < limits.width; ++ix)
      grid.at(ix, iy) = img.at<uint8_t>(limits.height - 1 - iy, ix) >= 128 ? 1 : 0;
  return grid;
}

std::string formatExact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace coopmap

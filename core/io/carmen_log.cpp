#include "core/io/carmen_log.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>

namespace coopmap {
namespace {

constexpr int kMaxBeams = 100000;

std::string formatNumber(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  return buf;
}

// The fields of one message line, read left to right; every failure names the file, line,
// message and field.
class Fields {
 public:
  Fields(const std::string& file, int line, std::string message,
         std::vector<std::string_view> tokens)
      : file_(file), line_(line), message_(std::move(message)), tokens_(std::move(tokens)) {}

  int line() const { return line_; }
  const std::string& message() const { return message_; }

  [[noreturn]] void fail(const std::string& field, const std::string& expected,
                         std::optional<std::string_view> got) const {
    std::string text = file_ + ":" + std::to_string(line_) + ": " + message_ + " field '" + field +
                       "': expected " + expected + ", got ";
    text += got ? "'" + std::string(*got) + "'" : std::string("the end of the line");
    throw CarmenLogError(text);
  }

  std::optional<std::string_view> next() {
    if (pos_ >= tokens_.size()) return std::nullopt;
    return tokens_[pos_++];
  }

  double number(const std::string& field) {
    const auto token = next();
    if (!token) fail(field, "a number", token);
    double v = 0.0;
    const char* end = token->data() + token->size();
    const auto [ptr, ec] = std::from_chars(token->data(), end, v);
    if (ec != std::errc() || ptr != end) fail(field, "a number", token);
    if (!std::isfinite(v)) fail(field, "a finite number", token);
    return v;
  }

  // A number > 0 (and <= hi).
  double positive(const std::string& field, double hi) {
    const std::string_view token = pos_ < tokens_.size() ? tokens_[pos_] : std::string_view();
    const double v = number(field);
    if (!(v > 0.0 && v <= hi)) fail(field, "a number in (0, " + formatNumber(hi) + "]", token);
    return v;
  }

  int integer(const std::string& field, int lo, int hi) {
    const auto token = next();
    const std::string expected =
        "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!token) fail(field, expected, token);
    int v = 0;
    const char* end = token->data() + token->size();
    const auto [ptr, ec] = std::from_chars(token->data(), end, v);
    if (ec != std::errc() || ptr != end || v < lo || v > hi) fail(field, expected, token);
    return v;
  }

  std::string_view word(const std::string& field) {
    const auto token = next();
    if (!token) fail(field, "a word", token);
    return *token;
  }

  Pose2 pose(const std::string& x, const std::string& y, const std::string& theta) {
    Pose2 p;
    p.x = number(x);
    p.y = number(y);
    p.theta = number(theta);
    return p;
  }

  // The trailer every logged message has: ipc_timestamp ipc_hostname logger_timestamp; then
  // the line must end. Returns the ipc timestamp.
  double trailer() {
    stamp_token_ = pos_ < tokens_.size() ? tokens_[pos_] : std::string_view();
    const double stamp = number("ipc_timestamp");
    word("ipc_hostname");
    number("logger_timestamp");
    if (pos_ < tokens_.size())
      throw CarmenLogError(file_ + ":" + std::to_string(line_) + ": " + message_ +
                           ": expected the end of the line after field 'logger_timestamp', "
                           "got '" +
                           std::string(tokens_[pos_]) + "'");
    return stamp;
  }

  // Checks, after trailer(), that a stream's stamps do not go back in time; `stream` names
  // the previous message ("ODOM", "scan of laser 1").
  void notBefore(double stamp, double previous, int previous_line,
                 const std::string& stream) const {
    if (previous_line > 0 && stamp < previous)
      fail("ipc_timestamp",
           "a time not before the previous " + stream + " (" + formatNumber(previous) +
               " at line " + std::to_string(previous_line) + ")",
           stamp_token_);
  }

 private:
  const std::string& file_;
  int line_;
  std::string message_;
  std::vector<std::string_view> tokens_;
  size_t pos_ = 1;  // token 0 is the message name
  std::string_view stamp_token_;
};

std::vector<float> readRanges(Fields& f, int n, const char* name) {
  std::vector<float> ranges(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    ranges[static_cast<size_t>(i)] =
        static_cast<float>(f.number(std::string(name) + "[" + std::to_string(i) + "]"));
  return ranges;
}

// FLASER/RLASER carry no laser configuration; CARMEN's conventions for the SICK LMS modes
// (its carmen_laser_guess_* functions) give one from the number of beams: 180 or 181 beams
// at 1 degree, 360 or 361 at 0.5 degree from -90 degrees; 400 or 401 at 0.25 degree (the
// 100 degree mode, centred on the laser's heading here); otherwise 180 degrees evenly.
void guessOldLaserConfig(CarmenLaser& l) {
  const size_t n = l.ranges.size();
  const double deg = M_PI / 180.0;
  if (n == 180 || n == 181) {
    l.angular_resolution = deg;
    l.start_angle = -90.0 * deg;
  } else if (n == 360 || n == 361) {
    l.angular_resolution = 0.5 * deg;
    l.start_angle = -90.0 * deg;
  } else if (n == 400 || n == 401) {
    l.angular_resolution = 0.25 * deg;
    l.start_angle = -50.0 * deg;
  } else {
    l.angular_resolution = n > 1 ? M_PI / static_cast<double>(n - 1) : M_PI;
    l.start_angle = -90.0 * deg;
  }
  l.field_of_view = l.angular_resolution * static_cast<double>(n > 1 ? n - 1 : 1);
  l.max_range = 80.0;  // CARMEN's guess for these messages
  l.accuracy = 0.01;
}

// RAWLASERn and ROBOTLASERn start alike: the laser configuration, ranges and remissions.
void readLaserConfigAndRanges(Fields& f, CarmenLaser& l) {
  f.integer("laser_type", -1000, 1000);
  l.start_angle = f.number("start_angle");
  if (std::abs(l.start_angle) > 2.0 * M_PI)
    f.fail("start_angle", "an angle in [-2 pi, 2 pi] rad", formatNumber(l.start_angle));
  l.field_of_view = f.positive("field_of_view", 2.0 * M_PI + 1e-3);
  l.angular_resolution = f.positive("angular_resolution", M_PI);
  l.max_range = f.positive("maximum_range", 1e6);
  l.accuracy = f.number("accuracy");
  f.integer("remission_mode", -1000, 1000);
  const int n = f.integer("num_readings", 1, kMaxBeams);
  l.ranges = readRanges(f, n, "range");
  const int m = f.integer("num_remissions", 0, kMaxBeams);
  for (int i = 0; i < m; ++i) f.number("remission[" + std::to_string(i) + "]");
}

}  // namespace

std::optional<double> CarmenLog::numericParam(const std::string& name) const {
  const auto it = params.find(name);
  if (it == params.end()) return std::nullopt;
  const std::string& v = it->second.value;
  double out = 0.0;
  const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
  if (ec != std::errc() || ptr != v.data() + v.size() || !std::isfinite(out))
    throw CarmenLogError(file + ":" + std::to_string(it->second.line) + ": PARAM field '" + name +
                         "': expected a number, got '" + v + "'");
  return out;
}

CarmenLog parseCarmenLog(std::string_view text, const std::string& file) {
  CarmenLog log;
  log.file = file;
  if (text.size() >= 2 && static_cast<unsigned char>(text[0]) == 0x1f &&
      static_cast<unsigned char>(text[1]) == 0x8b)
    throw CarmenLogError(file + ": a gzip-compressed log: decompress it first (gunzip)");

  double odom_stamp = 0.0, truth_stamp = 0.0;
  int odom_line = 0, truth_line = 0;
  std::map<int, std::pair<double, int>> laser_last;  // laser -> (stamp, line)
  std::vector<std::string_view> tokens;
  size_t start = 0;
  int line = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view row = text.substr(start, end - start);
    start = end + 1;
    ++line;
    if (!row.empty() && row.back() == '\r') row.remove_suffix(1);
    tokens.clear();
    for (size_t i = 0; i < row.size();) {
      while (i < row.size() && (row[i] == ' ' || row[i] == '\t')) ++i;
      const size_t b = i;
      while (i < row.size() && row[i] != ' ' && row[i] != '\t') ++i;
      if (i > b) tokens.push_back(row.substr(b, i - b));
    }
    if (tokens.empty() || tokens[0].front() == '#') continue;
    const std::string name(tokens[0]);
    Fields f(file, line, name, tokens);

    if (name == "ODOM") {
      CarmenOdometry o;
      o.line = line;
      o.pose = f.pose("x", "y", "theta");
      o.tv = f.number("tv");
      o.rv = f.number("rv");
      o.accel = f.number("accel");
      o.stamp = f.trailer();
      f.notBefore(o.stamp, odom_stamp, odom_line, "ODOM");
      odom_stamp = o.stamp;
      odom_line = line;
      log.odometry.push_back(o);
    } else if (name == "TRUEPOS") {
      CarmenTruePose t;
      t.line = line;
      t.truth = f.pose("true_x", "true_y", "true_theta");
      t.odometry = f.pose("odom_x", "odom_y", "odom_theta");
      t.stamp = f.trailer();
      f.notBefore(t.stamp, truth_stamp, truth_line, "TRUEPOS");
      truth_stamp = t.stamp;
      truth_line = line;
      log.truth.push_back(t);
    } else if (name == "PARAM") {
      const std::string key(f.word("param_name"));
      log.params[key] = {std::string(f.word("param_value")), line};
    } else if (name == "FLASER" || name == "RLASER" ||
               (name.size() == 9 && name.starts_with("RAWLASER") && name[8] >= '1' &&
                name[8] <= '4') ||
               (name.size() == 11 && name.starts_with("ROBOTLASER") &&
                (name[10] == '1' || name[10] == '2'))) {
      CarmenLaser l;
      l.message = name;
      l.line = line;
      if (name == "FLASER" || name == "RLASER") {
        l.laser = name == "FLASER" ? 1 : 2;
        const int n = f.integer("num_readings", 1, kMaxBeams);
        l.ranges = readRanges(f, n, "range");
        guessOldLaserConfig(l);
        l.laser_pose = f.pose("x", "y", "theta");
        l.robot_pose = f.pose("odom_x", "odom_y", "odom_theta");
      } else if (name.starts_with("RAWLASER")) {
        l.laser = name[8] - '0';
        readLaserConfigAndRanges(f, l);
      } else {
        l.laser = name[10] - '0';
        readLaserConfigAndRanges(f, l);
        l.laser_pose = f.pose("laser_pose_x", "laser_pose_y", "laser_pose_theta");
        l.robot_pose = f.pose("robot_pose_x", "robot_pose_y", "robot_pose_theta");
        for (const char* field :
             {"laser_tv", "laser_rv", "forward_safety_dist", "side_safety_dist", "turn_axis"})
          f.number(field);
      }
      l.stamp = f.trailer();
      auto [it, first] = laser_last.try_emplace(l.laser, l.stamp, line);
      if (!first) {
        f.notBefore(l.stamp, it->second.first, it->second.second,
                    "scan of laser " + std::to_string(l.laser));
        it->second = {l.stamp, line};
      }
      log.lasers.push_back(std::move(l));
    } else {
      ++log.skipped_messages[name];
    }
  }
  log.lines = line;
  return log;
}

CarmenLog readCarmenLog(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CarmenLogError(path + ": cannot open the log file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw CarmenLogError(path + ": cannot read the log file");
  return parseCarmenLog(text, path);
}

}  // namespace coopmap

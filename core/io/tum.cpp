#include "core/io/tum.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/io/atomic_file.h"

namespace coopmap {

std::string formatTum(const std::vector<StampedPose2>& trajectory, const std::string& comment) {
  std::string out = "# " + comment + "\n# timestamp tx ty tz qx qy qz qw\n";
  char line[160];
  for (const StampedPose2& p : trajectory) {
    const double h = 0.5 * p.pose.theta;
    std::snprintf(line, sizeof line, "%.6f %.6f %.6f 0 0 0 %.9f %.9f\n", p.stamp, p.pose.x,
                  p.pose.y, std::sin(h), std::cos(h));
    out += line;
  }
  return out;
}

std::vector<StampedPose2> parseTum(const std::string& text, const std::string& source) {
  std::vector<StampedPose2> out;
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double v[8];
    int k = 0;
    while (k < 8 && fields >> v[k]) ++k;
    std::string rest;
    if (k < 8 || (fields >> rest) || !std::isfinite(v[0]))
      throw std::runtime_error(source + ":" + std::to_string(n) +
                               ": expected 8 numbers (timestamp tx ty tz qx qy qz qw), got '" +
                               line + "'");
    if (!out.empty() && v[0] < out.back().stamp)
      throw std::runtime_error(source + ":" + std::to_string(n) + ": timestamp " +
                               std::to_string(v[0]) + " is earlier than the one before (" +
                               std::to_string(out.back().stamp) + ")");
    const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    out.push_back({v[0], Pose2(v[1], v[2], yaw)});
  }
  return out;
}

std::vector<StampedPose2> readTum(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read the trajectory");
  std::ostringstream text;
  text << in.rdbuf();
  return parseTum(text.str(), path);
}

void writeTum(const std::string& path, const std::vector<StampedPose2>& trajectory,
              const std::string& comment) {
  writeFileAtomic(path, formatTum(trajectory, comment));
}

const Pose2* tumPoseAt(const std::vector<StampedPose2>& trajectory, double stamp) {
  const auto it = std::lower_bound(trajectory.begin(), trajectory.end(), stamp - 1e-3,
                                   [](const StampedPose2& p, double t) { return p.stamp < t; });
  if (it == trajectory.end() || std::abs(it->stamp - stamp) > 1e-3) return nullptr;
  return &it->pose;
}

}  // namespace coopmap

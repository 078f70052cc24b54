#include "core/io/robot_outputs.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/mapping/map_io.h"

namespace coopmap {

void writeRobotOutputs(const std::string& dir, const RobotOutputs& r) {
  const std::string& name = r.name;
  const bool has_truth_path = r.groundtruth && !r.groundtruth->empty();
  writeRosMap(*r.grid, dir, "map_" + name);
  std::vector<TrajectoryOverlay> overlays;
  if (has_truth_path) overlays.push_back({*r.groundtruth, 0, 160, 0});
  std::vector<StampedPose2> odometry = *r.odometry;  // drawn where the first look placed it
  for (StampedPose2& p : odometry) p.pose = r.odometry_in_map * p.pose;
  overlays.push_back({odometry, 0, 0, 230});
  writeMapPng(dir + "/map_" + name + ".png", *r.grid, overlays);
  if (r.truth)
    writeFileAtomic(dir + "/map_" + name + "_evaluation.png",
                    encodeEvaluationPng(*r.grid, *r.truth));
  if (has_truth_path)
    writeTum(dir + "/trajectory_" + name + "_groundtruth.tum", *r.groundtruth,
             "coopmap ground truth of " + name + " (map frame) in world " + r.world);
  writeTum(dir + "/trajectory_" + name + "_odometry.tum", *r.odometry,
           "coopmap odometry of " + name + " (odometry frame) in world " + r.world);
  saveTraverseLog(dir + "/traverse_" + name + ".traverse", *r.traverse);
}

std::string RunLog::trajectory(const std::string& kind) const {
  return (std::filesystem::path(path).parent_path() / ("trajectory_" + robot + "_" + kind + ".tum"))
      .string();
}

std::vector<RunLog> runLogsIn(const std::string& dir) {
  std::vector<RunLog> out;
  std::error_code error;
  for (const auto& e : std::filesystem::directory_iterator(dir, error)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("traverse_", 0) == 0 && e.path().extension() == ".traverse")
      out.push_back(
          {e.path().stem().string().substr(std::string("traverse_").size()), e.path().string()});
  }
  if (error)
    throw std::runtime_error(dir + ": cannot read the run folder (" + error.message() + ")");
  std::sort(out.begin(), out.end(),
            [](const RunLog& a, const RunLog& b) { return a.robot < b.robot; });
  return out;
}

}  // namespace coopmap

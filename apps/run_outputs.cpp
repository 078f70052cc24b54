#include "apps/run_outputs.h"

#include "core/io/atomic_file.h"
#include "core/mapping/map_io.h"

namespace coopmap {

void writeRobotOutputs(const std::string& dir, const RobotOutputs& r) {
  const std::string& name = r.name;
  const bool has_truth_path = r.groundtruth && !r.groundtruth->empty();
  writeRosMap(*r.grid, dir, "map_" + name);
  std::vector<TrajectoryOverlay> overlays;
  if (has_truth_path) overlays.push_back({*r.groundtruth, 0, 160, 0});
  overlays.push_back({*r.odometry, 0, 0, 230});
  writeMapPng(dir + "/map_" + name + ".png", *r.grid, overlays);
  if (r.truth)
    writeFileAtomic(dir + "/map_" + name + "_evaluation.png",
                    encodeEvaluationPng(*r.grid, *r.truth));
  if (has_truth_path)
    writeTum(dir + "/trajectory_" + name + "_groundtruth.tum", *r.groundtruth,
             "coopmap ground truth of " + name + " in world " + r.world);
  writeTum(dir + "/trajectory_" + name + "_odometry.tum", *r.odometry,
           "coopmap odometry of " + name + " in world " + r.world);
  saveTraverseLog(dir + "/traverse_" + name + ".traverse", *r.traverse);
}

}  // namespace coopmap

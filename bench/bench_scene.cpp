#include "bench/bench_scene.h"

#include <cmath>

#include "sim/world/world.h"

namespace coopmap::bench {

BenchScene& labScene() {
  static BenchScene* scene = [] {
    auto* s = new BenchScene;
    const sim::World world = sim::loadWorld(std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml");
    s->model = loadRobotModel(world.robots[0].model_file);
    s->sim = std::make_unique<sim::Simulator>(world, 1);
    s->sim->addRobot(world.robots[0], {s->model.description, s->model.drive, s->model.odometry});
    s->frame = s->sim->capture(0, &s->truth_depth);
    return s;
  }();
  return *scene;
}

StereoScore score(const cv::Mat& disparity, const cv::Mat& truth_depth, double focal_baseline,
                  int border) {
  int total = 0, valid = 0, bad = 0;
  for (int v = border; v < disparity.rows - border; ++v)
    for (int u = border; u < disparity.cols - border; ++u) {
      const float z = truth_depth.at<float>(v, u);
      if (!(z > 0.0f)) continue;
      ++total;
      const float d = disparity.at<float>(v, u);
      if (!(d > 0.0f)) continue;
      ++valid;
      bad += std::abs(d - focal_baseline / z) > 1.0;
    }
  StereoScore s;
  s.density = total ? double(valid) / total : 0.0;
  s.bad_pixel_rate = valid ? double(bad) / valid : 0.0;
  return s;
}

}  // namespace coopmap::bench

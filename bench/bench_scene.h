// A rendered lab frame shared by the benchmarks, with its ground-truth depth.
#pragma once

#include <memory>

#include "robots/robot_model.h"
#include "sim/simulator.h"

namespace coopmap::bench {

struct BenchScene {
  std::unique_ptr<sim::Simulator> sim;
  RobotModel model;
  TrinocularFrame frame;  // jose at its start pose in worlds/lab.yaml
  cv::Mat truth_depth;    // reference camera, metres along the optical axis
};

// Built once per process and image size (90 degree horizontal field of view).
BenchScene& labScene(int width = 160, int height = 120);

}  // namespace coopmap::bench

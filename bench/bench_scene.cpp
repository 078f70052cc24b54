#include "bench/bench_scene.h"

#include <cmath>
#include <map>
#include <utility>

#include "sim/world/world.h"

namespace coopmap::bench {

BenchScene& labScene(int width, int height) {
  static std::map<std::pair<int, int>, std::unique_ptr<BenchScene>> scenes;
  auto& slot = scenes[{width, height}];
  if (!slot) {
    slot = std::make_unique<BenchScene>();
    BenchScene& s = *slot;
    const sim::World world = sim::loadWorld(std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml");
    s.model = loadRobotModel(world.robots[0].model_file);
    s.model.description.rig.intrinsics = CameraIntrinsics::fromFov(width, height, M_PI / 2);
    s.sim = std::make_unique<sim::Simulator>(world, 1);
    s.sim->addRobot(world.robots[0],
                    {s.model.description, s.model.drive, s.model.odometry, s.model.cameras});
    s.frame = s.sim->capture(0, &s.truth_depth);
  }
  return *slot;
}

}  // namespace coopmap::bench

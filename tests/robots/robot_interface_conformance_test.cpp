// The RobotInterface conformance suite on the simulated B-14, on the replay driver, and on
// the real B-14's composite driver (its rFLEX base, here an emulated controller, and its
// camera head, here reading a recorded image sequence).
#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "robots/b14/b14_robot.h"
#include "robots/replay/replay_robot.h"
#include "robots/rflex/rflex_emulator.h"
#include "robots/robot_model.h"
#include "robots/sim/sim_robot.h"
#include "sim/simulator.h"
#include "sim/world/world.h"
#include "tests/robots/recorded_run.h"
#include "tests/robots/robot_interface_conformance.h"
#include "tests/support/test_world.h"

namespace coopmap::test_support {
namespace {

// A simulator with one B-14 in a small room, and the driver over it.
DriverUnderTest makeSimDriver() {
  struct Owner {
    std::unique_ptr<sim::Simulator> sim;
    std::unique_ptr<SimRobot> robot;
  };
  const TestWorldFile world_file =
      writeTestWorld("conformance_room",
                     R"(floor: {min: [-2, -2], max: [2, 2], texture: carpet}
walls:
  - {from: [2, -2], to: [2, 2], thickness: 0.1, height: 2.5, texture: poster}
home_base:
  corners:
    - {position: [1.5, -1.5], heading_deg: 0}
    - {position: [1.5, 1.5], heading_deg: 0}
  texture: wood
)");
  const sim::World world = sim::loadWorld(world_file.path());
  auto owner = std::make_shared<Owner>();
  owner->sim = std::make_unique<sim::Simulator>(world, 1);
  const RobotModel model = loadRobotModel(world.robots[0].model_file);
  const int index = owner->sim->addRobot(
      world.robots[0], {model.description, model.drive, model.odometry, model.cameras});
  owner->robot = std::make_unique<SimRobot>(*owner->sim, index);
  sim::Simulator* sim = owner->sim.get();
  return {owner, owner->robot.get(), [sim](double dt) { sim->advance(dt); }};
}

// The replay driver over the shared recording; a recording's clock moves with its frames.
DriverUnderTest makeReplayDriver() {
  const RecordedRun& run = recordedRun();
  const RecordingInfo info = readRecordingInfo(run.dir);
  auto robot = std::make_shared<ReplayRobot>(readRobotRecording(run.dir, info, info.robots[0]));
  return {robot, robot.get(), [](double) {}};
}

// The B-14 as one robot: the emulated rFLEX controller drives the base on the wall clock, the
// cameras read the shared recording's rectified images (as a camera head that rectifies
// itself delivers them).
DriverUnderTest makeB14Driver() {
  const RecordedRun& run = recordedRun();
  struct Owner {
    std::unique_ptr<RflexEmulator> emulator;
    std::unique_ptr<B14Robot> robot;  // destroyed first: the driver before the controller
  };
  auto owner = std::make_shared<Owner>();
  owner->emulator = std::make_unique<RflexEmulator>();
  const RobotDescription d =
      loadRobotModel(std::string(COOPMAP_SOURCE_DIR) + "/robots/b14/b14.yaml").description;
  RflexConfig c;
  c.device = owner->emulator->device();
  c.report_period = 0.02;
  c.watchdog_timeout = 1.0;
  c.startup_timeout = 5.0;
  c.write_timeout = 1.0;
  const std::string images = run.dir + "/r/images/%06d_";
  owner->robot = std::make_unique<B14Robot>(
      std::make_unique<RflexRobot>(c, d),
      std::make_unique<TrinocularCamera>(
          CameraSources{images + "reference.png", images + "horizontal.png",
                        images + "vertical.png"},
          d.rig),
      d);
  return {owner, owner->robot.get(),
          [](double dt) { std::this_thread::sleep_for(std::chrono::duration<double>(dt)); }};
}

INSTANTIATE_TEST_SUITE_P(Drivers, RobotInterfaceConformance,
                         ::testing::Values(DriverCase{"SimRobot", &makeSimDriver},
                                           DriverCase{"ReplayRobot", &makeReplayDriver},
                                           DriverCase{"B14Robot", &makeB14Driver}),
                         driverCaseName);

}  // namespace
}  // namespace coopmap::test_support

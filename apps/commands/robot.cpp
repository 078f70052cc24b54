// coopmap robot: a real B-14 on the wall clock, with a mission or following a route.
#include <cstdio>
#include <string>

#include "apps/commands/commands.h"
#include "core/io/robot_outputs.h"
#include "robots/b14/robot_mission.h"

namespace coopmap::apps {
namespace {

class RobotCommand : public Command {
 public:
  explicit RobotCommand(CLI::App& app);
  int run() override;

 private:
  RobotCommandOptions options_;
};

RobotCommand::RobotCommand(CLI::App& app)
    : Command(app.add_subcommand(
          "robot",
          "Run a real B-14 (its rFLEX base over a serial port, its trinocular cameras) on the "
          "wall clock. With a mission (the config's `mission:` and `cameras:`), the robot's "
          "agent runs as in simulation: it looks at the home base to find where it stands, "
          "explores (mode explore) or follows a route (mode route) in sorties, and back home "
          "localizes, corrects its traverse, posts it to the shared map and imports it, until "
          "it is done or Ctrl-C (then a safe stop); --out receives its map, traverse log and "
          "odometry. Without one, the base alone follows the config's route in the odometry "
          "frame. The config names the serial device and baud, the robot model file, and the "
          "mission or the route.")) {
  CLI::App* cmd = cli();
  cmd->add_option("config", options_.config, "Robot config file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_flag("--dry-run", options_.dry_run,
                "Check the config and that the controller answers; move nothing");
  cmd->add_flag("--quiet", options_.quiet, "No progress lines");
  cmd->add_option("--out", options_.out_dir,
                  "With a mission: folder for the robot's map (map_<robot>.pgm/.yaml/.png), "
                  "traverse log and odometry (created if missing)")
      ->check(kOutputFolder);
}

int RobotCommand::run() {
  RobotMissionResult mission;
  const int code = runRobotCommand(options_, stdout, &mission);
  if (!options_.out_dir.empty() && mission.grid) {
    StagedFolder out(options_.out_dir, "coopmap robot");
    writeRobotOutputs(options_.out_dir,
                      {mission.name, "", &*mission.grid, nullptr, &mission.odometry, nullptr,
                       &mission.traverse, mission.odometry_in_map});
    out.commit();
    std::printf("outputs in %s\n", out.given().c_str());
  }
  return code;
}

}  // namespace

std::unique_ptr<Command> addRobotCommand(CLI::App& app) {
  return std::make_unique<RobotCommand>(app);
}

}  // namespace coopmap::apps

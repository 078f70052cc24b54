// coopmap stereo-scale: the odometry's distance scale measured by the cameras over runs'
// traverse logs.
#include "apps/commands/commands.h"
#include "sim/runner/stereo_scale_logs.h"

namespace coopmap::apps {
namespace {

class StereoScaleCommand : public Command {
 public:
  explicit StereoScaleCommand(CLI::App& app)
      : Command(app.add_subcommand(
            "stereo-scale",
            "The odometry's distance scale measured by the cameras over runs' traverse logs "
            "(each at the run's raw odometry), per log and pooled: a calibration of the robot "
            "from logs, for a mission's `odometry_distance_scale`. With the runs' ground truth, "
            "each log's true scale beside it.")) {
    CLI::App* cmd = cli();
    cmd->add_option("runs", options_.run_dirs, "`coopmap run` output folders")
        ->required()
        ->check(CLI::ExistingDirectory);
    cmd->add_option("--robot", options_.robot, "Only this robot's logs")->capture_default_str();
  }

  int run() override {
    printStereoScaleSummary(runStereoScale(options_));
    return 0;
  }

 private:
  StereoScaleOptions options_;
};

}  // namespace

std::unique_ptr<Command> addStereoScaleCommand(CLI::App& app) {
  return std::make_unique<StereoScaleCommand>(app);
}

}  // namespace coopmap::apps

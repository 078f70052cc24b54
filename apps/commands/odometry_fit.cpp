// coopmap odometry-fit: odometry error growth of a real log, and the simulator preset that
// reproduces it.
#include <cstdio>

#include "apps/commands/commands.h"
#include "sim/runner/odometry_fit.h"

namespace coopmap::apps {
namespace {

class OdometryFitCommand : public Command {
 public:
  explicit OdometryFitCommand(CLI::App& app);
  int run() override;

 private:
  OdometryFitOptions options_;
};

OdometryFitCommand::OdometryFitCommand(CLI::App& app)
    : Command(app.add_subcommand(
          "odometry-fit",
          "Odometry error growth of a real log with ground truth (UTIAS MRCLAM format: 'time x "
          "y theta' and 'time v w'), per metre driven and per radian turned, over windows; the "
          "simulator preset with those errors; with --simulate, the same statistics of the "
          "simulated robot driven by the log's commands with that preset.")) {
  options_.robot_model = "robots/b14/b14.yaml";
  CLI::App* cmd = cli();
  cmd->add_option("--groundtruth", options_.groundtruth, "Ground-truth file")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--odometry", options_.odometry, "Odometry file")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--window", options_.window_s, "Window length (s)")->capture_default_str();
  cmd->add_flag("--simulate", options_.simulate, "Replay the commands on the simulated robot");
  cmd->add_option("--robot", options_.robot_model, "Robot model file for --simulate")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  cmd->add_option("--seed", options_.seed, "Seed of the simulated odometry")
      ->check(kSeed)
      ->capture_default_str();
}

int OdometryFitCommand::run() {
  const OdometryFitResult r = runOdometryFit(options_);
  auto row = [](const char* name, const DriftStats& s) {
    std::printf("| %s | %d | %.2f | %.2f | %.5f | %.5f | %.4f | %.4f | %.4f | %.4f |\n", name,
                s.windows, s.metres_per_window, s.radians_per_window, s.heading_bias_per_m,
                s.turn_bias, s.scale_bias, s.heading_sigma_per_sqrt_m, s.heading_sigma_per_sqrt_rad,
                s.distance_sigma_per_sqrt_m);
  };
  std::printf(
      "| source | windows | m/window | rad/window | heading bias rad/m | turn bias "
      "rad/rad | scale bias | heading sigma rad/sqrt(m) | heading sigma "
      "rad/sqrt(rad) | distance sigma m/sqrt(m) "
      "|\n|---|---|---|---|---|---|---|---|---|---|\n");
  row("real log", r.real);
  if (options_.simulate) row("simulated, fitted preset", r.simulated);
  const auto& p = r.preset;
  std::printf(
      "\nfitted preset (robot file, simulation.odometry):\n  preset: drifting\n"
      "  scale_error: %.5f\n  turn_scale_error: %.5f\n  heading_drift: %.6f\n"
      "  linear_noise: %.5f\n  angular_noise: %.5f\n  heading_noise: %.5f\n",
      p.scale_error, p.turn_scale_error, p.heading_drift, p.linear_noise, p.angular_noise,
      p.heading_noise);
  return 0;
}

}  // namespace

std::unique_ptr<Command> addOdometryFitCommand(CLI::App& app) {
  return std::make_unique<OdometryFitCommand>(app);
}

}  // namespace coopmap::apps

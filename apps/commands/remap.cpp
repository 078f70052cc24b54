// coopmap remap: a run's map rebuilt at a chosen trajectory and scored against the world.
#include "sim/runner/remap.h"
#include "apps/commands/commands.h"

namespace coopmap::apps {
namespace {

class RemapCommand : public Command {
 public:
  explicit RemapCommand(CLI::App& app);
  int run() override;

 private:
  RemapOptions options_;
};

RemapCommand::RemapCommand(CLI::App& app)
    : Command(app.add_subcommand(
          "remap",
          "Rebuild a run's map from its traverse logs at a chosen trajectory and score it "
          "against the world's true occupancy: at the ground truth, what stereo alone allows; "
          "at the corrected traverses, what their pose errors cost (false obstacles split by "
          "their distance to the true ones).")) {
  CLI::App* cmd = cli();
  cmd->add_option("run", options_.run_dir, "A `coopmap run` output folder")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--world", options_.world_file, "The world the run was in")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--poses", options_.poses,
                  "logged (the poses in the traverse logs: the live estimate), corrected, "
                  "estimate, odometry or groundtruth (trajectory_<robot>_<poses>.tum)")
      ->capture_default_str();
  cmd->add_option("--max-error", options_.max_error_m,
                  "Only the radial maps whose pose is within this many metres of the ground "
                  "truth (an oracle's choice; 0: all)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--oracle", options_.oracle,
                  "Take this part of each pose from the ground truth and the rest from "
                  "--poses, to see which part of the pose error costs the map: position, "
                  "heading, or the position error's part along the true heading (along) or "
                  "across it (across)")
      ->check(CLI::IsMember({"position", "heading", "along", "across"}));
  cmd->add_option("--out", options_.out_dir, "Folder for map.{pgm,yaml,png} and map_evaluation.png")
      ->check(kOutputFolder);
  cmd->add_option("--band", options_.band,
                  "Each return drawn over this share of its modelled range sigma (the "
                  "published shared map's by default; 1: the robots' own maps')")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 2.0));
  cmd->add_flag("--range-errors", options_.range_errors,
                "With --poses groundtruth: the radial maps' range errors against the "
                "world's true surfaces by range (median, robust sd, RMS), beside the "
                "stereo's modelled sigma and the share of errors within it");
}

int RemapCommand::run() {
  StagedFolder out(options_.out_dir, "coopmap remap");
  const RemapSummary r = runRemap(options_);
  out.commit();
  options_.out_dir = out.given();
  printRemapSummary(options_, r);
  return 0;
}

}  // namespace

std::unique_ptr<Command> addRemapCommand(CLI::App& app) {
  return std::make_unique<RemapCommand>(app);
}

}  // namespace coopmap::apps

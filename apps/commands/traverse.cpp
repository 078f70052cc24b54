// coopmap traverse: a map rebuilt from a traverse log at its odometry poses.
#include "apps/commands/commands.h"
#include "sim/runner/traverse_tool.h"

namespace coopmap::apps {
namespace {

class TraverseCommand : public Command {
 public:
  explicit TraverseCommand(CLI::App& app)
      : Command(app.add_subcommand(
            "traverse",
            "Rebuild a map from a traverse log (traverse_<robot>.traverse of a run) at its "
            "odometry poses: map.{pgm,yaml,png} in --out; prints what the log holds.")) {
    CLI::App* cmd = cli();
    cmd->add_option("log", options_.log_file, "Traverse log")->required()->check(CLI::ExistingFile);
    cmd->add_option("--out", options_.out_dir, "Output folder")->required()->check(kOutputFolder);
    cmd->add_option("--first", options_.first, "First entry used")->capture_default_str();
    cmd->add_option("--last", options_.last, "Last entry used (-1: the end)")
        ->capture_default_str();
    cmd->add_option("--resolution", options_.resolution, "Map resolution (m)")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->add_option("--align-stretch", options_.align_stretch,
                    "Also align each stretch of N entries (end to end) to the map from its "
                    "logged poses and print how far the alignments move them, one row per "
                    "stretch in stretches.csv (with exact poses, --odometry perfect, that is "
                    "the scan alignment's own error; 0: off)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
  }

  int run() override {
    StagedFolder out(options_.out_dir, "coopmap traverse");
    const TraverseSummary r = runTraverse(options_);
    out.commit();
    options_.out_dir = out.given();
    printTraverseSummary(options_, r);
    return 0;
  }

 private:
  TraverseOptions options_;
};

}  // namespace

std::unique_ptr<Command> addTraverseCommand(CLI::App& app) {
  return std::make_unique<TraverseCommand>(app);
}

}  // namespace coopmap::apps

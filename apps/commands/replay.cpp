// coopmap replay: a recording through the robot interface into the live run's outputs.
#include <cstdio>

#include "apps/commands/commands.h"
#include "sim/runner/replay_run.h"

namespace coopmap::apps {
namespace {

class ReplayCommand : public Command {
 public:
  explicit ReplayCommand(CLI::App& app)
      : Command(app.add_subcommand(
            "replay",
            "Replay a recording (`coopmap run --record DIR`) through the robot interface: the "
            "same mapping core writes the same outputs as the live run to --out (maps, "
            "trajectories, traverse logs, metrics.json); a simulator recording reproduces the "
            "live maps bit for bit.")) {
    cli()
        ->add_option("recording", options_.recording, "Recording folder")
        ->required()
        ->check(CLI::ExistingDirectory);
    cli()
        ->add_option("--out", options_.out_dir, "Output folder (created if missing)")
        ->required()
        ->check(kOutputFolder);
  }

  int run() override {
    StagedFolder out(options_.out_dir, "coopmap replay");
    const ReplayResult r = runReplay(options_);
    out.commit();
    for (const auto& robot : r.robots)
      std::printf("%s: %d frames over %.1f s, odometry path %.1f m\n", robot.name.c_str(),
                  robot.frames, robot.duration_s, robot.odometry_path_length_m);
    std::printf("replayed %s in %.1f s wall; outputs in %s\n", options_.recording.c_str(),
                r.wall_time_s, out.given().c_str());
    return 0;
  }

 private:
  ReplayOptions options_;
};

}  // namespace

std::unique_ptr<Command> addReplayCommand(CLI::App& app) {
  return std::make_unique<ReplayCommand>(app);
}

}  // namespace coopmap::apps

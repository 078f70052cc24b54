// coopmap bench: the scenario benchmarks, `bench drift` and `bench explore`, and `bench
// speedup`, two robots against one on the worlds of two `bench explore` outputs.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/commands/commands.h"
#include "sim/runner/drift_bench.h"
#include "sim/runner/explore_bench.h"
#include "sim/runner/team_speedup.h"

namespace coopmap::apps {
namespace {

class DriftBenchCommand : public Command {
 public:
  explicit DriftBenchCommand(CLI::App& bench);
  int run() override;

 private:
  DriftBenchOptions options_;
  std::vector<std::string> models_;
  bool no_camera_noise_ = false;
  bool quiet_ = false;
};

DriftBenchCommand::DriftBenchCommand(CLI::App& bench)
    : Command(bench.add_subcommand(
          "drift",
          "The drift-error benchmark (the paper's long traverse): for each seed a robot drives "
          "the world's loop on drifting odometry, localizes at the home base, and each "
          "correction model corrects its traverse and rebuilds its map. Writes drift.csv (a "
          "row per seed and model), drift.md (the summary table beside the paper's figures), "
          "and seeds/<seed>/ with TUM trajectories (ground truth, odometry, each model) and "
          "maps.png (the maps side by side) to --out.")) {
  CLI::App* cmd = cli();
  cmd->add_option("--world", options_.world_file, "World file with a home base and a loop")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options_.out_dir, "Output folder")->required()->check(kOutputFolder);
  cmd->add_option("--seeds", options_.seeds, "Number of seeds")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--first-seed", options_.first_seed, "First seed")
      ->check(kSeed)
      ->capture_default_str();
  cmd->add_option("--odometry", options_.odometry,
                  "Odometry preset of the robot file ('drifting' is its default preset)")
      ->capture_default_str();
  cmd->add_option("--models", models_,
                  "Correction models: none, uniform, turns-and-straights, heading-drift, "
                  "pose-graph (default: all)");
  cmd->add_flag("--no-camera-noise", no_camera_noise_, "Noise-free cameras");
  cmd->add_flag("--quiet", quiet_, "No line per seed on stderr");
}

int DriftBenchCommand::run() {
  if (!models_.empty()) {
    options_.models.clear();
    for (const std::string& m : models_) {
      const auto parsed = parseCorrectionModel(m);
      if (!parsed)
        throw std::invalid_argument(
            "--models: expected none, uniform, turns-and-straights, "
            "heading-drift or pose-graph, got '" +
            m + "'");
      options_.models.push_back(*parsed);
    }
  }
  options_.camera_noise = !no_camera_noise_;
  options_.progress = !quiet_;
  StagedFolder out(options_.out_dir, "coopmap bench drift");
  const DriftBenchResult r = runDriftBench(options_);
  out.commit();
  std::printf("%s\n%s/drift.csv, drift.md and seeds/ written\n", r.markdown.c_str(),
              out.given().c_str());
  return 0;
}

class ExploreBenchCommand : public Command {
 public:
  explicit ExploreBenchCommand(CLI::App& bench);
  int run() override;

 private:
  ExploreBenchOptions options_;
  bool quiet_ = false;
};

ExploreBenchCommand::ExploreBenchCommand(CLI::App& bench)
    : Command(bench.add_subcommand(
          "explore",
          "The exploration benchmark: for each seed, generates a world (`world generate`, "
          "family and area drawn from the seed) and runs the robots exploring it on their "
          "default settings, each world in its own process. Writes explore.csv (a row per "
          "world), explore.md (the distribution, the targets met, the worst worlds), worlds/ "
          "and runs/ to --out.")) {
  CLI::App* cmd = cli();
  cmd->add_option("--first-seed", options_.first_seed, "First seed")
      ->check(kSeed)
      ->capture_default_str();
  cmd->add_option("--count", options_.count, "Number of worlds")->capture_default_str();
  cmd->add_option("--run-seed-offset", options_.run_seed_offset,
                  "Each world's run takes the seed world seed + this (0: the world's own): "
                  "the same worlds again with other camera and odometry noise and people's "
                  "walks, to measure how far the scores move from run to run")
      ->capture_default_str();
  cmd->add_option("--robots", options_.robots, "Robots exploring: 1 or 2")->capture_default_str();
  cmd->add_option("--duration", options_.duration, "Simulated seconds per world at most")
      ->capture_default_str();
  cmd->add_option("--jobs", options_.jobs, "Worlds run at once (default: the number of processors)")
      ->capture_default_str();
  cmd->add_option("--out", options_.out_dir, "Output folder")->required()->check(kOutputFolder);
  cmd->add_flag("--quiet", quiet_, "No line per world on stderr");
}

int ExploreBenchCommand::run() {
  options_.progress = !quiet_;
  StagedFolder out(options_.out_dir, "coopmap bench explore");
  runExploreBench(options_);
  out.commit();
  std::printf("%s/explore.csv, explore.md, worlds/ and runs/ written\n", out.given().c_str());
  return 0;
}

class SpeedupBenchCommand : public Command {
 public:
  explicit SpeedupBenchCommand(CLI::App& bench);
  int run() override;

 private:
  std::string two_dir_, one_dir_;
};

SpeedupBenchCommand::SpeedupBenchCommand(CLI::App& bench)
    : Command(bench.add_subcommand(
          "speedup",
          "Two robots against one: reads two `bench explore` outputs of the same seeds, one "
          "run with two robots and one with --robots 1, and prints (Markdown) in how many "
          "worlds two robots reached 90 % coverage sooner, the median speed-up, and a row per "
          "world.")) {
  CLI::App* cmd = cli();
  cmd->add_option("--two", two_dir_, "Output of `bench explore` with two robots")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--one", one_dir_, "Output of `bench explore --robots 1` on the same seeds")
      ->required()
      ->check(CLI::ExistingDirectory);
}

int SpeedupBenchCommand::run() {
  const TeamSpeedup comparison = compareTeams(two_dir_, one_dir_);
  std::printf("%s", formatTeamSpeedup(comparison, two_dir_, one_dir_).c_str());
  return 0;
}

}  // namespace

std::unique_ptr<Command> addBenchCommand(CLI::App& app) {
  auto bench = std::make_unique<CommandGroup>(app.add_subcommand("bench", "Scenario benchmarks"));
  bench->cli()->require_subcommand(1);
  bench->add(std::make_unique<DriftBenchCommand>(*bench->cli()));
  bench->add(std::make_unique<ExploreBenchCommand>(*bench->cli()));
  bench->add(std::make_unique<SpeedupBenchCommand>(*bench->cli()));
  return bench;
}

}  // namespace coopmap::apps

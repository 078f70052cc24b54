// coopmap run: a world run headless, its outputs and a summary per robot.
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/commands/commands.h"
#include "core/agent/agent_settings.h"
#include "core/io/yaml_reader.h"
#include "sim/runner/world_run.h"
#include "sim/runner/world_run_outputs.h"

namespace coopmap::apps {
namespace {

class RunCommand : public Command {
 public:
  explicit RunCommand(CLI::App& app);
  int run() override;

 private:
  RunOptions options_;
  std::string out_;
  std::string odometry_;
  int robots_ = 0;
  bool explore_ = false, routes_ = false;
  std::string settings_file_;
  // The settings given as flags, (name, value) in command-line order.
  std::vector<std::pair<std::string, std::string>> setting_values_;
  std::optional<YamlField> file_settings_;  // the --settings file, read before the run
  bool quiet_ = false;
  bool events_ = false;
};

RunCommand::RunCommand(CLI::App& app)
    : Command(app.add_subcommand(
          "run",
          "Run a world headless: each robot's agent finds its start from the home base, follows "
          "its scripted route or explores in sorties, maps from trinocular stereo, and shares "
          "its corrected sorties; maps, trajectories, traverse logs, metrics.json and a report "
          "are written to --out (docs/formats.md).")) {
  CLI::App* cmd = cli();
  cmd->add_option("world", options_.world_file, "World file (YAML), e.g. worlds/lab.yaml")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", out_, "Output folder (created if missing)")
      ->required()
      ->check(kOutputFolder);
  cmd->add_option("--seed", options_.seed, "Seed for every random choice of the run")
      ->check(kSeed)
      ->capture_default_str();
  cmd->add_option("--duration", options_.duration, "Simulated seconds at most")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--robots", robots_, "Use only the first N robots of the world")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--odometry", odometry_,
                  "Override the robot file's odometry: 'perfect', 'drifting' (its default "
                  "preset), or the name of a preset in the robot file (e.g. utias_robot1)");
  cmd->add_flag("--steer-by-truth", options_.steer_by_truth,
                "Follow the route by the true pose, as a person driving it would: the path "
                "is the intended one and odometry only records it (drift experiments)");
  cmd->add_option("--record", options_.record_dir,
                  "Record each robot's raw stream (camera images, stamps, odometry, "
                  "commands, rig and robot description) and the ground truth into this "
                  "folder, for `coopmap replay` (layout: its README.md)")
      ->check(kOutputFolder);
  cmd->add_option("--shared-map", options_.shared_map_dir,
                  "Keep the robots' shared map in this folder (shared_map.bin, saved before "
                  "each post is acknowledged): a run on a folder that holds one goes on from "
                  "it, and a killed run loses no acknowledged post")
      ->check(CLI::NonexistentPath | CLI::ExistingDirectory);
  cmd->add_flag("--explore", explore_,
                "Autonomous missions instead of the routes: look at the home base, explore "
                "frontiers with OMPL paths, come home when the budget is spent or nothing "
                "reachable is left, look at the home base again (the default of a world "
                "whose robots have no routes)");
  cmd->add_flag("--routes", routes_,
                "Follow the scripted routes of the world file (the default where it gives "
                "them)")
      ->excludes("--explore");
  // The agents' settings (core/agent/agent_settings.h): a settings file, then each as
  // --kebab-case-name VALUE, over the robot model's odometry calibration and coopmap's
  // defaults.
  cmd->add_option("--settings", settings_file_,
                  "A YAML file of the agents' settings (`name: value` per line, the names of "
                  "the flags below in snake_case); flags given too go over it")
      ->check(CLI::ExistingFile);
  for (const SettingInfo& info : agentSettingInfos()) {
    const std::string name = info.name;
    std::string help = info.help;
    if (*info.unit) help += " [" + std::string(info.unit) + "]";
    AgentSettings defaults;
    defaults.visit([&](const SettingInfo& i, const auto& value) {
      if (name != i.name) return;
      std::ostringstream v;
      v << std::boolalpha << value;
      help += " (default " + v.str() + ")";
    });
    cmd->add_option_function<std::string>(
        settingFlag(name),
        [this, name](const std::string& v) { setting_values_.emplace_back(name, v); }, help);
  }
  cmd->add_option("--published-band", options_.published_band,
                  "The shared map published (maps, metrics): each return drawn over this "
                  "share of its modelled range sigma (the robots' own maps and the shared map "
                  "they import: 1)")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 2.0));
  cmd->add_flag("--quiet", quiet_, "No progress bar");
  cmd->add_flag("--events", events_,
                "Print each robot's mission events as they happen (simulated time, robot, "
                "what it decided)");
}

int RunCommand::run() {
  if (explore_) options_.explore = true;
  if (routes_) options_.explore = false;
  // Checked before the run, so that a bad value costs no simulation.
  if (!settings_file_.empty()) file_settings_ = YamlField::loadFile(settings_file_);
  AgentSettings check;
  if (file_settings_) readAgentSettings(*file_settings_, check);
  for (const auto& [name, value] : setting_values_) setAgentSetting(check, name, value);
  options_.settings = [this](AgentSettings& s) {
    if (file_settings_) readAgentSettings(*file_settings_, s);
    for (const auto& [name, value] : setting_values_) setAgentSetting(s, name, value);
  };
  if (robots_ > 0) options_.robots = robots_;
  if (!odometry_.empty()) options_.odometry = odometry_;
  options_.progress = !quiet_ && !events_;
  if (events_)
    options_.event_observer = [](const std::string& robot, double t, const std::string& event) {
      std::printf("%.1f s %s: %s\n", t, robot.c_str(), event.c_str());
      std::fflush(stdout);  // as it happens, also into a pipe
    };
  options_.share_maps = true;
  StagedFolder out(out_, "coopmap run");
  StagedFolder record(options_.record_dir, "coopmap run --record");
  const RunResult r = runWorld(options_);
  writeRunOutputs(out_, r);
  record.commit();
  out.commit();
  for (const auto& robot : r.robots)
    std::printf(
        "%s: path %.1f m, %d frames, collisions %d, wall_recall %.3f, "
        "false_occupied_rate %.4f, coverage %.3f, odometry error %.3f m %.2f deg\n",
        robot.name.c_str(), robot.path_length_m, robot.frames, robot.collisions,
        robot.map.wall_recall, robot.map.false_occupied_rate, robot.map.coverage,
        robot.odometry_error_m, robot.odometry_error_deg);
  if (r.shared_map.computed)
    std::printf(
        "shared map (home-base protocol, %d posts): wall_recall %.3f, false_occupied_rate "
        "%.4f, coverage %.3f; naive sharing: %.3f, %.4f, %.3f; as the robots import it: "
        "%.3f, %.4f\n",
        r.shared_map.posts_accepted, r.shared_map.protocol.wall_recall,
        r.shared_map.protocol.false_occupied_rate, r.shared_map.protocol.coverage,
        r.shared_map.naive.wall_recall, r.shared_map.naive.false_occupied_rate,
        r.shared_map.naive.coverage, r.shared_map.imported.wall_recall,
        r.shared_map.imported.false_occupied_rate);
  for (const auto& robot : r.robots) {
    for (const std::string& line : robot.log)
      std::printf("%s %s\n", robot.name.c_str(), line.c_str());
    std::string errors;
    char e[96];
    if (robot.start_fix_error) {
      std::snprintf(e, sizeof e, "start %.1f cm %.2f deg", 100.0 * robot.start_fix_error->error_m,
                    robot.start_fix_error->error_deg);
      errors += e;
    }
    if (robot.placed_error) {
      std::snprintf(e, sizeof e, "; placed %.1f cm %.2f deg", 100.0 * robot.placed_error->error_m,
                    robot.placed_error->error_deg);
      errors += e;
    }
    for (const FixError& f : robot.fix_errors) {
      std::snprintf(e, sizeof e, "%ssortie %d %.1f cm %.2f deg", errors.empty() ? "" : "; ",
                    f.sortie, 100.0 * f.error_m, f.error_deg);
      errors += e;
    }
    if (!errors.empty())
      std::printf("%s fixes against the truth: %s\n", robot.name.c_str(), errors.c_str());
  }
  if (r.time_to_90_s >= 0.0) std::printf("90 %% coverage after %.0f s\n", r.time_to_90_s);
  std::printf(
      "simulated %.1f s in %.1f s wall (%.1fx real time: physics %.1f s, render "
      "%.1f s, stereo %.1f s, mapping %.1f s); outputs in %s\n",
      r.sim_time_s, r.wall_time_s, r.real_time_factor, r.timing.physics_s, r.timing.render_s,
      r.timing.stereo_s, r.timing.mapping_s, out.given().c_str());
  return 0;
}

}  // namespace

std::unique_ptr<Command> addRunCommand(CLI::App& app) { return std::make_unique<RunCommand>(app); }

}  // namespace coopmap::apps

// coopmap: the command-line program.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "core/agent/agent_settings.h"
#include "core/io/atomic_file.h"
#include "core/io/json_writer.h"
#include "core/io/output_folder.h"
#include "core/io/robot_outputs.h"
#include "core/io/yaml_reader.h"
#include "core/landmarks/corner_report.h"
#include "robots/b14/robot_mission.h"
#include "robots/camera/calibrate_rig.h"
#include "robots/carmen/carmen_mapping.h"
#include "sim/runner/drift_bench.h"
#include "sim/runner/explore_bench.h"
#include "sim/runner/odometry_fit.h"
#include "sim/runner/remap.h"
#include "sim/runner/replay_run.h"
#include "sim/runner/stereo_evaluation.h"
#include "sim/runner/stereo_scale_logs.h"
#include "sim/runner/traverse_tool.h"
#include "sim/runner/world_run.h"
#include "sim/runner/world_run_outputs.h"
#include "sim/world/world.h"
#include "sim/world/world_generator.h"

namespace {

// A seed as typed: a decimal integer that fits 64 unsigned bits. (CLI11 alone would take
// "-1" and wrap it, or cap a longer number, and two different seeds would give one run.)
const CLI::Validator kSeed(
    [](std::string& text) -> std::string {
      uint64_t value = 0;
      const char* end = text.data() + text.size();
      const auto [at, error] = std::from_chars(text.data(), end, value);
      if (text.empty() || error != std::errc() || at != end)
        return "expected an integer from 0 to 18446744073709551615, got '" + text + "'";
      return "";
    },
    "SEED");

// A folder a command writes its outputs to, checked before any work: absent (and can be
// created), empty, or one coopmap wrote; outputs replace it all or nothing (OutputFolder).
const CLI::Validator kOutputFolder(
    [](std::string& path) -> std::string { return coopmap::outputFolderProblem(path); }, "FOLDER");

}  // namespace

int main(int argc, char** argv) {
  // coopmap reports what went wrong itself, naming the file: no library log lines before it.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  CLI::App app{
      "coopmap: a simulation-first testbed for cooperative stereo-vision mapping with B-14 "
      "robots (Little, Jennings, Murray)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", COOPMAP_VERSION);

  coopmap::RunOptions run;
  std::string run_out;
  std::string odometry;
  int robots = 0;
  auto* cmd_run = app.add_subcommand(
      "run",
      "Run a world headless: each robot's agent finds its start from the home base, follows "
      "its scripted route or explores in sorties, maps from trinocular stereo, and shares "
      "its corrected sorties; maps, trajectories, traverse logs, metrics.json and a report "
      "are written to --out (docs/formats.md).");
  cmd_run->add_option("world", run.world_file, "World file (YAML), e.g. worlds/lab.yaml")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_run->add_option("--out", run_out, "Output folder (created if missing)")
      ->required()
      ->check(kOutputFolder);
  cmd_run->add_option("--seed", run.seed, "Seed for every random choice of the run")
      ->check(kSeed)
      ->capture_default_str();
  cmd_run->add_option("--duration", run.duration, "Simulated seconds at most")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd_run->add_option("--robots", robots, "Use only the first N robots of the world")
      ->check(CLI::PositiveNumber);
  cmd_run->add_option("--odometry", odometry,
                      "Override the robot file's odometry: 'perfect', 'drifting' (its default "
                      "preset), or the name of a preset in the robot file (e.g. utias_robot1)");
  cmd_run->add_flag("--steer-by-truth", run.steer_by_truth,
                    "Follow the route by the true pose, as a person driving it would: the path "
                    "is the intended one and odometry only records it (drift experiments)");
  cmd_run
      ->add_option("--record", run.record_dir,
                   "Record each robot's raw stream (camera images, stamps, odometry, "
                   "commands, rig and robot description) and the ground truth into this "
                   "folder, for `coopmap replay` (layout: its README.md)")
      ->check(kOutputFolder);
  cmd_run
      ->add_option("--shared-map", run.shared_map_dir,
                   "Keep the robots' shared map in this folder (shared_map.bin, saved before "
                   "each post is acknowledged): a run on a folder that holds one goes on from "
                   "it, and a killed run loses no acknowledged post")
      ->check(CLI::NonexistentPath | CLI::ExistingDirectory);
  bool explore_flag = false, routes_flag = false;
  cmd_run->add_flag("--explore", explore_flag,
                    "Autonomous missions instead of the routes: look at the home base, explore "
                    "frontiers with OMPL paths, come home when the budget is spent or nothing "
                    "reachable is left, look at the home base again (the default of a world "
                    "whose robots have no routes)");
  cmd_run
      ->add_flag("--routes", routes_flag,
                 "Follow the scripted routes of the world file (the default where it gives "
                 "them)")
      ->excludes("--explore");
  // The agents' settings (core/agent/agent_settings.h): a settings file, then each as
  // --kebab-case-name VALUE, over the robot model's odometry calibration and coopmap's
  // defaults.
  std::string settings_file;
  cmd_run
      ->add_option("--settings", settings_file,
                   "A YAML file of the agents' settings (`name: value` per line, the names of "
                   "the flags below in snake_case); flags given too go over it")
      ->check(CLI::ExistingFile);
  std::vector<std::pair<std::string, std::string>> setting_values;
  for (const coopmap::SettingInfo& info : coopmap::agentSettingInfos()) {
    const std::string name = info.name;
    std::string help = info.help;
    if (*info.unit) help += " [" + std::string(info.unit) + "]";
    coopmap::AgentSettings defaults;
    defaults.visit([&](const coopmap::SettingInfo& i, const auto& value) {
      if (name != i.name) return;
      std::ostringstream v;
      v << std::boolalpha << value;
      help += " (default " + v.str() + ")";
    });
    cmd_run->add_option_function<std::string>(
        coopmap::settingFlag(name),
        [&setting_values, name](const std::string& v) { setting_values.emplace_back(name, v); },
        help);
  }
  cmd_run
      ->add_option("--published-band", run.published_band,
                   "The shared map published (maps, metrics): each return drawn over this "
                   "share of its modelled range sigma (the robots' own maps and the shared map "
                   "they import: 1)")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 2.0));
  bool quiet = false;
  cmd_run->add_flag("--quiet", quiet, "No progress bar");
  bool events = false;
  cmd_run->add_flag("--events", events,
                    "Print each robot's mission events as they happen (simulated time, robot, "
                    "what it decided)");

  bool settings_markdown = false;
  auto* cmd_settings = app.add_subcommand(
      "settings",
      "The agents' settings with their defaults, as a settings file for `run --settings` (or, "
      "with --markdown, the reference docs/settings.md)");
  cmd_settings->add_flag("--markdown", settings_markdown,
                         "A Markdown table of every setting: flag, default, range and help");

  coopmap::ReplayOptions replay;
  auto* cmd_replay = app.add_subcommand(
      "replay",
      "Replay a recording (`coopmap run --record DIR`) through the robot interface: the same "
      "mapping core writes the same outputs as the live run to --out (maps, trajectories, "
      "traverse logs, metrics.json); a simulator recording reproduces the live maps bit for "
      "bit.");
  cmd_replay->add_option("recording", replay.recording, "Recording folder")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd_replay->add_option("--out", replay.out_dir, "Output folder (created if missing)")
      ->required()
      ->check(kOutputFolder);

  coopmap::StereoEvalOptions eval;
  std::string tsukuba;
  bool json = false;
  auto* cmd_eval = app.add_subcommand(
      "stereo-eval",
      "Score trinocular stereo against ground truth: bad-pixel rate (error > 1 px), mean "
      "absolute error and density. Sources: an image triple with a truth image, the Tsukuba "
      "multi-view set (--tsukuba), or frames rendered along a world's route (--world).");
  cmd_eval
      ->add_option("--tsukuba", tsukuba,
                   "Tsukuba folder: reference row3.col3, horizontal row3.col4, vertical "
                   "row2.col3, truth truedisp.row3.col3.pgm / 16")
      ->check(CLI::ExistingDirectory);
  cmd_eval->add_option("--reference", eval.reference, "Reference image")->check(CLI::ExistingFile);
  cmd_eval->add_option("--horizontal", eval.horizontal, "Horizontal partner image")
      ->check(CLI::ExistingFile);
  cmd_eval->add_option("--vertical", eval.vertical, "Vertical partner image")
      ->check(CLI::ExistingFile);
  cmd_eval->add_option("--truth", eval.truth, "Ground-truth disparity image")
      ->check(CLI::ExistingFile);
  cmd_eval
      ->add_option("--truth-scale", eval.truth_scale,
                   "Truth pixel value per pixel of disparity (Tsukuba: 16)")
      ->check(CLI::PositiveNumber);
  cmd_eval
      ->add_option("--horizontal-offset", eval.horizontal_offset,
                   "Horizontal partner's offset along the reference camera's x (right), in "
                   "baselines; any sign and length")
      ->capture_default_str();
  cmd_eval
      ->add_option("--vertical-offset", eval.vertical_offset,
                   "Vertical partner's offset along the reference camera's y (down), in "
                   "baselines of the horizontal pair; any sign and length")
      ->capture_default_str();
  cmd_eval->add_option("--rig", eval.rig, "Take the partner offsets (metres) from a robot file")
      ->check(CLI::ExistingFile);
  cmd_eval->add_option("--world", eval.world, "Render frames along the first robot's route")
      ->check(CLI::ExistingFile);
  cmd_eval->add_option("--frames", eval.frames, "Frames to evaluate from the world run")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd_eval->add_option("--seed", eval.seed, "Seed of the world run")
      ->check(kSeed)
      ->capture_default_str();
  cmd_eval->add_option("--disparities", eval.stereo.num_disparities, "Disparities searched")
      ->capture_default_str();
  cmd_eval->add_option("--window", eval.stereo.window, "SAD window side (odd, 3..11)")
      ->capture_default_str();
  cmd_eval
      ->add_option("--uniqueness", eval.stereo.uniqueness,
                   "Best must beat the runner-up by this fraction")
      ->capture_default_str();
  cmd_eval
      ->add_option("--min-texture", eval.stereo.min_texture,
                   "Minimum mean |gradient| in the window (grey levels)")
      ->capture_default_str();
  cmd_eval
      ->add_option("--pair-consistency", eval.stereo.pair_consistency,
                   "Fraction each pair's cost at the winner may exceed its own best "
                   "(negative: off)")
      ->capture_default_str();
  cmd_eval
      ->add_option("--window-shift", eval.stereo.window_shift,
                   "Shiftable windows: px each pixel's window may move left or right against "
                   "foreground fattening (0: centred windows, at most window / 2)")
      ->capture_default_str();
  std::string photometric = coopmap::toString(eval.stereo.photometric);
  cmd_eval
      ->add_option("--photometric", photometric,
                   "Photometric normalisation: global (partners' mean and spread matched to "
                   "the reference), local (mean removed over --prefilter-window), none")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "global", "local"}));
  cmd_eval
      ->add_option("--prefilter-window", eval.stereo.prefilter_window,
                   "Window of the local prefilter (odd px)")
      ->capture_default_str();
  cmd_eval->add_option("--border", eval.border, "Pixels skipped on every side")
      ->capture_default_str();
  bool single_pair = false;
  cmd_eval->add_flag("--single-pair", single_pair, "Use the horizontal pair only");
  cmd_eval->add_option("--png", eval.png_dir,
                       "Folder for pictures: reference, disparity and truth in colour, errors");
  cmd_eval->add_flag("--json", json, "Print bad_pixel_rate, mae, bias, density as JSON");

  coopmap::CornersOptions corners;
  auto* cmd_corners = app.add_subcommand(
      "corners",
      "Find corner landmarks in a ROS map_server map (MAP.yaml + image): writes corners.png "
      "(edges blue, fitted corners red) and corners.json (position in metres, heading, RMS "
      "in cells, iterations) to --out.");
  cmd_corners->add_option("map", corners.map_yaml, "Map YAML (map_server format)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_corners->add_option("--out", corners.out_dir, "Output folder")
      ->required()
      ->check(kOutputFolder);
  cmd_corners->add_option("--arm-length", corners.arm_length, "Arm length of the corner model (m)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);

  coopmap::CarmenOptions carmen;
  auto* cmd_carmen = app.add_subcommand(
      "carmen",
      "Map a laser log in CARMEN format (ODOM, FLASER/RLASER, RAWLASER1-4, ROBOTLASER1-2 "
      "lines; the classic public robot data sets) through the robot interface: writes the "
      "occupancy grid (map.pgm/.yaml/.png), its corners (corners.json/.png) and the "
      "trajectory (trajectory_odometry.tum; trajectory_groundtruth.tum with TRUEPOS) to --out.");
  cmd_carmen->add_option("log", carmen.log, "CARMEN log file (uncompressed)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_carmen->add_option("--out", carmen.out_dir, "Output folder")
      ->required()
      ->check(kOutputFolder);
  cmd_carmen->add_option("--resolution", carmen.resolution, "Map resolution (m per cell)")
      ->capture_default_str();
  cmd_carmen
      ->add_option("--max-range", carmen.max_range,
                   "Usable laser range (m): farther returns only clear free space up to it; 0: "
                   "the laser's maximum (FLASER: 80 m)")
      ->capture_default_str();
  cmd_carmen
      ->add_option("--laser", carmen.laser,
                   "Laser to map with: 1 front (FLASER, RAWLASER1, ROBOTLASER1), 2 rear, 3, 4; "
                   "0: the lowest in the log")
      ->capture_default_str();
  cmd_carmen->add_option("--arm-length", carmen.arm_length, "Arm length of the corner model (m)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);

  coopmap::OdometryFitOptions fit;
  fit.robot_model = "robots/b14/b14.yaml";
  auto* cmd_fit = app.add_subcommand(
      "odometry-fit",
      "Odometry error growth of a real log with ground truth (UTIAS MRCLAM format: 'time x y "
      "theta' and 'time v w'), per metre driven and per radian turned, over windows; the "
      "simulator preset with those errors; with --simulate, the same statistics of the "
      "simulated robot driven by the log's commands with that preset.");
  cmd_fit->add_option("--groundtruth", fit.groundtruth, "Ground-truth file")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_fit->add_option("--odometry", fit.odometry, "Odometry file")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_fit->add_option("--window", fit.window_s, "Window length (s)")->capture_default_str();
  cmd_fit->add_flag("--simulate", fit.simulate, "Replay the commands on the simulated robot");
  cmd_fit->add_option("--robot", fit.robot_model, "Robot model file for --simulate")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  cmd_fit->add_option("--seed", fit.seed, "Seed of the simulated odometry")
      ->check(kSeed)
      ->capture_default_str();

  coopmap::DriftBenchOptions drift;
  std::vector<std::string> drift_models;
  auto* cmd_bench = app.add_subcommand("bench", "Scenario benchmarks");
  cmd_bench->require_subcommand(1);
  auto* cmd_drift = cmd_bench->add_subcommand(
      "drift",
      "The drift-error benchmark (the paper's long traverse): for each seed a robot drives "
      "the world's loop on drifting odometry, localizes at the home base, and each "
      "correction model corrects its traverse and rebuilds its map. Writes drift.csv (a row "
      "per seed and model), drift.md (the summary table beside the paper's figures), and "
      "seeds/<seed>/ with TUM trajectories (ground truth, odometry, each model) and maps.png "
      "(the maps side by side) to --out.");
  cmd_drift->add_option("--world", drift.world_file, "World file with a home base and a loop")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  cmd_drift->add_option("--out", drift.out_dir, "Output folder")->required()->check(kOutputFolder);
  cmd_drift->add_option("--seeds", drift.seeds, "Number of seeds")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd_drift->add_option("--first-seed", drift.first_seed, "First seed")
      ->check(kSeed)
      ->capture_default_str();
  cmd_drift
      ->add_option("--odometry", drift.odometry,
                   "Odometry preset of the robot file ('drifting' is its default preset)")
      ->capture_default_str();
  cmd_drift->add_option("--models", drift_models,
                        "Correction models: none, uniform, turns-and-straights, heading-drift, "
                        "pose-graph (default: all)");
  bool drift_no_noise = false;
  cmd_drift->add_flag("--no-camera-noise", drift_no_noise, "Noise-free cameras");
  bool drift_quiet = false;
  cmd_drift->add_flag("--quiet", drift_quiet, "No line per seed on stderr");

  coopmap::ExploreBenchOptions explore_bench;
  auto* cmd_explore_bench = cmd_bench->add_subcommand(
      "explore",
      "The exploration benchmark: for each seed, generates a world (`world generate`, family "
      "and area drawn from the seed) and runs the robots exploring it on their default "
      "settings, each world in its own process. Writes explore.csv (a row per world), "
      "explore.md (the distribution, the targets met, the worst worlds), worlds/ and runs/ "
      "to --out.");
  cmd_explore_bench->add_option("--first-seed", explore_bench.first_seed, "First seed")
      ->check(kSeed)
      ->capture_default_str();
  cmd_explore_bench->add_option("--count", explore_bench.count, "Number of worlds")
      ->capture_default_str();
  cmd_explore_bench->add_option("--robots", explore_bench.robots, "Robots exploring: 1 or 2")
      ->capture_default_str();
  cmd_explore_bench
      ->add_option("--duration", explore_bench.duration, "Simulated seconds per world at most")
      ->capture_default_str();
  cmd_explore_bench
      ->add_option("--jobs", explore_bench.jobs,
                   "Worlds run at once (default: the number of processors)")
      ->capture_default_str();
  cmd_explore_bench->add_option("--out", explore_bench.out_dir, "Output folder")
      ->required()
      ->check(kOutputFolder);
  bool explore_bench_quiet = false;
  cmd_explore_bench->add_flag("--quiet", explore_bench_quiet, "No line per world on stderr");

  coopmap::TraverseOptions trav;
  auto* cmd_traverse = app.add_subcommand(
      "traverse",
      "Rebuild a map from a traverse log (traverse_<robot>.traverse of a run) at its odometry "
      "poses: map.{pgm,yaml,png} in --out; prints what the log holds.");
  cmd_traverse->add_option("log", trav.log_file, "Traverse log")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_traverse->add_option("--out", trav.out_dir, "Output folder")
      ->required()
      ->check(kOutputFolder);
  cmd_traverse->add_option("--first", trav.first, "First entry used")->capture_default_str();
  cmd_traverse->add_option("--last", trav.last, "Last entry used (-1: the end)")
      ->capture_default_str();
  cmd_traverse->add_option("--resolution", trav.resolution, "Map resolution (m)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd_traverse
      ->add_option("--align-stretch", trav.align_stretch,
                   "Also align each stretch of N entries (end to end) to the map from its "
                   "logged poses and print how far the alignments move them, one row per "
                   "stretch in stretches.csv (with exact poses, --odometry perfect, that is the "
                   "scan alignment's own error; 0: off)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);

  coopmap::RemapOptions remap;
  auto* cmd_remap = app.add_subcommand(
      "remap",
      "Rebuild a run's map from its traverse logs at a chosen trajectory and score it against "
      "the world's true occupancy: at the ground truth, what stereo alone allows; at the "
      "corrected traverses, what their pose errors cost (false obstacles split by their "
      "distance to the true ones).");
  cmd_remap->add_option("run", remap.run_dir, "A `coopmap run` output folder")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd_remap->add_option("--world", remap.world_file, "The world the run was in")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_remap
      ->add_option("--poses", remap.poses,
                   "logged (the poses in the traverse logs: the live estimate), corrected, "
                   "estimate, odometry or groundtruth (trajectory_<robot>_<poses>.tum)")
      ->capture_default_str();
  cmd_remap
      ->add_option("--max-error", remap.max_error_m,
                   "Only the radial maps whose pose is within this many metres of the ground "
                   "truth (an oracle's choice; 0: all)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd_remap
      ->add_option("--oracle", remap.oracle,
                   "Take this part of each pose from the ground truth and the rest from --poses, "
                   "to see which part of the pose error costs the map: position, heading, or "
                   "the position error's part along the true heading (along) or across it "
                   "(across)")
      ->check(CLI::IsMember({"position", "heading", "along", "across"}));
  cmd_remap
      ->add_option("--out", remap.out_dir, "Folder for map.{pgm,yaml,png} and map_evaluation.png")
      ->check(kOutputFolder);
  cmd_remap
      ->add_option("--band", remap.band,
                   "Each return drawn over this share of its modelled range sigma (the "
                   "published shared map's by default; 1: the robots' own maps')")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 2.0));
  cmd_remap->add_flag("--range-errors", remap.range_errors,
                      "With --poses groundtruth: the radial maps' range errors against the "
                      "world's true surfaces by range (median, robust sd, RMS), beside the "
                      "stereo's modelled sigma and the share of errors within it");

  coopmap::StereoScaleOptions scale;
  auto* cmd_scale = app.add_subcommand(
      "stereo-scale",
      "The odometry's distance scale measured by the cameras over runs' traverse logs (each "
      "at the run's raw odometry), per log and pooled: a calibration of the robot from logs, "
      "for a mission's `odometry_distance_scale`. With the runs' ground truth, each log's true "
      "scale beside it.");
  cmd_scale->add_option("runs", scale.run_dirs, "`coopmap run` output folders")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd_scale->add_option("--robot", scale.robot, "Only this robot's logs")->capture_default_str();
  cmd_scale
      ->add_option("--passes", scale.passes,
                   "Passes of the measurement, each from the odometry rescaled to the one "
                   "before's figure (1-10; one pass finds about 70 % of a scale)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10));

  coopmap::RobotCommandOptions robot_options;
  auto* cmd_robot = app.add_subcommand(
      "robot",
      "Run a real B-14 (its rFLEX base over a serial port, its trinocular cameras) on the wall "
      "clock. With a mission (the config's `mission:` and `cameras:`), the robot's agent runs "
      "as in simulation: it looks at the home base to find where it stands, explores (mode "
      "explore) or follows a route (mode route) in sorties, and back home localizes, corrects "
      "its traverse, posts it to the shared map and imports it, until it is done or Ctrl-C "
      "(then a safe stop); --out receives its map, traverse log and odometry. Without one, the "
      "base alone follows the config's route in the odometry frame. The config names the "
      "serial device and baud, the robot model file, and the mission or the route.");
  cmd_robot->add_option("config", robot_options.config, "Robot config file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd_robot->add_flag("--dry-run", robot_options.dry_run,
                      "Check the config and that the controller answers; move nothing");
  cmd_robot->add_flag("--quiet", robot_options.quiet, "No progress lines");
  cmd_robot
      ->add_option("--out", robot_options.out_dir,
                   "With a mission: folder for the robot's map (map_<robot>.pgm/.yaml/.png), "
                   "traverse log and odometry (created if missing)")
      ->check(kOutputFolder);

  coopmap::CalibrateOptions calibrate;
  auto* cmd_calibrate = app.add_subcommand(
      "calibrate",
      "Calibrate the trinocular rig from checkerboard views: each camera (focal lengths, "
      "principal point, distortion k1 k2 p1 p2 k3), each partner against the reference "
      "(rotation, baseline); prints them with the reprojection RMS and writes the calibration "
      "(OpenCV FileStorage YAML) that the camera driver rectifies with.");
  cmd_calibrate
      ->add_option("--reference", calibrate.sources[0],
                   "Reference camera's views: an image sequence (printf pattern, e.g. "
                   "ref_%04d.png) or a video file")
      ->required();
  cmd_calibrate->add_option("--horizontal", calibrate.sources[1], "Horizontal partner's views")
      ->required();
  cmd_calibrate->add_option("--vertical", calibrate.sources[2], "Vertical partner's views")
      ->required();
  cmd_calibrate->add_option("--board", calibrate.board, "Inner corners COLSxROWS, e.g. 9x6")
      ->required();
  cmd_calibrate->add_option("--square", calibrate.square, "Side of a square (m)")
      ->required()
      ->check(CLI::PositiveNumber);
  cmd_calibrate->add_option("--out", calibrate.out_file, "Calibration file to write (YAML)")
      ->required();

  // Options are taken as text and checked here, so that every bad value exits with code 2
  // and a message naming the option.
  std::string gen_seed, gen_area, gen_family, gen_out;
  auto* cmd_world = app.add_subcommand("world", "World files");
  cmd_world->require_subcommand(1);
  auto* cmd_generate = cmd_world->add_subcommand(
      "generate",
      "Generate a world file: an office-like building (100-600 m^2) the robots have never "
      "seen, with rooms, doorways, furniture, low-texture walls, people walking the "
      "corridors, slippery patches, and a start room with the home base and the robots jose "
      "and eric. Each world is checked (it loads; all floor reachable; starts clear; home "
      "base in view) before it is written; the same options write the same bytes.");
  cmd_generate->add_option("--seed", gen_seed, "Seed of every choice (a non-negative integer)");
  cmd_generate->add_option("--out", gen_out, "World file to write (YAML)");
  cmd_generate->add_option("--family", gen_family,
                           "corridor, lt, loop or open (default: drawn from the seed)");
  cmd_generate->add_option("--area", gen_area,
                           "Floor area in m^2, 100-600 (default: drawn from the seed)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Help and version exit 0; every bad option or value exits 2, as all bad input does.
    return app.exit(e) == 0 ? 0 : 2;
  }

  // Each command writes into a staging folder and puts it in place when it is done (all or
  // nothing); the messages name the folder as given.
  std::optional<coopmap::OutputFolder> out_folder, record_folder;
  auto stage = [](std::optional<coopmap::OutputFolder>& folder, std::string& dir,
                  const char* command) {
    if (dir.empty()) return std::string();
    const std::string given = dir;
    folder.emplace(dir, command);
    dir = folder->path().string();
    return given;
  };
  auto commit = [](std::optional<coopmap::OutputFolder>& folder) {
    if (folder) folder->commit();
  };
  try {
    if (cmd_robot->parsed()) {
      coopmap::RobotMissionResult mission;
      const int code = coopmap::runRobotCommand(robot_options, stdout, &mission);
      if (!robot_options.out_dir.empty() && mission.grid) {
        const std::string given = stage(out_folder, robot_options.out_dir, "coopmap robot");
        coopmap::writeRobotOutputs(robot_options.out_dir,
                                   {mission.name, "", &*mission.grid, nullptr, &mission.odometry,
                                    nullptr, &mission.traverse, mission.odometry_in_map});
        commit(out_folder);
        std::printf("outputs in %s\n", given.c_str());
      }
      return code;
    }
    if (cmd_generate->parsed()) {
      coopmap::sim::WorldGeneratorOptions gen;
      auto number = [](const std::string& option, const std::string& text, const char* expected) {
        size_t used = 0;
        double value = 0.0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (text.empty() || used != text.size() || !std::isfinite(value))
          throw coopmap::ConfigError(option + ": expected " + expected + ", got '" + text + "'");
        return value;
      };
      if (gen_seed.empty()) throw coopmap::ConfigError("--seed: expected a seed, none given");
      if (gen_seed.find_first_not_of("0123456789") != std::string::npos || gen_seed.size() > 19)
        throw coopmap::ConfigError("--seed: expected a non-negative integer, got '" + gen_seed +
                                   "'");
      gen.seed = std::stoull(gen_seed);
      gen.family = gen_family;
      if (cmd_generate->count("--family") && gen_family.empty())
        throw coopmap::ConfigError("--family: expected corridor, lt, loop or open, got ''");
      if (!gen_area.empty()) gen.area = number("--area", gen_area, "a floor area in m^2");
      gen.out_file = gen_out;
      gen.validate();
      const coopmap::sim::GeneratedWorld w = coopmap::sim::generateWorld(gen);
      try {
        coopmap::writeFileAtomic(gen_out, w.yaml);
      } catch (const std::exception& e) {
        throw coopmap::ConfigError("--out: expected a writable file path: " +
                                   std::string(e.what()));
      }
      std::printf("%s: %s building, %.1f m^2 of floor, %d rooms, %d doorways\n", gen_out.c_str(),
                  w.family.c_str(), w.floor_area, w.rooms, w.doors);
    }
    if (cmd_calibrate->parsed()) std::printf("%s", coopmap::runCalibrate(calibrate).report.c_str());
    if (cmd_traverse->parsed()) {
      const std::string given = stage(out_folder, trav.out_dir, "coopmap traverse");
      const coopmap::TraverseSummary r = coopmap::runTraverse(trav);
      commit(out_folder);
      trav.out_dir = given;
      coopmap::printTraverseSummary(trav, r);
    }
    if (cmd_remap->parsed()) {
      const std::string given = stage(out_folder, remap.out_dir, "coopmap remap");
      const coopmap::RemapSummary r = coopmap::runRemap(remap);
      commit(out_folder);
      remap.out_dir = given;
      coopmap::printRemapSummary(remap, r);
    }
    if (cmd_scale->parsed()) coopmap::printStereoScaleSummary(coopmap::runStereoScale(scale));
    if (cmd_drift->parsed()) {
      if (!drift_models.empty()) {
        drift.models.clear();
        for (const std::string& m : drift_models) {
          const auto parsed = coopmap::parseCorrectionModel(m);
          if (!parsed)
            throw std::invalid_argument(
                "--models: expected none, uniform, turns-and-straights, "
                "heading-drift or pose-graph, got '" +
                m + "'");
          drift.models.push_back(*parsed);
        }
      }
      drift.camera_noise = !drift_no_noise;
      drift.progress = !drift_quiet;
      const std::string given = stage(out_folder, drift.out_dir, "coopmap bench drift");
      const coopmap::DriftBenchResult r = coopmap::runDriftBench(drift);
      commit(out_folder);
      std::printf("%s\n%s/drift.csv, drift.md and seeds/ written\n", r.markdown.c_str(),
                  given.c_str());
    }
    if (cmd_explore_bench->parsed()) {
      explore_bench.progress = !explore_bench_quiet;
      const std::string given = stage(out_folder, explore_bench.out_dir, "coopmap bench explore");
      coopmap::runExploreBench(explore_bench);
      commit(out_folder);
      std::printf("%s/explore.csv, explore.md, worlds/ and runs/ written\n", given.c_str());
    }
    if (cmd_fit->parsed()) {
      const coopmap::OdometryFitResult r = coopmap::runOdometryFit(fit);
      auto row = [](const char* name, const coopmap::DriftStats& s) {
        std::printf("| %s | %d | %.2f | %.2f | %.5f | %.5f | %.4f | %.4f | %.4f | %.4f |\n", name,
                    s.windows, s.metres_per_window, s.radians_per_window, s.heading_bias_per_m,
                    s.turn_bias, s.scale_bias, s.heading_sigma_per_sqrt_m,
                    s.heading_sigma_per_sqrt_rad, s.distance_sigma_per_sqrt_m);
      };
      std::printf(
          "| source | windows | m/window | rad/window | heading bias rad/m | turn bias "
          "rad/rad | scale bias | heading sigma rad/sqrt(m) | heading sigma "
          "rad/sqrt(rad) | distance sigma m/sqrt(m) "
          "|\n|---|---|---|---|---|---|---|---|---|---|\n");
      row("real log", r.real);
      if (fit.simulate) row("simulated, fitted preset", r.simulated);
      const auto& p = r.preset;
      std::printf(
          "\nfitted preset (robot file, simulation.odometry):\n  preset: drifting\n"
          "  scale_error: %.5f\n  turn_scale_error: %.5f\n  heading_drift: %.6f\n"
          "  linear_noise: %.5f\n  angular_noise: %.5f\n  heading_noise: %.5f\n",
          p.scale_error, p.turn_scale_error, p.heading_drift, p.linear_noise, p.angular_noise,
          p.heading_noise);
    }
    if (cmd_corners->parsed()) {
      const std::string given = stage(out_folder, corners.out_dir, "coopmap corners");
      const coopmap::CornersResult r = coopmap::runCorners(corners);
      commit(out_folder);
      std::printf(
          "%zu corners (%d candidates, %d rejected by RMS, %d not converged, %d edge "
          "cells); %s/corners.png and corners.json written\n",
          r.search.corners.size(), r.search.candidates, r.search.rejected_rms,
          r.search.not_converged, r.edge_cells, given.c_str());
    }
    if (cmd_carmen->parsed()) {
      const std::string given = stage(out_folder, carmen.out_dir, "coopmap carmen");
      const coopmap::CarmenResult r = coopmap::runCarmen(carmen);
      commit(out_folder);
      const coopmap::MapLimits& lim = r.grid->limits();
      std::printf(
          "%d scans of laser %d over %.1f s, odometry path %.1f m; map %d x %d cells at %.3f "
          "m: %d occupied, %d free; %zu corners; outputs in %s\n",
          r.scans, r.laser, r.duration_s, r.path_length_m, lim.width, lim.height, lim.resolution,
          r.occupied_cells, r.free_cells, r.corners.search.corners.size(), given.c_str());
    }
    if (cmd_eval->parsed()) {
      if (!tsukuba.empty()) {
        eval.reference = tsukuba + "/scene1.row3.col3.ppm";
        eval.horizontal = tsukuba + "/scene1.row3.col4.ppm";
        eval.vertical = tsukuba + "/scene1.row2.col3.ppm";
        eval.truth = tsukuba + "/truedisp.row3.col3.pgm";
        eval.truth_scale = 16.0;
        if (cmd_eval->count("--disparities") == 0) eval.stereo.num_disparities = 16;
      }
      eval.stereo.use_vertical = !single_pair;
      eval.stereo.photometric = coopmap::parsePhotometric(photometric);
      if (eval.world.empty() && (eval.reference.empty() || eval.truth.empty()))
        throw std::invalid_argument(
            "stereo-eval: expected --tsukuba DIR, --world FILE, or --reference/--horizontal/"
            "--vertical/--truth");
      const coopmap::StereoEvalResult r = coopmap::runStereoEval(eval);
      if (json) {
        coopmap::JsonWriter j;
        j.beginObject();
        j.value("bad_pixel_rate", r.score.bad_pixel_rate).value("mae", r.score.mae);
        j.value("bias", r.score.bias);
        j.value("density", r.score.density).value("frames", r.frames);
        j.value("evaluated_pixels", r.score.evaluated).value("valid_pixels", r.score.valid);
        j.endObject();
        std::printf("%s", j.str().c_str());
      } else {
        std::printf(
            "frames %d: bad_pixel_rate %.4f (> 1 px), mae %.3f px, bias %+.3f px (good "
            "pixels), density %.3f (%d of %d pixels with ground truth)\n",
            r.frames, r.score.bad_pixel_rate, r.score.mae, r.score.bias, r.score.density,
            r.score.valid, r.score.evaluated);
      }
    }
    if (cmd_settings->parsed())
      std::fputs(settings_markdown ? coopmap::agentSettingsMarkdown().c_str()
                                   : coopmap::agentSettingsYaml(coopmap::AgentSettings{}).c_str(),
                 stdout);
    if (cmd_replay->parsed()) {
      const std::string given = stage(out_folder, replay.out_dir, "coopmap replay");
      const coopmap::ReplayResult r = coopmap::runReplay(replay);
      commit(out_folder);
      for (const auto& robot : r.robots)
        std::printf("%s: %d frames over %.1f s, odometry path %.1f m\n", robot.name.c_str(),
                    robot.frames, robot.duration_s, robot.odometry_path_length_m);
      std::printf("replayed %s in %.1f s wall; outputs in %s\n", replay.recording.c_str(),
                  r.wall_time_s, given.c_str());
    }
    if (cmd_run->parsed()) {
      if (explore_flag) run.explore = true;
      if (routes_flag) run.explore = false;
      // Checked before the run, so that a bad value costs no simulation.
      std::optional<coopmap::YamlField> file_settings;
      if (!settings_file.empty()) file_settings = coopmap::YamlField::loadFile(settings_file);
      coopmap::AgentSettings check;
      if (file_settings) coopmap::readAgentSettings(*file_settings, check);
      for (const auto& [name, value] : setting_values) coopmap::setAgentSetting(check, name, value);
      run.settings = [&setting_values, &file_settings](coopmap::AgentSettings& s) {
        if (file_settings) coopmap::readAgentSettings(*file_settings, s);
        for (const auto& [name, value] : setting_values) coopmap::setAgentSetting(s, name, value);
      };
      if (robots > 0) run.robots = robots;
      if (!odometry.empty()) run.odometry = odometry;
      run.progress = !quiet && !events;
      if (events)
        run.event_observer = [](const std::string& robot, double t, const std::string& event) {
          std::printf("%.1f s %s: %s\n", t, robot.c_str(), event.c_str());
          std::fflush(stdout);  // as it happens, also into a pipe
        };
      run.share_maps = true;
      const std::string given = stage(out_folder, run_out, "coopmap run");
      stage(record_folder, run.record_dir, "coopmap run --record");
      const coopmap::RunResult r = coopmap::runWorld(run);
      coopmap::writeRunOutputs(run_out, r);
      commit(record_folder);
      commit(out_folder);
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
          std::snprintf(e, sizeof e, "start %.1f cm %.2f deg",
                        100.0 * robot.start_fix_error->error_m, robot.start_fix_error->error_deg);
          errors += e;
        }
        if (robot.placed_error) {
          std::snprintf(e, sizeof e, "; placed %.1f cm %.2f deg",
                        100.0 * robot.placed_error->error_m, robot.placed_error->error_deg);
          errors += e;
        }
        for (const coopmap::FixError& f : robot.fix_errors) {
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
          r.timing.stereo_s, r.timing.mapping_s, given.c_str());
    }
  } catch (const coopmap::ConfigError& e) {
    std::fprintf(stderr, "coopmap: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "coopmap: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

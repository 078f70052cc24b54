// Runs a world headless: robots follow their routes, map with stereo, and the run's maps,
// trajectories and metrics are written to an output folder.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/correction/traverse_log.h"
#include "core/io/tum.h"
#include "core/mapping/map_metrics.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

struct RunOptions {
  std::string world_file;
  std::string out_dir;  // empty: write nothing
  // Empty: no recording; else each robot's raw stream (images, stamps, odometry, commands,
  // description) and the ground truth are recorded there (robots/replay/recording.h).
  std::string record_dir;
  uint64_t seed = 1;
  double duration = 600.0;              // s of simulated time at most
  std::optional<int> robots;            // use only the first N robots of the world
  std::optional<std::string> odometry;  // "perfect", "drifting" or a preset of the model file
  bool camera_noise = true;             // false: noise-free cameras whatever the model says
  bool steer_by_truth = false;          // follow the route by the true pose (drift experiments)
  // After the run, merge the robots' traverses into a shared map twice: as the paper's
  // home-base protocol does (only data corrected at the home base) and naively (every
  // radial map at its odometry pose); RunResult::shared_map and shared_map*.{pgm,yaml,png}.
  bool share_maps = false;
  bool explore = false;  // autonomous missions (core/agent/mission.h) instead of the routes
  std::optional<double> sensing_rate;  // Hz; overrides the world's
  bool progress = false;               // progress bar on stderr
  // Called with every sensing frame and its ground-truth depth (reference camera, metres),
  // for evaluation tools; rendering the depth costs a little, so only when set.
  std::function<void(const std::string& robot, const TrinocularFrame& frame,
                     const cv::Mat& truth_depth)>
      frame_observer;
};

struct RobotRunResult {
  std::string name;
  double path_length_m = 0.0;
  int collisions = 0;
  int frames = 0;
  bool route_complete = false;
  double odometry_error_m = 0.0;  // final |odometry - truth|
  double odometry_error_deg = 0.0;
  MapMetrics map;
  std::vector<StampedPose2> groundtruth, odometry;
  TraverseLog traverse;  // every radial map with the odometry pose it was taken at
  // The robot's map at the end.
  std::optional<OccupancyGrid> grid;
  // Autonomous runs (RunOptions::explore):
  std::string mission_phase;  // where the mission stopped ("done" when it came home)
  bool exploration_complete = false;
  int goals_reached = 0, goals_failed = 0, safety_stops = 0;
  std::string mission_event;  // the mission's last event, for people
};

// Wall time per stage of a run, all robots together (s).
struct RunTiming {
  double physics_s = 0.0, render_s = 0.0, stereo_s = 0.0, mapping_s = 0.0;
};

// The shared maps of a run (RunOptions::share_maps).
struct SharedMapResult {
  bool computed = false;
  MapMetrics protocol;               // robots' traverses corrected at the home base, posted
  MapMetrics naive;                  // every radial map at its odometry pose, posted as taken
  int posts_accepted = 0;            // corrected posts the shared map accepted
  std::vector<std::string> posted;   // robots whose corrected traverse entered
  std::vector<std::string> refused;  // robots without a home-base fix ("name: reason")
  std::optional<OccupancyGrid> protocol_grid, naive_grid;
};

struct RunResult {
  std::vector<RobotRunResult> robots;
  SharedMapResult shared_map;
  RunTiming timing;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  double real_time_factor = 0.0;
};

// Runs the world. Throws ConfigError for bad world or robot files, std::invalid_argument
// for bad options, std::runtime_error when outputs or the recording cannot be written.
RunResult runWorld(const RunOptions& options);

}  // namespace coopmap

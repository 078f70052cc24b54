// The runner: a world run headless. It steps the simulator and one agent per robot
// (core/agent/robot_agent.h) on the simulator's clock; the agents see their robots only
// through the robot interface. Ground truth is an observer of the run: it scores the maps,
// the trajectories and the fixes, and records, and never feeds back into an agent.
//
// Frames: each robot's odometry starts at its own origin. The map frame is the home base's,
// as the robots' home-base design states it (HomeBaseDesign); the runner relates it to the
// world frame through where the world file puts the home base, for scoring only. Every pose
// and map the result holds is in the map frame; odometry is in each robot's odometry frame.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/agent/agent_settings.h"
#include "core/correction/odometry_calibration.h"
#include "core/correction/traverse_log.h"
#include "core/io/tum.h"
#include "core/localization/home_base.h"
#include "core/mapping/map_metrics.h"
#include "core/mapping/occupancy_grid.h"
#include "core/robot/robot_interface.h"
#include "core/sharing/shared_map.h"
#include "sim/runner/phase_time.h"

namespace coopmap {

struct RunOptions {
  std::string world_file;
  // Empty: no recording; else each robot's raw stream (images, stamps, odometry, status,
  // commands, description, the agent's setup and settings) and the ground truth are recorded
  // there (robots/replay/recording.h), so that `coopmap replay` runs the same agents again.
  std::string record_dir;
  // Empty: the shared map lives in memory for the run; else the shared map service keeps it
  // in this folder (shared_map.bin, saved before each post is acknowledged), and a run on a
  // folder that holds one goes on from it.
  std::string shared_map_dir;
  uint64_t seed = 1;
  double duration = 600.0;              // s of simulated time at most
  std::optional<int> robots;            // use only the first N robots of the world
  std::optional<std::string> odometry;  // "perfect", "drifting" or a preset of the model file
  bool camera_noise = true;             // false: noise-free cameras whatever the model says
  // Drift experiments: a person drives each robot along its route by its true pose, so the
  // path is the intended one; the agents map and log what the robots do (AgentSetup::
  // kDriven) and decide nothing.
  bool steer_by_truth = false;
  // After a run of robots driven by a person (steer_by_truth), merge their traverses into a
  // shared map twice: as the paper's home-base protocol does (only data corrected at the home
  // base) and naively (every radial map at its odometry pose, placed by the robot's first
  // look); RunResult::shared_map. (Robots that drive themselves share as they go.)
  bool share_maps = false;
  // Autonomous missions (AgentSetup::kExplore) instead of the routes; unset: explore when no
  // robot of the world has a route.
  std::optional<bool> explore;
  // The agents' settings: coopmap's defaults and each robot model's odometry calibration
  // (calibrated_distance_scale), then this.
  std::function<void(AgentSettings&)> settings;
  // The home base as the robots are told it was designed (it defines the map frame); unset:
  // coopmap's standard home base (HomeBaseDesign's defaults). The world's must match it.
  std::optional<HomeBaseDesign> home_base;
  // The band of the shared map the run publishes (outputs, metrics), as OccupancyConfig::
  // sigma_scale; the robots' maps and the shared map they import keep the default's.
  double published_band = kPublishedSigmaScale;
  double timeline_period_s = 10.0;  // s between samples of coverage and error over time
  bool progress = false;            // progress bar on stderr
  // Called with every sensing frame and its ground-truth depth (reference camera, metres),
  // for evaluation tools; rendering the depth costs a little, so only when set.
  std::function<void(const std::string& robot, const TrinocularFrame& frame,
                     const cv::Mat& truth_depth)>
      frame_observer;
  // Called whenever a robot's mission reports a new event (what it decided, why it stopped),
  // with the simulated time: for people following a run.
  std::function<void(const std::string& robot, double t, const std::string& event)> event_observer;
};

// A contact of a robot with anything (the simulator's truth): when, with what, where, and
// what the robot was doing.
struct ContactRecord {
  double t = 0.0;               // s
  std::string with;             // "static_world", "person" or "robot"
  Eigen::Vector2d point{0, 0};  // contact point (m, map frame)
  Pose2 robot;                  // the robot's true pose (map frame)
  std::string phase;            // the agent's phase ("route" for scripted runs)
};

// A home-base fix against the truth.
struct FixError {
  int sortie = 0;  // 0: the start
  double stamp = 0.0;
  double error_m = 0.0, error_deg = 0.0;
};

struct RobotRunResult {
  std::string name;
  double path_length_m = 0.0;
  int collisions = 0;         // distinct contacts with anything
  int collisions_static = 0;  // of them, with walls, doors, furniture, the home base
  int collisions_people = 0;  // with people
  int collisions_robots = 0;  // with other robots
  std::vector<ContactRecord> contacts;
  std::vector<PhaseTime> phases;  // in the order first entered
  int frames = 0;
  bool route_complete = false;
  double odometry_error_m = 0.0;  // final |odometry - truth|, both in the odometry frame
  double odometry_error_deg = 0.0;
  MapMetrics map;
  std::vector<StampedPose2> groundtruth;  // map frame
  std::vector<StampedPose2> odometry;     // the encoders', odometry frame (starts at the origin)
  Pose2 odometry_in_map;  // X_MO: the odometry frame as the first look placed it (drawing)
  TraverseLog traverse;   // every radial map with the estimate it was taken at (map frame)
  std::optional<OccupancyGrid> grid;  // the robot's map at the end
  GridU8 truth;                       // true occupancy up to its swept height (map frame)
  Pose2 map_in_world;                 // X_WM: the robot's map frame in the world (scoring)
  std::string phase;                  // where the agent stopped ("done" when it came home)
  // Home-base worlds: whether the looks at the start placed the robot; the first look's fix
  // against the truth (where the robot believed it started), and the estimate when it was
  // placed (after driving nearer and looking again, if it started far).
  bool placed = false;
  std::optional<FixError> start_fix_error;
  std::optional<FixError> placed_error;
  // Autonomous runs:
  bool exploration_complete = false;
  int goals_reached = 0, goals_failed = 0, safety_stops = 0;
  int early_returns = 0;                // sorties ended because the frontiers left were teammates'
  std::string mission_event;            // the mission's last event, for people
  int sorties = 0;                      // sorties ended at the home base
  int sorties_fixed = 0;                // of them, localized there
  int sorties_posted = 0;               // of them, posted to the shared map
  std::vector<std::string> log;         // the agent's lines for people (start, sorties, looks)
  OdometryBias calibration;             // the online odometry calibration at the end
  std::vector<FixError> fix_errors;     // each sortie's home-base fix against the truth
  std::vector<StampedPose2> estimate;   // the robot's own pose estimate (map frame)
  std::vector<StampedPose2> corrected;  // entries posted, at their corrected poses
};

// Coverage and error over a run, sampled every RunOptions::timeline_period_s.
struct TimelineSample {
  double t = 0.0;
  double shared_coverage = 0.0;        // the shared map (cooperative runs), else the union
  std::vector<double> robot_coverage;  // each robot's own map
  std::vector<double> robot_error_m;   // |estimate - truth| per robot
};

// Wall time per stage of a run, all robots together (s).
struct RunTiming {
  double physics_s = 0.0, render_s = 0.0, stereo_s = 0.0, mapping_s = 0.0;
};

// The shared maps of a run.
struct SharedMapResult {
  bool computed = false;
  MapMetrics protocol;  // robots' traverses corrected at the home base, posted
  MapMetrics naive;     // every radial map at its odometry pose, posted as taken
  // The protocol's shared grid the robots import (the robots' band), for comparison with
  // the published `protocol`.
  MapMetrics imported;
  int posts_accepted = 0;            // corrected posts the shared map accepted
  std::vector<std::string> posted;   // robots whose corrected traverse entered
  std::vector<std::string> refused;  // robots without a home-base fix ("name: reason")
  std::optional<OccupancyGrid> protocol_grid, naive_grid;
};

struct RunResult {
  std::string world;       // the world's name
  std::string world_file;  // as given
  uint64_t seed = 0;
  bool explore = false;
  std::vector<RobotRunResult> robots;
  SharedMapResult shared_map;
  bool cooperative = false;  // the shared map was built during the run, sortie by sortie
                             // (a route is one sortie)
  AgentSettings settings;    // what the agents ran with
  double published_band = kPublishedSigmaScale;
  GridU8 floor;         // the drivable floor over the map (what the metrics score)
  GridU8 shared_truth;  // the true occupancy the shared map is scored against
  std::vector<TimelineSample> timeline;
  double timeline_period_s = 10.0;
  double time_to_90_s = -1.0;  // first sample with shared coverage >= 0.9 (-1: never)
  double time_to_50_s = -1.0, time_to_75_s = -1.0;  // the same for 0.5 and 0.75
  RunTiming timing;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  double real_time_factor = 0.0;
};

// Runs the world. Throws ConfigError for bad world or robot files, std::invalid_argument
// for bad options, std::runtime_error when the recording cannot be written.
RunResult runWorld(const RunOptions& options);

}  // namespace coopmap

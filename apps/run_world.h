// Runs a world headless: robots follow their routes, map with stereo, and the run's maps,
// trajectories and metrics are written to an output folder.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/agent/cooperation.h"
#include "core/correction/traverse_log.h"
#include "core/io/tum.h"
#include "core/mapping/map_metrics.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"
#include "core/robot/robot_interface.h"
#include "core/sharing/shared_map.h"

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
  // Autonomous runs go out in sorties of at most this many metres; after each the robot
  // localizes at the home base, posts its corrected traverse to the shared map and imports
  // it (core/agent/cooperation.h), then goes again, at most max_sorties times. With
  // max_sorties 1 it explores once and the maps are shared after the run (share_maps).
  // m of a sortie; unset: the world's mission setting, else 25.
  std::optional<double> sortie_budget_m;
  // Unset: the world's mission settings (World::Exploration), else MissionConfig's and
  // FrontierConfig's defaults.
  std::optional<double> first_sortie_budget_m;  // 0: sortie_budget_m
  std::optional<double> safety_distance;        // m: MissionConfig::safety_distance
  std::optional<double> slow_distance;          // m: MissionConfig::slow_distance (0: off)
  std::optional<double> fringe_clearance;       // m: FrontierConfig::fringe_clearance (0: off)
  std::optional<double> goal_clearance;         // m: FrontierConfig::goal_clearance (0: off)
  std::optional<double> doorway_width;          // m: FrontierConfig::doorway_width (0: off)
  std::optional<bool> retry_frontiers;          // MissionConfig::retry_frontiers
  std::optional<double> floor_edge_depth;       // m: RadialMapConfig::floor_edge_depth (0: off)
  std::optional<int> beyond_support;            // pixels: RadialMapConfig::beyond_support
  std::optional<bool> shaped_closures;          // CooperationConfig::closure_shape
  std::optional<bool> closure_seen_points;      // AlignmentConfig::seen_points_only (closures)
  std::optional<bool> closure_decided_points;   // AlignmentConfig::decided_points_only (same)
  std::optional<bool> bump_away;                // MissionConfig::bump_away
  std::optional<double> visited_radius;         // m: MissionConfig::visited_radius (0: radius)
  std::optional<double> max_linear_accel;       // m/s^2: MissionConfig::max_linear_accel (0: off)
  std::optional<double> recent_hits_s;          // s: MissionConfig::recent_hits_s (0: off)
  std::optional<double> passage_width;          // m: MissionConfig::passage_width (0: off)
  double sortie_budget_s = 400.0;               // s: a robot stuck (wheels slipping) goes home too
  int max_sorties = 12;
  // A robot whose first fix at the end of a sortie puts it farther than this (m) from its
  // start drives there by that fix and looks again before the sortie is corrected.
  double reapproach_m = 0.1;
  // The band of the shared map the run publishes (outputs, metrics: the protocol's and the
  // naive one's alike), as OccupancyConfig::sigma_scale; the robots' maps and the shared map
  // they import keep the default's (core/sharing/shared_map.h).
  double published_band = kPublishedSigmaScale;
  // Between fixes, track the robot's estimate against the shared map it imported at home
  // (core/agent/map_tracker.h). Off by default: on the lab (10 seeds) it brought 23 contacts
  // against 6 without, at the same map quality (its 6-scan alignments turn the estimate by
  // a few degrees at times); steering by calibrated odometry, as the paper's robots steered
  // by odometry, is the default.
  bool track_shared_map = false;
  // Calibrate the odometry online from each sortie's fitted systematic errors
  // (core/correction/odometry_calibration.h); false: raw odometry every sortie.
  bool calibrate_odometry = true;
  // Whether that calibration includes the distance scale (OdometryCalibration); unset: the
  // world's mission setting, else true.
  std::optional<bool> calibrate_distance_scale;
  // The calibration's distance scale measured by stereo along straight stretches
  // (core/correction/stereo_scale.h) instead; unset: the world's mission setting, else false.
  std::optional<bool> stereo_distance_scale;
  // The calibration's distance scale at the start (the robot calibrated from logs, `coopmap
  // stereo-scale`): the first sortie drives on it; unset: the world's mission setting, else 0.
  std::optional<double> odometry_distance_scale;
  // With more than one robot: frontiers near teammates' goals are worth less, and a robot
  // whose own part is explored goes home to share it (MissionConfig::claimed_return_factor);
  // false: each robot explores as if alone.
  bool coordinate = true;
  // m kept clear around the robot's body when exploring robots plan (on top of its radius;
  // PlanningMapConfig::margin): room for the estimate's drift between home-base fixes.
  // Unset: the world's mission setting, else 0.05.
  std::optional<double> planning_margin;
  // m beyond the body the paths keep from walls where the map leaves room (on top of the
  // radius; PlannerConfig::preferred_margin). Unset: the world's mission setting, else 0 (off).
  std::optional<double> preferred_margin;
  // The sorties' loop closures: "none", "self", "shared" or "both". Unset: the world's mission
  // setting, else `cooperation` as it is (closures within the sortie only, by default).
  std::optional<std::string> closures;
  // m: stretches of a corrected sortie the shared map would move farther than this are not
  // posted (CooperationConfig::post_gate_m). Unset: the world's mission setting, else 0 (off).
  std::optional<double> post_gate_m;
  // deg: 1-sigma of the headings the walls give the sorties' corrections, in a building whose
  // walls run along the map frame's axes (CooperationConfig::manhattan_sigma_rad). Unset: the
  // world's mission setting, else 0 (off).
  std::optional<double> manhattan_sigma_deg;
  // The share of the walls' turn from the map frame's axes by which an exploring robot's
  // estimate is turned back while driving, every few radial maps (WallHeadingConfig::gain).
  // Unset: the world's mission setting, else 0 (off).
  std::optional<double> wall_heading_gain;
  // Radial maps per stretch of a sortie's correction: the stretches aligned to the shared map
  // (closures), the headings from the walls and the post gate (CooperationConfig::
  // closure_scans). Unset: the world's mission setting, else `cooperation`'s (6).
  std::optional<int> closure_scans;
  // Never-observed cells a frontier whose goal was reached must still have to be gone to once
  // more, for a full turn there (FrontierConfig::look_again_gain). Unset: the world's
  // mission setting, else 0 (off).
  std::optional<int> look_again_gain;
  // m: returns this close to where a teammate reports itself are the teammate, and are not
  // logged or posted (Mapper::setTeammates); 0: teammates are logged like the world. 0.8 m:
  // a report is off by the teammate's drift, and stereo fattens its body; with 0.5 m, home-
  // base fixes were up to 0.92 deg off over 20 lab seeds (a teammate in the look), with 0.8 m
  // at most 0.75 deg.
  double teammate_mask_m = 0.8;
  // How each sortie is localized, corrected and checked before it is shared.
  CooperationConfig cooperation;
  double timeline_period_s = 10.0;     // s between samples of coverage and error over time
  std::optional<double> sensing_rate;  // Hz; overrides the world's
  bool progress = false;               // progress bar on stderr
  // Called with every sensing frame and its ground-truth depth (reference camera, metres),
  // for evaluation tools; rendering the depth costs a little, so only when set.
  std::function<void(const std::string& robot, const TrinocularFrame& frame,
                     const cv::Mat& truth_depth)>
      frame_observer;
};

// A contact of a robot with anything (the simulator's truth): when, with what, where, and
// what the robot was doing.
struct ContactRecord {
  double t = 0.0;               // s
  std::string with;             // "static_world", "person" or "robot"
  Eigen::Vector2d point{0, 0};  // contact point (m, world)
  Pose2 robot;                  // the robot's true pose
  std::string phase;            // mission phase ("route" for scripted runs)
};

struct RobotRunResult {
  std::string name;
  double path_length_m = 0.0;
  int collisions = 0;         // distinct contacts with anything
  int collisions_static = 0;  // of them, with walls, doors, furniture, the home base
  int collisions_people = 0;  // with people
  int collisions_robots = 0;  // with other robots
  std::vector<ContactRecord> contacts;
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
  int early_returns = 0;                // sorties ended because the frontiers left were teammates'
  std::string mission_event;            // the mission's last event, for people
  int sorties = 0;                      // sorties ended at the home base
  int sorties_fixed = 0;                // of them, localized there
  int sorties_posted = 0;               // of them, posted to the shared map
  std::vector<std::string> sortie_log;  // one line per sortie, for people
  // The online odometry calibration at the end (cooperative runs): what the robot drives on,
  // its distance scale RunOptions::odometry_distance_scale's, or from stereo when
  // RunOptions::stereo_distance_scale.
  OdometryBias calibration;
  // Each home-base fix of the sorties against the true pose (m, deg).
  std::vector<std::pair<double, double>> fix_errors;
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

// The shared maps of a run (RunOptions::share_maps).
struct SharedMapResult {
  bool computed = false;
  MapMetrics protocol;  // robots' traverses corrected at the home base, posted
  MapMetrics naive;     // every radial map at its odometry pose, posted as taken
  // The protocol's shared grid the robots import (RunOptions::published_band aside: the
  // robots' band), for comparison with the published `protocol`.
  MapMetrics imported;
  int posts_accepted = 0;            // corrected posts the shared map accepted
  std::vector<std::string> posted;   // robots whose corrected traverse entered
  std::vector<std::string> refused;  // robots without a home-base fix ("name: reason")
  std::optional<OccupancyGrid> protocol_grid, naive_grid;
};

struct RunResult {
  std::vector<RobotRunResult> robots;
  SharedMapResult shared_map;
  bool cooperative = false;  // the shared map was built during the run, sortie by sortie
  // The mission settings the run used (command line, else the world's, else defaults).
  struct MissionSettings {
    double sortie_budget_m = 0.0;
    double first_sortie_budget_m = 0.0, safety_distance = 0.0, slow_distance = 0.0;
    double fringe_clearance = 0.0, goal_clearance = 0.0, doorway_width = 0.0;
    bool retry_frontiers = false;
    double floor_edge_depth = 0.0;
    int beyond_support = 1;
    bool shaped_closures = false;
    bool closure_seen_points = false;
    bool closure_decided_points = false;
    bool bump_away = false;
    double visited_radius = 0.0;
    double recent_hits_s = 0.0;
    bool calibrate_distance_scale = true;
    bool stereo_distance_scale = false;
    double odometry_distance_scale = 0.0;
    double passage_width = 0.0;
    double planning_margin = 0.0;
    double preferred_margin = 0.0;
    std::string closures;  // none, self, shared or both
    double post_gate_m = 0.0;
    double manhattan_sigma_deg = 0.0;
    double wall_heading_gain = 0.0;
    int closure_scans = 0;
    int look_again_gain = 0;
    double max_linear_accel = 0.0;
  };
  std::optional<MissionSettings> mission_settings;  // with --explore
  std::vector<TimelineSample> timeline;
  double time_to_90_s = -1.0;  // first sample with shared coverage >= 0.9 (-1: never)
  double time_to_50_s = -1.0, time_to_75_s = -1.0;  // the same for 0.5 and 0.75
  RunTiming timing;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  double real_time_factor = 0.0;
};

// Runs the world. Throws ConfigError for bad world or robot files, std::invalid_argument
// for bad options, std::runtime_error when outputs or the recording cannot be written.
RunResult runWorld(const RunOptions& options);

}  // namespace coopmap

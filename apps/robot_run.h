// The run loop's per-robot state and the sharing steps it takes (apps/run_world.cpp):
// internal to the runner, shared by run_world.cpp and run_sharing.cpp.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "apps/run_world.h"
#include "core/agent/cooperation.h"
#include "core/agent/map_tracker.h"
#include "core/agent/mapper.h"
#include "core/agent/mission.h"
#include "core/agent/route_follower.h"
#include "core/correction/odometry_calibration.h"
#include "core/correction/stereo_scale.h"
#include "core/localization/home_base.h"
#include "core/sharing/shared_map.h"
#include "robots/sim/sim_robot.h"
#include "sim/world/world.h"

namespace coopmap::run_detail {

struct RobotRun {
  std::unique_ptr<SimRobot> driver;
  std::unique_ptr<Mapper> mapper;
  std::unique_ptr<RouteFollower> follower;
  std::unique_ptr<MissionAgent> mission;      // autonomous runs
  std::unique_ptr<HomeBaseCooperation> coop;  // cooperative autonomous runs
  size_t sortie_begin = 0;                    // the current sortie's first traverse entry
  // A robot back away from its start drives there by a first fix and looks again (the
  // start placed in its estimate's frame by the fix; its map and log stay in that frame).
  bool reapproaching = false;
  // Looks at the home base that found no fix, this sortie: the robot drives to where its
  // estimate places the start and looks again (kLooksAgain times) before it stops, lost.
  int looks_again = 0;
  // The sortie's entries before this are not part of the next look: each look at the home
  // base sees only its own turn (a robot looking again where it stood saw, in its earlier
  // turn's scans, whoever had hidden the home base).
  size_t look_from = 0;
  Pose2 home;  // its start (the map frame is its odometry frame at the start)
  // The estimate's frame (X_MO) when the sortie began. The tracker moves the estimate during
  // the sortie; the sortie is corrected on its odometry chain from this frame.
  Pose2 sortie_frame;
  MapTracker tracker;           // against the shared map imported at the last home visit
  WallHeadingTracker headings;  // off unless the mission turns it on
  // Cooperative runs: odometry calibrated online from the fixes; the mapper, the mission
  // and the teammates see the calibrated odometry. `raw` keeps what the encoders said at
  // each radial map (naive sharing posts at it).
  OdometryCalibration calibration;
  bool calibrate = false;
  // With `calibrate`: the distance scale from stereo along straight stretches, pooled over
  // the sorties (core/correction/stereo_scale.h), rather than from the sorties' corrections.
  bool stereo_scale = false;
  StereoScale stereo;
  size_t stereo_measured = SIZE_MAX;  // sortie_begin of the sortie last pooled
  double sortie_scale = 0.0;          // the calibration's distance scale the sortie began on
  std::vector<Pose2> raw;
  Pose2 odo;  // this step's odometry as the robot uses it (calibrated when `calibrate`)
  const RadialMap* latest = nullptr;  // this step's radial map, for the mission
  RobotRunResult result;
  Pose2 last_true;
  GridU8 truth;  // true occupancy up to the robot's swept height
  // Control steps of each kind of motion since the last sensing cycle: the cycle's segment
  // is the kind most of them had.
  int turn_steps = 0, straight_steps = 0;
  int recording = -1;                   // the robot's index in the recording
  RobotDescription mapper_description;  // what the mapper was given
};

// Pairs of radial maps a stereo distance scale needs before the calibration takes it, and
// the largest it takes. A robot gathers 100-230 in a 1800 s run of the building (pairs at
// every entry); a sortie posted before the scale is taken is drawn at the encoders' scale
// (1 % long), and an early, noisier figure is no worse a bet: the building (post gate at
// 0.2 m, seeds 1-24) measured wall_recall 0.943 with either, false_occupied_rate 0.0150 with
// 10 and 0.0161 with 30 (README).
inline constexpr int kMinStereoScalePairs = 10;
// Looks again at the home base after one that found no fix (a person or a teammate in the
// view, a look from off the start), before the robot stops for good. The building lost a
// robot so in 2 runs of 48 (seeds 24 and 41, calibrated scale).
inline constexpr int kLooksAgain = 2;
inline constexpr double kMaxStereoScale = 0.05;

// How far a scripted traverse's home-base fix may move the robot, per metre driven (m/m,
// rad/m): a generous bound on drifting odometry (the building's loop, 78 m: 5.3 m and 25
// degrees off; the B-14's heading drift is 0.0055 rad/m).
inline constexpr double kScriptedDriftPerMetre = 0.15;
inline constexpr double kScriptedTurnDriftPerMetre = 0.01;

// The robot whose true occupancy the shared map is measured against: the tallest (each
// robot's truth is the world up to its swept height).
inline const RobotRun& tallestRobot(const std::vector<RobotRun>& runs) {
  const RobotRun* tallest = &runs.front();
  for (const RobotRun& r : runs)
    if (r.mapper_description.swept_height > tallest->mapper_description.swept_height) tallest = &r;
  return *tallest;
}

// The home base as the world file designed it (map frame).
HomeBase nominalHomeBase(const sim::World& world);
// Adds `b`'s evidence to `a` (log-odds summed and clamped, seen where either has seen).
void mergeSeen(OccupancyGrid& a, const OccupancyGrid& b);
// The naive shared map: every radial map of every robot at its raw odometry pose.
// `published`: the shared map's published update rule (LocalSharedMap).
OccupancyGrid naiveSharedMap(const MapLimits& limits, const std::vector<RobotRun>& runs,
                             const OccupancyConfig& published);
// After a scripted run: the paper's two ways of sharing, the home-base protocol (each
// robot's traverse one sortie of HomeBaseCooperation: localized at the home base, corrected,
// checked against what is shared, posted) and naive. `closures`: the loop closures of the
// corrections, by CooperationConfig::setClosureKinds's names (checked by the caller). Both
// maps are the published grids of `published`'s rule.
SharedMapResult shareMaps(const sim::World& world, const MapLimits& limits, const GridU8& floor,
                          const std::vector<RobotRun>& runs, const std::string& closures,
                          const OccupancyConfig& published);
// The robot is back at the home base and has looked at it: localize, correct and post the
// sortie (core/agent/cooperation.h), apply the fix to its estimate, import the shared map,
// and send it out again (or stop it, without a trusted fix).
void endSortie(RobotRun& r, LocalSharedMap& live, double now, double reapproach_m, bool track);

// Writes the run's outputs to opt.out_dir (run_world_outputs.cpp). `floor`: the drivable
// floor over the run's map limits (what the metrics score).
void writeOutputs(const RunOptions& opt, const sim::World& world, const RunResult& result,
                  const std::vector<RobotRun>& runs, const GridU8& floor);
// Each new radial map while driving: the tracker's and the walls' corrections of the
// estimate (run_sharing.cpp).
void trackWhileDriving(RobotRun& r);

}  // namespace coopmap::run_detail

// Drift correction of a traverse (section 4.1 of the paper): back at the home base the
// robot knows its true pose; the difference from its odometry pose is spread back over the
// traverse by one of several models, and the map is rebuilt from the corrected poses.
//
// Frames: odometry poses X_OR are those recorded in the log; the traverse starts at the
// map frame's origin of odometry (the first pose is right: the robot registered the home
// base there). Corrected poses are X_MR, in the map frame.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/correction/traverse_log.h"
#include "core/geometry/pose2.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

enum class CorrectionModel {
  kNone,               // the odometry poses as they are
  kUniform,            // the pose error spread along the path length (paper)
  kTurnsAndStraights,  // rotation error to turns, translation error to straight runs (paper)
  kHeadingDrift,       // heading drifts per metre as well as per radian turned; fitted
  kPoseGraph,          // least squares over every odometry step (Ceres)
};
const char* toString(CorrectionModel m);
// Parses "none", "uniform", "turns-and-straights", "heading-drift", "pose-graph".
std::optional<CorrectionModel> parseCorrectionModel(const std::string& name);
const std::vector<CorrectionModel>& allCorrectionModels();

// The home base's verdict: the true (map-frame) pose of the robot at one entry of the log.
struct PoseObservation {
  size_t entry = 0;           // index into the log
  Pose2 pose;                 // X_MR at that entry
  double sigma_xy = 0.02;     // m, 1-sigma
  double sigma_theta = 0.01;  // rad, 1-sigma
  // When set, replaces sigma_xy: the information (inverse covariance, per m^2) of the
  // position, map frame; e.g. an alignment in a corridor pins the position across it only.
  std::optional<Eigen::Matrix2d> xy_information;
};

// Odometry error model used by the fitted models (heading-drift, pose-graph): random
// errors per step grow with sqrt(distance) and sqrt(angle); systematic errors (the unknowns
// the models estimate) have zero-mean priors of the given spread.
struct OdometryErrorModel {
  double linear_per_sqrt_m = 0.02;     // m / sqrt(m) driven
  double heading_per_sqrt_m = 0.002;   // rad / sqrt(m) driven
  double angular_per_sqrt_rad = 0.01;  // rad / sqrt(rad) turned
  double prior_heading_drift = 0.02;   // rad/m
  double prior_turn_scale = 0.05;      // fraction
  double prior_distance_scale = 0.05;  // fraction

  void validate() const;  // throws std::invalid_argument naming the field
};

struct CorrectionConfig {
  CorrectionModel model = CorrectionModel::kHeadingDrift;
  OdometryErrorModel odometry;
  // Pose graph: the distance scale is one of the unknowns. False: held at zero (as the
  // heading-drift model always holds it), for odometry whose scale is calibrated
  // beforehand: with only a home-base fix and the walls' headings to go on, a sortie that
  // comes home ends where it would on any scale, and fitting one soaks up the random errors,
  // drawing the far corridors' walls short or long (measured:
  // docs/experiments/2026-12-building-sessions-25-34.md).
  bool fit_distance_scale = true;
  int max_iterations = 50;  // solver iterations (fitted models)
};

// The systematic odometry errors a fitted model found (odometry minus truth).
struct OdometryBias {
  double heading_drift = 0.0;   // rad per metre driven
  double turn_scale = 0.0;      // fraction of the angle turned
  double distance_scale = 0.0;  // fraction of the distance driven
};

struct CorrectionResult {
  bool ok = false;
  std::string message;       // why not, when !ok
  std::vector<Pose2> poses;  // X_MR per log entry
  OdometryBias bias;         // fitted models only
  int iterations = 0;        // solver iterations (fitted models)
  double final_cost = 0.0;   // solver cost (fitted models)
};

// The motion the robot really made in one odometry increment u = X_O(i-1)O(i) if its
// odometry erred by exactly `bias` (the step model of the fitted corrections).
Pose2 correctedIncrement(const Pose2& u, const OdometryBias& bias);

// Corrects the poses of every entry of `log` given the home-base observation. Entries
// after the observed one move rigidly with it. `closures` are further observations of
// poses along the way (loop closures, e.g. scans matched to the map made at the start);
// only the pose-graph model uses them.
CorrectionResult correctTraverse(const TraverseLog& log, const PoseObservation& home,
                                 const CorrectionConfig& config,
                                 const std::vector<PoseObservation>& closures = {});

// Rebuilds an occupancy grid from the log's radial maps at the given poses (one per entry).
OccupancyGrid rebuildMap(const TraverseLog& log, const std::vector<Pose2>& poses,
                         const MapLimits& limits, const OccupancyConfig& config = {});

}  // namespace coopmap

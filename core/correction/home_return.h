// The home-base protocol on a traverse log: the robot turns in place at the home base at
// the start (registering its two corners) and again on return; the corners found in the
// local map of the return turn give its true pose, the observation drift correction needs.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/correction/drift_correction.h"
#include "core/correction/traverse_log.h"
#include "core/localization/home_base.h"
#include "core/localization/scan_alignment.h"

namespace coopmap {

struct HomeReturnConfig {
  double resolution = 0.025;            // m, local map cells (finer than the robot's map)
  double local_radius = 4.5;            // m, local map half-size around the turn
  double turn_radius = 0.05;            // m: entries this close to the turn's first one are in it
  double facing_half_angle = 0.70;      // rad: scans used must face the home base this well
  double register_radius = 0.3;         // m, search radius around the given corner positions
  double register_max_turn = 0.35;      // rad: the reference map holds the scans taken before
                                        // the start turn has turned more than this (exact poses)
  double refined_sigma_xy = 0.01;       // m, 1-sigma of a fix refined by dense alignment
  double refined_sigma_theta = 0.0035;  // rad
  double matched_view_margin = 0.1;     // rad: the final refinement uses the return scans
                                        // looking as the reference scans did, within this,
  double matched_view_radius = 0.15;    // m: when the robot is back this close to its start
  double search_radius = 1.0;           // m: without a corner fix, the robot is searched for
                                        // within this of the start (it believes it is home)
  double max_separation_error = 0.1;    // m, observed vs registered corner separation
  // How far the robot's estimate can be off (a robot that was localized at its last
  // return knows its pose better than one back from its first long tour): fixes that
  // turn it more than max_correction_rad or move it more than max_correction_m are other
  // corners mistaken for the home base, and the heading sweep stays within the bound.
  double max_correction_rad = M_PI;
  double max_correction_m = 10.0;
  CornerConfig corners;       // arm_cells is set from the home base's arm length
  AlignmentConfig alignment;  // dense refinement against the reference map
  void validate() const;      // throws std::invalid_argument naming the field
};

// Entries of the turn in place at the start (at_end = false) or end of a log: the run of
// consecutive entries within `turn_radius` of the first entry, or at the end of the last
// entry that turned (entries after it, nudged farther away, are left out).
std::vector<size_t> turnInPlaceEntries(const TraverseLog& log, bool at_end, double turn_radius);

// Of `entries`, those whose odometry heading points at `target` (odometry frame, m) within
// `half_angle` (rad).
std::vector<size_t> entriesFacing(const TraverseLog& log, const std::vector<size_t>& entries,
                                  const Eigen::Vector2d& target, double half_angle);

// An occupancy grid of the given entries at their odometry poses.
OccupancyGrid localMap(const TraverseLog& log, const std::vector<size_t>& entries,
                       const MapLimits& limits, const OccupancyConfig& config = {});
// An occupancy grid of all entries at their odometry poses.
OccupancyGrid localMap(const TraverseLog& log, const MapLimits& limits,
                       const OccupancyConfig& config = {});

// Registers the home base from the start turn: corners near `first` and `second` (m, map
// frame = odometry frame at the start). `arm_length` is the corners' arm length (m).
HomeBaseRegistration registerHomeBaseFromLog(const TraverseLog& log, const Eigen::Vector2d& first,
                                             const Eigen::Vector2d& second, double arm_length,
                                             const HomeReturnConfig& config = {});

// The entries of the start turn taken before it had turned more than register_max_turn
// (odometry still exact there): the reference scans.
std::vector<size_t> referenceEntries(const TraverseLog& log, const HomeReturnConfig& config = {});

// The reference map of the home base: the scans of the start turn taken before the robot
// had turned more than register_max_turn (its odometry is still exact there, so this map
// is in the map frame), at the local map resolution around the start.
OccupancyGrid homeBaseReferenceMap(const TraverseLog& log, const HomeReturnConfig& config = {});

enum class HomeReturnStatus { kOk, kNoReturnTurn, kHomeBaseNotFound };
const char* toString(HomeReturnStatus s);

struct HomeReturn {
  HomeReturnStatus status = HomeReturnStatus::kNoReturnTurn;
  HomeBaseFix fix;              // the final fix (corrected pose at `observation.entry`)
  PoseObservation observation;  // for drift correction
  int scans = 0;                // scans of the return turn used for the final fix
  HomeBaseFix corner_fix;       // the paper's fix: corners only
  bool refined = false;         // the fix was refined by dense alignment to the reference
  AlignmentResult alignment;
};

// Localizes at the end of the log. The home base is first searched anywhere near the
// robot in the local map of the whole return turn (odometry may have drifted metres and
// tens of degrees: its pair of corners is recognised by their geometry); then the scans
// facing it are mapped again on their own and the corners refitted there (the paper's fix:
// position from the corners, heading from the line joining them). With a `reference` map
// (see homeBaseReferenceMap), the fix is then refined by aligning those scans' obstacle
// points to it.
// Entries before `first_return` are never part of the return turn (scans put in front of
// the log to stand for the start, which a sortie that never left home would otherwise join).
HomeReturn localizeFromLog(const TraverseLog& log, const HomeBase& home, double arm_length,
                           const HomeReturnConfig& config = {},
                           const OccupancyGrid* reference = nullptr, size_t first_return = 0);

// The home-base protocol on a whole log: registration from the start turn (corners near
// `nominal`, the home base as designed; if they are not found, the nominal corners stand in:
// the reference map does the fine work), the reference map, and localization at return
// (entries before `first_return` never part of the return turn, as for localizeFromLog).
struct HomeBaseProtocol {
  HomeBaseRegistration registration;  // the robot's own, if it found the corners
  HomeBase home;                      // what localization used: registered or nominal
  std::optional<OccupancyGrid> reference;
  HomeReturn result;
  std::string method;  // how the fix was found, for people
};
HomeBaseProtocol runHomeBaseProtocol(const TraverseLog& log, const HomeBase& nominal,
                                     double arm_length, const HomeReturnConfig& config = {},
                                     size_t first_return = 0);

}  // namespace coopmap

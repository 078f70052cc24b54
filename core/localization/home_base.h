// Home-base localization (section 3 of the paper): two corners registered in the map frame
// at the start are found again on return; the rigid transform that takes them back to
// their registered places corrects the robot's odometry pose. Heading comes from the line
// joining the corners (one corner's own angle is too inaccurate), position from the corners.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/pose2.h"
#include "core/landmarks/corner_detector.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"

namespace coopmap {

struct HomeBase {
  Corner first, second;  // registered at start, map frame
};

// The home base as designed: two L corners, each of two arms (solid boxes `thickness` thick
// and `arm_length` long, as in the world files) leaving the corner's vertex at its heading
// +/- 45 degrees, so the heading points into the L's concave side. The map frame is the home
// base's: `corners` place the vertices in it (the arms' centre lines meet at a vertex). The
// defaults are coopmap's standard home base: corners 1.4 m apart, both opening towards -x,
// where the robots stand; the map frame's origin midway between them, x pointing from the
// robots to the home base.
struct HomeBaseDesign {
  HomeBase corners = {Corner{{0.0, -0.7}, M_PI}, Corner{{0.0, 0.7}, M_PI}};
  double arm_length = 0.6;  // m
  double thickness = 0.04;  // m

  // A rectangle of the design, map frame: centre, half sizes along and across, direction.
  struct Arm {
    Eigen::Vector2d center{0.0, 0.0};
    double half_length = 0.0, half_width = 0.0;
    double yaw = 0.0;
  };
  std::vector<Arm> arms() const;  // four: the first corner's two, then the second's
  // The corners as a robot's grid shows them: where the arms' inner faces meet, thickness /
  // sqrt(2) from each vertex along its heading. What the corner detector fits.
  HomeBase visibleCorners() const;
  void validate() const;  // throws std::invalid_argument naming the field
};

enum class HomeBaseStatus { kOk, kCornerNotFound, kGeometryMismatch };

struct HomeBaseFix {
  HomeBaseStatus status = HomeBaseStatus::kCornerNotFound;
  Pose2 correction;          // X_MO: maps poses from the drifted (odometry) frame to the map frame
  Pose2 pose;                // the corrected robot pose (map frame)
  double sigma_xy = 0.0;     // m, 1-sigma position uncertainty from the fits
  double sigma_theta = 0.0;  // rad, 1-sigma heading uncertainty
  double rms = 0.0;          // cells, worse of the two corner fits
  double separation_error = 0.0;  // m, |observed - registered| corner separation
  Corner first, second;           // as observed (odometry frame)
};

// Registers the home base: the two corners found near the predicted positions (m).
// Returns nullopt with the detector's status when a corner is not found.
struct HomeBaseRegistration {
  std::optional<HomeBase> home;
  CornerStatus status = CornerStatus::kOk;
};
HomeBaseRegistration registerHomeBase(const CornerDetector& detector, const Eigen::Vector2d& first,
                                      const Eigen::Vector2d& second, double search_radius);

// Localizes against the home base: `detector` works on a map built in the odometry frame on
// return; `odometry` is the robot's odometry pose. Corners are searched within
// `search_radius` of where the correction guess X_MO (map from odometry; identity: where
// uncorrected odometry predicts them) puts the registered corners.
HomeBaseFix localizeAtHomeBase(const CornerDetector& detector, const HomeBase& home,
                               const Pose2& odometry, double search_radius,
                               double max_separation_error = 0.1, const Pose2& guess = {});

// Localizes against the home base when odometry may be far off: every corner of `corners`
// (found in a grid of `resolution` m) within `radius` of `center` (odometry frame, m) is a
// candidate, and the pair whose separation and headings relative to the line joining them
// match the registered corners best is taken as the home base.
HomeBaseFix findHomeBase(const std::vector<Corner>& corners, double resolution,
                         const HomeBase& home, const Pose2& odometry, const Eigen::Vector2d& center,
                         double radius, double max_separation_error = 0.1);

// The placement X_MO that puts the corner `seen` (odometry frame) on `designed` (map frame):
// vertex on vertex, heading on heading.
Pose2 placementOnCorner(const Corner& seen, const Corner& designed);

}  // namespace coopmap

// Dense alignment of radial maps to a reference occupancy grid: the rigid correction that
// puts the scans' obstacle points onto the reference's occupied cells (least squares on the
// distance field of the occupied cells, robust to points the reference never saw).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "core/geometry/pose2.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"

namespace coopmap {

struct AlignmentConfig {
  double max_range = 3.5;         // m: farther returns are too noisy to help
  double robust_scale = 3.0;      // cells: Tukey loss scale, points farther off count nothing
  double inlier_cells = 1.0;      // a point within this of an occupied cell is an inlier
  double min_inlier_share = 0.5;  // fewer inliers than this share of the points: failure
  int min_points = 50;
  int max_iterations = 50;
  // Every point_stride-th hit of the scans only (1: all): an alignment that only has to reach
  // the right basin (a search's candidates) needs far fewer points than a fix.
  int point_stride = 1;
  // Stereo depth error grows with range (as range squared for a fixed disparity error):
  // each point's squared residual is weighted by min(1, weight_range / range)^range_exponent.
  // 2 (sigma grows as range): on the lab over 10 seeds the worst home-base heading error
  // fell from 0.61 to 0.38 deg; 0: every point alike.
  double range_exponent = 2.0;
  double weight_range = 1.5;  // m
  // Which points the reference judges. Off: every point in a cell it has seen or within
  // robust_scale of an occupied cell. On: in a cell it has seen, or just behind a surface it
  // saw from the other side (a stretch placed a little too far); not where it saw nothing:
  // past the mapped end of a wall, the wall's continuation is pulled back onto the wall's
  // last cells otherwise. (In the building, with exact odometry, each sortie going on into
  // new ground was pulled back toward home: the far corridors were mapped about 1 % short.)
  bool seen_points_only = false;
  // Nor where it saw something but is unsure what (a seen cell neither free nor occupied,
  // e.g. a wall's far part seen weakly once): counted against the nearest occupied cell,
  // such points put the later of two radial maps 1-1.5 m apart 4-8 % too near the earlier
  // (building, exact poses; 0-1 % with this rule).
  bool decided_points_only = false;
  void validate() const;  // throws std::invalid_argument naming the field
};

struct AlignmentResult {
  bool ok = false;
  std::string message;  // why not, when !ok
  Pose2 correction;     // X_MO: maps the scans' odometry frame onto the reference's frame
  int points = 0;       // obstacle points used
  int inliers = 0;
  double rms_cells = 0.0;  // RMS distance of the inliers to the nearest occupied cell
  int iterations = 0;
  // Gauss-Newton information of the correction's parameters (x m, y m, theta rad) over the
  // inliers at the solution (residuals in cells, range-weighted): what the scans' obstacles
  // pin down. A stretch of straight corridor pins the across-corridor offset and the
  // heading, not the offset along it.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
};

// The information `alignment` gives about the position of a point at `at` (map frame,
// after the correction), the heading left free (Schur complement): 2x2, per m^2.
Eigen::Matrix2d positionInformation(const AlignmentResult& alignment, const Eigen::Vector2d& at);

// A reference map prepared for alignment (its distance field computed once).
// Every `stride`-th obstacle point (a hit) of the scans within max_range (m), each placed by
// its scan's `odometry` pose.
std::vector<Eigen::Vector2d> hitPoints(const std::vector<const RadialMap*>& scans, double max_range,
                                       int stride = 1);

class ScanAligner {
 public:
  explicit ScanAligner(const OccupancyGrid& reference, const AlignmentConfig& config = {});
  ScanAligner(const ScanAligner&) = delete;
  ScanAligner& operator=(const ScanAligner&) = delete;

  // Aligns `scans` (each at its own odometry pose) to the reference, starting from `guess`
  // (X_MO). Only hits within max_range are used.
  AlignmentResult align(const std::vector<const RadialMap*>& scans, const Pose2& guess) const;
  // Share of the scans' obstacle points within `robust_scale` of a reference obstacle when
  // the scans are placed by `guess` (0 when there are no points): a cheap score for search.
  double score(const std::vector<const RadialMap*>& scans, const Pose2& guess) const;
  // The same for points already in the odometry frame (see obstaclePoints).
  // `within_cells` > 0 replaces robust_scale as the distance that counts (coarse searches).
  double score(const std::vector<Eigen::Vector2d>& points, const Pose2& guess,
               double within_cells = 0.0) const;
  // Every `stride`-th obstacle point of the scans within max_range, odometry frame.
  std::vector<Eigen::Vector2d> obstaclePoints(const std::vector<const RadialMap*>& scans,
                                              int stride = 1) const;

 private:
  std::vector<Eigen::Vector2d> points(const std::vector<const RadialMap*>& scans,
                                      const Pose2& guess,
                                      std::vector<double>* weights = nullptr) const;
  double distance(const Eigen::Vector2d& map_point) const;  // cells; large off the map
  // An unseen cell within robust_scale of an occupied one, behind a surface whose other
  // side the reference saw (see points()).
  bool behindSeenSurface(int ix, int iy) const;
  static constexpr int kMaxSurfaceCells = 6;  // thickest surface walked through
  const OccupancyGrid& reference_;
  AlignmentConfig config_;
  cv::Mat field_;  // CV_32F distance to the nearest occupied cell (cells), rows = y
  int occupied_ = 0;
};

// One-shot alignment (see ScanAligner::align).
AlignmentResult alignScans(const std::vector<const RadialMap*>& scans,
                           const OccupancyGrid& reference, const Pose2& guess,
                           const AlignmentConfig& config = {});

}  // namespace coopmap

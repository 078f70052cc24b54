// Corner landmarks in occupancy grids (section 3 of the paper): edges between certain free
// and occupied space, corner candidates from an orientation map of the dilated edges, a
// damped Gauss-Newton fit of an L-shaped corner model to the distance field of the edges,
// and selection by RMS and closeness to a prediction.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "core/mapping/grid.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

// What a map cell is known to be.
enum class CellClass : uint8_t {
  kUnknown = 0,    // never seen
  kFree = 1,       // confidently free
  kOccupied = 2,   // confidently occupied
  kUncertain = 3,  // seen, but neither
};

// Classes of an occupancy grid's cells (its thresholds decide free and occupied).
GridU8 classifyCells(const OccupancyGrid& grid);

struct CornerConfig {
  int grow_iterations = 3;       // passes growing certain regions into uncertain cells
  int dilate_iterations = 1;     // 3x3 dilations of the edge image before the orientation map
  int line_cells = 4;            // an orientation bit needs this many dilated edge cells in a row
  double arm_cells = 15.0;       // length of each arm of the corner model (cells)
  double point_spacing = 0.5;    // spacing of the model points along an arm (cells)
  double truncate_cells = 2.0;   // residuals are capped here: far points do not pull the fit
  double damping = 0.1;          // W = damping * I, in cells and degrees (the paper's 0.1)
  int max_iterations = 10;       // the paper's limit
  double min_step = 0.02;        // converged when the step is below this (cells and degrees)
  double settled_step = 0.25;    // after max_iterations: not converged if still moving this much
  double max_rms = 1.5;          // cells: fits above this are rejected (the paper's gate)
  double min_support = 0.8;      // and fits with less of either arm on an edge (within a cell)
  int upsample = 4;              // distance field resolution: cells / upsample
  double smoothing_cells = 0.0;  // Gaussian smoothing of the signed distance field (sigma, cells)
  double merge_cells = 1.5;      // fits closer than this (and within merge_degrees) are one
  double merge_degrees = 20.0;

  void validate() const;  // throws std::invalid_argument naming the field
};

// A fitted corner: vertex, and the heading of the bisector between its two arms (the arms
// leave the vertex at heading +/- 45 degrees).
struct Corner {
  Eigen::Vector2d position{0.0, 0.0};  // m, map frame
  double heading = 0.0;                // rad, map frame
  double rms = 0.0;                    // cells
  double support = 0.0;                // share of the weaker arm's points on an edge
  int iterations = 0;
  bool converged = false;
};

enum class CornerStatus { kOk, kNoCandidates, kNoConvergence, kRmsTooHigh };
const char* toString(CornerStatus s);

struct CornerSearch {
  CornerStatus status = CornerStatus::kNoCandidates;
  std::vector<Corner> corners;  // accepted fits (RMS gate passed), best RMS first
  int candidates = 0;           // corner candidates tried
  int rejected_rms = 0;         // RMS above the gate or too little support
  int not_converged = 0;
};

class CornerDetector {
 public:
  // Builds edges and their distance field from a classified grid (see classifyCells).
  CornerDetector(const GridU8& classes, const CornerConfig& config = {});

  // Every corner in the grid.
  CornerSearch findAll() const;
  // The accepted corner closest to `predicted` (m) among candidates within `radius` (m);
  // status says why there is none. A predicted heading, if given, seeds the fits too.
  CornerSearch findNear(const Eigen::Vector2d& predicted, double radius,
                        std::optional<double> predicted_heading = std::nullopt) const;
  // Fits the corner model from an initial guess (m, rad).
  Corner fit(const Eigen::Vector2d& position, double heading) const;

  const GridU8& edges() const { return edges_; }  // 1 on edge cells
  const MapLimits& limits() const { return limits_; }

 private:
  struct Guess {
    Eigen::Vector2d cell;  // cell coordinates (cells from the origin)
    double degrees;
  };
  std::vector<Guess> findCandidates() const;  // from the orientation map, once
  CornerSearch search(const std::vector<Guess>& guesses) const;
  double distance(double cx, double cy) const;  // signed, cells, bilinear, at cell coordinates

  CornerConfig config_;
  MapLimits limits_;
  GridU8 edges_;
  GridU8 dilated_;
  std::vector<Guess> candidates_;  // every corner candidate of the grid
  cv::Mat field_;  // CV_32F signed distance to the nearest edge (cells; < 0 in occupied)
};

}  // namespace coopmap

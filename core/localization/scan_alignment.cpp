#include "core/localization/scan_alignment.h"

#include <ceres/cubic_interpolation.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/sized_cost_function.h>
#include <ceres/solver.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/core/mat.hpp>
#include <opencv2/imgproc.hpp>

namespace coopmap {

namespace {

using Field = ceres::Grid2D<float, 1>;
using Interpolator = ceres::BiCubicInterpolator<Field>;

// Distance (cells) from a point's place in the reference to the nearest occupied cell, and
// its derivatives by the pose (x, y, theta) from the interpolated field's own gradient.
class PointResidual final : public ceres::SizedCostFunction<1, 3> {
 public:
  PointResidual(const Interpolator* field, const Eigen::Vector2d& p, const MapLimits& limits)
      : field_(field), p_(p), limits_(limits) {}
  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const double* pose = parameters[0];
    const double c = std::cos(pose[2]), s = std::sin(pose[2]);
    const double x = pose[0] + c * p_.x() - s * p_.y();
    const double y = pose[1] + s * p_.x() + c * p_.y();
    const double col = (x - limits_.origin.x()) / limits_.resolution - 0.5;
    const double row = (y - limits_.origin.y()) / limits_.resolution - 0.5;
    double d_row = 0.0, d_col = 0.0;
    field_->Evaluate(row, col, residual, &d_row, &d_col);
    if (jacobians && jacobians[0]) {
      const double gx = d_col / limits_.resolution, gy = d_row / limits_.resolution;
      jacobians[0][0] = gx;
      jacobians[0][1] = gy;
      jacobians[0][2] = gx * (-s * p_.x() - c * p_.y()) + gy * (c * p_.x() - s * p_.y());
    }
    return true;
  }

 private:
  const Interpolator* field_;
  Eigen::Vector2d p_;
  MapLimits limits_;
};

}  // namespace

void AlignmentConfig::validate() const {
  auto check = [](const char* field, double v) {
    if (!(v > 0.0 && std::isfinite(v)))
      throw std::invalid_argument(std::string("scan alignment: field '") + field +
                                  "': expected a positive number, got " + std::to_string(v));
  };
  check("max_range", max_range);
  check("weight_range", weight_range);
  if (!(range_exponent >= 0.0 && range_exponent <= 4.0))
    throw std::invalid_argument(
        "alignment: field 'range_exponent': expected a number in [0, 4], "
        "got " +
        std::to_string(range_exponent));
  check("robust_scale", robust_scale);
  check("inlier_cells", inlier_cells);
  check("min_inlier_share", min_inlier_share);
  check("min_points", min_points);
  check("max_iterations", max_iterations);
  check("point_stride", point_stride);
}

ScanAligner::ScanAligner(const OccupancyGrid& reference, const AlignmentConfig& config)
    : reference_(reference), config_(config) {
  config_.validate();
  const MapLimits& lim = reference.limits();
  cv::Mat free_mask(lim.height, lim.width, CV_8U);
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      const bool occ = reference.state(ix, iy) == CellState::kOccupied;
      free_mask.at<uint8_t>(iy, ix) = occ ? 0 : 255;
      occupied_ += occ;
    }
  cv::distanceTransform(free_mask, field_, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
}

bool ScanAligner::behindSeenSurface(int ix, int iy) const {
  const MapLimits& lim = reference_.limits();
  const float d = field_.at<float>(iy, ix);
  if (d > config_.robust_scale || ix < 1 || iy < 1 || ix + 1 >= lim.width || iy + 1 >= lim.height)
    return false;
  // Down the distance field to the nearest occupied cell, through the surface (at most a
  // few cells thick), to the first cell past it: seen there means the surface was seen from
  // that side, and the cell is behind it. Along a wall, past its mapped end, the walk runs
  // into the wall's own cells or into cells nobody saw.
  const double gx = field_.at<float>(iy, ix + 1) - field_.at<float>(iy, ix - 1);
  const double gy = field_.at<float>(iy + 1, ix) - field_.at<float>(iy - 1, ix);
  const double norm = std::hypot(gx, gy);
  if (norm < 1e-6) return false;
  const Eigen::Vector2d down = -lim.resolution * Eigen::Vector2d(gx, gy) / norm;
  const Eigen::Vector2d from = lim.cellCenter(ix, iy);
  bool in_surface = false;
  for (double t = 0.5; t <= d + kMaxSurfaceCells; t += 0.5) {  // half-cell steps
    const Eigen::Vector2d at = from + t * down;
    const int x = lim.cellX(at.x()), y = lim.cellY(at.y());
    if (!lim.contains(x, y)) return false;
    if (reference_.state(x, y) == CellState::kOccupied) {
      in_surface = true;
    } else if (in_surface) {
      return reference_.seen(x, y);
    }
  }
  return false;
}

double ScanAligner::distance(const Eigen::Vector2d& q) const {
  const MapLimits& lim = reference_.limits();
  const int ix = lim.cellX(q.x()), iy = lim.cellY(q.y());
  if (!lim.contains(ix, iy)) return 1e9;
  return field_.at<float>(iy, ix);
}

std::vector<Eigen::Vector2d> ScanAligner::points(const std::vector<const RadialMap*>& scans,
                                                 const Pose2& guess,
                                                 std::vector<double>* weights) const {
  // Obstacle points in the odometry frame; only those the reference can judge (see
  // AlignmentConfig::seen_points_only).
  const MapLimits& lim = reference_.limits();
  std::vector<Eigen::Vector2d> out;
  int hit = 0;
  for (const RadialMap* scan : scans)
    for (const RadialReading& r : scan->readings) {
      if (r.kind != RadialKind::kHit || r.range > config_.max_range) continue;
      if (hit++ % config_.point_stride != 0) continue;
      const Eigen::Vector2d in_robot =
          scan->sensor_origin + r.range * Eigen::Vector2d(std::cos(r.bearing), std::sin(r.bearing));
      const Eigen::Vector2d p = scan->odometry * in_robot;
      const Eigen::Vector2d q = guess * p;
      const int ix = lim.cellX(q.x()), iy = lim.cellY(q.y());
      if (!lim.contains(ix, iy)) continue;
      if (!reference_.seen(ix, iy) &&
          (config_.seen_points_only ? !behindSeenSurface(ix, iy)
                                    : field_.at<float>(iy, ix) > config_.robust_scale))
        continue;
      // Seen but undecided (neither free nor occupied): the reference has weak evidence of
      // something there, e.g. a wall's far part seen once at long range. Counted against the
      // nearest cell it is sure of, a point there is pulled back along the wall.
      if (config_.decided_points_only && reference_.seen(ix, iy) &&
          reference_.state(ix, iy) == CellState::kUnknown)
        continue;
      out.push_back(p);
      if (weights)
        weights->push_back(
            std::pow(std::min(1.0, config_.weight_range / r.range), config_.range_exponent));
    }
  return out;
}

std::vector<Eigen::Vector2d> hitPoints(const std::vector<const RadialMap*>& scans, double max_range,
                                       int stride) {
  std::vector<Eigen::Vector2d> out;
  int k = 0;
  for (const RadialMap* scan : scans)
    for (const RadialReading& r : scan->readings) {
      if (r.kind != RadialKind::kHit || r.range > max_range) continue;
      if (k++ % std::max(1, stride) != 0) continue;
      out.push_back(scan->odometry *
                    (scan->sensor_origin +
                     r.range * Eigen::Vector2d(std::cos(r.bearing), std::sin(r.bearing))));
    }
  return out;
}

std::vector<Eigen::Vector2d> ScanAligner::obstaclePoints(const std::vector<const RadialMap*>& scans,
                                                         int stride) const {
  return hitPoints(scans, config_.max_range, stride);
}

double ScanAligner::score(const std::vector<Eigen::Vector2d>& points, const Pose2& guess,
                          double within_cells) const {
  const double within = within_cells > 0.0 ? within_cells : config_.robust_scale;
  int near = 0;
  for (const Eigen::Vector2d& p : points) near += distance(guess * p) <= within;
  return points.empty() ? 0.0 : static_cast<double>(near) / points.size();
}

double ScanAligner::score(const std::vector<const RadialMap*>& scans, const Pose2& guess) const {
  return score(obstaclePoints(scans), guess);
}

AlignmentResult ScanAligner::align(const std::vector<const RadialMap*>& scans,
                                   const Pose2& guess) const {
  AlignmentResult result;
  if (occupied_ == 0) {
    result.message = "the reference map has no occupied cells";
    return result;
  }
  const MapLimits& lim = reference_.limits();
  const Field field(field_.ptr<float>(), 0, lim.height, 0, lim.width);
  const Interpolator interpolator(field);
  std::vector<double> weights;
  const std::vector<Eigen::Vector2d> pts = points(scans, guess, &weights);
  result.points = static_cast<int>(pts.size());
  if (result.points < config_.min_points) {
    result.message = std::to_string(result.points) + " obstacle points in the reference's view, " +
                     "expected at least " + std::to_string(config_.min_points);
    return result;
  }
  double pose[3] = {guess.x, guess.y, guess.theta};
  ceres::Problem problem;
  for (size_t i = 0; i < pts.size(); ++i) {
    ceres::LossFunction* loss = new ceres::TukeyLoss(config_.robust_scale);
    if (weights[i] < 1.0) loss = new ceres::ScaledLoss(loss, weights[i], ceres::TAKE_OWNERSHIP);
    problem.AddResidualBlock(new PointResidual(&interpolator, pts[i], lim), loss, pose);
  }
  ceres::Solver::Options options;
  options.max_num_iterations = config_.max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.linear_solver_type = ceres::DENSE_QR;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  result.iterations = static_cast<int>(summary.iterations.size());
  result.correction = Pose2(pose[0], pose[1], wrapAngle(pose[2]));
  // Inliers, their RMS and the information of the solution: J^T W J over the inliers.
  double sq = 0.0;
  const double* params[1] = {pose};
  for (size_t i = 0; i < pts.size(); ++i) {
    double d = 0.0, jac[3] = {0.0, 0.0, 0.0};
    double* jacobians[1] = {jac};
    PointResidual(&interpolator, pts[i], lim).Evaluate(params, &d, jacobians);
    if (std::abs(d) > config_.inlier_cells) continue;
    ++result.inliers;
    sq += d * d;
    const Eigen::Vector3d j(jac[0], jac[1], jac[2]);
    result.information += weights[i] * j * j.transpose();
  }
  result.rms_cells = result.inliers > 0 ? std::sqrt(sq / result.inliers) : 0.0;
  if (result.inliers < config_.min_inlier_share * result.points) {
    char share[32];
    std::snprintf(share, sizeof share, "%.2f", config_.min_inlier_share);
    result.message = std::to_string(result.inliers) + " of " + std::to_string(result.points) +
                     " points on the reference's obstacles, expected a share of at least " + share;
    return result;
  }
  result.ok = summary.IsSolutionUsable();
  if (!result.ok) result.message = "the solver failed: " + summary.message;
  return result;
}

Eigen::Matrix2d positionInformation(const AlignmentResult& alignment, const Eigen::Vector2d& at) {
  // Parameters of the correction C (x, y, theta; a point q maps to R q + t) against those of
  // the corrected point's position and a rotation about it: d(at) = dt + dtheta J (at - t),
  // so d(C) = A^-1 d(at, theta) with A = [I, J u; 0, 1], u = at - t.
  const Eigen::Vector2d u = at - alignment.correction.translation();
  Eigen::Matrix3d a_inv = Eigen::Matrix3d::Identity();
  a_inv(0, 2) = u.y();
  a_inv(1, 2) = -u.x();
  const Eigen::Matrix3d h = a_inv.transpose() * alignment.information * a_inv;
  Eigen::Matrix2d out = h.topLeftCorner<2, 2>();
  if (h(2, 2) > 0.0) out -= h.topRightCorner<2, 1>() * h.bottomLeftCorner<1, 2>() / h(2, 2);
  return out;
}

AlignmentResult alignScans(const std::vector<const RadialMap*>& scans,
                           const OccupancyGrid& reference, const Pose2& guess,
                           const AlignmentConfig& config) {
  return ScanAligner(reference, config).align(scans, guess);
}

}  // namespace coopmap

#include "core/correction/trajectory_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace coopmap {

TrajectoryError trajectoryError(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth,
                                const std::vector<double>& lengths_m, double stride_m) {
  if (estimate.size() != truth.size())
    throw std::invalid_argument("trajectoryError: " + std::to_string(estimate.size()) +
                                " estimated poses against " + std::to_string(truth.size()) +
                                " true ones");
  TrajectoryError e;
  const size_t n = truth.size();
  if (n == 0) return e;
  double sq = 0.0, sq_heading = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double d = std::hypot(estimate[i].x - truth[i].x, estimate[i].y - truth[i].y);
    sq += d * d;
    e.ate_max_m = std::max(e.ate_max_m, d);
    const double h = wrapAngle(estimate[i].theta - truth[i].theta) * 180.0 / M_PI;
    sq_heading += h * h;
  }
  e.ate_rmse_m = std::sqrt(sq / n);
  // Least-squares scale about the first pose: s = sum(a.b) / sum(a.a).
  double ab = 0.0, aa = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = estimate[i].translation() - estimate[0].translation();
    const Eigen::Vector2d b = truth[i].translation() - estimate[0].translation();
    ab += a.dot(b);
    aa += a.dot(a);
  }
  e.scale = aa > 0.0 ? ab / aa : 1.0;
  double sq_scaled = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p = estimate[0].translation() +
                              e.scale * (estimate[i].translation() - estimate[0].translation());
    sq_scaled += (p - truth[i].translation()).squaredNorm();
  }
  e.ate_scale_aligned_m = std::sqrt(sq_scaled / n);
  e.heading_rmse_deg = std::sqrt(sq_heading / n);

  std::vector<double> arc(n, 0.0);
  for (size_t i = 1; i < n; ++i)
    arc[i] = arc[i - 1] + std::hypot(truth[i].x - truth[i - 1].x, truth[i].y - truth[i - 1].y);
  double sum_t = 0.0, sum_r = 0.0;
  double next_start = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (arc[i] < next_start) continue;
    next_start = arc[i] + stride_m;
    for (double length : lengths_m) {
      const auto it = std::lower_bound(arc.begin() + i, arc.end(), arc[i] + length);
      if (it == arc.end()) continue;
      const size_t j = static_cast<size_t>(it - arc.begin());
      const Pose2 rel_true = truth[i].inverse() * truth[j];
      const Pose2 rel_est = estimate[i].inverse() * estimate[j];
      const Pose2 err = rel_est.inverse() * rel_true;
      sum_t += std::hypot(err.x, err.y) / length;
      sum_r += std::abs(err.theta) * 180.0 / M_PI / length;
      ++e.subpaths;
    }
  }
  if (e.subpaths > 0) {
    e.drift_percent = 100.0 * sum_t / e.subpaths;
    e.drift_deg_per_m = sum_r / e.subpaths;
  }
  return e;
}

}  // namespace coopmap

#include "core/correction/stereo_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/geometry/pose2.h"

namespace coopmap {

namespace {

// Obstacle points within max_range of the entries [from, to], each at its odometry pose: only
// matched surfaces (a floor's end lies where the floor stops being matched, which moves with
// the view, and its range error grows with depth as a scale error would).
std::vector<Eigen::Vector2d> pointsOf(const TraverseLog& log, size_t from, size_t to,
                                      double max_range) {
  std::vector<Eigen::Vector2d> out;
  for (size_t k = from; k <= to; ++k) {
    const RadialMap& scan = log.entries[k].scan;
    for (const RadialReading& r : scan.readings)
      if (r.kind == RadialKind::kHit && !r.floor_edge && r.range <= max_range)
        out.push_back(scan.odometry *
                      (scan.sensor_origin +
                       r.range * Eigen::Vector2d(std::cos(r.bearing), std::sin(r.bearing))));
  }
  return out;
}

// The earlier points as surfaces: each with the normal of the line fitted through its
// neighbours (none where they do not lie along a line), found through a hash of cells.
class Surfaces {
 public:
  Surfaces(std::vector<Eigen::Vector2d> points, double cell)
      : points_(std::move(points)), cell_(cell) {
    for (size_t i = 0; i < points_.size(); ++i) cells_[key(points_[i])].push_back(i);
    normals_.resize(points_.size(), Eigen::Vector2d::Zero());
    means_.resize(points_.size(), Eigen::Vector2d::Zero());
    for (size_t i = 0; i < points_.size(); ++i) {
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      std::vector<size_t> near;
      forNear(points_[i], cell_, [&](size_t j) { near.push_back(j); });
      if (near.size() < 4) continue;
      for (size_t j : near) mean += points_[j];
      mean /= static_cast<double>(near.size());
      Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
      for (size_t j : near) cov += (points_[j] - mean) * (points_[j] - mean).transpose();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
      // Along a line: the spread across it a small share of the spread along it.
      if (eig.eigenvalues()(0) > 0.04 * eig.eigenvalues()(1)) continue;
      normals_[i] = eig.eigenvectors().col(0);
      means_[i] = mean;
    }
  }
  // The nearest earlier point with a normal within `within` of p, or -1.
  long nearest(const Eigen::Vector2d& p, double within) const {
    long best = -1;
    double best_d2 = within * within;
    forNear(p, within, [&](size_t j) {
      const double d2 = (points_[j] - p).squaredNorm();
      if (d2 < best_d2 && normals_[j].squaredNorm() > 0.0) {
        best_d2 = d2;
        best = static_cast<long>(j);
      }
    });
    return best;
  }
  const Eigen::Vector2d& point(long i) const { return points_[static_cast<size_t>(i)]; }
  const Eigen::Vector2d& normal(long i) const { return normals_[static_cast<size_t>(i)]; }
  // The centroid of the neighbours the normal was fitted through, on the surface's middle:
  // the nearest point itself lies anywhere across a noisy surface's thickness, and a later
  // point's residual to it leans toward the shift the match stands at.
  const Eigen::Vector2d& centre(long i) const { return means_[static_cast<size_t>(i)]; }

 private:
  int64_t key(const Eigen::Vector2d& p) const { return key(cellOf(p.x()), cellOf(p.y())); }
  static int64_t key(int64_t x, int64_t y) { return (x << 32) ^ (y & 0xffffffff); }
  int64_t cellOf(double v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
  template <typename F>
  void forNear(const Eigen::Vector2d& p, double radius, F&& f) const {
    const int64_t x0 = cellOf(p.x() - radius), x1 = cellOf(p.x() + radius);
    const int64_t y0 = cellOf(p.y() - radius), y1 = cellOf(p.y() + radius);
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y) {
        const auto it = cells_.find(key(x, y));
        if (it == cells_.end()) continue;
        for (size_t j : it->second)
          if ((points_[j] - p).squaredNorm() <= radius * radius) f(j);
      }
  }
  std::vector<Eigen::Vector2d> points_;
  std::vector<Eigen::Vector2d> normals_;
  std::vector<Eigen::Vector2d> means_;
  double cell_;
  std::unordered_map<int64_t, std::vector<size_t>> cells_;
};

}  // namespace

void StereoScaleConfig::validate() const {
  auto fail = [](const char* field, const std::string& expected) {
    throw std::invalid_argument(std::string("stereo scale: field '") + field + "': expected " +
                                expected);
  };
  if (!(min_gap_m > 0.0 && max_gap_m >= min_gap_m && std::isfinite(max_gap_m)))
    fail("min_gap_m/max_gap_m", "0 < min_gap_m <= max_gap_m");
  if (half_window < 0 || half_window > 20) fail("half_window", "an integer in [0, 20]");
  if (step < 1) fail("step", "an integer >= 1");
  if (!(max_turn_rad > 0.0)) fail("max_turn_rad", "a positive angle");
  if (!(max_range_m > 0.0)) fail("max_range_m", "positive metres");
  if (!(match_m > 0.0)) fail("match_m", "positive metres");
  if (!(normal_radius_m > 0.0)) fail("normal_radius_m", "positive metres");
  if (!(max_sigma_m > 0.0)) fail("max_sigma_m", "positive metres");
  if (max_iterations < 1) fail("max_iterations", "an integer >= 1");
  if (!(max_shift_m > 0.0)) fail("max_shift_m", "positive metres");
}

void StereoScale::add(const StereoScale& other) {
  pairs_measured.insert(pairs_measured.end(), other.pairs_measured.begin(),
                        other.pairs_measured.end());
}

namespace {

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

double StereoScale::scale() const {
  if (pairs_measured.empty()) return 0.0;
  std::vector<double> values;
  for (const Pair& p : pairs_measured) values.push_back(p.over_count);
  double k = median(values);  // a robust start
  // The spread between pairs, tau: the smallest at which the pairs' residuals, each over
  // sqrt(sigma^2 + tau^2), have the median absolute value of a unit normal (0.6745).
  std::vector<double> z(pairs_measured.size());
  auto medianZ = [&](double tau) {
    for (size_t i = 0; i < pairs_measured.size(); ++i)
      z[i] = std::abs(pairs_measured[i].over_count - k) / std::hypot(pairs_measured[i].sigma, tau);
    return median(z);
  };
  double tau = 0.0;
  if (medianZ(0.0) > 0.6745) {
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (medianZ(mid) > 0.6745) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    tau = hi;
  }
  // Huber's weights (1.345 standardised residuals) on the pairs' variances, from the median.
  for (int it = 0; it < 50; ++it) {
    double sum = 0.0, weights = 0.0;
    for (const Pair& p : pairs_measured) {
      const double var = p.sigma * p.sigma + tau * tau;
      const double r = std::abs(p.over_count - k) / std::sqrt(var);
      const double w = (r <= 1.345 ? 1.0 : 1.345 / r) / var;
      sum += w * p.over_count;
      weights += w;
    }
    const double next = weights > 0.0 ? sum / weights : k;
    const bool settled = std::abs(next - k) < 1e-9;
    k = next;
    if (settled) break;
  }
  return k;
}

StereoScale stereoDistanceScale(const TraverseLog& log, const StereoScaleConfig& config) {
  config.validate();
  StereoScale out;
  const size_t n = log.entries.size();
  const size_t half = static_cast<size_t>(config.half_window);
  if (n < 2 * half + 2) return out;
  auto odometry = [&](size_t i) -> const Pose2& { return log.entries[i].scan.odometry; };
  std::vector<double> arc(n, 0.0);
  for (size_t i = 1; i < n; ++i)
    arc[i] = arc[i - 1] + (odometry(i).translation() - odometry(i - 1).translation()).norm();
  for (size_t i = half; i + half < n; i += static_cast<size_t>(config.step)) {
    size_t j = i;
    while (j < n && arc[j] - arc[i] < config.min_gap_m) ++j;
    if (j + half >= n || arc[j] - arc[i] > config.max_gap_m) continue;
    double turn = 0.0;
    for (size_t k = i - half + 1; k <= j + half; ++k)
      turn += std::abs(wrapAngle(odometry(k).theta - odometry(k - 1).theta));
    if (turn > config.max_turn_rad) continue;
    const Eigen::Vector2d d_o = odometry(j).translation() - odometry(i).translation();
    if (d_o.norm() < 0.8 * config.min_gap_m) continue;  // the arc wandered: not straight
    const Surfaces earlier(pointsOf(log, i - half, i + half, config.max_range_m),
                           config.normal_radius_m);
    const std::vector<Eigen::Vector2d> later =
        pointsOf(log, j - half, j + half, config.max_range_m);
    // Point to line: the later points moved by a turn `dtheta` about the later entry and a
    // shift t (the odometry's heading drifts a few milliradians over the pair, and a face
    // across the travel off to one side would take that turn as a shift along it);
    // Huber-weighted residuals.
    const Eigen::Vector2d pivot = odometry(j).translation();
    Eigen::Vector3d x = Eigen::Vector3d::Zero();  // t.x, t.y, dtheta
    Eigen::Matrix3d info = Eigen::Matrix3d::Zero();
    double sq = 0.0;
    int matched = 0;
    auto moved = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
      const double c = std::cos(x(2)), sn = std::sin(x(2));
      const Eigen::Vector2d v = p - pivot;
      return Eigen::Vector2d(c * v.x() - sn * v.y(), sn * v.x() + c * v.y()) + pivot + x.head<2>();
    };
    for (int it = 0; it < config.max_iterations; ++it) {
      Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
      Eigen::Vector3d b = Eigen::Vector3d::Zero();
      sq = 0.0;
      matched = 0;
      for (const Eigen::Vector2d& p : later) {
        const Eigen::Vector2d m = moved(p);
        const long q = earlier.nearest(m, config.match_m);
        if (q < 0) continue;
        const Eigen::Vector2d& nq = earlier.normal(q);
        const double r = nq.dot(m - earlier.centre(q));
        const Eigen::Vector2d arm = m - pivot - x.head<2>();
        const Eigen::Vector3d jac(nq.x(), nq.y(), nq.x() * -arm.y() + nq.y() * arm.x());
        const double w = std::abs(r) <= 0.02 ? 1.0 : 0.02 / std::abs(r);
        a += w * jac * jac.transpose();
        b += w * r * jac;
        sq += w * r * r;
        ++matched;
      }
      if (matched < 20 || std::abs(a.determinant()) < 1e-12) break;
      const Eigen::Vector3d step = -a.ldlt().solve(b);
      x += step;
      info = a;
      if (x.head<2>().norm() > config.max_shift_m) break;
      if (step.head<2>().norm() < 1e-5 && std::abs(step(2)) < 1e-6) break;
    }
    // Farther than any plausible odometry error over the gap: it matched other surfaces.
    if (matched < 20 || info(2, 2) <= 0.0 || x.head<2>().norm() > config.max_shift_m) continue;
    const double sigma_r = std::sqrt(sq / matched);
    // The position's information with the turn left free (Schur complement).
    const Eigen::Matrix2d info_xy = info.topLeftCorner<2, 2>() - info.topRightCorner<2, 1>() *
                                                                     info.bottomLeftCorner<1, 2>() /
                                                                     info(2, 2);
    const Eigen::Vector2d u = d_o.normalized();
    const double info_u = u.dot(info_xy * u) / std::max(sigma_r * sigma_r, 1e-6);
    if (!(info_u > 0.0) || 1.0 / std::sqrt(info_u) > config.max_sigma_m) continue;
    const Eigen::Vector2d t = x.head<2>();
    const double d_s = u.dot(d_o + t);
    const double d_odometry = u.dot(d_o);
    // The over-count and its 1-sigma through the stereo displacement's.
    out.pairs_measured.push_back(
        {d_odometry / d_s - 1.0, d_odometry / (d_s * d_s * std::sqrt(info_u))});
  }
  return out;
}

}  // namespace coopmap

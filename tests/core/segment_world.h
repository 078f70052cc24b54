// A 2D world of wall segments for synthetic radial maps: where a ray meets them.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/pose2.h"
#include "core/perception/radial_map.h"

namespace coopmap::test {

struct Segment {
  Eigen::Vector2d a, b;
};

// Distance from `origin` along the unit direction `dir` to the nearest segment within
// max_range, or -1 when there is none.
inline double castRay(const std::vector<Segment>& walls, const Eigen::Vector2d& origin,
                      const Eigen::Vector2d& dir, double max_range) {
  double best = -1.0;
  for (const Segment& w : walls) {
    const Eigen::Vector2d e = w.b - w.a;
    const double den = dir.x() * e.y() - dir.y() * e.x();
    if (std::abs(den) < 1e-12) continue;
    const Eigen::Vector2d d = w.a - origin;
    const double t = (d.x() * e.y() - d.y() * e.x()) / den;
    const double u = (d.x() * dir.y() - d.y() * dir.x()) / den;
    if (t > 0.0 && t <= max_range && u >= 0.0 && u <= 1.0 && (best < 0.0 || t < best)) best = t;
  }
  return best;
}

// What a 60-degree camera at `pose` sees of the segments: one reading per column (80),
// hits within 4 m with a 1 cm range sigma, "beyond" where nothing is that near.
inline RadialMap cameraScan(const Pose2& pose, const std::vector<Segment>& walls) {
  RadialMap m;
  m.odometry = pose;
  m.max_range = 4.0;
  for (int k = 0; k < 80; ++k) {
    RadialReading r;
    r.bearing = (k - 39.5) / 79.0 * (M_PI / 3.0);
    const double a = pose.theta + r.bearing;
    const double t = castRay(walls, pose.translation(), {std::cos(a), std::sin(a)}, 4.0);
    r.range = t < 0.0 ? 4.0 : t;
    r.kind = t < 0.0 ? RadialKind::kBeyond : RadialKind::kHit;
    r.sigma = 0.01;
    m.readings.push_back(r);
  }
  return m;
}

}  // namespace coopmap::test

// A 2D world of wall segments for synthetic radial maps: where a ray meets them.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

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

}  // namespace coopmap::test

#include "core/planning/keep_clear.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace coopmap {
namespace {

struct Ends {
  Eigen::Vector2d from, to;
  double from_clearance = 0.0, to_clearance = 0.0;
  double want = 0.0, ramp = 1.0;
  double cap(const Eigen::Vector2d& p) const {
    return std::min(
        {want, from_clearance + ramp * (p - from).norm(), to_clearance + ramp * (p - to).norm()});
  }
};

// The shortfall of one segment, sampled every half cell; `at` the worst point's fraction.
struct SegmentShortfall {
  double integral = 0.0;
  double worst = 0.0;
  double at = 0.5;
};

SegmentShortfall segmentShortfall(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                  const PlanningMap& map, const Ends& ends) {
  SegmentShortfall s;
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * map.limits().resolution))));
  const double ds = len / n;
  for (int k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    const Eigen::Vector2d p = a + t * (b - a);
    const double short_by = std::max(0.0, ends.cap(p) - clearanceAt(map, p));
    s.integral += short_by * ((k == 0 || k == n) ? 0.5 * ds : ds);
    if (short_by > s.worst) {
      s.worst = short_by;
      s.at = t;
    }
  }
  return s;
}

// Two segments' shortfall together (a waypoint's two sides).
SegmentShortfall joined(const SegmentShortfall& x, const SegmentShortfall& y) {
  return {x.integral + y.integral, std::max(x.worst, y.worst), 0.0};
}

// From p up the clearance map in half-cell steps until the wanted clearance, a ridge (the
// middle of a passage), or twice the distance the clearance is short by.
Eigen::Vector2d climb(const PlanningMap& map, const Eigen::Vector2d& p, double want) {
  const double h = 0.5 * map.limits().resolution;
  const double c0 = clearanceAt(map, p);
  const double max_move = 2.0 * std::max(0.0, want - c0) + h;
  Eigen::Vector2d q = p;
  double c = c0;
  for (double moved = 0.0; moved < max_move && c < want; moved += h) {
    const Eigen::Vector2d ex(h, 0.0), ey(0.0, h);
    const Eigen::Vector2d g((clearanceAt(map, q + ex) - clearanceAt(map, q - ex)) / (2.0 * h),
                            (clearanceAt(map, q + ey) - clearanceAt(map, q - ey)) / (2.0 * h));
    if (g.norm() < 1e-6) break;
    const Eigen::Vector2d next = q + h * g.normalized();
    const double cn = clearanceAt(map, next);
    if (cn <= c + 1e-9) break;
    q = next;
    c = cn;
  }
  return q;
}

// The change from `before` to `after` is worth making: less shortfall in all, and no worse
// at its worst.
bool better(const SegmentShortfall& after, const SegmentShortfall& before, double tol) {
  return after.integral < before.integral - tol * tol && after.worst <= before.worst + 1e-9;
}

}  // namespace

double clearanceAt(const PlanningMap& map, const Eigen::Vector2d& p) {
  const MapLimits& l = map.limits();
  const Eigen::Vector2d u = (p - l.origin) / l.resolution - Eigen::Vector2d(0.5, 0.5);
  const int x0 = static_cast<int>(std::floor(u.x())), y0 = static_cast<int>(std::floor(u.y()));
  const double fx = u.x() - x0, fy = u.y() - y0;
  auto c = [&](int ix, int iy) { return l.contains(ix, iy) ? map.clearance(ix, iy) : 0.0; };
  return (1.0 - fx) * (1.0 - fy) * c(x0, y0) + fx * (1.0 - fy) * c(x0 + 1, y0) +
         (1.0 - fx) * fy * c(x0, y0 + 1) + fx * fy * c(x0 + 1, y0 + 1);
}

Shortfall shortfallOf(const std::vector<Eigen::Vector2d>& w, const PlanningMap& map,
                      const KeepClearConfig& config) {
  Shortfall out;
  if (w.size() < 2) return out;
  const Ends ends{
      w.front(),        w.back(),   clearanceAt(map, w.front()), clearanceAt(map, w.back()),
      config.clearance, config.ramp};
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    const SegmentShortfall s = segmentShortfall(w[i], w[i + 1], map, ends);
    out.integral += s.integral;
    out.worst = std::max(out.worst, s.worst);
  }
  return out;
}

std::vector<Eigen::Vector2d> keepClear(std::vector<Eigen::Vector2d> w, const PlanningMap& map,
                                       const KeepClearConfig& config) {
  if (w.size() < 2 || !(config.clearance > 0.0)) return w;
  const Ends ends{
      w.front(),        w.back(),   clearanceAt(map, w.front()), clearanceAt(map, w.back()),
      config.clearance, config.ramp};
  const double tol = 0.5 * map.limits().resolution;
  auto shortfall = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return segmentShortfall(a, b, map, ends);
  };
  int added = 0;
  for (int pass = 0; pass < config.passes; ++pass) {
    bool changed = false;
    // Waypoints up the clearance map.
    for (size_t i = 1; i + 1 < w.size(); ++i) {
      const SegmentShortfall before = joined(shortfall(w[i - 1], w[i]), shortfall(w[i], w[i + 1]));
      if (before.worst <= tol) continue;
      const Eigen::Vector2d q = climb(map, w[i], config.clearance);
      if ((q - w[i]).norm() < 1e-9 || !map.segmentFree(w[i - 1], q) ||
          !map.segmentFree(q, w[i + 1]))
        continue;
      if (better(joined(shortfall(w[i - 1], q), shortfall(q, w[i + 1])), before, tol)) {
        w[i] = q;
        changed = true;
      }
    }
    // New waypoints where a segment runs close to something, moved up the clearance map.
    std::vector<Eigen::Vector2d> out{w.front()};
    for (size_t i = 0; i + 1 < w.size(); ++i) {
      const Eigen::Vector2d &a = w[i], &b = w[i + 1];
      const SegmentShortfall before = shortfall(a, b);
      if (added < config.max_added && before.worst > tol) {
        const Eigen::Vector2d q = climb(map, a + before.at * (b - a), config.clearance);
        if ((q - a).norm() > tol && (q - b).norm() > tol && map.segmentFree(a, q) &&
            map.segmentFree(q, b) &&
            better(joined(shortfall(a, q), shortfall(q, b)), before, tol)) {
          out.push_back(q);
          ++added;
          changed = true;
        }
      }
      out.push_back(b);
    }
    w = std::move(out);
    if (!changed) break;
  }
  // Waypoints that no longer earn their turn: dropped where the straight way past them is
  // free and no worse.
  for (size_t i = 1; i + 1 < w.size();) {
    const SegmentShortfall with = joined(shortfall(w[i - 1], w[i]), shortfall(w[i], w[i + 1]));
    const SegmentShortfall without = shortfall(w[i - 1], w[i + 1]);
    if (map.segmentFree(w[i - 1], w[i + 1]) && without.integral <= with.integral + tol * tol &&
        without.worst <= with.worst + 1e-9)
      w.erase(w.begin() + static_cast<std::ptrdiff_t>(i));
    else
      ++i;
  }
  return w;
}

}  // namespace coopmap

#include "core/planning/frontiers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace coopmap {

void FrontierConfig::validate() const {
  auto bad = [](const std::string& field, const std::string& expected, double v) {
    throw std::invalid_argument("frontier config: field '" + field + "': expected " + expected +
                                ", got " + std::to_string(v));
  };
  if (min_cells < 1) bad("min_cells", "an integer >= 1", min_cells);
  if (!(gain_radius > 0.0)) bad("gain_radius", "a positive number", gain_radius);
  if (!(goal_search_radius > 0.0))
    bad("goal_search_radius", "a positive number", goal_search_radius);
  if (!(cost_weight >= 0.0)) bad("cost_weight", "a number >= 0", cost_weight);
  if (!(blacklist_radius >= 0.0)) bad("blacklist_radius", "a number >= 0", blacklist_radius);
  if (max_plans < 1) bad("max_plans", "an integer >= 1", max_plans);
  if (!(claim_radius >= 0.0)) bad("claim_radius", "a number >= 0", claim_radius);
  if (!(fringe_clearance >= 0.0)) bad("fringe_clearance", "a number >= 0", fringe_clearance);
  if (!(doorway_width >= 0.0)) bad("doorway_width", "a number >= 0", doorway_width);
  if (!(doorway_min_width >= 0.0)) bad("doorway_min_width", "a number >= 0", doorway_min_width);
}

namespace {

// Whether cell (ix, iy) lies between two occupied cells on opposite sides, along a grid
// axis or a diagonal, whose gap (the distance between them less a cell) is within
// [doorway_min_width, doorway_width].
bool inOpening(const OccupancyGrid& grid, int ix, int iy, const FrontierConfig& config) {
  if (!(config.doorway_width > 0.0)) return false;
  const MapLimits& lim = grid.limits();
  const int dirs[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  for (const auto& d : dirs) {
    const double step = lim.resolution * std::hypot(d[0], d[1]);
    const int reach = static_cast<int>(config.doorway_width / step) + 1;
    // Steps to the first occupied cell that way, or 0 when none within reach.
    auto occupiedAt = [&](int sx, int sy) {
      for (int k = 1; k <= reach; ++k) {
        const int jx = ix + k * sx, jy = iy + k * sy;
        if (!lim.contains(jx, jy)) return 0;
        if (grid.state(jx, jy) == CellState::kOccupied) return k;
      }
      return 0;
    };
    const int a = occupiedAt(d[0], d[1]);
    if (a == 0) continue;
    const int b = occupiedAt(-d[0], -d[1]);
    if (b == 0) continue;
    const double gap = (a + b - 1) * step;
    if (gap >= config.doorway_min_width && gap <= config.doorway_width) return true;
  }
  return false;
}

// Open unknown: never observed, or observed too little to tell free from occupied, at least
// `clearance` (m) from obstacles and joined (4-connected, through such cells) to never-observed
// ones. The far ends of long stereo rays leave a fringe of the latter between free and
// unobserved space, which once hid whole corridors from the explorer (no free cell touched an
// unobserved one). Uncertain cells beside obstacles (stereo's bands along walls and
// furniture) are left out: driving up to them shows little and bumps into things. With
// clearance 0, only never-observed cells. Uncertain cells in an opening (see inOpening) are
// open however near the obstacles either side.
GridU8 openUnknown(const OccupancyGrid& grid, const FrontierConfig& config) {
  const double clearance = config.fringe_clearance;
  const MapLimits& lim = grid.limits();
  const int w = lim.width, h = lim.height;
  GridU8 open(lim, 0);
  for (int iy = 0; iy < h; ++iy)
    for (int ix = 0; ix < w; ++ix) open.at(ix, iy) = !grid.seen(ix, iy);
  const int keep = static_cast<int>(std::ceil(clearance / lim.resolution));
  if (keep <= 0) return open;
  GridU8 near_obstacle(lim, 0);
  std::vector<std::pair<int, int>> ring, next;
  for (int iy = 0; iy < h; ++iy)
    for (int ix = 0; ix < w; ++ix)
      if (grid.state(ix, iy) == CellState::kOccupied) {
        near_obstacle.at(ix, iy) = 1;
        ring.push_back({ix, iy});
      }
  for (int step = 0; step < keep && !ring.empty(); ++step) {
    next.clear();
    for (const auto& [x, y] : ring)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int jx = x + dx, jy = y + dy;
          if (lim.contains(jx, jy) && !near_obstacle.at(jx, jy)) {
            near_obstacle.at(jx, jy) = 1;
            next.push_back({jx, jy});
          }
        }
    ring.swap(next);
  }
  std::vector<std::pair<int, int>> todo;
  for (int iy = 0; iy < h; ++iy)
    for (int ix = 0; ix < w; ++ix)
      if (open.at(ix, iy)) todo.push_back({ix, iy});
  while (!todo.empty()) {
    const auto [x, y] = todo.back();
    todo.pop_back();
    const int n[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& d : n) {
      const int jx = x + d[0], jy = y + d[1];
      if (lim.contains(jx, jy) && !open.at(jx, jy) && grid.state(jx, jy) == CellState::kUnknown &&
          (!near_obstacle.at(jx, jy) || inOpening(grid, jx, jy, config))) {
        open.at(jx, jy) = 1;
        todo.push_back({jx, jy});
      }
    }
  }
  return open;
}

}  // namespace

std::vector<Frontier> findFrontiers(const OccupancyGrid& grid, const PlanningMap& planning,
                                    const Eigen::Vector2d& robot, const FrontierConfig& config) {
  config.validate();
  const MapLimits& lim = grid.limits();
  if (planning.limits().width != lim.width || planning.limits().height != lim.height)
    throw std::invalid_argument("findFrontiers: the planning map's limits differ from the grid's");
  const int w = lim.width, h = lim.height;
  const GridU8 open = openUnknown(grid, config);
  auto unknown = [&](int ix, int iy) { return open.at(ix, iy) != 0; };
  auto isFrontier = [&](int ix, int iy) {
    if (grid.state(ix, iy) != CellState::kFree) return false;
    const int n[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& d : n) {
      const int jx = ix + d[0], jy = iy + d[1];
      if (lim.contains(jx, jy) && unknown(jx, jy)) return true;
    }
    return false;
  };
  GridU8 mark(lim, 0);
  for (int iy = 0; iy < h; ++iy)
    for (int ix = 0; ix < w; ++ix) mark.at(ix, iy) = isFrontier(ix, iy);

  const int robot_region = planning.region(lim.cellX(robot.x()), lim.cellY(robot.y()));
  std::vector<Frontier> out;
  std::vector<std::pair<int, int>> stack;
  for (int iy = 0; iy < h; ++iy)
    for (int ix = 0; ix < w; ++ix) {
      if (mark.at(ix, iy) != 1) continue;
      Frontier f;
      mark.at(ix, iy) = 2;
      stack.assign(1, {ix, iy});
      while (!stack.empty()) {  // 8-connected group
        const auto [cx, cy] = stack.back();
        stack.pop_back();
        f.cells.push_back(lim.cellCenter(cx, cy));
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int jx = cx + dx, jy = cy + dy;
            if (lim.contains(jx, jy) && mark.at(jx, jy) == 1) {
              mark.at(jx, jy) = 2;
              stack.push_back({jx, jy});
            }
          }
      }
      if (static_cast<int>(f.cells.size()) < config.min_cells) continue;
      for (const Eigen::Vector2d& c : f.cells) f.centroid += c;
      f.centroid /= static_cast<double>(f.cells.size());
      // Gain: never-observed cells around the centroid (cells observed but not known are
      // mostly beside obstacles, where stereo leaves them uncertain: a look more rarely helps).
      const int r = static_cast<int>(std::ceil(config.gain_radius / lim.resolution));
      const int gx = lim.cellX(f.centroid.x()), gy = lim.cellY(f.centroid.y());
      for (int jy = gy - r; jy <= gy + r; ++jy)
        for (int jx = gx - r; jx <= gx + r; ++jx)
          if (lim.contains(jx, jy) && !grid.seen(jx, jy) &&
              (lim.cellCenter(jx, jy) - f.centroid).norm() <= config.gain_radius)
            ++f.gain;
      // Goal: the free cell, reachable from the robot, nearest to one of the frontier's cells
      // (nearest to the centroid among ties in distance bands of a cell).
      if (robot_region > 0) {
        const int s = static_cast<int>(std::ceil(config.goal_search_radius / lim.resolution));
        double best = 1e300;
        for (int jy = gy - s; jy <= gy + s; ++jy)
          for (int jx = gx - s; jx <= gx + s; ++jx) {
            if (planning.region(jx, jy) != robot_region) continue;
            const Eigen::Vector2d c = lim.cellCenter(jx, jy);
            const double d = (c - f.centroid).norm();
            if (d > config.goal_search_radius) continue;
            if (d < best) {
              best = d;
              f.goal = c;
              f.has_goal = true;
            }
          }
      }
      out.push_back(std::move(f));
    }
  return out;
}

FrontierExplorer::FrontierExplorer(const FrontierConfig& frontiers, const PlannerConfig& planner)
    : config_(frontiers), planner_(planner) {
  config_.validate();
}

bool FrontierExplorer::near(const std::vector<Eigen::Vector2d>& places, const Eigen::Vector2d& goal,
                            double radius) {
  for (const Eigen::Vector2d& b : places)
    if ((b - goal).norm() <= radius) return true;
  return false;
}

bool FrontierExplorer::reached(const Eigen::Vector2d& goal) const {
  return near(reached_, goal, config_.blacklist_radius);
}

bool FrontierExplorer::blacklisted(const Eigen::Vector2d& goal) const {
  return reached(goal) || near(blacklist_, goal, config_.blacklist_radius);
}

double FrontierExplorer::claimFactor(const Eigen::Vector2d& goal,
                                     const std::vector<Eigen::Vector2d>& claimed) const {
  double factor = 1.0;
  if (config_.claim_radius <= 0.0) return factor;
  for (const Eigen::Vector2d& c : claimed)
    factor = std::min(factor, (c - goal).norm() / config_.claim_radius);
  return factor;
}

ExploreStep FrontierExplorer::next(const OccupancyGrid& grid, const PlanningMap& planning,
                                   const Pose2& robot,
                                   const std::vector<Eigen::Vector2d>& claimed) {
  if (!planning.freeAt(robot.translation())) {
    ExploreStep step;
    step.status = ExploreStatus::kBlocked;
    step.reason = "the robot stands on a blocked cell";
    return step;
  }
  FrontierConfig plain = config_;
  plain.fringe_clearance = 0.0;
  ExploreStep step = nextWith(plain, grid, planning, robot, claimed);
  if (step.status == ExploreStatus::kDone && config_.fringe_clearance > 0.0)
    step = nextWith(config_, grid, planning, robot, claimed);
  return step;
}

ExploreStep FrontierExplorer::nextWith(const FrontierConfig& config, const OccupancyGrid& grid,
                                       const PlanningMap& planning, const Pose2& robot,
                                       const std::vector<Eigen::Vector2d>& claimed) {
  ExploreStep step;
  const std::vector<Frontier> frontiers =
      findFrontiers(grid, planning, robot.translation(), config);
  step.frontiers = static_cast<int>(frontiers.size());
  // Candidates by straight-line utility first; only the best few are planned.
  struct Candidate {
    const Frontier* f;
    double utility;
    double claim;
  };
  std::vector<Candidate> candidates;
  for (const Frontier& f : frontiers) {
    if (!f.has_goal || f.gain == 0 || blacklisted(f.goal)) continue;
    const double d = (f.goal - robot.translation()).norm();
    const double claim = claimFactor(f.goal, claimed);
    candidates.push_back({&f, claim * f.gain / (1.0 + config_.cost_weight * d), claim});
  }
  if (candidates.empty()) {
    if (frontiers.empty()) {
      step.reason = "no frontier left";
      return step;
    }
    // Where they are and why none is a goal: for people reading the mission's last event.
    step.reason = std::to_string(frontiers.size()) +
                  " frontiers, none with a reachable goal not blacklisted:";
    char buf[96];
    for (const Frontier& f : frontiers) {
      const bool seen_from_goal = f.has_goal && reached(f.goal);
      std::snprintf(buf, sizeof buf, " (%.1f, %.1f) %s;", f.centroid.x(), f.centroid.y(),
                    !f.has_goal      ? "no reachable goal"
                    : f.gain == 0    ? "nothing unknown near"
                    : seen_from_goal ? "looked from its goal before"
                                     : "goal blacklisted");
      step.reason += buf;
      step.failed_left += f.gain > 0 && !seen_from_goal;
      if (!f.has_goal || seen_from_goal) step.out_of_reach.push_back(f);
    }
    step.reason.pop_back();
    return step;
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.utility > b.utility; });
  double best = -1.0;
  for (size_t k = 0; k < candidates.size() && static_cast<int>(k) < config_.max_plans; ++k) {
    const Frontier& f = *candidates[k].f;
    const double claim = candidates[k].claim;
    PlanResult plan = planner_.plan(planning, robot, f.goal);
    if (!plan.solved()) {
      blacklist(f.goal);  // unreachable now; not fatal
      continue;
    }
    const double utility = claim * f.gain / (1.0 + config_.cost_weight * plan.path.length());
    if (utility > best) {
      best = utility;
      step.status = ExploreStatus::kGoal;
      step.claim_factor = claim;
      step.frontier = f;
      step.plan = std::move(plan);
    }
  }
  if (step.status == ExploreStatus::kDone) {
    step.reason = "no plan to any of the " + std::to_string(candidates.size()) + " frontiers";
    step.failed_left = static_cast<int>(candidates.size());
  }
  return step;
}

}  // namespace coopmap

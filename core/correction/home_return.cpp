#include "core/correction/home_return.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace coopmap {

namespace {

MapLimits localLimits(const Eigen::Vector2d& center, const HomeReturnConfig& config) {
  const Eigen::Vector2d half(config.local_radius, config.local_radius);
  return MapLimits::covering(center - half, center + half, config.resolution);
}

CornerConfig cornerConfig(const HomeReturnConfig& config, double arm_length) {
  CornerConfig c = config.corners;
  c.arm_cells = arm_length / config.resolution;
  return c;
}

}  // namespace

void HomeReturnConfig::validate() const {
  auto check = [](const char* field, double v) {
    if (!(v > 0.0 && std::isfinite(v)))
      throw std::invalid_argument(std::string("home return: field '") + field +
                                  "': expected a positive number, got " + std::to_string(v));
  };
  check("resolution", resolution);
  check("local_radius", local_radius);
  check("turn_radius", turn_radius);
  check("facing_half_angle", facing_half_angle);
  check("register_radius", register_radius);
  check("register_max_turn", register_max_turn);
  check("max_separation_error", max_separation_error);
  check("max_correction_rad", max_correction_rad);
  check("max_correction_m", max_correction_m);
  if (!(search_radius >= 0.0))
    throw std::invalid_argument("home return: field 'search_radius': expected a number >= 0, got " +
                                std::to_string(search_radius));
}

const char* toString(HomeReturnStatus s) {
  switch (s) {
    case HomeReturnStatus::kOk:
      return "ok";
    case HomeReturnStatus::kNoReturnTurn:
      return "no turn in place at the end of the log";
    case HomeReturnStatus::kHomeBaseNotFound:
      return "home base not found in the return turn's map";
  }
  return "?";
}

std::vector<size_t> turnInPlaceEntries(const TraverseLog& log, bool at_end, double turn_radius) {
  std::vector<size_t> out;
  const size_t n = log.entries.size();
  if (n == 0) return out;
  // At the end, the turn is anchored at the last entry that turned: a robot standing after
  // its turn may be nudged (by a teammate, a person) and is then no longer where it turned.
  size_t anchor = at_end ? n - 1 : 0;
  if (at_end)
    for (size_t i = n - 1; i > 0; --i)
      if (std::abs(wrapAngle(log.entries[i].scan.odometry.theta -
                             log.entries[i - 1].scan.odometry.theta)) > 1e-3) {
        anchor = i;
        break;
      }
  const Pose2 a = log.entries[anchor].scan.odometry;
  auto near = [&](size_t i) {
    const Pose2& p = log.entries[i].scan.odometry;
    return std::hypot(p.x - a.x, p.y - a.y) < turn_radius;
  };
  if (at_end) {
    size_t i = anchor + 1;
    while (i > 0 && near(i - 1)) --i;
    for (size_t j = i; j < n && (j <= anchor || near(j)); ++j) out.push_back(j);
  } else {
    for (size_t i = 0; i < n && near(i); ++i) out.push_back(i);
  }
  return out;
}

std::vector<size_t> entriesFacing(const TraverseLog& log, const std::vector<size_t>& entries,
                                  const Eigen::Vector2d& target, double half_angle) {
  std::vector<size_t> out;
  for (size_t i : entries) {
    const Pose2& p = log.entries[i].scan.odometry;
    const Eigen::Vector2d to = target - p.translation();
    if (std::abs(wrapAngle(std::atan2(to.y(), to.x()) - p.theta)) < half_angle) out.push_back(i);
  }
  return out;
}

OccupancyGrid localMap(const TraverseLog& log, const std::vector<size_t>& entries,
                       const MapLimits& limits, const OccupancyConfig& config) {
  OccupancyGrid grid(limits, config);
  for (size_t i : entries) grid.insert(log.entries[i].scan, log.entries[i].scan.odometry);
  return grid;
}

OccupancyGrid localMap(const TraverseLog& log, const MapLimits& limits,
                       const OccupancyConfig& config) {
  OccupancyGrid grid(limits, config);
  for (const TraverseEntry& e : log.entries) grid.insert(e.scan, e.scan.odometry);
  return grid;
}

std::vector<size_t> referenceEntries(const TraverseLog& log, const HomeReturnConfig& config) {
  std::vector<size_t> entries;
  double turned = 0.0;
  for (size_t i : turnInPlaceEntries(log, false, config.turn_radius)) {
    if (i > 0)
      turned += std::abs(
          wrapAngle(log.entries[i].scan.odometry.theta - log.entries[i - 1].scan.odometry.theta));
    if (turned > config.register_max_turn) break;
    entries.push_back(i);
  }
  return entries;
}

HomeBaseRegistration registerHomeBaseFromLog(const TraverseLog& log, const Eigen::Vector2d& first,
                                             const Eigen::Vector2d& second, double arm_length,
                                             const HomeReturnConfig& config) {
  config.validate();
  const std::vector<size_t> turn = turnInPlaceEntries(log, false, config.turn_radius);
  const std::vector<size_t> facing =
      entriesFacing(log, turn, 0.5 * (first + second), config.facing_half_angle);
  const std::vector<size_t> reference = referenceEntries(log, config);
  if (facing.empty() || reference.empty()) return {};
  const Eigen::Vector2d center = log.entries.front().scan.odometry.translation();
  const MapLimits limits = localLimits(center, config);
  OccupancyGrid map = localMap(log, reference, limits);
  // The later scans facing the home base (the end of the turn, after a full circle) carry
  // the turn's odometry error: align them to the reference scans first, then add them, so
  // the map shows the home base from both sides of the first view without double walls.
  std::vector<const RadialMap*> later;
  for (size_t i : facing)
    if (i > reference.back()) later.push_back(&log.entries[i].scan);
  if (!later.empty()) {
    const AlignmentResult a = alignScans(later, map, Pose2(), config.alignment);
    if (a.ok)
      for (const RadialMap* scan : later) map.insert(*scan, a.correction * scan->odometry);
  }
  const CornerDetector detector(classifyCells(map), cornerConfig(config, arm_length));
  return registerHomeBase(detector, first, second, config.register_radius);
}

OccupancyGrid homeBaseReferenceMap(const TraverseLog& log, const HomeReturnConfig& config) {
  config.validate();
  const Eigen::Vector2d center =
      log.entries.empty() ? Eigen::Vector2d(0, 0) : log.entries.front().scan.odometry.translation();
  return localMap(log, referenceEntries(log, config), localLimits(center, config));
}

HomeReturn localizeFromLog(const TraverseLog& log, const HomeBase& home, double arm_length,
                           const HomeReturnConfig& config, const OccupancyGrid* reference,
                           size_t first_return) {
  config.validate();
  HomeReturn out;
  std::vector<size_t> turn = turnInPlaceEntries(log, true, config.turn_radius);
  std::erase_if(turn, [&](size_t i) { return i < first_return; });
  if (turn.size() < 4) return out;
  out.status = HomeReturnStatus::kHomeBaseNotFound;
  const Pose2 at_turn = log.entries[turn.back()].scan.odometry;
  const Eigen::Vector2d center = at_turn.translation();
  const MapLimits limits = localLimits(center, config);
  const CornerConfig corners = cornerConfig(config, arm_length);
  const Eigen::Vector2d home_mid = 0.5 * (home.first.position + home.second.position);

  // 1. The paper's fix. The whole turn: where is the home base, roughly? Then only the
  // scans facing it (a few seconds of turning: little drift among them), corners refitted.
  const OccupancyGrid whole = localMap(log, turn, limits);
  const std::vector<Corner> whole_corners =
      CornerDetector(classifyCells(whole), corners).findAll().corners;
  const HomeBaseFix rough = findHomeBase(whole_corners, config.resolution, home, at_turn, center,
                                         config.local_radius, config.max_separation_error);
  HomeBaseFix fix = rough;
  auto plausible = [&](const Pose2& correction) {
    return std::abs(correction.theta) <= config.max_correction_rad &&
           ((correction * at_turn).translation() - center).norm() <= config.max_correction_m;
  };
  if (fix.status == HomeBaseStatus::kOk && !plausible(fix.correction))
    fix.status = HomeBaseStatus::kGeometryMismatch;
  size_t entry = turn.back();
  std::vector<size_t> facing;
  if (fix.status == HomeBaseStatus::kOk) {
    const Eigen::Vector2d mid = 0.5 * (rough.first.position + rough.second.position);
    facing = entriesFacing(log, turn, mid, config.facing_half_angle);
    if (facing.size() >= 3) {
      const OccupancyGrid map = localMap(log, facing, limits);
      const CornerDetector detector(classifyCells(map), corners);
      const HomeBaseFix refined =
          localizeAtHomeBase(detector, home, log.entries[facing[facing.size() / 2]].scan.odometry,
                             0.3, config.max_separation_error, rough.correction);
      if (refined.status == HomeBaseStatus::kOk && plausible(refined.correction)) {
        fix = refined;
        entry = facing[facing.size() / 2];
      }
    }
    fix.pose = fix.correction * log.entries[entry].scan.odometry;
    out.corner_fix = fix;
  }

  // 2. Better: align the scans facing the home base to the reference map of the start.
  // Without a corner fix, the robot is at least back at the home base: one corner seen places
  // it, or else every heading with the turn's centre near the start position is scored, and
  // the best few are aligned.
  if (reference) {
    const ScanAligner aligner(*reference, config.alignment);
    // The same reference with a tighter robust scale, for the second pass of each alignment:
    // points near but off the reference's walls (another side of an obstacle, a stereo
    // outlier) stop pulling.
    AlignmentConfig tight_config = config.alignment;
    tight_config.robust_scale = std::max(1.0, 0.5 * tight_config.robust_scale);
    const ScanAligner tight(*reference, tight_config);
    // The robot believes it is home: headings in 2 degree steps and positions in 10 cm
    // steps within search_radius of the start, scoring a subsample of the points; the
    // best position per heading, then the best headings at least 10 degrees apart.
    const Pose2 start = log.entries.front().scan.odometry;
    auto searchedGuesses = [&] {
      std::vector<Pose2> guesses;
      std::vector<const RadialMap*> all;
      for (size_t i : turn) all.push_back(&log.entries[i].scan);
      const std::vector<Eigen::Vector2d> pts = aligner.obstaclePoints(all, 8);
      const int steps = static_cast<int>(std::floor(config.search_radius / 0.1));
      // A point counts when within what the 10 cm, 2 degree grid can be off at 3 m.
      const double sweep_cells = std::max(config.alignment.robust_scale, 0.12 / config.resolution);
      std::vector<std::pair<double, Pose2>> per_heading;
      for (int k = 0; k < 180; ++k) {
        const double turn_by = wrapAngle(k * M_PI / 90.0);
        if (std::abs(turn_by) > config.max_correction_rad + 1e-9) continue;
        const double heading = wrapAngle(at_turn.theta + turn_by);
        std::pair<double, Pose2> best{-1.0, Pose2()};
        for (int i = -steps; i <= steps; ++i)
          for (int j = -steps; j <= steps; ++j) {
            if (std::hypot(i, j) > steps) continue;
            const Pose2 g =
                Pose2(start.x + 0.1 * i, start.y + 0.1 * j, heading) * at_turn.inverse();
            const double sc = aligner.score(pts, g, sweep_cells);
            if (sc > best.first) best = {sc, g};
          }
        per_heading.push_back(best);
      }
      std::sort(per_heading.begin(), per_heading.end(),
                [](const auto& a, const auto& b) { return a.first > b.first; });
      for (const auto& [sc, g] : per_heading) {
        bool distinct = true;
        for (const Pose2& h : guesses)
          distinct = distinct && std::abs(wrapAngle(g.theta - h.theta)) > 10.0 * M_PI / 180.0;
        if (distinct) guesses.push_back(g);
        if (guesses.size() >= 5) break;
      }
      return guesses;
    };
    // One L of the home base seen (the other hidden, or blurred by the turn): each corner
    // found in the turn's map placed on the first designed corner (the spacing below tries the
    // second), where it puts the robot within search_radius of the start. The search over
    // every heading and position stands in when no such placement aligns.
    auto cornerGuesses = [&] {
      std::vector<Pose2> guesses;
      for (const Corner& c : whole_corners) {
        const Pose2 g = placementOnCorner(c, home.first);
        if (plausible(g) &&
            ((g * at_turn).translation() - start.translation()).norm() <= config.search_radius)
          guesses.push_back(g);
      }
      return guesses;
    };
    std::vector<size_t> best_view;
    size_t best_entry = entry;
    double best_score = -1.0;
    std::vector<const RadialMap*> turn_scans;
    for (size_t i : turn) turn_scans.push_back(&log.entries[i].scan);
    const std::vector<Eigen::Vector2d> turn_points = aligner.obstaclePoints(turn_scans, 4);
    auto alignGuesses = [&](std::vector<Pose2> guesses) {
      // The two corners look alike: moved by their spacing, one L lies on the other, and an
      // alignment started there converges there (fixes 1.4 m off the truth were seen). Each
      // guess is also tried moved by the spacing either way; the score over the whole turn
      // (both L's and the room around them) tells the right one.
      const Eigen::Vector2d spacing = home.second.position - home.first.position;
      const size_t own_guesses = guesses.size();
      for (size_t k = 0; k < own_guesses; ++k)
        for (double side : {-1.0, 1.0})
          guesses.push_back(Pose2(side * spacing.x(), side * spacing.y(), 0.0) * guesses[k]);
      for (const Pose2& guess : guesses) {
        std::vector<size_t> view = facing;
        size_t view_entry = entry;
        if (fix.status != HomeBaseStatus::kOk) {
          view = entriesFacing(log, turn, guess.inverse() * home_mid, config.facing_half_angle);
          view_entry = view.empty() ? turn.back() : view[view.size() / 2];
        }
        std::vector<const RadialMap*> scans;
        for (size_t i : view.size() >= 3 ? view : turn) scans.push_back(&log.entries[i].scan);
        AlignmentResult a = aligner.align(scans, guess);
        if (a.ok) {
          const AlignmentResult second = tight.align(scans, a.correction);
          if (second.ok) a = second;
        }
        if (a.ok && !plausible(a.correction)) {
          a.ok = false;
          a.message = "the alignment moved the robot farther than it can be off";
        }
        if (&guess == &guesses.front() && !out.alignment.ok) out.alignment = a;  // first reason
        // Every guess is tried; the alignment that puts most of the whole turn's points on
        // the reference's obstacles wins (a wrong heading can align its own view too).
        const double sc = a.ok ? aligner.score(turn_points, a.correction) : -1.0;
        if (a.ok && (!out.alignment.ok || sc > best_score)) {
          out.alignment = a;
          best_score = sc;
          best_view = view;
          best_entry = view_entry;
        }
      }
    };
    if (fix.status == HomeBaseStatus::kOk) {
      alignGuesses({fix.correction});
    } else {
      const std::vector<Pose2> from_corners = cornerGuesses();
      if (!from_corners.empty()) alignGuesses(from_corners);
      if (!out.alignment.ok) alignGuesses(searchedGuesses());
    }
    if (out.alignment.ok) {
      facing = best_view;
      entry = best_entry;
    }
    if (out.alignment.ok) {
      // Last, only the scans that look the way the reference scans looked: stereo's own
      // systematic errors depend on where in the image a wall is seen, and cancel only
      // between views taken from the same place in the same direction.
      const std::vector<size_t> own = referenceEntries(log, config);
      double lo = 1e9, hi = -1e9;
      for (size_t i : own) {
        const double h = log.entries[i].scan.odometry.theta;
        lo = std::min(lo, h);
        hi = std::max(hi, h);
      }
      const double margin = config.matched_view_margin;
      std::vector<size_t> matched;
      for (size_t i : turn) {
        const double h = (out.alignment.correction * log.entries[i].scan.odometry).theta;
        const double mid = 0.5 * (lo + hi);
        if (std::abs(wrapAngle(h - mid)) <= 0.5 * (hi - lo) + margin) matched.push_back(i);
      }
      // (Only from the same place: elsewhere the views differ anyway.)
      const Pose2 at_home = out.alignment.correction * at_turn;
      const Pose2 start = log.entries.front().scan.odometry;
      const bool same_place =
          std::hypot(at_home.x - start.x, at_home.y - start.y) <= config.matched_view_radius;
      if (same_place && matched.size() >= 3) {
        std::vector<const RadialMap*> scans;
        for (size_t i : matched) scans.push_back(&log.entries[i].scan);
        const AlignmentResult m = tight.align(scans, out.alignment.correction);
        if (m.ok) {
          out.alignment = m;
          facing = matched;
          entry = matched[matched.size() / 2];
        }
      }
      out.refined = true;
      fix.status = HomeBaseStatus::kOk;
      fix.correction = out.alignment.correction;
      fix.pose = fix.correction * log.entries[entry].scan.odometry;
      fix.sigma_xy = config.refined_sigma_xy;
      fix.sigma_theta = config.refined_sigma_theta;
    }
  }
  out.fix = fix;
  if (fix.status != HomeBaseStatus::kOk) return out;
  out.scans = static_cast<int>(facing.size() >= 3 ? facing.size() : turn.size());
  out.observation.entry = entry;
  out.observation.pose = fix.pose;
  out.observation.sigma_xy = std::max(fix.sigma_xy, 0.005);
  out.observation.sigma_theta = std::max(fix.sigma_theta, 0.002);
  out.status = HomeReturnStatus::kOk;
  return out;
}

HomeBaseProtocol runHomeBaseProtocol(const TraverseLog& log, const HomeBase& nominal,
                                     double arm_length, const HomeReturnConfig& config,
                                     size_t first_return) {
  HomeBaseProtocol p;
  p.registration = registerHomeBaseFromLog(log, nominal.first.position, nominal.second.position,
                                           arm_length, config);
  p.home = p.registration.home ? *p.registration.home : nominal;
  p.reference.emplace(homeBaseReferenceMap(log, config));
  p.result = localizeFromLog(log, p.home, arm_length, config, &*p.reference, first_return);
  p.method =
      std::string(p.registration.home ? "registered" : "nominal") + " corners" +
      (p.result.corner_fix.status == HomeBaseStatus::kOk ? "" : " (not found)") +
      (p.result.refined ? " + alignment" : " (alignment: " + p.result.alignment.message + ")");
  return p;
}

}  // namespace coopmap

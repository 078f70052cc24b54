#include "core/correction/start_fix.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/landmarks/corner_detector.h"
#include "core/localization/scan_alignment.h"

namespace coopmap {

namespace {

// m: how far off a surface a point may be and still count, for the search (a corner's own
// heading is a few degrees off), the alignment and its second pass, and inliers.
constexpr double kSearchReach = 0.20;
constexpr double kModelReach = 0.08;
constexpr double kModelInlier = 0.02;
constexpr double kModelResolution = 0.01;
// The search's alignments use every kSearchStride-th point of the turn: they only have to
// bring a placement into the basin the fine alignment refines.
constexpr int kSearchStride = 4;
// A placement must put at least this many of the turn's points on each L, and on three of
// the four arms at least kMinPointsPerArm (a wall near one L's place fits one arm, not two
// at right angles; from afar one arm may be seen edge on).
constexpr int kMinPointsPerCorner = 30;
constexpr int kMinPointsPerArm = 10;
// ... and put the robot on the home base's open side, at most this far from its axis (a robot
// looks into the L's; the arms' backs, seen from behind, make L's of their own).
constexpr double kMaxBearingRad = 80.0 * M_PI / 180.0;
// How far the fine alignment may move the search's placement (it only refines it).
constexpr double kMaxRefineM = 0.15;
constexpr double kMaxRefineRad = 5.0 * M_PI / 180.0;

// One face of an arm: a segment and its outward normal, map frame.
struct Face {
  Eigen::Vector2d a, b, normal;
};

std::vector<Face> facesOf(const HomeBaseDesign::Arm& arm) {
  const Eigen::Vector2d u(std::cos(arm.yaw), std::sin(arm.yaw)), v(-u.y(), u.x());
  const Eigen::Vector2d l = arm.half_length * u, w = arm.half_width * v;
  const Eigen::Vector2d& c = arm.center;
  return {{c + l - w, c + l + w, u},
          {c - l - w, c - l + w, -u},
          {c - l + w, c + l + w, v},
          {c - l - w, c + l - w, -v}};
}

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-18), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Which arm lies nearest `p` (an index into `arm_faces`, one entry per arm of
// HomeBaseDesign::arms()), and how near (m).
std::pair<size_t, double> nearestArm(const std::vector<std::vector<Face>>& arm_faces,
                                     const Eigen::Vector2d& p) {
  std::pair<size_t, double> best{0, 1e300};
  for (size_t k = 0; k < arm_faces.size(); ++k)
    for (const Face& f : arm_faces[k]) {
      const double d = distanceToSegment(p, f.a, f.b);
      if (d < best.second) best = {k, d};
    }
  return best;
}

// How many of the turn's points a placement puts within `reach` of each arm, and whether
// that makes a view of the home base: enough points on each L, and on three of its four arms.
struct ArmSupport {
  std::vector<int> on;
  int total() const { return on[0] + on[1] + on[2] + on[3]; }
  bool enough() const {
    int arms_seen = 0;
    for (int n : on) arms_seen += n >= kMinPointsPerArm;
    return arms_seen >= 3 && std::min(on[0] + on[1], on[2] + on[3]) >= kMinPointsPerCorner;
  }
};

ArmSupport armSupport(const std::vector<std::vector<Face>>& arm_faces,
                      const std::vector<Eigen::Vector2d>& points, const Pose2& placement,
                      double reach) {
  ArmSupport out{std::vector<int>(arm_faces.size(), 0)};
  for (const Eigen::Vector2d& p : points) {
    const auto [k, d] = nearestArm(arm_faces, placement * p);
    if (d <= reach) ++out.on[k];
  }
  return out;
}

// The whole turn, then arcs of it kArcRad long every kArcRad / 2 (by the odometry's heading).
constexpr double kArcRad = M_PI / 2.0;
std::vector<std::vector<size_t>> turnArcs(const TraverseLog& log, const std::vector<size_t>& turn) {
  std::vector<std::vector<size_t>> out{turn};
  std::vector<double> turned(turn.size(), 0.0);
  for (size_t k = 1; k < turn.size(); ++k)
    turned[k] = turned[k - 1] + std::abs(wrapAngle(log.entries[turn[k]].scan.odometry.theta -
                                                   log.entries[turn[k - 1]].scan.odometry.theta));
  for (double from = 0.0; from < turned.back(); from += 0.5 * kArcRad) {
    std::vector<size_t> arc;
    for (size_t k = 0; k < turn.size(); ++k)
      if (turned[k] >= from && turned[k] <= from + kArcRad) arc.push_back(turn[k]);
    if (arc.size() >= 3) out.push_back(std::move(arc));
  }
  return out;
}

}  // namespace

OccupancyGrid homeBaseModelGrid(const HomeBaseDesign& design, double resolution,
                                const std::optional<Eigen::Vector2d>& viewpoint) {
  std::vector<Face> faces;
  for (const HomeBaseDesign::Arm& arm : design.arms())
    for (const Face& f : facesOf(arm))
      if (!viewpoint || f.normal.dot(*viewpoint - 0.5 * (f.a + f.b)) > 0.0) faces.push_back(f);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Face& f : faces) {
    lo = lo.cwiseMin(f.a).cwiseMin(f.b);
    hi = hi.cwiseMax(f.a).cwiseMax(f.b);
  }
  const Eigen::Vector2d margin(0.5, 0.5);
  const MapLimits limits = MapLimits::covering(lo - margin, hi + margin, resolution);
  OccupancyGrid grid(limits, OccupancyConfig{});
  const size_t n = static_cast<size_t>(limits.width) * static_cast<size_t>(limits.height);
  std::vector<int16_t> log_odds(n, 0);
  std::vector<uint8_t> seen(n, 0);
  for (int iy = 0; iy < limits.height; ++iy)
    for (int ix = 0; ix < limits.width; ++ix) {
      const Eigen::Vector2d c = limits.cellCenter(ix, iy);
      for (const Face& f : faces)
        if (distanceToSegment(c, f.a, f.b) <= 0.5 * resolution) {
          const size_t i = static_cast<size_t>(iy) * limits.width + ix;
          log_odds[i] = static_cast<int16_t>(grid.config().clamp);
          seen[i] = 1;
          break;
        }
    }
  grid.assign(log_odds, seen);
  return grid;
}

const char* toString(StartFixStatus s) {
  switch (s) {
    case StartFixStatus::kOk:
      return "ok";
    case StartFixStatus::kNoTurn:
      return "no turn in place at the start of the log";
    case StartFixStatus::kHomeBaseNotFound:
      return "home base not found in the start turn's map";
    case StartFixStatus::kAlignmentFailed:
      return "the view of the home base does not align to its design";
  }
  return "?";
}

StartFix localizeStart(const TraverseLog& log, const HomeBaseDesign& design,
                       const HomeReturnConfig& config) {
  config.validate();
  design.validate();
  StartFix out;
  const std::vector<size_t> turn = turnInPlaceEntries(log, true, config.turn_radius);
  if (turn.size() < 4) {
    out.method = toString(out.status);
    return out;
  }
  out.turn_begin = turn.front();
  out.status = StartFixStatus::kHomeBaseNotFound;
  const Pose2 at_turn = log.entries[turn.front()].scan.odometry;
  const Eigen::Vector2d center = at_turn.translation();
  const Eigen::Vector2d half(config.local_radius, config.local_radius);
  const MapLimits limits = MapLimits::covering(center - half, center + half, config.resolution);
  CornerConfig corner_config = config.corners;
  corner_config.arm_cells = design.arm_length / config.resolution;
  const HomeBase visible = design.visibleCorners();

  // Where is the home base? Each corner of the whole turn's map placed on either designed
  // corner, aligned, and scored by the turn's points on the arms; then, if none places it, the
  // corners of the turn's arcs (the whole turn is blurred by the turn's drift, and an arc sees
  // one side sharp).
  std::vector<const RadialMap*> turn_scans;
  for (size_t i : turn) turn_scans.push_back(&log.entries[i].scan);
  const OccupancyGrid outline = homeBaseModelGrid(design, kModelResolution);
  AlignmentConfig search = config.alignment;
  search.robust_scale = kSearchReach / kModelResolution;
  search.inlier_cells = kModelInlier / kModelResolution;
  search.point_stride = kSearchStride;
  const ScanAligner searcher(outline, search);
  const std::vector<Eigen::Vector2d> points = searcher.obstaclePoints(turn_scans);
  const Eigen::Vector2d home_mid =
      0.5 * (design.corners.first.position + design.corners.second.position);
  const Eigen::Vector2d open_side = (Eigen::Vector2d(std::cos(design.corners.first.heading),
                                                     std::sin(design.corners.first.heading)) +
                                     Eigen::Vector2d(std::cos(design.corners.second.heading),
                                                     std::sin(design.corners.second.heading)))
                                        .normalized();
  std::vector<std::vector<Face>> arm_faces;
  for (const HomeBaseDesign::Arm& arm : design.arms()) arm_faces.push_back(facesOf(arm));
  int best_support = 0;
  Pose2 placed;
  std::vector<Pose2> tried;
  size_t found = 0;
  for (const std::vector<size_t>& part : turnArcs(log, turn)) {
    // The arcs only when the whole turn's corners place nothing.
    if (best_support > 0) break;
    const OccupancyGrid map = localMap(log, part, limits);
    const CornerSearch corners = CornerDetector(classifyCells(map), corner_config).findAll();
    for (const Corner& c : corners.corners) {
      if ((c.position - center).norm() > config.local_radius) continue;
      ++found;
      for (const Corner* designed : {&visible.first, &visible.second}) {
        const Pose2 guess = placementOnCorner(c, *designed);
        // The same corner found in the whole turn and in an arc aligns the same way.
        if (std::any_of(tried.begin(), tried.end(), [&](const Pose2& t) {
              return (t.translation() - guess.translation()).norm() < 1e-4 &&
                     std::abs(wrapAngle(t.theta - guess.theta)) < 1e-4;
            }))
          continue;
        tried.push_back(guess);
        // The alignment pulls only points within the search's reach of the arms: a placement
        // without a view of the home base there cannot align into one.
        if (!armSupport(arm_faces, points, guess, kSearchReach).enough()) continue;
        const AlignmentResult a = searcher.align(turn_scans, guess);
        if (!a.ok) continue;
        const Eigen::Vector2d from_home = (a.correction * at_turn).translation() - home_mid;
        if (from_home.normalized().dot(open_side) < std::cos(kMaxBearingRad)) continue;
        const ArmSupport on = armSupport(arm_faces, points, a.correction, kModelInlier);
        const int support = on.enough() ? on.total() : 0;
        if (support > best_support) {
          best_support = support;
          placed = a.correction;
        }
      }
    }
  }
  if (best_support == 0) {
    out.method = std::string(toString(out.status)) + " (" + std::to_string(found) +
                 " corners tried: none places both L's on the turn's points, the robot in front)";
    return out;
  }

  // The longest run of consecutive turn entries facing it: one stretch of the turn, whose
  // odometry has drifted little within it.
  const Eigen::Vector2d middle =
      placed.inverse() * (0.5 * (design.corners.first.position + design.corners.second.position));
  std::vector<size_t> best, run;
  for (size_t k = 0; k <= turn.size(); ++k) {
    if (k < turn.size() &&
        !entriesFacing(log, {turn[k]}, middle, config.facing_half_angle).empty()) {
      run.push_back(turn[k]);
      continue;
    }
    if (run.size() > best.size()) best = run;
    run.clear();
  }
  if (best.size() < 3) {
    out.method = "home base found, but fewer than 3 radial maps of the turn face it";
    return out;
  }
  out.view = best;
  out.entry = best[best.size() / 2];
  const Pose2& at_entry = log.entries[out.entry].scan.odometry;

  // That view's points on the faces of the design turned towards the robot: twice, the second
  // time with half the reach, so that points off the arms stop pulling.
  const OccupancyGrid model =
      homeBaseModelGrid(design, kModelResolution, (placed * at_entry).translation());
  AlignmentConfig wide = config.alignment;
  wide.robust_scale = kModelReach / kModelResolution;
  wide.inlier_cells = kModelInlier / kModelResolution;
  AlignmentConfig tight = wide;
  tight.robust_scale = 0.5 * wide.robust_scale;
  std::vector<const RadialMap*> scans;
  for (size_t i : best) scans.push_back(&log.entries[i].scan);
  AlignmentResult a = ScanAligner(model, wide).align(scans, placed);
  if (a.ok) {
    const AlignmentResult second = ScanAligner(model, tight).align(scans, a.correction);
    if (second.ok) a = second;
  }
  const Pose2 moved = a.correction * at_entry, from = placed * at_entry;
  if (a.ok && ((moved.translation() - from.translation()).norm() > kMaxRefineM ||
               std::abs(wrapAngle(moved.theta - from.theta)) > kMaxRefineRad)) {
    a.ok = false;
    a.message = "the alignment moved the home base's placement too far";
  }
  if (!a.ok) {
    out.status = StartFixStatus::kAlignmentFailed;
    out.method = std::string(toString(out.status)) + ": " + a.message;
    return out;
  }
  out.status = StartFixStatus::kOk;
  out.correction = a.correction;
  out.pose = a.correction * at_entry;
  out.points = a.points;
  out.inlier_share = a.points > 0 ? static_cast<double>(a.inliers) / a.points : 0.0;
  out.method = "home base placed by a corner (" + std::to_string(best_support) +
               " points of the turn on its arms), aligned on " + std::to_string(best.size()) +
               " radial maps facing it (" + std::to_string(a.points) + " points)";
  return out;
}

}  // namespace coopmap

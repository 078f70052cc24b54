#include "core/agent/cooperation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include <Eigen/Eigenvalues>

namespace coopmap {

namespace {

// Radial maps [begin, end) of a log placed at other poses (the corrected ones), for the
// aligner, which places each scan at its own pose.
struct PlacedScans {
  PlacedScans(const TraverseLog& log, const std::vector<Pose2>& poses, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      maps.push_back(log.entries[i].scan);
      maps.back().odometry = poses[i];
    }
    for (const RadialMap& m : maps) pointers.push_back(&m);
  }
  PlacedScans(const PlacedScans&) = delete;
  PlacedScans& operator=(const PlacedScans&) = delete;
  std::vector<RadialMap> maps;
  std::vector<const RadialMap*> pointers;
};

// Whether an alignment's correction (map frame) moves `pose` by at most `max_m` and turns it
// by at most `max_rad` (the post gate asks at a stretch's middle, the closures at the map's
// origin: see mapClosures).
bool movesWithin(const Pose2& correction, const Pose2& pose, double max_m, double max_rad) {
  const Pose2 moved = correction * pose;
  return (moved.translation() - pose.translation()).norm() <= max_m &&
         std::abs(wrapAngle(moved.theta - pose.theta)) <= max_rad;
}

}  // namespace

std::string CooperationConfig::closureKinds() const {
  return closures ? (self_closures ? "both" : "shared") : (self_closures ? "self" : "none");
}

bool CooperationConfig::setClosureKinds(const std::string& name) {
  if (name != "none" && name != "self" && name != "shared" && name != "both") return false;
  closures = name == "both" || name == "shared";
  self_closures = name == "both" || name == "self";
  return true;
}

void CooperationConfig::validate() const {
  if (!(max_fix_jump_m > 0.0))
    throw std::invalid_argument(
        "cooperation config: field 'max_fix_jump_m': expected a positive number, got " +
        std::to_string(max_fix_jump_m));
  if (!(min_home_agreement >= 0.0 && min_home_agreement <= 1.0) || home_check_scans < 1)
    throw std::invalid_argument(
        "cooperation config: fields 'min_home_agreement' and 'home_check_scans': expected a "
        "share in [0, 1] and at least 1 scan");
  if (!(max_disagreement_m > 0.0))
    throw std::invalid_argument(
        "cooperation config: field 'max_disagreement_m': expected a positive number, got " +
        std::to_string(max_disagreement_m));
  if (!(max_fix_jump_rad > 0.0))
    throw std::invalid_argument(
        "cooperation config: field 'max_fix_jump_rad': expected a positive number, got " +
        std::to_string(max_fix_jump_rad));
  home_return.validate();
  closure_alignment.validate();
  if (manhattan_passes < 1)
    throw std::invalid_argument(
        "cooperation config: field 'manhattan_passes': expected an integer >= 1, got " +
        std::to_string(manhattan_passes));
  if (self_closure_gap < 0)
    throw std::invalid_argument(
        "cooperation config: field 'self_closure_gap': expected an integer >= 0, got " +
        std::to_string(self_closure_gap));
  if (closure_scans < 1 || closure_stride < 1)
    throw std::invalid_argument(
        "cooperation config: fields 'closure_scans' and 'closure_stride': expected at least 1, "
        "got " +
        std::to_string(closure_scans) + " and " + std::to_string(closure_stride));
  if (!(closure_min_inliers >= 0.0 && closure_min_inliers <= 1.0))
    throw std::invalid_argument(
        "cooperation config: field 'closure_min_inliers': expected a share in [0, 1], got " +
        std::to_string(closure_min_inliers));
  if (!(closure_max_m > 0.0 && closure_max_rad > 0.0 && closure_sigma_xy > 0.0 &&
        closure_sigma_theta > 0.0))
    throw std::invalid_argument(
        "cooperation config: fields 'closure_max_m', 'closure_max_rad', 'closure_sigma_xy', "
        "'closure_sigma_theta': expected positive numbers");
  if (!(post_gate_m >= 0.0) || !(post_gate_rad > 0.0))
    throw std::invalid_argument(
        "cooperation config: fields 'post_gate_m' and 'post_gate_rad': expected a number >= 0 "
        "(0: off) and a positive angle, got " +
        std::to_string(post_gate_m) + " and " + std::to_string(post_gate_rad));
  if (!(rival_search_m >= 0.0 && rival_min_shift_m >= 0.0 && rival_max_turn_rad >= 0.0 &&
        rival_margin >= 0.0 && rival_margin <= 1.0) ||
      (rival_search_m > 0.0 && !(rival_min_shift_m < rival_search_m)))
    throw std::invalid_argument(
        "cooperation config: fields 'rival_search_m', 'rival_min_shift_m', "
        "'rival_max_turn_rad', 'rival_margin': expected numbers >= 0 (0: off), the shift "
        "below the search radius and the margin a share in [0, 1], got " +
        std::to_string(rival_search_m) + ", " + std::to_string(rival_min_shift_m) + ", " +
        std::to_string(rival_max_turn_rad) + " and " + std::to_string(rival_margin));
  if (!(manhattan_sigma_rad >= 0.0))
    throw std::invalid_argument(
        "cooperation config: field 'manhattan_sigma_rad': expected a number >= 0 (0: off), got " +
        std::to_string(manhattan_sigma_rad));
  manhattan.validate();
  if (!(closure_max_sigma_m >= closure_sigma_xy))
    throw std::invalid_argument(
        "cooperation config: field 'closure_max_sigma_m': expected a number >= closure_sigma_xy "
        "(" +
        std::to_string(closure_sigma_xy) + "), got " + std::to_string(closure_max_sigma_m));
}

HomeBaseCooperation::HomeBaseCooperation(std::string robot, const HomeBase& nominal,
                                         double arm_length, SharedMapService* shared,
                                         const CooperationConfig& config)
    : robot_(std::move(robot)),
      nominal_(nominal),
      home_(nominal),
      arm_length_(arm_length),
      shared_(shared),
      config_(config) {
  config_.validate();
  if (!shared_) throw std::invalid_argument("HomeBaseCooperation: no shared map service");
}

HomeBaseCooperation::SharedView::SharedView(const SharedMapService& shared,
                                            const AlignmentConfig& config) {
  const SharedMapSnapshot snap = shared.snapshot();
  if (snap.version == 0) return;
  map.emplace(shared.limits(), shared.config());
  map->assign(snap.log_odds, snap.seen);
  aligner.emplace(*map, config);
}

HomeBaseCooperation::Located HomeBaseCooperation::locateSortie(const TraverseLog& sortie,
                                                               const SharedView& view) const {
  Located l;
  SortieReport& rep = l.rep;
  rep.sortie = static_cast<int>(reports_.size()) + 1;
  rep.entries = sortie.entries.size();
  if (sortie.entries.empty()) {
    rep.method = "no radial maps in the sortie";
    return l;
  }
  rep.stamp = sortie.entries.back().scan.stamp;

  // The first sortie starts with the look at the home base: it registers the home base
  // and keeps its first scans as the reference. Later sorties are localized against that
  // reference: its scans go in front of the sortie's, so the log looks like the first one
  // did (a start at the home base, a turn at the end).
  // After a sortie the robot is off by what one sortie drifts at most.
  HomeReturnConfig bounded = config_.home_return;
  bounded.max_correction_rad = std::min(bounded.max_correction_rad, config_.max_fix_jump_rad);
  bounded.max_correction_m = std::min(bounded.max_correction_m, config_.max_fix_jump_m);
  HomeReturn ret;
  size_t offset = 0;
  if (!reference_) {
    l.protocol = runHomeBaseProtocol(sortie, nominal_, arm_length_, bounded);
    ret = l.protocol->result;
    rep.method = l.protocol->method;
  } else {
    TraverseLog joined = reference_log_;
    offset = joined.entries.size();
    joined.entries.insert(joined.entries.end(), sortie.entries.begin(), sortie.entries.end());
    ret = localizeFromLog(joined, home_, arm_length_, bounded, &*reference_, offset);
    rep.method = ret.refined ? "alignment to the reference" : "corners";
    if (ret.status == HomeReturnStatus::kOk && ret.observation.entry < offset) {
      rep.method = "the fix fell on a reference scan, not on the return turn";
      return l;
    }
  }
  if (ret.status != HomeReturnStatus::kOk) {
    rep.method = std::string(toString(ret.status)) +
                 (ret.alignment.message.empty() ? "" : " (" + ret.alignment.message + ")");
    return l;
  }
  l.observation = ret.observation;
  l.observation.entry -= offset;
  if (reference_ && config_.rival_search_m > 0.0 && view.aligner &&
      !checkRival(sortie, *view.aligner, l))
    return l;
  const size_t at = l.observation.entry;
  rep.fix = l.observation.pose;
  rep.fix_stamp = sortie.entries[at].scan.stamp;
  rep.correction = l.observation.pose * sortie.entries[at].scan.odometry.inverse();
  // How far the fix moves the robot: from its pose on the sortie's odometry then. Not the
  // correction's translation, which for a turn adds the turn times the robot's distance from
  // the map's origin (seed 48 of the building with --doorway-width 1.2: a look at home
  // turning the sortie 14 degrees, 3.2 m from the origin, was refused as a 3.16 m move, and
  // the robot stopped for good; trusted, its sortie was fixed 0.6 cm off the truth).
  const Pose2& believed = sortie.entries[at].scan.odometry;
  const double move_m = (l.observation.pose.translation() - believed.translation()).norm();
  const double turn_rad = wrapAngle(l.observation.pose.theta - believed.theta);
  if (move_m > config_.max_fix_jump_m || std::abs(turn_rad) > config_.max_fix_jump_rad) {
    char note[96];
    std::snprintf(note, sizeof note, "fix not trusted: it moves the robot %.2f m and %.1f deg",
                  move_m, turn_rad * 180.0 / M_PI);
    rep.method = note;
    return l;
  }
  rep.fixed = true;
  return l;
}

RivalPlacement rivalPlacement(const ScanAligner& aligner,
                              const std::vector<Eigen::Vector2d>& points,
                              const Eigen::Vector2d& pivot, double search_m, double min_shift_m,
                              double max_turn_rad) {
  // Coarse to fine: 0.1 m and 2 degree steps scored within 1.5 cells, then the best of those
  // and its neighbours at half the steps scored within a cell.
  constexpr double kStep = 0.1, kTurnStep = 2.0 * M_PI / 180.0;
  const Pose2 from_pivot(-pivot.x(), -pivot.y(), 0.0);
  auto placement = [&](double dx, double dy, double turn) {
    return Pose2(pivot.x() + dx, pivot.y() + dy, turn) * from_pivot;
  };
  auto allowed = [&](double dx, double dy, double turn) {
    const double d = std::hypot(dx, dy);
    return d >= min_shift_m && d <= search_m && std::abs(turn) <= max_turn_rad + 1e-9;
  };
  RivalPlacement best;
  best.here = aligner.score(points, Pose2(), 1.0);
  const int shifts = static_cast<int>(std::floor(search_m / kStep + 1e-9));
  const int turns = static_cast<int>(std::floor(max_turn_rad / kTurnStep + 1e-9));
  double coarse = -1.0, cx = 0.0, cy = 0.0, ct = 0.0;
  for (int it = -turns; it <= turns; ++it)
    for (int ix = -shifts; ix <= shifts; ++ix)
      for (int iy = -shifts; iy <= shifts; ++iy) {
        const double dx = ix * kStep, dy = iy * kStep, turn = it * kTurnStep;
        if (!allowed(dx, dy, turn)) continue;
        const double score = aligner.score(points, placement(dx, dy, turn), 1.5);
        if (score > coarse) coarse = score, cx = dx, cy = dy, ct = turn;
      }
  if (coarse < 0.0) return best;  // no placement allowed
  best.score = -1.0;
  for (int it = -1; it <= 1; ++it)
    for (int ix = -1; ix <= 1; ++ix)
      for (int iy = -1; iy <= 1; ++iy) {
        const double dx = cx + ix * kStep / 2, dy = cy + iy * kStep / 2,
                     turn = ct + it * kTurnStep / 2;
        if (!allowed(dx, dy, turn)) continue;
        const Pose2 c = placement(dx, dy, turn);
        const double score = aligner.score(points, c, 1.0);
        if (score > best.score) best.score = score, best.correction = c;
      }
  best.score = std::max(best.score, 0.0);
  return best;
}

bool HomeBaseCooperation::checkRival(const TraverseLog& sortie, const ScanAligner& aligner,
                                     Located& l) const {
  // The look at home (the sortie's last radial maps) placed by the fix, on the sortie's
  // odometry about it.
  const size_t n = sortie.entries.size();
  const size_t k = std::min(n, static_cast<size_t>(config_.home_check_scans));
  const Pose2 to_map =
      l.observation.pose * sortie.entries[l.observation.entry].scan.odometry.inverse();
  std::vector<Pose2> poses(n);
  for (size_t i = n - k; i < n; ++i) poses[i] = to_map * sortie.entries[i].scan.odometry;
  const PlacedScans look(sortie, poses, n - k, n);
  const std::vector<Eigen::Vector2d> all = aligner.obstaclePoints(look.pointers);
  if (all.size() < 50) return true;
  constexpr size_t kSearchPoints = 300;  // enough to tell places apart, and fast
  std::vector<Eigen::Vector2d> some;
  const size_t stride = std::max<size_t>(1, all.size() / kSearchPoints);
  for (size_t i = 0; i < all.size(); i += stride) some.push_back(all[i]);
  const RivalPlacement rival =
      rivalPlacement(aligner, some, l.observation.pose.translation(), config_.rival_search_m,
                     config_.rival_min_shift_m, config_.rival_max_turn_rad);
  if (rival.score <= rival.here + config_.rival_margin) return true;
  // Somewhere else fits the shared map better: align the look from there.
  const AlignmentResult a = aligner.align(look.pointers, rival.correction);
  const double here = aligner.score(all, Pose2(), 1.0);
  const double there = a.ok ? aligner.score(all, a.correction, 1.0) : 0.0;
  const Pose2 moved = a.correction * l.observation.pose;
  const double m = (moved.translation() - l.observation.pose.translation()).norm();
  const double deg = wrapAngle(moved.theta - l.observation.pose.theta) * 180.0 / M_PI;
  char note[240];
  // The aligned place must still be one of those searched (within a fine step).
  const bool searched = m >= config_.rival_min_shift_m - 0.05 &&
                        m <= config_.rival_search_m + 0.05 &&
                        std::abs(deg) <= config_.rival_max_turn_rad * 180.0 / M_PI + 1.0;
  if (a.ok && a.inliers >= config_.closure_min_inliers * a.points &&
      there > here + config_.rival_margin && searched) {
    std::snprintf(note, sizeof note,
                  "; the shared map moved the fix %.2f m and %.1f deg (the look's points within "
                  "a cell of its obstacles: %.2f there, %.2f at the fix)",
                  m, deg, there, here);
    l.observation.pose = moved;
    l.rep.method += note;
    l.rep.fix_moved_m = m;
    return true;
  }
  std::snprintf(
      note, sizeof note,
      "; fix not trusted: the look fits the shared map better %.2f m away (%.2f of its "
      "points within a cell of an obstacle there, %.2f at the fix)",
      ((rival.correction * l.observation.pose).translation() - l.observation.pose.translation())
          .norm(),
      rival.score, rival.here);
  l.rep.method += note;
  return false;
}

SortieReport HomeBaseCooperation::locate(const TraverseLog& sortie) const {
  return locateSortie(sortie, SharedView(*shared_, config_.closure_alignment)).rep;
}

SortieReport HomeBaseCooperation::endSortie(const TraverseLog& sortie,
                                            const std::optional<Eigen::Vector2d>& expected,
                                            const std::vector<Pose2>* estimate) {
  // The shared map as it is now, prepared for alignment (once).
  const SharedView view(*shared_, config_.closure_alignment);
  Located l = locateSortie(sortie, view);
  SortieReport& rep = l.rep;
  if (rep.fixed && expected &&
      (rep.fix.translation() - *expected).norm() > config_.max_disagreement_m) {
    rep.fixed = false;
    rep.method +=
        "; fix not trusted: " + std::to_string((rep.fix.translation() - *expected).norm()) +
        " m from where the first fix sent the robot";
  }
  auto done = [&]() {
    rep.map_version = shared_->snapshot().version;
    reports_.push_back(rep);
    return rep;
  };
  if (l.protocol) {  // the first sortie registered the home base
    home_ = l.protocol->home;
    reference_ = l.protocol->reference;
    reference_log_.robot = sortie.robot;
    for (size_t i : referenceEntries(sortie, config_.home_return))
      reference_log_.entries.push_back(sortie.entries[i]);
  }
  if (!rep.fixed) return done();
  const PoseObservation& observation = l.observation;

  // Correct the sortie's traverse and share it.
  CorrectionResult c = correctTraverse(sortie, observation, config_.correction);
  if (!c.ok) {
    rep.fixed = false;
    rep.method += "; correction failed: " + c.message;
    return done();
  }
  const std::optional<ScanAligner>& aligner = view.aligner;
  const size_t n = sortie.entries.size();
  std::vector<PoseObservation> closures;
  std::string closure_note;
  if (config_.closures && aligner) {
    closures = mapClosures(sortie, c.poses, *aligner, config_, 0, n, estimate);
    if (!closures.empty())
      closure_note += " + " + std::to_string(closures.size()) + " closures to the shared map";
  }
  const size_t gap = static_cast<size_t>(config_.self_closure_gap);
  if (config_.self_closures && n >= 2 * gap + 4 * static_cast<size_t>(config_.closure_scans)) {
    // The sortie against itself: stretches of its second half aligned to the map of its first
    // half, and the other way round, leaving out `gap` entries either side of the middle so
    // that no stretch aligns to the scans it was taken among. Out and back meet where the
    // robot came by again, and the pose graph makes them agree.
    const size_t mid = n / 2;
    OccupancyGrid first(shared_->limits(), shared_->config());
    OccupancyGrid second(shared_->limits(), shared_->config());
    for (size_t i = 0; i + gap < mid; ++i) first.insert(sortie.entries[i].scan, c.poses[i]);
    for (size_t i = mid + gap; i < n; ++i) second.insert(sortie.entries[i].scan, c.poses[i]);
    const ScanAligner to_first(first, config_.closure_alignment);
    const ScanAligner to_second(second, config_.closure_alignment);
    std::vector<PoseObservation> self = mapClosures(sortie, c.poses, to_first, config_, mid, n);
    const std::vector<PoseObservation> back =
        mapClosures(sortie, c.poses, to_second, config_, 0, mid);
    self.insert(self.end(), back.begin(), back.end());
    if (!self.empty())
      closure_note += " + " + std::to_string(self.size()) + " closures within the sortie";
    closures.insert(closures.end(), self.begin(), self.end());
  }
  const std::vector<PoseObservation> headings =
      config_.manhattan_sigma_rad > 0.0
          ? manhattanHeadings(sortie, c.poses, config_.closure_scans, config_.closure_stride,
                              config_.closure_alignment.max_range, config_.manhattan_sigma_rad,
                              config_.manhattan)
          : std::vector<PoseObservation>{};
  if (!headings.empty()) {
    closure_note += " + " + std::to_string(headings.size()) + " headings from the walls";
    closures.insert(closures.end(), headings.begin(), headings.end());
  }
  if (!closures.empty()) {
    CorrectionConfig graph = config_.correction;
    graph.model = CorrectionModel::kPoseGraph;
    CorrectionResult g = correctTraverse(sortie, observation, graph, closures);
    // The walls' turn is searched within a few degrees of the axes: where the first
    // correction left the heading farther off, the walls give nothing. Found again on the
    // graph's poses, where the headings found so far brought it within reach (see
    // CooperationConfig::manhattan_passes).
    size_t heading_count = headings.size();
    for (int pass = 1; pass < config_.manhattan_passes && g.ok && config_.manhattan_sigma_rad > 0.0;
         ++pass) {
      std::vector<PoseObservation> again = manhattanHeadings(
          sortie, g.poses, config_.closure_scans, config_.closure_stride,
          config_.closure_alignment.max_range, config_.manhattan_sigma_rad, config_.manhattan);
      if (again.size() <= heading_count) break;
      std::vector<PoseObservation> all(closures.begin(),
                                       closures.end() - static_cast<std::ptrdiff_t>(heading_count));
      all.insert(all.end(), again.begin(), again.end());
      CorrectionResult next = correctTraverse(sortie, observation, graph, all);
      if (!next.ok) break;
      closure_note += " (" + std::to_string(again.size()) + " when found again)";
      heading_count = again.size();
      closures = std::move(all);
      g = std::move(next);
    }
    if (g.ok) {
      c = std::move(g);
      rep.closures = static_cast<int>(closures.size());
      rep.method += closure_note;
    }
  }
  if (aligner) {
    const size_t k = std::min(n, static_cast<size_t>(config_.home_check_scans));
    const PlacedScans look(sortie, c.poses, n - k, n);
    const std::vector<Eigen::Vector2d> points = aligner->obstaclePoints(look.pointers);
    if (points.size() >= 50) {
      rep.home_agreement = aligner->score(points, Pose2());
      if (rep.home_agreement < config_.min_home_agreement) {
        rep.fixed = false;
        rep.method += "; not shared: at the fix, home does not look like the shared map's (" +
                      std::to_string(rep.home_agreement) + " of the points on its obstacles)";
        return done();
      }
    }
  }
  rep.bias = c.bias;
  for (size_t i = 1; i < sortie.entries.size(); ++i)
    rep.length_m += (sortie.entries[i].scan.odometry.translation() -
                     sortie.entries[i - 1].scan.odometry.translation())
                        .norm();
  TraverseLog kept;
  std::vector<Pose2> kept_poses;
  if (config_.post_gate_m > 0.0 && aligner) {
    const std::vector<bool> misplaced =
        misplacedEntries(sortie, c.poses, *aligner, config_.closure_scans,
                         config_.closure_min_inliers, config_.post_gate_m, config_.post_gate_rad);
    kept.robot = sortie.robot;
    for (size_t i = 0; i < n; ++i) {
      if (misplaced[i]) {
        ++rep.withheld;
        continue;
      }
      kept.entries.push_back(sortie.entries[i]);
      kept_poses.push_back(c.poses[i]);
    }
    if (rep.withheld > 0)
      rep.method += "; " + std::to_string(rep.withheld) +
                    " radial maps withheld (the shared map says they are misplaced)";
  }
  rep.post = rep.withheld > 0 ? shared_->post(correctedPost(kept, kept_poses, next_post_++))
                              : shared_->post(correctedPost(sortie, c.poses, next_post_++));
  rep.posted = rep.post.status == PostStatus::kAccepted;
  if (rep.posted)
    for (size_t i = 0; i < c.poses.size(); ++i)
      corrected_.push_back({sortie.entries[i].scan.stamp, c.poses[i]});
  return done();
}

std::vector<bool> misplacedEntries(const TraverseLog& log, const std::vector<Pose2>& poses,
                                   const ScanAligner& aligner, int scans, double min_inliers,
                                   double max_m, double max_rad) {
  if (poses.size() != log.entries.size())
    throw std::invalid_argument("misplacedEntries: " + std::to_string(poses.size()) +
                                " poses for a log of " + std::to_string(log.entries.size()) +
                                " entries");
  if (scans < 1) throw std::invalid_argument("misplacedEntries: expected at least 1 scan");
  const size_t n = log.entries.size(), k = static_cast<size_t>(scans);
  std::vector<bool> out(n, false);
  for (size_t begin = 0; begin < n; begin += k) {
    // A rest shorter than a stretch joins the one before it.
    const size_t end = n - begin < 2 * k ? n : begin + k;
    const PlacedScans stretch(log, poses, begin, end);
    const AlignmentResult a = aligner.align(stretch.pointers, Pose2());
    if (a.ok && a.inliers >= min_inliers * a.points &&
        !movesWithin(a.correction, poses[(begin + end) / 2], max_m, max_rad))
      for (size_t i = begin; i < end; ++i) out[i] = true;
    if (end == n) break;
  }
  return out;
}

std::vector<PoseObservation> manhattanHeadings(const TraverseLog& log,
                                               const std::vector<Pose2>& poses, int scans,
                                               int stride, double max_range, double sigma_rad,
                                               const ManhattanConfig& config) {
  if (poses.size() != log.entries.size())
    throw std::invalid_argument("manhattanHeadings: " + std::to_string(poses.size()) +
                                " poses for a log of " + std::to_string(log.entries.size()) +
                                " entries");
  if (scans < 1 || stride < 1)
    throw std::invalid_argument("manhattanHeadings: expected at least 1 scan and a stride of 1");
  std::vector<PoseObservation> out;
  const size_t k = static_cast<size_t>(scans), n = log.entries.size();
  for (size_t begin = 0; begin + k <= n; begin += static_cast<size_t>(stride)) {
    const PlacedScans stretch(log, poses, begin, begin + k);
    const std::optional<ManhattanFit> fit =
        manhattanTurn(hitPoints(stretch.pointers, max_range), config);
    if (!fit) continue;
    // The walls are turned by the heading's error: the heading, turned back, is observed;
    // the position is left to the rest of the graph.
    PoseObservation o;
    o.entry = begin + k / 2;
    o.pose = poses[o.entry];
    o.pose.theta = wrapAngle(o.pose.theta - fit->turn_rad);
    o.sigma_theta = sigma_rad;
    o.xy_information = Eigen::Matrix2d::Identity() * 1e-9;
    out.push_back(o);
  }
  return out;
}

namespace {

// A closure's position information (map frame) from its alignment's, at `at`.
Eigen::Matrix2d closureInformation(const AlignmentResult& a, const Eigen::Vector2d& at,
                                   const CooperationConfig& config) {
  // The alignment's own information is far too confident (its points' errors are not
  // independent); only its shape is used: the strongest direction gets closure_sigma_xy.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(positionInformation(a, at));
  const Eigen::Vector2d lambda = eig.eigenvalues();  // ascending
  const double strong = 1.0 / (config.closure_sigma_xy * config.closure_sigma_xy);
  if (!(lambda(1) > 0.0)) return Eigen::Matrix2d::Identity() * strong;
  const double ratio = std::max(lambda(0), 0.0) / lambda(1);
  const double floor = std::pow(config.closure_sigma_xy / config.closure_max_sigma_m, 2);
  const Eigen::Vector2d weak_dir = eig.eigenvectors().col(0),
                        strong_dir = eig.eigenvectors().col(1);
  return strong * (strong_dir * strong_dir.transpose() +
                   std::max(ratio, floor) * weak_dir * weak_dir.transpose());
}

}  // namespace

std::vector<PoseObservation> mapClosures(const TraverseLog& log,
                                         const std::vector<Pose2>& corrected,
                                         const ScanAligner& aligner,
                                         const CooperationConfig& config, size_t from, size_t to,
                                         const std::vector<Pose2>* estimate) {
  const size_t n = log.entries.size();
  if (corrected.size() != n || (estimate && estimate->size() != n))
    throw std::invalid_argument("mapClosures: " + std::to_string(corrected.size()) + " and " +
                                std::to_string(estimate ? estimate->size() : n) +
                                " poses for a log of " + std::to_string(n) + " entries");
  std::vector<PoseObservation> out;
  const size_t k = static_cast<size_t>(config.closure_scans);
  std::vector<Pose2> anchored = corrected;
  for (size_t begin = from; begin + k <= std::min(to, n);
       begin += static_cast<size_t>(config.closure_stride)) {
    const size_t mid = begin + k / 2;
    // An alignment of the stretch placed at `poses` that fits: enough of its points on the
    // map's obstacles, and moving the map's origin (by the home base) little. Measured at
    // the origin, not at the stretch: a sortie's drift turns it about where it began, so a
    // right correction far out turns and shifts the stretch together and moves the origin
    // little, where a turn without the shift it implies (the alignment's own heading error)
    // moves the origin far. Seeds 1-12 of the building: wall_recall 0.841 and
    // false_occupied_rate 0.0237 this way; at the stretch's middle, 0.796 and 0.0306 (0.792
    // and 0.0278 with closure_max_rad 0.03); about the home base's middle, 0.820 and 0.0283;
    // closure_max_m 0.3 at the origin, 0.806 and 0.0296.
    auto fit = [&](const std::vector<Pose2>& poses) {
      const PlacedScans stretch(log, poses, begin, begin + k);
      AlignmentResult a = aligner.align(stretch.pointers, Pose2());
      a.ok = a.ok && a.inliers >= config.closure_min_inliers * a.points &&
             movesWithin(a.correction, Pose2(), config.closure_max_m, config.closure_max_rad);
      return a;
    };
    AlignmentResult a = fit(corrected);
    Pose2 placed = corrected[mid];
    if (estimate) {
      // The stretch on its own odometry where the live estimate had its middle: the better
      // fit of the two (the larger share of points on the map) is the closure.
      const Pose2 frame = (*estimate)[mid] * log.entries[mid].scan.odometry.inverse();
      for (size_t i = begin; i < begin + k; ++i) anchored[i] = frame * log.entries[i].scan.odometry;
      const AlignmentResult b = fit(anchored);
      if (b.ok && (!a.ok || b.inliers * a.points > a.inliers * b.points)) {
        a = b;
        placed = anchored[mid];
      }
    }
    if (!a.ok) continue;
    PoseObservation o;
    o.entry = mid;
    o.pose = a.correction * placed;
    o.sigma_xy = config.closure_sigma_xy;
    o.sigma_theta = config.closure_sigma_theta;
    if (config.closure_shape)
      o.xy_information = closureInformation(a, o.pose.translation(), config);
    out.push_back(o);
  }
  return out;
}

}  // namespace coopmap

#include "core/agent/cooperation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/agent/placed_scans.h"

namespace coopmap {

using detail::movesWithin;
using detail::PlacedScans;

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
  if (!(team_frame_max_m > 0.0 && team_frame_max_rad > 0.0 && team_frame_min_points >= 1 &&
        team_frame_min_inliers >= 0.0 && team_frame_min_inliers <= 1.0))
    throw std::invalid_argument(
        "cooperation config: fields 'team_frame_max_m', 'team_frame_max_rad', "
        "'team_frame_min_points', 'team_frame_min_inliers': expected positive bounds, at least "
        "one point and a share in [0, 1]");
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
  next_post_ = shared_->lastPost(robot_) + 1;
}

HomeBaseCooperation::SharedView::SharedView(const SharedMapService& shared,
                                            const AlignmentConfig& config) {
  const SharedMapSnapshot snap = shared.snapshot();
  version = snap.version;
  if (snap.version == 0) return;
  map.emplace(shared.limits(), shared.config());
  map->assign(snap.log_odds, snap.seen);
  aligner.emplace(*map, config);
}

const char* toString(SortieStatus s) {
  switch (s) {
    case SortieStatus::kFixed:
      return "fixed";
    case SortieStatus::kNoEntries:
      return "no radial maps in the sortie";
    case SortieStatus::kNotLocalized:
      return "no fix from the look at the home base";
    case SortieStatus::kFixOnReference:
      return "the fix fell on a reference scan";
    case SortieStatus::kFixJumps:
      return "fix not trusted: it moves the robot farther than a sortie drifts";
    case SortieStatus::kRivalPlacement:
      return "fix not trusted: the look fits the shared map better elsewhere";
    case SortieStatus::kDisagrees:
      return "fix not trusted: far from where the first fix sent the robot";
    case SortieStatus::kCorrectionFailed:
      return "correction failed";
    case SortieStatus::kHomeUnlike:
      return "not shared: home does not look like the shared map's";
  }
  return "?";
}

HomeBaseCooperation::Located HomeBaseCooperation::locateSortie(const TraverseLog& sortie,
                                                               const SharedView& view,
                                                               size_t look_from) const {
  Located l;
  l.entries = sortie.entries.size();
  l.look_from = look_from;
  l.shared_version = view.version;
  SortieReport& rep = l.rep;
  rep.sortie = static_cast<int>(reports_.size()) + 1;
  rep.entries = sortie.entries.size();
  if (sortie.entries.empty()) {
    rep.status = SortieStatus::kNoEntries;
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
    l.protocol = runHomeBaseProtocol(sortie, nominal_, arm_length_, bounded, look_from);
    ret = l.protocol->result;
    rep.method = l.protocol->method;
  } else {
    TraverseLog joined = reference_log_;
    offset = joined.entries.size();
    joined.entries.insert(joined.entries.end(), sortie.entries.begin(), sortie.entries.end());
    ret = localizeFromLog(joined, home_, arm_length_, bounded, &*reference_, offset + look_from);
    rep.method = ret.refined ? "alignment to the reference" : "corners";
    if (ret.status == HomeReturnStatus::kOk && ret.observation.entry < offset) {
      rep.status = SortieStatus::kFixOnReference;
      rep.method = "the fix fell on a reference scan, not on the return turn";
      return l;
    }
  }
  if (ret.status != HomeReturnStatus::kOk) {
    rep.status = SortieStatus::kNotLocalized;
    rep.method = std::string(toString(ret.status)) +
                 (ret.alignment.message.empty() ? "" : " (" + ret.alignment.message + ")");
    return l;
  }
  l.observation = ret.observation;
  l.observation.entry -= offset;
  if (reference_ && config_.rival_search_m > 0.0 && view.aligner &&
      !checkRival(sortie, *view.aligner, l))
    return l;
  const Pose2& believed = sortie.entries[l.observation.entry].scan.odometry;
  rep.fix = l.observation.pose;
  rep.fix_stamp = sortie.entries[l.observation.entry].scan.stamp;
  rep.correction = l.observation.pose * believed.inverse();
  // How far the fix moves the robot from its pose on the sortie's odometry. Not the
  // correction's translation, which for a turn adds the turn times the robot's distance from
  // the map's origin: a right fix that mostly turns a long sortie would be refused as a long
  // move, and its robot would stop for good (measured:
  // docs/experiments/2026-12-building-sessions-25-34.md).
  if (!movesWithin(rep.correction, believed, config_.max_fix_jump_m, config_.max_fix_jump_rad)) {
    char note[96];
    std::snprintf(note, sizeof note, "fix not trusted: it moves the robot %.2f m and %.1f deg",
                  (rep.fix.translation() - believed.translation()).norm(),
                  wrapAngle(rep.fix.theta - believed.theta) * 180.0 / M_PI);
    rep.status = SortieStatus::kFixJumps;
    rep.method = note;
    return l;
  }
  rep.status = SortieStatus::kFixed;
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
  l.rep.status = SortieStatus::kRivalPlacement;
  return false;
}

void HomeBaseCooperation::checkExpected(SortieReport& rep,
                                        const std::optional<Eigen::Vector2d>& expected) const {
  if (rep.fixed() && expected &&
      (rep.fix.translation() - *expected).norm() > config_.max_disagreement_m) {
    rep.status = SortieStatus::kDisagrees;
    rep.method +=
        "; fix not trusted: " + std::to_string((rep.fix.translation() - *expected).norm()) +
        " m from where the first fix sent the robot";
  }
}

void HomeBaseCooperation::joinTeamFrame(const TraverseLog& sortie, const ScanAligner& aligner,
                                        std::vector<Pose2>& poses, SortieReport& rep) {
  // The whole corrected sortie against what the teammates have shared: one rigid motion.
  const PlacedScans all(sortie, poses, 0, poses.size());
  const AlignmentResult a = aligner.align(all.pointers, Pose2());
  const Eigen::Vector2d mid = 0.5 * (home_.first.position + home_.second.position);
  char note[200];
  if (!a.ok || a.points < config_.team_frame_min_points ||
      a.inliers < config_.team_frame_min_inliers * a.points ||
      !movesWithin(a.correction, Pose2(mid.x(), mid.y(), 0.0), config_.team_frame_max_m,
                   config_.team_frame_max_rad)) {
    std::snprintf(
        note, sizeof note, "; kept its own frame (no sure fit to the shared map: %s)",
        a.ok ? "it would move the home base too far or fits too few points" : a.message.c_str());
    rep.method += note;
    return;
  }
  const Pose2& T = a.correction;
  for (Pose2& p : poses) p = T * p;
  rep.team_frame = T;
  rep.correction = T * rep.correction;
  rep.fix = T * rep.fix;
  for (Corner* c : {&home_.first, &home_.second}) {
    c->position = T * c->position;
    c->heading = wrapAngle(c->heading + T.theta);
  }
  for (TraverseEntry& e : reference_log_.entries) e.scan.odometry = T * e.scan.odometry;
  if (reference_) reference_ = homeBaseReferenceMap(reference_log_, config_.home_return);
  const Pose2 moved = T * Pose2(mid.x(), mid.y(), 0.0);
  std::snprintf(note, sizeof note,
                "; joined the team's frame: turned %.2f deg, the home base moved %.1f cm (%d of "
                "%d points on the shared map)",
                T.theta * 180.0 / M_PI, 100.0 * (moved.translation() - mid).norm(), a.inliers,
                a.points);
  rep.method += note;
}

HomeBaseCooperation::Located HomeBaseCooperation::locate(
    const TraverseLog& sortie, const std::optional<Eigen::Vector2d>& expected,
    size_t look_from) const {
  Located l = locateSortie(sortie, SharedView(*shared_, config_.closure_alignment), look_from);
  l.expected = expected;
  checkExpected(l.rep, expected);
  return l;
}

SortieReport HomeBaseCooperation::endSortie(const TraverseLog& sortie,
                                            const std::optional<Eigen::Vector2d>& expected,
                                            const std::vector<Pose2>* estimate, size_t look_from,
                                            const Located* located) {
  // The shared map as it is now, prepared for alignment (once).
  const SharedView view(*shared_, config_.closure_alignment);
  const bool same = located && located->entries == sortie.entries.size() &&
                    located->look_from == look_from && located->expected == expected &&
                    located->shared_version == view.version &&
                    located->rep.sortie == static_cast<int>(reports_.size()) + 1;
  Located l = same ? *located : locateSortie(sortie, view, look_from);
  if (!same) checkExpected(l.rep, expected);
  SortieReport& rep = l.rep;
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
  if (!rep.fixed()) return done();
  const PoseObservation& observation = l.observation;

  // Correct the sortie's traverse and share it.
  CorrectionResult c = correctTraverse(sortie, observation, config_.correction);
  if (!c.ok) {
    rep.status = SortieStatus::kCorrectionFailed;
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
  if (aligner && config_.join_team_frame && !joined_) joinTeamFrame(sortie, *aligner, c.poses, rep);
  joined_ = true;  // a robot joins with its first post, or keeps its own frame
  if (aligner) {
    const size_t k = std::min(n, static_cast<size_t>(config_.home_check_scans));
    const PlacedScans look(sortie, c.poses, n - k, n);
    const std::vector<Eigen::Vector2d> points = aligner->obstaclePoints(look.pointers);
    if (points.size() >= 50) {
      rep.home_agreement = aligner->score(points, Pose2());
      if (rep.home_agreement < config_.min_home_agreement) {
        rep.status = SortieStatus::kHomeUnlike;
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

}  // namespace coopmap

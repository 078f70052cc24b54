// The cooperation layer's corrections against the shared map and the walls (declared in
// core/agent/cooperation.h): the post gate's misplaced stretches, the walls' headings, and the
// closures of a corrected sortie's stretches to the shared map.
#include "core/agent/cooperation.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/agent/placed_scans.h"

namespace coopmap {

using detail::movesWithin;
using detail::PlacedScans;

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

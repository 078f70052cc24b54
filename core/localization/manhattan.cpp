#include "core/localization/manhattan.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace coopmap {

void ManhattanConfig::validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("ManhattanConfig: ") + what);
  };
  require(std::isfinite(axes_rad), "axes_rad must be finite");
  require(search_rad > 0.0 && search_rad < 0.7, "search_rad must be in (0, 0.7) rad");
  require(step_rad > 0.0 && step_rad <= search_rad, "step_rad must be in (0, search_rad]");
  require(bin_m > 0.0, "bin_m must be positive");
  require(min_points >= 2, "min_points must be at least 2");
  require(min_sharpness_gain >= 1.0, "min_sharpness_gain must be at least 1");
  require(min_wall_points >= 2, "min_wall_points must be at least 2");
  require(min_wall_m > 0.0, "min_wall_m must be positive");
  require(min_wall_samples >= 3, "min_wall_samples must be at least 3");
  require(max_gap_m > 0.0, "max_gap_m must be positive");
}

namespace {

// `d` turned by -turn, given turn's cosine and sine.
Eigen::Vector2d turnedBack(const Eigen::Vector2d& d, double c, double s) {
  return {c * d.x() + s * d.y(), -s * d.x() + c * d.y()};
}

// Sum of squared bin counts of the points' coordinates along both axes, after turning them by
// -turn about the centre they are given from: the more points share a bin (a wall along an
// axis), the larger. `counts` holds 2 * `half_bins` bins per axis.
double sharpness(const std::vector<Eigen::Vector2d>& centred, double turn, double bin,
                 int half_bins, std::vector<int>& counts) {
  const double c = std::cos(turn), s = std::sin(turn);
  const int n = 2 * half_bins;
  counts.assign(2 * static_cast<size_t>(n), 0);
  for (const Eigen::Vector2d& d : centred) {
    const Eigen::Vector2d q = turnedBack(d, c, s);
    const double x = q.x(), y = q.y();
    ++counts[static_cast<size_t>(
        std::clamp(static_cast<int>(std::floor(x / bin)) + half_bins, 0, n - 1))];
    ++counts[static_cast<size_t>(
        n + std::clamp(static_cast<int>(std::floor(y / bin)) + half_bins, 0, n - 1))];
  }
  double score = 0.0;
  for (int k : counts) score += static_cast<double>(k) * k;
  return score;
}

}  // namespace

std::optional<ManhattanFit> manhattanTurn(const std::vector<Eigen::Vector2d>& points,
                                          const ManhattanConfig& config) {
  config.validate();
  if (static_cast<int>(points.size()) < config.min_points) return std::nullopt;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  std::vector<Eigen::Vector2d> centred;
  centred.reserve(points.size());
  double radius = 0.0;
  for (const Eigen::Vector2d& p : points) {
    centred.push_back(p - centre);
    radius = std::max(radius, centred.back().norm());
  }
  const int half_bins = static_cast<int>(std::ceil(radius / config.bin_m)) + 1;
  std::vector<int> counts;
  const int half = static_cast<int>(std::floor(config.search_rad / config.step_rad));
  std::vector<double> scores;
  scores.reserve(2 * half + 1);
  for (int k = -half; k <= half; ++k)
    scores.push_back(
        sharpness(centred, config.axes_rad + k * config.step_rad, config.bin_m, half_bins, counts));
  const size_t best =
      static_cast<size_t>(std::max_element(scores.begin(), scores.end()) - scores.begin());
  if (best == 0 || best + 1 == scores.size()) return std::nullopt;
  std::vector<double> sorted = scores;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  if (!(median > 0.0) || scores[best] < config.min_sharpness_gain * median) return std::nullopt;
  // The histograms place the walls to a bin over their length (a degree for 3 m of wall
  // with 5 cm bins): the turn is refined by fitting a line to each wall they found.
  const double coarse = static_cast<double>(best) - half;
  const double turn0 = config.axes_rad + coarse * config.step_rad;
  const double c = std::cos(turn0), s = std::sin(turn0);
  std::vector<Eigen::Vector2d> turned;  // on the axes, by the coarse turn
  turned.reserve(centred.size());
  for (const Eigen::Vector2d& d : centred) turned.push_back(turnedBack(d, c, s));
  sharpness(centred, turn0, config.bin_m, half_bins, counts);
  const int n = 2 * half_bins;
  double weighted = 0.0, weights = 0.0;
  int walls = 0;
  for (int axis = 0; axis < 2; ++axis) {  // 0: walls across x (along y), 1: along x
    const int* h = counts.data() + axis * n;
    for (int b = 0; b < n; ++b) {
      if (h[b] < config.min_wall_points || (b > 0 && h[b - 1] > h[b]) ||
          (b + 1 < n && h[b + 1] >= h[b]))
        continue;
      const double at = (b - half_bins + 0.5) * config.bin_m;
      // The band's points by bins along it, each bin's median across: a clump (the end of a
      // wall that crosses this one, a person) counts as one sample like any stretch of wall.
      std::map<int, std::vector<double>> by_bin;
      int in_band = 0;
      for (const Eigen::Vector2d& q : turned)
        if (std::abs(q[axis] - at) <= 1.5 * config.bin_m) {
          by_bin[static_cast<int>(std::floor(q[1 - axis] / config.bin_m))].push_back(q[axis]);
          ++in_band;
        }
      if (in_band < config.min_wall_points) continue;
      std::vector<Eigen::Vector2d> samples;  // (along, across)
      for (auto& [k, across] : by_bin) {
        std::nth_element(across.begin(), across.begin() + across.size() / 2, across.end());
        samples.emplace_back((k + 0.5) * config.bin_m, across[across.size() / 2]);
      }
      // Runs of samples without gaps are walls; their first and last samples (corners) are
      // left out.
      size_t start = 0;
      for (size_t e = 1; e <= samples.size(); ++e) {
        if (e < samples.size() && samples[e].x() - samples[e - 1].x() <= config.max_gap_m) continue;
        std::vector<Eigen::Vector2d> run(samples.begin() + static_cast<long>(start),
                                         samples.begin() + static_cast<long>(e));
        start = e;
        if (run.size() < 3) continue;
        run = std::vector<Eigen::Vector2d>(run.begin() + 1, run.end() - 1);
        if (static_cast<int>(run.size()) < config.min_wall_samples ||
            run.back().x() - run.front().x() < config.min_wall_m)
          continue;
        // across = a + slope * along, fitted again without the samples far from the line.
        double slope = 0.0, rms = 0.0;
        std::vector<Eigen::Vector2d> kept = run;
        for (int pass = 0; pass < 2 && kept.size() >= 3; ++pass) {
          Eigen::Vector2d mean = Eigen::Vector2d::Zero();
          for (const Eigen::Vector2d& q : kept) mean += q;
          mean /= static_cast<double>(kept.size());
          double suu = 0.0, suv = 0.0;
          for (const Eigen::Vector2d& q : kept) {
            suu += (q.x() - mean.x()) * (q.x() - mean.x());
            suv += (q.x() - mean.x()) * (q.y() - mean.y());
          }
          slope = suv / suu;
          double ss = 0.0;
          for (const Eigen::Vector2d& q : kept) {
            const double r = q.y() - mean.y() - slope * (q.x() - mean.x());
            ss += r * r;
          }
          rms = std::sqrt(ss / static_cast<double>(kept.size()));
          if (pass == 0) {
            std::vector<Eigen::Vector2d> near;
            for (const Eigen::Vector2d& q : kept)
              if (std::abs(q.y() - mean.y() - slope * (q.x() - mean.x())) <=
                  2.5 * std::max(rms, 0.01))
                near.push_back(q);
            kept.swap(near);
          }
        }
        if (static_cast<int>(kept.size()) < config.min_wall_samples) continue;
        // Along x (axis 1) the slope is the wall's turn; along y a turn tilts x = a + slope y
        // the other way.
        const double deviation = axis == 1 ? std::atan(slope) : -std::atan(slope);
        if (std::abs(deviation) > config.search_rad) continue;
        const double extent = kept.back().x() - kept.front().x();
        const double sigma = std::max(rms, 0.005);
        // A line's direction is known to about sigma / (extent sqrt(n / 12)).
        const double w = static_cast<double>(kept.size()) * extent * extent / (sigma * sigma);
        weighted += w * deviation;
        weights += w;
        ++walls;
      }
    }
  }
  if (walls == 0) return std::nullopt;
  const double turn = coarse * config.step_rad + weighted / weights;
  if (std::abs(turn) > config.search_rad) return std::nullopt;
  ManhattanFit fit;
  fit.turn_rad = turn;
  fit.gain = scores[best] / median;
  fit.points = static_cast<int>(points.size());
  fit.walls = walls;
  return fit;
}

}  // namespace coopmap

#include "core/landmarks/corner_detector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace coopmap {

namespace {
constexpr double kDeg = M_PI / 180.0;
// The 8 directions i * 45 degrees as grid steps.
constexpr std::array<std::array<int, 2>, 8> kSteps = {
    {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};

double det3(const Eigen::Matrix3d& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
         m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}

// Solves the 3x3 system A x = b (A symmetric positive definite here) by Cramer's rule.
Eigen::Vector3d solve3(const Eigen::Matrix3d& A, const Eigen::Vector3d& b) {
  const double det = det3(A);
  Eigen::Vector3d x;
  for (int k = 0; k < 3; ++k) {
    Eigen::Matrix3d M = A;
    M.col(k) = b;
    x(k) = det3(M) / det;
  }
  return x;
}
}  // namespace

const char* toString(CornerStatus s) {
  switch (s) {
    case CornerStatus::kOk:
      return "ok";
    case CornerStatus::kNoCandidates:
      return "no corner candidates";
    case CornerStatus::kNoConvergence:
      return "no fit converged";
    case CornerStatus::kRmsTooHigh:
      return "every fit's RMS is above the gate";
  }
  return "?";
}

void CornerConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("corner config: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (grow_iterations < 0 || grow_iterations > 20) bad("grow_iterations", "0..20", grow_iterations);
  if (dilate_iterations < 0 || dilate_iterations > 5)
    bad("dilate_iterations", "0..5", dilate_iterations);
  if (line_cells < 1 || line_cells > 50) bad("line_cells", "1..50", line_cells);
  if (!(arm_cells >= 2.0 && arm_cells <= 200.0)) bad("arm_cells", "2..200", arm_cells);
  if (!(point_spacing > 0.0 && point_spacing <= arm_cells / 2))
    bad("point_spacing", "(0, arm_cells / 2]", point_spacing);
  if (!(truncate_cells > 0.0)) bad("truncate_cells", "a positive number", truncate_cells);
  if (!(damping >= 0.0)) bad("damping", "a number >= 0", damping);
  if (max_iterations < 1 || max_iterations > 100) bad("max_iterations", "1..100", max_iterations);
  if (!(min_step > 0.0)) bad("min_step", "a positive number", min_step);
  if (!(max_rms > 0.0)) bad("max_rms", "a positive number", max_rms);
  if (upsample < 1 || upsample > 8) bad("upsample", "1..8", upsample);
}

GridU8 classifyCells(const OccupancyGrid& grid) {
  const MapLimits& lim = grid.limits();
  GridU8 out(lim, static_cast<uint8_t>(CellClass::kUnknown));
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      if (!grid.seen(ix, iy)) continue;
      const CellState s = grid.state(ix, iy);
      out.at(ix, iy) = static_cast<uint8_t>(s == CellState::kFree       ? CellClass::kFree
                                            : s == CellState::kOccupied ? CellClass::kOccupied
                                                                        : CellClass::kUncertain);
    }
  return out;
}

CornerDetector::CornerDetector(const GridU8& classes, const CornerConfig& config)
    : config_(config), limits_(classes.limits) {
  config_.validate();
  const int W = limits_.width, H = limits_.height;
  if (W <= 0 || H <= 0) throw std::invalid_argument("CornerDetector: empty grid");
  const auto kFree = static_cast<uint8_t>(CellClass::kFree);
  const auto kOcc = static_cast<uint8_t>(CellClass::kOccupied);
  const auto kUnc = static_cast<uint8_t>(CellClass::kUncertain);

  // Grow the regions of certainty into uncertain cells; never-seen cells stay unknown.
  GridU8 grown = classes;
  for (int it = 0; it < config_.grow_iterations; ++it) {
    GridU8 next = grown;
    bool changed = false;
    for (int iy = 0; iy < H; ++iy)
      for (int ix = 0; ix < W; ++ix) {
        if (grown.at(ix, iy) != kUnc) continue;
        int free = 0, occ = 0;
        for (const auto& s : {std::array<int, 2>{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int x = ix + s[0], y = iy + s[1];
          if (!limits_.contains(x, y)) continue;
          free += grown.at(x, y) == kFree;
          occ += grown.at(x, y) == kOcc;
        }
        if (occ > 0 && occ >= free)
          next.at(ix, iy) = kOcc, changed = true;
        else if (free > 0)
          next.at(ix, iy) = kFree, changed = true;
      }
    grown = std::move(next);
    if (!changed) break;
  }

  // Edges: occupied cells touching free cells. The distance field's zero set is the border
  // between them: field pixel (u, v) sits at cell coordinates (u, v) / upsample, so cell
  // borders fall on pixel centres and the zero set is exact.
  const int up = config_.upsample;
  edges_ = GridU8(limits_, 0);
  cv::Mat border(H * up + 1, W * up + 1, CV_8UC1, cv::Scalar(255));
  for (int iy = 0; iy < H; ++iy)
    for (int ix = 0; ix < W; ++ix) {
      if (grown.at(ix, iy) != kOcc) continue;
      for (const auto& s : {std::array<int, 2>{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int x = ix + s[0], y = iy + s[1];
        if (!limits_.contains(x, y) || grown.at(x, y) != kFree) continue;
        edges_.at(ix, iy) = 1;
        if (s[0] != 0) {  // a vertical border at x = ix + (s[0] > 0)
          const int u = up * (ix + (s[0] > 0 ? 1 : 0));
          for (int v = up * iy; v <= up * (iy + 1); ++v) border.at<uint8_t>(v, u) = 0;
        } else {  // a horizontal border at y = iy + (s[1] > 0)
          const int v = up * (iy + (s[1] > 0 ? 1 : 0));
          for (int u = up * ix; u <= up * (ix + 1); ++u) border.at<uint8_t>(v, u) = 0;
        }
      }
    }
  cv::distanceTransform(border, field_, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  // Signed: negative inside occupied cells, so the field crosses zero linearly at the
  // border and its interpolation locates the border to a fraction of a cell.
  for (int v = 0; v < field_.rows; ++v) {
    float* row = field_.ptr<float>(v);
    const int iy = std::min(v / up, H - 1);
    for (int u = 0; u < field_.cols; ++u) {
      const bool occupied = grown.at(std::min(u / up, W - 1), iy) == kOcc;
      row[u] *= (occupied ? -1.0f : 1.0f) / up;
    }
  }
  if (config_.smoothing_cells > 0.0)
    cv::GaussianBlur(field_, field_, cv::Size(0, 0), config_.smoothing_cells * up);

  cv::Mat e(H, W, CV_8UC1, edges_.cells.data());
  cv::Mat d;
  if (config_.dilate_iterations > 0)
    cv::dilate(e, d, cv::Mat(), cv::Point(-1, -1), config_.dilate_iterations);
  else
    d = e.clone();
  dilated_ = GridU8(limits_, 0);
  std::copy(d.datastart, d.dataend, dilated_.cells.begin());
  candidates_ = findCandidates();
}

double CornerDetector::distance(double cx, double cy) const {
  const int up = config_.upsample;
  const double px = cx * up, py = cy * up;
  const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= field_.cols || y0 + 1 >= field_.rows)
    return config_.truncate_cells;
  const double fx = px - x0, fy = py - y0;
  const float* r0 = field_.ptr<float>(y0);
  const float* r1 = field_.ptr<float>(y0 + 1);
  return (r0[x0] * (1 - fx) + r0[x0 + 1] * fx) * (1 - fy) +
         (r1[x0] * (1 - fx) + r1[x0 + 1] * fx) * fy;
}

Corner CornerDetector::fit(const Eigen::Vector2d& position, double heading) const {
  const double res = limits_.resolution;
  Eigen::Vector3d x((position.x() - limits_.origin.x()) / res,
                    (position.y() - limits_.origin.y()) / res, heading / kDeg);
  const double T = config_.truncate_cells, h = 0.25;
  const int per_arm = static_cast<int>(std::floor(config_.arm_cells / config_.point_spacing));
  const double w2 = config_.damping * config_.damping;
  Corner c;
  // Residuals (capped distances) of the model points, and the normal equations.
  auto evaluate = [&](const Eigen::Vector3d& p, Eigen::Matrix3d* A, Eigen::Vector3d* g) {
    double sse = 0.0;
    int n = 0;
    for (int arm = -1; arm <= 1; arm += 2) {
      const double a = (p.z() + arm * 45.0) * kDeg;
      const Eigen::Vector2d dir(std::cos(a), std::sin(a)), ddir(-std::sin(a), std::cos(a));
      for (int k = arm < 0 ? 0 : 1; k <= per_arm; ++k) {
        const double t = k * config_.point_spacing;
        const Eigen::Vector2d m = p.head<2>() + t * dir;
        const double d = distance(m.x(), m.y());
        const double e = std::clamp(d, -T, T);
        sse += e * e;
        ++n;
        if (!A || std::abs(d) >= T) continue;  // capped: no pull
        const double gx = (distance(m.x() + h, m.y()) - distance(m.x() - h, m.y())) / (2 * h);
        const double gy = (distance(m.x(), m.y() + h) - distance(m.x(), m.y() - h)) / (2 * h);
        const Eigen::Vector3d J(gx, gy, (gx * ddir.x() + gy * ddir.y()) * t * kDeg);
        *A += J * J.transpose();
        *g += J * e;
      }
    }
    return std::sqrt(sse / std::max(1, n));
  };
  // The candidates' headings come in 45 degree steps and their cells sit on the edge, not
  // at the vertex: refine the start by a coarse search (heading in 2.5 degree steps, vertex
  // within a cell) of the model's capped error, then fit.
  {
    Eigen::Vector3d best_x = x;
    double best = evaluate(x, nullptr, nullptr);
    for (double dz = -25.0; dz <= 25.0; dz += 2.5)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Vector3d t(x.x() + dx, x.y() + dy, x.z() + dz);
          const double e = evaluate(t, nullptr, nullptr);
          if (e < best) best = e, best_x = t;
        }
    x = best_x;
  }
  // Damped Gauss-Newton, (J'J + W'W) dx = -J'e. Distances to edges do not vanish at the
  // optimum (cells quantise the walls), so a step that would raise the error is halved.
  double err = evaluate(x, nullptr, nullptr);
  for (int it = 0; it < config_.max_iterations; ++it) {
    Eigen::Matrix3d A = w2 * Eigen::Matrix3d::Identity();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    evaluate(x, &A, &g);
    Eigen::Vector3d step = -solve3(A, g);
    if (!step.allFinite()) break;
    double next = evaluate(x + step, nullptr, nullptr);
    for (int halvings = 0; next > err && halvings < 6; ++halvings) {
      step *= 0.5;
      next = evaluate(x + step, nullptr, nullptr);
    }
    c.iterations = it + 1;
    if (next > err) {  // no descent along the step: at the optimum to this precision
      c.converged = true;
      break;
    }
    x += step;
    err = next;
    const double moved = step.cwiseAbs().maxCoeff();
    if (moved < config_.min_step) {
      c.converged = true;
      break;
    }
    // Out of iterations: settled if the last step was small; still moving otherwise.
    if (it + 1 == config_.max_iterations) c.converged = moved < config_.settled_step;
  }
  c.rms = evaluate(x, nullptr, nullptr);
  // Support: the share of each arm's points lying on an edge (within one cell).
  c.support = 1.0;
  for (int arm = -1; arm <= 1; arm += 2) {
    const double a = (x.z() + arm * 45.0) * kDeg;
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    int on = 0;
    for (int k = 1; k <= per_arm; ++k) {
      const Eigen::Vector2d m = x.head<2>() + k * config_.point_spacing * dir;
      on += std::abs(distance(m.x(), m.y())) <= 1.0;
    }
    c.support = std::min(c.support, static_cast<double>(on) / std::max(1, per_arm));
  }
  c.position = limits_.origin + x.head<2>() * res;
  c.heading = std::remainder(x.z() * kDeg, 2 * M_PI);
  return c;
}

std::vector<CornerDetector::Guess> CornerDetector::findCandidates() const {
  std::vector<Guess> out;
  GridU8 taken(limits_, 0);  // bit i: a candidate of orientation i is near
  const int L = config_.line_cells, W = limits_.width, H = limits_.height;
  auto extends = [&](int ix, int iy, int i) {
    for (int k = 1; k <= L; ++k) {
      const int x = ix + k * kSteps[i][0], y = iy + k * kSteps[i][1];
      if (!limits_.contains(x, y) || !dilated_.at(x, y)) return false;
    }
    return true;
  };
  for (int iy = 0; iy < H; ++iy)
    for (int ix = 0; ix < W; ++ix) {
      if (!edges_.at(ix, iy)) continue;
      int bits = 0;
      for (int i = 0; i < 8; ++i) bits |= extends(ix, iy, i) << i;
      for (int i = 0; i < 8; ++i) {
        if (!(bits >> i & 1) || !(bits >> ((i + 2) % 8) & 1)) continue;
        if (taken.at(ix, iy) >> i & 1) continue;
        out.push_back({{ix + 0.5, iy + 0.5}, (i + 1) * 45.0});
        for (int y = std::max(0, iy - 3); y <= std::min(H - 1, iy + 3); ++y)
          for (int x = std::max(0, ix - 3); x <= std::min(W - 1, ix + 3); ++x)
            taken.at(x, y) = static_cast<uint8_t>(taken.at(x, y) | (1 << i));
      }
    }
  return out;
}

CornerSearch CornerDetector::search(const std::vector<Guess>& guesses) const {
  CornerSearch s;
  s.candidates = static_cast<int>(guesses.size());
  const double res = limits_.resolution;
  for (const Guess& g : guesses) {
    const Corner c = fit(limits_.origin + g.cell * res, g.degrees * kDeg);
    if (!c.converged) {
      ++s.not_converged;
      continue;
    }
    if (c.rms > config_.max_rms || c.support < config_.min_support) {
      ++s.rejected_rms;
      continue;
    }
    bool merged = false;
    for (Corner& o : s.corners) {
      const double dd = (o.position - c.position).norm() / res;
      const double da = std::abs(std::remainder(o.heading - c.heading, 2 * M_PI)) / kDeg;
      // One corner per place: fits that land together are the same corner (or an
      // ambiguous spot); the clearly better supported, else the lower-RMS, fit stands.
      if (dd < config_.merge_cells ||
          (dd < 2 * config_.merge_cells && da < config_.merge_degrees)) {
        if (c.support > o.support + 0.1 || (c.support > o.support - 0.1 && c.rms < o.rms)) o = c;
        merged = true;
        break;
      }
    }
    if (!merged) s.corners.push_back(c);
  }
  std::sort(s.corners.begin(), s.corners.end(),
            [](const Corner& a, const Corner& b) { return a.rms < b.rms; });
  s.status = !s.corners.empty()    ? CornerStatus::kOk
             : guesses.empty()     ? CornerStatus::kNoCandidates
             : s.rejected_rms == 0 ? CornerStatus::kNoConvergence
                                   : CornerStatus::kRmsTooHigh;
  return s;
}

CornerSearch CornerDetector::findAll() const { return search(candidates_); }

CornerSearch CornerDetector::findNear(const Eigen::Vector2d& predicted, double radius,
                                      std::optional<double> predicted_heading) const {
  std::vector<Guess> near;
  const double res = limits_.resolution;
  for (const Guess& g : candidates_)
    if ((limits_.origin + g.cell * res - predicted).norm() <= radius) near.push_back(g);
  // The prediction itself seeds a fit when its heading is known; with no candidate near
  // (edges broken by missing cells), it seeds fits at the eight candidate orientations.
  const Eigen::Vector2d at = (predicted - limits_.origin) / res;
  if (predicted_heading) {
    near.push_back({at, *predicted_heading / kDeg});
  } else if (near.empty()) {
    for (int i = 0; i < 8; ++i) near.push_back({at, (i + 1) * 45.0});
  }
  CornerSearch s = search(near);
  std::sort(s.corners.begin(), s.corners.end(), [&](const Corner& a, const Corner& b) {
    return (a.position - predicted).norm() < (b.position - predicted).norm();
  });
  return s;
}

}  // namespace coopmap

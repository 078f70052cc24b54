#include "core/odometry/drift_stats.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace coopmap {

std::vector<StampedPose2> integrateVelocities(const std::vector<VelocitySample>& odometry,
                                              const Pose2& start,
                                              const std::vector<double>& stamps) {
  std::vector<StampedPose2> out;
  out.reserve(stamps.size());
  Pose2 p = start;
  double t = stamps.empty() ? 0.0 : stamps.front();
  size_t k = 0;  // the odometry sample in force at time t
  while (k + 1 < odometry.size() && odometry[k + 1].stamp <= t) ++k;
  for (double target : stamps) {
    while (t < target) {
      const double next =
          k + 1 < odometry.size() ? std::min(odometry[k + 1].stamp, target) : target;
      const double dt = next - t;
      const double v = odometry.empty() || odometry[k].stamp > t ? 0.0 : odometry[k].v;
      const double w = odometry.empty() || odometry[k].stamp > t ? 0.0 : odometry[k].w;
      const double mid = p.theta + 0.5 * w * dt;
      p.x += v * dt * std::cos(mid);
      p.y += v * dt * std::sin(mid);
      p.theta = wrapAngle(p.theta + w * dt);
      t = next;
      if (k + 1 < odometry.size() && odometry[k + 1].stamp <= t) ++k;
    }
    out.push_back({target, p});
  }
  return out;
}

DriftStats driftStats(const std::vector<StampedPose2>& truth,
                      const std::vector<StampedPose2>& odometry, double window_s) {
  if (truth.size() != odometry.size() || truth.size() < 2)
    throw std::invalid_argument(
        "driftStats: truth and odometry must be sampled at the same stamps");
  struct Window {
    double d, turned, turned_signed, dtheta, ds;
  };
  std::vector<Window> ws;
  size_t i0 = 0;
  while (i0 < truth.size()) {
    size_t i1 = i0;
    double d = 0.0, turned = 0.0, signed_turn = 0.0;
    while (i1 + 1 < truth.size() && truth[i1 + 1].stamp - truth[i0].stamp <= window_s) {
      const Pose2 &a = truth[i1].pose, &b = truth[i1 + 1].pose;
      d += std::hypot(b.x - a.x, b.y - a.y);
      const double dth = wrapAngle(b.theta - a.theta);
      turned += std::abs(dth);
      signed_turn += dth;
      ++i1;
    }
    if (i1 == i0 || truth[i1].stamp - truth[i0].stamp < 0.8 * window_s) break;
    const Pose2 dt = truth[i0].pose.inverse() * truth[i1].pose;
    const Pose2 dodo = odometry[i0].pose.inverse() * odometry[i1].pose;
    Window w;
    w.d = d;
    w.turned = turned;
    w.turned_signed = signed_turn;
    w.dtheta = wrapAngle(dt.theta - dodo.theta);
    w.ds = std::hypot(dodo.x, dodo.y) - std::hypot(dt.x, dt.y);
    ws.push_back(w);
    i0 = i1;
  }
  DriftStats s;
  s.windows = static_cast<int>(ws.size());
  s.window_s = window_s;
  if (ws.size() < 3) return s;
  // Systematic heading error: least squares dtheta = a d + b turned_signed.
  double sdd = 0, stt = 0, sdt = 0, sde = 0, ste = 0;
  double sum_d = 0, sum_ds = 0;
  for (const Window& w : ws) {
    sdd += w.d * w.d;
    stt += w.turned_signed * w.turned_signed;
    sdt += w.d * w.turned_signed;
    sde += w.d * w.dtheta;
    ste += w.turned_signed * w.dtheta;
    sum_d += w.d;
    sum_ds += w.ds;
    s.metres_per_window += w.d;
    s.radians_per_window += w.turned;
  }
  const double det = sdd * stt - sdt * sdt;
  if (std::abs(det) > 1e-12) {
    s.heading_bias_per_m = (sde * stt - ste * sdt) / det;
    s.turn_bias = (ste * sdd - sde * sdt) / det;
  }
  s.scale_bias = sum_d > 0 ? sum_ds / sum_d : 0.0;
  // Random parts: residual variances regressed on d and |turned| (non-negative).
  double a11 = 0, a22 = 0, a12 = 0, b1 = 0, b2 = 0, dd = 0, dr = 0;
  for (const Window& w : ws) {
    const double r = w.dtheta - s.heading_bias_per_m * w.d - s.turn_bias * w.turned_signed;
    a11 += w.d * w.d;
    a22 += w.turned * w.turned;
    a12 += w.d * w.turned;
    b1 += w.d * r * r;
    b2 += w.turned * r * r;
    const double rd = w.ds - s.scale_bias * w.d;
    dd += w.d * w.d;
    dr += w.d * rd * rd;
  }
  const double det2 = a11 * a22 - a12 * a12;
  double vm = 0, vr = 0;
  if (std::abs(det2) > 1e-12) {
    vm = (b1 * a22 - b2 * a12) / det2;
    vr = (b2 * a11 - b1 * a12) / det2;
  }
  if (vm < 0) vm = 0, vr = a22 > 0 ? b2 / a22 : 0;  // constrained fits
  if (vr < 0) vr = 0, vm = a11 > 0 ? b1 / a11 : 0;
  s.heading_sigma_per_sqrt_m = std::sqrt(std::max(0.0, vm));
  s.heading_sigma_per_sqrt_rad = std::sqrt(std::max(0.0, vr));
  s.distance_sigma_per_sqrt_m = dd > 0 ? std::sqrt(std::max(0.0, dr / dd)) : 0.0;
  s.metres_per_window /= ws.size();
  s.radians_per_window /= ws.size();
  return s;
}

namespace {
template <typename Row>
std::vector<Row> readRows(const std::string& path, int columns, Row (*make)(const double* values)) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open file");
  std::vector<Row> rows;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    double v[4] = {0, 0, 0, 0};
    for (int c = 0; c < columns; ++c)
      if (!(ss >> v[c]))
        throw std::runtime_error(path + ":" + std::to_string(n) + ": expected " +
                                 std::to_string(columns) + " numbers, got '" + line + "'");
    rows.push_back(make(v));
  }
  return rows;
}
}  // namespace

std::vector<StampedPose2> readUtiasGroundtruth(const std::string& path) {
  return readRows<StampedPose2>(path, 4, [](const double* v) {
    return StampedPose2{v[0], Pose2(v[1], v[2], v[3])};
  });
}

std::vector<VelocitySample> readUtiasOdometry(const std::string& path) {
  return readRows<VelocitySample>(path, 3, [](const double* v) {
    return VelocitySample{v[0], v[1], v[2]};
  });
}

}  // namespace coopmap

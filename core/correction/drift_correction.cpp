#include "core/correction/drift_correction.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace coopmap {

namespace {

// One odometry step between consecutive log entries, in the frame of the earlier pose.
struct Step {
  double ds = 0.0;      // m, signed along the direction of travel
  double phi = 0.0;     // rad, direction of travel relative to the earlier heading
  double dtheta = 0.0;  // rad, heading change
  MotionSegment segment = MotionSegment::kStop;
};

// One odometry increment u = X_O(i-1)O(i) as a step.
Step stepOf(const Pose2& u) {
  Step s;
  s.ds = std::hypot(u.x, u.y);
  s.phi = s.ds > 1e-9 ? std::atan2(u.y, u.x) : 0.0;
  if (std::cos(s.phi) < 0.0) {  // backwards
    s.ds = -s.ds;
    s.phi = wrapAngle(s.phi + M_PI);
  }
  s.dtheta = u.theta;
  return s;
}

std::vector<Step> stepsOf(const TraverseLog& log, size_t last) {
  std::vector<Step> steps;
  steps.reserve(last);
  for (size_t i = 1; i <= last; ++i) {
    Step s = stepOf(log.entries[i - 1].scan.odometry.inverse() * log.entries[i].scan.odometry);
    s.segment = log.entries[i].segment;
    steps.push_back(s);
  }
  return steps;
}

// A step with the systematic errors b (rad/m), k (turn scale), sigma (distance scale)
// taken out: the motion the robot really made if the odometry erred by exactly these.
template <typename T>
void correctedStep(const Step& s, const T* bias, T* ds, T* phi, T* dtheta) {
  *ds = T(s.ds) / (T(1.0) + bias[2]);
  *dtheta = (T(s.dtheta) - bias[0] * T(std::abs(s.ds))) / (T(1.0) + bias[1]);
  *phi = T(s.phi) + T(0.5) * (*dtheta - T(s.dtheta));
}

// Dead reckoning of corrected steps from the identity; pose after the last step.
template <typename T>
void integrate(const std::vector<Step>& steps, const T* bias, T* pose) {
  T x(0.0), y(0.0), th(0.0);
  for (const Step& s : steps) {
    T ds, phi, dth;
    correctedStep(s, bias, &ds, &phi, &dth);
    x += ds * cos(th + phi);
    y += ds * sin(th + phi);
    th += dth;
  }
  pose[0] = x;
  pose[1] = y;
  pose[2] = th;
}

// The home-base residual of the heading-drift model: where the corrected odometry ends
// against where the home base says the robot is.
struct EndResidual {
  EndResidual(const std::vector<Step>* steps, const Pose2& target, double sxy, double sth)
      : steps(steps), target(target), sxy(sxy), sth(sth) {}
  template <typename T>
  bool operator()(const T* bias, T* r) const {
    T pose[3];
    integrate(*steps, bias, pose);
    r[0] = (pose[0] - T(target.x)) / T(sxy);
    r[1] = (pose[1] - T(target.y)) / T(sxy);
    // The heading is not wrapped: the corrected steps sum to the target's unwrapped heading.
    r[2] = (pose[2] - T(target.theta)) / T(sth);
    return true;
  }
  const std::vector<Step>* steps;
  Pose2 target;
  double sxy, sth;
};

struct BiasPrior {
  explicit BiasPrior(const OdometryErrorModel& m) : m(m) {}
  template <typename T>
  bool operator()(const T* bias, T* r) const {
    r[0] = bias[0] / T(m.prior_heading_drift);
    r[1] = bias[1] / T(m.prior_turn_scale);
    r[2] = bias[2] / T(m.prior_distance_scale);
    return true;
  }
  OdometryErrorModel m;
};

// Pose-graph odometry edge: the relative motion of two consecutive poses against the
// bias-corrected odometry step.
struct StepResidual {
  StepResidual(const Step& s, double sxy, double sth) : s(s), sxy(sxy), sth(sth) {}
  template <typename T>
  bool operator()(const T* a, const T* b, const T* bias, T* r) const {
    T ds, phi, dth;
    correctedStep(s, bias, &ds, &phi, &dth);
    const T c = cos(a[2]), sn = sin(a[2]);
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    const T rx = c * dx + sn * dy, ry = -sn * dx + c * dy;
    r[0] = (rx - ds * cos(phi)) / T(sxy);
    r[1] = (ry - ds * sin(phi)) / T(sxy);
    r[2] = (b[2] - a[2] - dth) / T(sth);
    return true;
  }
  Step s;
  double sxy, sth;
};

// A pose observed: position residual whitened by `sqrt_info` (U with U^T U the position's
// information), heading by its sigma.
struct PoseResidual {
  PoseResidual(const Pose2& target, const Eigen::Matrix2d& sqrt_info, double sth)
      : target(target), sqrt_info(sqrt_info), sth(sth) {}
  PoseResidual(const Pose2& target, double sxy, double sth)
      : PoseResidual(target, Eigen::Matrix2d::Identity() / sxy, sth) {}
  template <typename T>
  bool operator()(const T* p, T* r) const {
    const T dx = p[0] - T(target.x), dy = p[1] - T(target.y);
    r[0] = T(sqrt_info(0, 0)) * dx + T(sqrt_info(0, 1)) * dy;
    r[1] = T(sqrt_info(1, 0)) * dx + T(sqrt_info(1, 1)) * dy;
    r[2] = (p[2] - T(target.theta)) / T(sth);
    return true;
  }
  Pose2 target;
  Eigen::Matrix2d sqrt_info;
  double sth;
};

// The whitening of an observation's position in a frame turned by `theta` from the map's
// (positions there are R(theta) times the map's).
Eigen::Matrix2d positionSqrtInfo(const PoseObservation& o, double theta) {
  if (!o.xy_information) return Eigen::Matrix2d::Identity() / o.sigma_xy;
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(theta).toRotationMatrix();
  const Eigen::Matrix2d info = r * *o.xy_information * r.transpose();
  return info.llt().matrixU();
}

// Heading of `target` unwrapped to the one nearest `reference`.
double unwrapNear(double target, double reference) {
  return reference + wrapAngle(target - reference);
}

// Spreads the remaining pose error uniformly along the path (start-relative poses):
// the correction at arc length s is the fraction s / S of the whole.
void spreadUniformly(std::vector<Pose2>& rel, const Pose2& target) {
  const size_t n = rel.size();
  std::vector<double> arc(n, 0.0);
  for (size_t i = 1; i < n; ++i)
    arc[i] = arc[i - 1] + std::hypot(rel[i].x - rel[i - 1].x, rel[i].y - rel[i - 1].y);
  const double total = arc.back();
  const Pose2 end = rel.back();
  const double dtheta = wrapAngle(target.theta - end.theta);
  // Rotation about the start, then translation: the end lands exactly on the target.
  const double c = std::cos(dtheta), s = std::sin(dtheta);
  const Eigen::Vector2d t =
      target.translation() - Eigen::Vector2d(c * end.x - s * end.y, s * end.x + c * end.y);
  for (size_t i = 1; i < n; ++i) {
    const double f = total > 1e-9 ? arc[i] / total : static_cast<double>(i) / (n - 1);
    const Pose2 e(f * t.x(), f * t.y(), f * dtheta);
    rel[i] = e * rel[i];
  }
}

std::vector<Pose2> dead_reckon(const std::vector<Step>& steps, const double* bias) {
  std::vector<Pose2> rel(1);
  double x = 0, y = 0, th = 0;
  for (const Step& s : steps) {
    double ds, phi, dth;
    correctedStep(s, bias, &ds, &phi, &dth);
    x += ds * std::cos(th + phi);
    y += ds * std::sin(th + phi);
    th += dth;
    rel.emplace_back(x, y, wrapAngle(th));
  }
  return rel;
}

ceres::Solver::Options solverOptions(int max_iterations) {
  ceres::Solver::Options o;
  o.max_num_iterations = max_iterations;
  o.num_threads = 1;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  o.function_tolerance = 1e-10;
  o.parameter_tolerance = 1e-10;
  return o;
}

}  // namespace

Pose2 correctedIncrement(const Pose2& u, const OdometryBias& bias) {
  const Step s = stepOf(u);
  const double b[3] = {bias.heading_drift, bias.turn_scale, bias.distance_scale};
  double ds, phi, dtheta;
  correctedStep(s, b, &ds, &phi, &dtheta);
  return Pose2(ds * std::cos(phi), ds * std::sin(phi), dtheta);
}

const char* toString(CorrectionModel m) {
  switch (m) {
    case CorrectionModel::kNone:
      return "none";
    case CorrectionModel::kUniform:
      return "uniform";
    case CorrectionModel::kTurnsAndStraights:
      return "turns-and-straights";
    case CorrectionModel::kHeadingDrift:
      return "heading-drift";
    case CorrectionModel::kPoseGraph:
      return "pose-graph";
  }
  return "?";
}

const std::vector<CorrectionModel>& allCorrectionModels() {
  static const std::vector<CorrectionModel> all = {
      CorrectionModel::kNone, CorrectionModel::kUniform, CorrectionModel::kTurnsAndStraights,
      CorrectionModel::kHeadingDrift, CorrectionModel::kPoseGraph};
  return all;
}

std::optional<CorrectionModel> parseCorrectionModel(const std::string& name) {
  for (CorrectionModel m : allCorrectionModels())
    if (name == toString(m)) return m;
  return std::nullopt;
}

void OdometryErrorModel::validate() const {
  auto check = [](const char* field, double v) {
    if (!(v > 0.0 && std::isfinite(v)))
      throw std::invalid_argument(std::string("odometry error model: field '") + field +
                                  "': expected a positive number, got " + std::to_string(v));
  };
  check("linear_per_sqrt_m", linear_per_sqrt_m);
  check("heading_per_sqrt_m", heading_per_sqrt_m);
  check("angular_per_sqrt_rad", angular_per_sqrt_rad);
  check("prior_heading_drift", prior_heading_drift);
  check("prior_turn_scale", prior_turn_scale);
  check("prior_distance_scale", prior_distance_scale);
}

CorrectionResult correctTraverse(const TraverseLog& log, const PoseObservation& home,
                                 const CorrectionConfig& config,
                                 const std::vector<PoseObservation>& closures) {
  config.odometry.validate();
  CorrectionResult result;
  const size_t n = log.entries.size();
  if (n == 0 || home.entry >= n) {
    result.message = "the home-base observation names entry " + std::to_string(home.entry) +
                     " of a log of " + std::to_string(n);
    return result;
  }
  if (!(home.sigma_xy > 0.0 && home.sigma_theta > 0.0)) {
    result.message = "the home-base observation needs positive sigmas";
    return result;
  }
  // Work relative to the start pose (the map frame's pose of entry 0).
  const Pose2 start = log.entries.front().scan.odometry;
  const Pose2 start_inv = start.inverse();
  const size_t last = home.entry;
  const std::vector<Step> steps = stepsOf(log, last);
  std::vector<Pose2> rel(last + 1);
  for (size_t i = 0; i <= last; ++i) rel[i] = start_inv * log.entries[i].scan.odometry;
  Pose2 target = start_inv * home.pose;
  // Unwrapped headings: the target's heading continues the odometry's turning.
  double odo_heading = 0.0;
  for (const Step& s : steps) odo_heading += s.dtheta;
  target.theta = unwrapNear(target.theta, odo_heading);

  switch (config.model) {
    case CorrectionModel::kNone:
      break;
    case CorrectionModel::kUniform:
      spreadUniformly(rel, target);
      break;
    case CorrectionModel::kTurnsAndStraights: {
      // Rotation error over the turns in proportion to their angle, then dead reckoning
      // with the corrected turns, then the remaining translation over the straight runs in
      // proportion to their length.
      double turned = 0.0, straight = 0.0;
      for (const Step& s : steps) {
        if (s.segment == MotionSegment::kTurn) turned += std::abs(s.dtheta);
        if (s.segment == MotionSegment::kStraight) straight += std::abs(s.ds);
      }
      const double dtheta = target.theta - odo_heading;
      double x = 0, y = 0, th = 0;
      for (size_t i = 0; i < steps.size(); ++i) {
        const Step& s = steps[i];
        double dth = s.dtheta;
        if (s.segment == MotionSegment::kTurn && turned > 0)
          dth += dtheta * std::abs(s.dtheta) / turned;
        const double mid = th + s.phi + 0.5 * (dth - s.dtheta);
        x += s.ds * std::cos(mid);
        y += s.ds * std::sin(mid);
        th += dth;
        rel[i + 1] = Pose2(x, y, wrapAngle(th));
      }
      const Eigen::Vector2d residual = target.translation() - Eigen::Vector2d(x, y);
      double along = 0.0;
      for (size_t i = 0; i < steps.size(); ++i) {
        if (steps[i].segment == MotionSegment::kStraight) along += std::abs(steps[i].ds);
        const double f =
            straight > 0 ? along / straight : static_cast<double>(i + 1) / steps.size();
        rel[i + 1].x += f * residual.x();
        rel[i + 1].y += f * residual.y();
      }
      if (turned == 0.0) rel.back().theta = wrapAngle(target.theta);
      break;
    }
    case CorrectionModel::kHeadingDrift: {
      // The heading error at home fixes b * metres + k * radians turned; the position error
      // splits it. Start from both ends of that line (all drift, all turn scale) and keep
      // the better fit: the problem is not convex and a start at zero can settle wrongly.
      double metres = 0.0, turned = 0.0;
      for (const Step& st : steps) {
        metres += std::abs(st.ds);
        turned += st.dtheta;
      }
      const double heading_error = odo_heading - target.theta;  // odometry minus truth
      // The end is matched to within what the random odometry errors allow (they are left
      // to the uniform spread below), not to the home base's precision: else the two
      // systematic terms bend to absorb noise. (Only the random walk along the path counts
      // here; random heading errors would allow so much that the split goes unobserved.)
      const OdometryErrorModel& m = config.odometry;
      double turned_abs = 0.0;
      for (const Step& st : steps) turned_abs += std::abs(st.dtheta);
      const double var_theta = m.angular_per_sqrt_rad * m.angular_per_sqrt_rad * turned_abs +
                               m.heading_per_sqrt_m * m.heading_per_sqrt_m * metres;
      const double end_sxy = std::sqrt(home.sigma_xy * home.sigma_xy +
                                       m.linear_per_sqrt_m * m.linear_per_sqrt_m * metres);
      const double end_sth = std::sqrt(home.sigma_theta * home.sigma_theta + var_theta);
      std::vector<std::array<double, 3>> starts = {{0.0, 0.0, 0.0}};
      if (metres > 1e-6) starts.push_back({heading_error / metres, 0.0, 0.0});
      if (std::abs(turned) > 1e-6) starts.push_back({0.0, heading_error / turned, 0.0});
      double best_cost = 1e300;
      for (const std::array<double, 3>& start : starts) {
        double bias[3] = {start[0], start[1], start[2]};
        ceres::Problem problem;
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<EndResidual, 3, 3>(
                                     new EndResidual(&steps, target, end_sxy, end_sth)),
                                 nullptr, bias);
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<BiasPrior, 3, 3>(new BiasPrior(config.odometry)),
            nullptr, bias);
        // Only the heading errors: on a loop that comes home the distance scale hardly moves
        // the end, so fitting it would soak up noise (it stays zero).
        problem.SetManifold(bias, new ceres::SubsetManifold(3, {2}));
        ceres::Solver::Summary summary;
        ceres::Solve(solverOptions(config.max_iterations), &problem, &summary);
        result.iterations += static_cast<int>(summary.iterations.size());
        if (summary.final_cost < best_cost) {
          best_cost = summary.final_cost;
          result.bias = {bias[0], bias[1], bias[2]};
        }
      }
      result.final_cost = best_cost;
      const double bias[3] = {result.bias.heading_drift, result.bias.turn_scale,
                              result.bias.distance_scale};
      rel = dead_reckon(steps, bias);
      spreadUniformly(rel, target);  // what the priors and the noise leave
      break;
    }
    case CorrectionModel::kPoseGraph: {
      // Initial guess: the heading-drift solution.
      CorrectionConfig init = config;
      init.model = CorrectionModel::kHeadingDrift;
      const CorrectionResult first = correctTraverse(log, home, init, {});
      if (!first.ok) return first;
      double bias[3] = {first.bias.heading_drift, first.bias.turn_scale, first.bias.distance_scale};
      std::vector<double> x(3 * (last + 1));
      for (size_t i = 0; i <= last; ++i) {
        const Pose2 p = start_inv * first.poses[i];
        x[3 * i] = p.x;
        x[3 * i + 1] = p.y;
        x[3 * i + 2] = i > 0 ? unwrapNear(p.theta, x[3 * (i - 1) + 2]) : 0.0;
      }
      ceres::Problem problem;
      const OdometryErrorModel& m = config.odometry;
      for (size_t i = 0; i < steps.size(); ++i) {
        const Step& s = steps[i];
        const double sxy = m.linear_per_sqrt_m * std::sqrt(std::abs(s.ds)) + 1e-3;
        const double sth = m.angular_per_sqrt_rad * std::sqrt(std::abs(s.dtheta)) +
                           m.heading_per_sqrt_m * std::sqrt(std::abs(s.ds)) + 1e-4;
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<StepResidual, 3, 3, 3, 3>(
                                     new StepResidual(s, sxy, sth)),
                                 nullptr, &x[3 * i], &x[3 * (i + 1)], bias);
      }
      problem.SetParameterBlockConstant(&x[0]);
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<PoseResidual, 3, 3>(
              new PoseResidual(target, positionSqrtInfo(home, start_inv.theta), home.sigma_theta)),
          nullptr, &x[3 * last]);
      for (const PoseObservation& c : closures) {
        if (c.entry == 0 || c.entry >= last) continue;
        Pose2 t = start_inv * c.pose;
        t.theta = unwrapNear(t.theta, x[3 * c.entry + 2]);
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<PoseResidual, 3, 3>(
                new PoseResidual(t, positionSqrtInfo(c, start_inv.theta), c.sigma_theta)),
            new ceres::HuberLoss(3.0), &x[3 * c.entry]);
      }
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BiasPrior, 3, 3>(new BiasPrior(m)),
                               nullptr, bias);
      if (!config.fit_distance_scale) problem.SetManifold(bias, new ceres::SubsetManifold(3, {2}));
      ceres::Solver::Options options = solverOptions(config.max_iterations);
      options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      ceres::Solver::Summary summary;
      ceres::Solve(options, &problem, &summary);
      result.iterations = first.iterations + static_cast<int>(summary.iterations.size());
      result.final_cost = summary.final_cost;
      result.bias = {bias[0], bias[1], bias[2]};
      for (size_t i = 0; i <= last; ++i)
        rel[i] = Pose2(x[3 * i], x[3 * i + 1], wrapAngle(x[3 * i + 2]));
      break;
    }
  }

  result.poses.resize(n);
  for (size_t i = 0; i <= last; ++i) result.poses[i] = start * rel[i];
  // Entries after the observed one move rigidly with it.
  const Pose2 tail = result.poses[last] * log.entries[last].scan.odometry.inverse();
  for (size_t i = last + 1; i < n; ++i) result.poses[i] = tail * log.entries[i].scan.odometry;
  result.ok = true;
  return result;
}

OccupancyGrid rebuildMap(const TraverseLog& log, const std::vector<Pose2>& poses,
                         const MapLimits& limits, const OccupancyConfig& config) {
  if (poses.size() != log.entries.size())
    throw std::invalid_argument("rebuildMap: " + std::to_string(poses.size()) +
                                " poses for a log of " + std::to_string(log.entries.size()) +
                                " entries");
  OccupancyGrid grid(limits, config);
  for (size_t i = 0; i < poses.size(); ++i) grid.insert(log.entries[i].scan, poses[i]);
  return grid;
}

}  // namespace coopmap

#include "sim/runner/odometry_fit.h"

#include <stdexcept>

#include "robots/robot_model.h"
#include "sim/physics/physics_world.h"

namespace coopmap {

sim::OdometryConfig presetFromStats(const DriftStats& s) {
  // Stats measure true - odometry; the model adds errors to what odometry measures.
  sim::OdometryConfig c;
  c.scale_error = s.scale_bias;
  c.turn_scale_error = -s.turn_bias;
  c.heading_drift = -s.heading_bias_per_m;
  c.linear_noise = s.distance_sigma_per_sqrt_m;
  c.angular_noise = s.heading_sigma_per_sqrt_rad;
  c.heading_noise = s.heading_sigma_per_sqrt_m;
  return c;
}

namespace {
// Samples of a trajectory at a fixed rate (the nearest earlier sample).
std::vector<StampedPose2> resample(const std::vector<StampedPose2>& t, double rate) {
  std::vector<StampedPose2> out;
  if (t.empty()) return out;
  size_t k = 0;
  for (double s = t.front().stamp; s <= t.back().stamp; s += 1.0 / rate) {
    while (k + 1 < t.size() && t[k + 1].stamp <= s) ++k;
    out.push_back({s, t[k].pose});
  }
  return out;
}
}  // namespace

OdometryFitResult runOdometryFit(const OdometryFitOptions& o) {
  if (!(o.window_s > 0.5)) throw std::invalid_argument("--window: expected more than 0.5 s");
  const auto truth_raw = readUtiasGroundtruth(o.groundtruth);
  const auto odometry = readUtiasOdometry(o.odometry);
  if (truth_raw.size() < 100 || odometry.size() < 100)
    throw std::runtime_error("odometry-fit: the logs hold too few samples");
  const auto truth = resample(truth_raw, 20.0);
  std::vector<double> stamps;
  for (const auto& s : truth) stamps.push_back(s.stamp);
  OdometryFitResult r;
  r.real = driftStats(truth, integrateVelocities(odometry, truth.front().pose, stamps), o.window_s);
  r.preset = presetFromStats(r.real);
  if (!o.simulate) return r;

  // The simulated robot driven by the log's velocity commands on an empty floor.
  const RobotModel model = loadRobotModel(o.robot_model);
  sim::World world;
  world.floor_min = {-100, -100};
  world.floor_max = {100, 100};
  const double h = 1.0 / 200.0;
  sim::PhysicsWorld physics(world, h);
  const Pose2 start = truth.front().pose;
  const int robot = physics.addRobot(model.description, start, model.drive);
  sim::OdometryModel odo(r.preset, start, o.seed);
  std::vector<StampedPose2> sim_truth, sim_odo;
  size_t k = 0;
  const double t0 = truth.front().stamp, t1 = truth.back().stamp;
  double next_sample = t0;
  for (double t = t0; t <= t1; t += h) {
    while (k + 1 < odometry.size() && odometry[k + 1].stamp <= t) ++k;
    physics.command(robot, {odometry[k].v, odometry[k].w});
    physics.step();
    odo.integrate(physics.bodyVelocity(robot), physics.truePose(robot), h);
    if (t >= next_sample) {
      sim_truth.push_back({t, physics.truePose(robot)});
      sim_odo.push_back({t, odo.pose()});
      next_sample += 1.0 / 20.0;
    }
  }
  r.simulated = driftStats(sim_truth, sim_odo, o.window_s);
  return r;
}

}  // namespace coopmap

#include "sim/runner/world_run.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "core/agent/mission.h"
#include "core/agent/robot_agent.h"
#include "core/sharing/team.h"
#include "robots/replay/recording_writer.h"
#include "robots/robot_model.h"
#include "robots/sim/sim_robot.h"
#include "sim/runner/run_scoring.h"
#include "sim/runner/shared_maps.h"
#include "sim/simulator.h"
#include "sim/world/ground_truth.h"

namespace coopmap {

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

void drawProgress(double t, double total) {
  const int width = 30;
  const double f = std::min(1.0, t / total);
  const int n = static_cast<int>(f * width);
  std::fprintf(stderr, "\r[%s%s] %3d%%  sim %.0f s", std::string(n, '#').c_str(),
               std::string(width - n, ' ').c_str(), static_cast<int>(100 * f), t);
  std::fflush(stderr);
}

// The simulated B-14 as its agent sees it, with the run's observers on the frames that pass:
// the ground-truth depth for a frame observer, and the raw frame for the recording.
class ObservedSimRobot final : public RobotInterface {
 public:
  ObservedSimRobot(sim::Simulator& sim, int index, std::string name, const RunOptions& options,
                   RunTiming& timing)
      : robot_(sim, index), sim_(sim), name_(std::move(name)), options_(options), timing_(timing) {}

  const RobotDescription& description() const override { return robot_.description(); }
  double now() const override { return robot_.now(); }
  std::optional<TrinocularFrame> captureFrame() override {
    const auto start = Clock::now();
    std::optional<TrinocularFrame> frame;
    if (options_.frame_observer) {
      cv::Mat depth;
      frame = sim_.capture(robot_.index(), &depth);
      options_.frame_observer(name_, *frame, depth);
    } else {
      frame = robot_.captureFrame();
    }
    timing_.render_s += seconds(start, Clock::now());
    last_ = frame;
    return frame;
  }
  Pose2 odometry() const override { return robot_.odometry(); }
  void command(const MotionCommand& cmd) override { robot_.command(cmd); }
  RobotStatus status() const override { return robot_.status(); }

  int index() const { return robot_.index(); }
  // The frame the agent took last, as the robot gave it.
  const std::optional<TrinocularFrame>& lastFrame() const { return last_; }

 private:
  SimRobot robot_;
  sim::Simulator& sim_;
  std::string name_;
  const RunOptions& options_;
  RunTiming& timing_;
  std::optional<TrinocularFrame> last_;
};

// One robot of the run: the simulated robot, its agent, and (steer_by_truth) the person who
// drives it.
struct RobotSlot {
  std::unique_ptr<ObservedSimRobot> robot;
  std::unique_ptr<RobotAgent> agent;
  std::unique_ptr<RouteFollower> driver;  // world frame, by the true pose
  int recording = -1;
  std::string last_event;  // the mission's, as the event observer last heard it
};

sim::OdometryConfig odometryOf(const RobotModel& model, const std::optional<std::string>& choice,
                               const std::string& model_file) {
  sim::OdometryConfig odometry = model.odometry;
  if (!choice) return odometry;
  if (*choice == "perfect") {
    odometry.perfect = true;
  } else if (*choice == "drifting") {
    odometry.perfect = false;
  } else {
    const auto preset = model.odometry_presets.find(*choice);
    if (preset == model.odometry_presets.end()) {
      std::string known = "perfect, drifting";
      for (const auto& [name, c] : model.odometry_presets) known += ", " + name;
      throw std::invalid_argument("--odometry: expected one of " + known + " (presets of " +
                                  model_file + "), got '" + *choice + "'");
    }
    odometry = preset->second;
    odometry.perfect = false;
  }
  return odometry;
}

// The distance scale the robot's operators measured for the encoders a run gives it: the
// model's default ones, or a preset's; perfect ones need none.
double calibratedDistanceScale(const RobotModel& model, const std::optional<std::string>& choice) {
  if (choice && *choice == "perfect") return 0.0;
  const std::string preset = !choice || *choice == "drifting" ? "default" : *choice;
  const auto it = model.calibrated_distance_scale.find(preset);
  return it == model.calibrated_distance_scale.end() ? 0.0 : it->second;
}

}  // namespace

RunResult runWorld(const RunOptions& opt) {
  if (!(opt.duration > 0.0))
    throw std::invalid_argument("--duration: expected a positive number of seconds");
  if (!(opt.timeline_period_s > 0.0))
    throw std::invalid_argument("timeline period: expected a positive number of seconds");
  if (!(opt.published_band > 0.0))
    throw std::invalid_argument("published band: expected a positive share of the range sigma");
  const auto wall_start = Clock::now();
  const sim::World world = sim::loadWorld(opt.world_file);
  const int robot_count = opt.robots ? *opt.robots : static_cast<int>(world.robots.size());
  if (robot_count < 1 || robot_count > static_cast<int>(world.robots.size()))
    throw std::invalid_argument("--robots: expected 1.." + std::to_string(world.robots.size()) +
                                " (robots in " + opt.world_file + "), got " +
                                std::to_string(robot_count));
  // Each robot's agent settings: coopmap's defaults, its model's odometry calibration, then
  // the run's.
  std::vector<RobotModel> models;
  std::vector<AgentSettings> robot_settings;
  for (int i = 0; i < robot_count; ++i) {
    const std::string& file = world.robots[i].model_file;
    RobotModel& model = models.emplace_back(loadRobotModel(file));
    model.odometry = odometryOf(model, opt.odometry, file);
    AgentSettings s;
    s.odometry_distance_scale = calibratedDistanceScale(model, opt.odometry);
    if (opt.settings) opt.settings(s);
    s.validate();
    if (!robot_settings.empty() && s.sensing_rate != robot_settings.front().sensing_rate)
      throw std::invalid_argument("sensing_rate: the robots of a run sense at one rate");
    robot_settings.push_back(s);
  }
  const AgentSettings& settings = robot_settings.front();
  // Unless the run says: the robots follow the routes the world gives them, and explore where
  // it gives none.
  const bool has_routes = std::any_of(world.robots.begin(), world.robots.end(),
                                      [](const sim::RobotSpec& r) { return !r.route.empty(); });
  const bool explore = opt.explore.value_or(!opt.steer_by_truth && !has_routes);
  if (opt.steer_by_truth && explore)
    throw std::invalid_argument("--steer-by-truth: the robots follow their routes, not explore");

  // The map frame: the home base's, where the world has one; else each robot's start.
  const bool has_home_base = world.home_base.corners.size() == 2;
  const HomeBaseDesign design = opt.home_base.value_or(HomeBaseDesign{});
  std::vector<Pose2> X_WM;  // per robot
  for (int i = 0; i < robot_count; ++i)
    X_WM.push_back(has_home_base ? sim::mapFrameInWorld(world, design) : world.robots[i].start);
  const MapLimits limits = sim::worldMapLimits(world, 0.5, X_WM.front());

  RunResult result;
  result.world = world.name;
  result.world_file = opt.world_file;
  result.seed = opt.seed;
  result.explore = explore;
  result.settings = settings;
  result.published_band = opt.published_band;
  result.timeline_period_s = opt.timeline_period_s;
  // The robots share their map as they go: exploring in sorties, or each route one sortie
  // (a robot driven by a person shares nothing until the run is over: share_maps).
  result.cooperative =
      has_home_base && !opt.steer_by_truth && (!explore || settings.max_sorties > 1);
  OccupancyConfig published;
  published.sigma_scale = opt.published_band;
  std::optional<LocalSharedMap> live;
  if (!opt.shared_map_dir.empty() && !result.cooperative)
    throw ConfigError("--shared-map: the robots of this run share no map as they go (" +
                      std::string(has_home_base ? "driven by the truth, or one sortie each"
                                                : "the world has no home base") +
                      ")");
  if (result.cooperative) {
    try {
      live.emplace(limits, OccupancyConfig{}, opt.shared_map_dir, published);
    } catch (const std::runtime_error& e) {
      throw ConfigError("--shared-map: " + std::string(e.what()));
    }
  }
  LocalTeamChannel team;

  sim::Simulator sim(world, opt.seed);
  std::vector<RobotSlot> slots;
  std::vector<RobotDescription> descriptions;
  for (int i = 0; i < robot_count; ++i) {
    const sim::RobotSpec& spec = world.robots[i];
    RobotModel& model = models[i];
    if (!opt.camera_noise) model.cameras = sim::CameraNoiseConfig{};
    const int index =
        sim.addRobot(spec, {model.description, model.drive, model.odometry, model.cameras});
    descriptions.push_back(model.description);
    RobotSlot slot;
    slot.robot = std::make_unique<ObservedSimRobot>(sim, index, spec.name, opt, result.timing);
    AgentSetup setup;
    setup.name = spec.name;
    setup.mode = explore              ? AgentSetup::Mode::kExplore
                 : opt.steer_by_truth ? AgentSetup::Mode::kDriven
                                      : AgentSetup::Mode::kRoute;
    // The route, a script for the robot, in its map frame.
    const Pose2 X_MW = X_WM[i].inverse();
    for (Waypoint w : spec.route) {
      w.position = X_MW * w.position;
      if (w.face) *w.face = wrapAngle(*w.face + X_MW.theta);
      setup.route.push_back(w);
    }
    if (setup.mode == AgentSetup::Mode::kRoute && setup.route.empty())
      setup.mode = AgentSetup::Mode::kDriven;  // no route: it stands where it is
    setup.map = limits;
    if (has_home_base) setup.home_base = design;
    setup.seed = static_cast<uint32_t>(opt.seed + i);
    setup.priority = i == 0;
    if (opt.steer_by_truth) {
      // The person starts with the look at the home base the protocol needs, unless the route
      // does (a slow full turn where the robot stands).
      std::vector<Waypoint> route = spec.route;
      const bool looks = !route.empty() && route.front().spin &&
                         (route.front().position - spec.start.translation()).norm() < 0.05;
      if (has_home_base && !looks) {
        const MissionConfig look;
        route.insert(route.begin(), Waypoint{spec.start.translation(), true, look.look_turn_rate,
                                             look.look_wait_s});
      }
      slot.driver = std::make_unique<RouteFollower>(route, RouteConfig{});
    }
    slot.agent = std::make_unique<RobotAgent>(*slot.robot, setup, robot_settings[i],
                                              live ? &*live : nullptr, &team);
    slots.push_back(std::move(slot));
  }

  const double control_dt = 1.0 / world.control_rate;
  std::optional<RecordingWriter> recorder;
  if (!opt.record_dir.empty()) {
    RecordingInfo info;
    info.source = "simulator";
    info.world = world.name;
    info.world_file = opt.world_file;
    info.seed = opt.seed;
    info.sensing_rate = settings.sensing_rate;
    info.control_rate = world.control_rate;
    info.map = limits;
    info.shared_map = live.has_value();
    recorder.emplace(opt.record_dir, info);
    for (size_t k = 0; k < slots.size(); ++k) {
      RobotSlot& s = slots[k];
      s.recording = recorder->addRobot(s.agent->name(), s.robot->description(),
                                       sim.spec(s.robot->index()).start);
      recorder->setAgent(s.recording, {s.agent->setup(), s.agent->settings()});
      recorder->setMapInWorld(s.recording, X_WM[k]);
    }
  }

  RunScoring scoring(world, limits, X_WM, descriptions, opt.timeline_period_s);
  const double sense_period = 1.0 / settings.sensing_rate;
  double next_sense = 0.0, next_progress = 0.0;
  const bool progress = opt.progress && ::isatty(2);
  std::vector<const RobotAgent*> agents;
  for (const RobotSlot& s : slots) agents.push_back(s.agent.get());
  while (true) {
    const double t = sim.time();
    const bool sense = t + 1e-9 >= next_sense;
    if (sense) next_sense += sense_period;
    bool all_done = true;
    for (size_t k = 0; k < slots.size(); ++k) {
      RobotSlot& s = slots[k];
      const int i = s.robot->index();
      if (s.driver)
        s.agent->stepDriven(s.driver->update(sim.truePose(i), t));
      else if (s.agent->setup().mode == AgentSetup::Mode::kDriven)
        s.agent->stepDriven(MotionCommand::stop());  // no route: it stands
      else
        s.agent->step();
      scoring.observeStep(k, t, sim.truePose(i), sim.odometry(i), *s.agent);
      if (const MissionAgent* m = s.agent->mission();
          opt.event_observer && m && m->lastEvent() != s.last_event) {
        s.last_event = m->lastEvent();
        opt.event_observer(s.agent->name(), t, s.last_event);
      }
      if (recorder) {
        if (s.agent->sensedLastStep() && s.robot->lastFrame())
          recorder->addFrame(s.recording, *s.robot->lastFrame(), s.agent->lastFrameSegment());
        recorder->addControl(s.recording, t, sim.odometry(i), sim.status(i), s.agent->lastCommand(),
                             sim.truePose(i));
      }
      // A robot without a route stands where it is for the whole run.
      const bool stands = s.agent->setup().mode == AgentSetup::Mode::kDriven && !s.driver;
      all_done = all_done && !stands &&
                 (s.driver ? s.driver->done() && s.agent->localized() : s.agent->done());
    }
    scoring.sample(t, agents, live ? &*live : nullptr);
    if (progress && t >= next_progress) {
      drawProgress(t, opt.duration);
      next_progress += 1.0;
    }
    if (t >= opt.duration || (all_done && sense)) break;
    const auto physics_start = Clock::now();
    sim.advance(control_dt);
    result.timing.physics_s += seconds(physics_start, Clock::now());
    for (size_t k = 0; k < slots.size(); ++k) {
      const int i = slots[k].robot->index();
      scoring.observeMotion(k, control_dt, sim.truePose(i), sim.contactLog(i),
                            slots[k].agent->phase());
    }
  }
  if (progress) std::fprintf(stderr, "\n");
  scoring.sample(sim.time(), agents, live ? &*live : nullptr, true);

  result.sim_time_s = sim.time();
  for (const RobotSlot& s : slots) {
    result.timing.stereo_s += s.agent->mapper().timing().stereo_s;
    result.timing.mapping_s += s.agent->mapper().timing().mapping_s;
  }
  for (size_t k = 0; k < slots.size(); ++k) {
    const RobotSlot& s = slots[k];
    const int i = s.robot->index();
    RobotRunResult r = scoring.robotResult(k, *s.agent);
    const sim::ContactCounts contacts = sim.contactCounts(i);
    r.collisions = sim.status(i).contact_events;
    r.collisions_static = contacts.static_world;
    r.collisions_people = contacts.people;
    r.collisions_robots = contacts.robots;
    const Pose2 truth = world.robots[i].start.inverse() * sim.truePose(i);
    const Pose2 odo = sim.odometry(i);
    r.odometry_error_m = std::hypot(truth.x - odo.x, truth.y - odo.y);
    r.odometry_error_deg = std::abs(wrapAngle(truth.theta - odo.theta)) * 180.0 / M_PI;
    if (s.driver) r.route_complete = s.driver->done();
    result.robots.push_back(std::move(r));
    if (recorder) recorder->setTruthOccupancy(s.recording, result.robots.back().truth);
  }
  result.floor = scoring.floor();
  result.shared_truth = scoring.sharedTruth();
  result.timeline = scoring.timeline();
  auto firstReaching = [&](double coverage) {
    for (const TimelineSample& sample : result.timeline)
      if (sample.shared_coverage >= coverage) return sample.t;
    return -1.0;
  };
  result.time_to_50_s = firstReaching(0.5);
  result.time_to_75_s = firstReaching(0.75);
  result.time_to_90_s = firstReaching(0.9);
  if (recorder) {
    recorder->setFloor(result.floor);
    recorder->finish();
  }
  if (result.cooperative) {
    result.shared_map =
        cooperativeSharedMaps(*live, agents, limits, published, result.shared_truth, result.floor,
                              result.robots.front().groundtruth.front().pose);
  } else if (opt.share_maps && has_home_base) {
    // The paper's correction (the heading-drift model, no closures) unless settings say.
    result.shared_map = shareMaps(design, limits, result.floor, result.shared_truth, agents, "none",
                                  published, result.robots.front().groundtruth.front().pose);
  }
  result.wall_time_s = seconds(wall_start, Clock::now());
  result.real_time_factor = result.wall_time_s > 0 ? result.sim_time_s / result.wall_time_s : 0.0;
  return result;
}

}  // namespace coopmap

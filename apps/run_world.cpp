#include "apps/run_world.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "apps/robot_run.h"
#include "core/agent/cooperation.h"
#include "core/agent/map_tracker.h"
#include "core/agent/mapper.h"
#include "core/agent/mission.h"
#include "core/agent/route_follower.h"
#include "core/correction/drift_correction.h"
#include "core/correction/home_return.h"
#include "core/correction/odometry_calibration.h"
#include "core/sharing/shared_map.h"
#include "robots/replay/recording_writer.h"
#include "robots/robot_model.h"
#include "robots/sim/sim_robot.h"
#include "sim/simulator.h"
#include "sim/world/ground_truth.h"

namespace coopmap {

using namespace run_detail;

namespace {

void drawProgress(double t, double total) {
  const int width = 30;
  const double f = std::min(1.0, t / total);
  const int n = static_cast<int>(f * width);
  std::fprintf(stderr, "\r[%s%s] %3d%%  sim %.0f s", std::string(n, '#').c_str(),
               std::string(width - n, ' ').c_str(), static_cast<int>(100 * f), t);
  std::fflush(stderr);
}

// Where the teammates of `self` report themselves (map frame: their estimates). A teammate
// that stopped without knowing where it is reports nothing: its estimate is not where it
// stands, so it is seen (mapped, avoided) like the rest of the world.
std::vector<Eigen::Vector2d> teammateReports(const std::vector<RobotRun>& runs,
                                             const RobotRun& self) {
  std::vector<Eigen::Vector2d> out;
  for (const RobotRun& o : runs)
    if (&o != &self && !(o.mission && o.mission->lost()))
      out.push_back(o.mapper->estimate(o.odo).translation());
  return out;
}

}  // namespace

RunResult runWorld(const RunOptions& opt) {
  if (!(opt.duration > 0.0))
    throw std::invalid_argument("--duration: expected a positive number of seconds");
  const auto wall_start = std::chrono::steady_clock::now();
  sim::World world = sim::loadWorld(opt.world_file);
  const int robot_count = opt.robots ? *opt.robots : static_cast<int>(world.robots.size());
  if (robot_count < 1 || robot_count > static_cast<int>(world.robots.size()))
    throw std::invalid_argument("--robots: expected 1.." + std::to_string(world.robots.size()) +
                                " (robots in " + opt.world_file + "), got " +
                                std::to_string(robot_count));

  sim::Simulator sim(world, opt.seed);
  const MapLimits limits = sim::worldMapLimits(world);
  // Cooperative autonomous runs share their map sortie by sortie, during the run.
  const bool cooperative =
      opt.explore && opt.max_sorties > 1 && world.home_base.corners.size() == 2;
  if (opt.explore && opt.sortie_budget_m && !(*opt.sortie_budget_m > 0.0))
    throw std::invalid_argument("--sortie-budget: expected a positive number of metres");
  if (opt.closures && !CooperationConfig{}.setClosureKinds(*opt.closures))
    throw std::invalid_argument("closures: expected one of none, self, shared, both, got '" +
                                *opt.closures + "'");
  if (opt.explore && opt.max_sorties < 1)
    throw std::invalid_argument("--sorties: expected at least 1");
  if (!(opt.timeline_period_s > 0.0))
    throw std::invalid_argument("timeline period: expected a positive number of seconds");
  if (!(opt.published_band > 0.0))
    throw std::invalid_argument("published band: expected a positive share of the range sigma");
  OccupancyConfig published;
  published.sigma_scale = opt.published_band;
  std::optional<LocalSharedMap> live;
  if (cooperative) live.emplace(limits, OccupancyConfig{}, "", published);
  std::vector<RobotRun> runs;
  std::optional<RunResult::MissionSettings> settings;
  for (int i = 0; i < robot_count; ++i) {
    const sim::RobotSpec& spec = world.robots[i];
    RobotModel model = loadRobotModel(spec.model_file);
    if (opt.odometry) {
      if (*opt.odometry == "perfect") {
        model.odometry.perfect = true;
      } else if (*opt.odometry == "drifting") {
        model.odometry.perfect = false;
      } else {
        const auto preset = model.odometry_presets.find(*opt.odometry);
        if (preset == model.odometry_presets.end()) {
          std::string known = "perfect, drifting";
          for (const auto& [name, c] : model.odometry_presets) known += ", " + name;
          throw std::invalid_argument("--odometry: expected one of " + known + " (presets of " +
                                      spec.model_file + "), got '" + *opt.odometry + "'");
        }
        model.odometry = preset->second;
        model.odometry.perfect = false;
      }
    }
    if (!opt.camera_noise) model.cameras = sim::CameraNoiseConfig{};
    const int index =
        sim.addRobot(spec, {model.description, model.drive, model.odometry, model.cameras});
    RobotRun r;
    r.driver = std::make_unique<SimRobot>(sim, index);
    r.odo = r.driver->odometry();  // teammates read it before this robot's first step
    MapperConfig mapper_config;
    mapper_config.radial.floor_edge_depth = opt.floor_edge_depth ? *opt.floor_edge_depth
                                            : world.exploration.floor_edge_depth
                                                ? *world.exploration.floor_edge_depth
                                                : mapper_config.radial.floor_edge_depth;
    mapper_config.radial.beyond_support =
        opt.beyond_support
            ? *opt.beyond_support
            : world.exploration.beyond_support.value_or(mapper_config.radial.beyond_support);
    r.mapper = std::make_unique<Mapper>(model.description, limits, mapper_config);
    r.mapper_description = model.description;
    r.mapper->setRobotName(spec.name);
    r.follower = std::make_unique<RouteFollower>(spec.route, RouteConfig{});
    if (opt.explore) {
      MissionConfig mission;
      mission.planning = PlanningMapConfig::forRobot(model.description);
      mission.planning.margin =
          opt.planning_margin.value_or(world.exploration.planning_margin.value_or(0.05));
      mission.planner.seed = static_cast<uint32_t>(opt.seed + i);
      mission.budget_m =
          opt.sortie_budget_m.value_or(world.exploration.sortie_budget_m.value_or(25.0));
      mission.budget_s = opt.sortie_budget_s;
      // The command line's settings, else the world's, else the defaults.
      const sim::World::Exploration& we = world.exploration;
      auto pick = [](const auto& option, const auto& from_world, auto fallback) {
        return option ? *option : from_world ? *from_world : fallback;
      };
      mission.first_budget_m =
          cooperative ? pick(opt.first_sortie_budget_m, we.first_sortie_budget_m, 0.0) : 0.0;
      mission.safety_distance =
          pick(opt.safety_distance, we.safety_distance, mission.safety_distance);
      mission.slow_distance = pick(opt.slow_distance, we.slow_distance, mission.slow_distance);
      mission.frontiers.fringe_clearance =
          pick(opt.fringe_clearance, we.fringe_clearance, mission.frontiers.fringe_clearance);
      mission.frontiers.goal_clearance =
          pick(opt.goal_clearance, we.goal_clearance, mission.frontiers.goal_clearance);
      mission.frontiers.doorway_width =
          pick(opt.doorway_width, we.doorway_width, mission.frontiers.doorway_width);
      mission.frontiers.look_again_gain =
          pick(opt.look_again_gain, we.look_again_gain, mission.frontiers.look_again_gain);
      mission.retry_frontiers =
          pick(opt.retry_frontiers, we.retry_frontiers, mission.retry_frontiers);
      mission.bump_away = pick(opt.bump_away, we.bump_away, mission.bump_away);
      mission.visited_radius = pick(opt.visited_radius, we.visited_radius, mission.visited_radius);
      mission.max_linear_accel =
          pick(opt.max_linear_accel, we.max_linear_accel, mission.max_linear_accel);
      mission.recent_hits_s = pick(opt.recent_hits_s, we.recent_hits_s, mission.recent_hits_s);
      mission.passage_width = pick(opt.passage_width, we.passage_width, mission.passage_width);
      mission.planner.preferred_margin =
          pick(opt.preferred_margin, we.preferred_margin, mission.planner.preferred_margin);
      mission.validate();
      const std::string closures = pick(opt.closures, we.closures, opt.cooperation.closureKinds());
      settings = RunResult::MissionSettings{
          mission.budget_m,
          mission.first_budget_m,
          mission.safety_distance,
          mission.slow_distance,
          mission.frontiers.fringe_clearance,
          mission.frontiers.goal_clearance,
          mission.frontiers.doorway_width,
          mission.retry_frontiers,
          mapper_config.radial.floor_edge_depth,
          mapper_config.radial.beyond_support,
          pick(opt.shaped_closures, we.shaped_closures, opt.cooperation.closure_shape),
          pick(opt.closure_seen_points, we.closure_seen_points,
               opt.cooperation.closure_alignment.seen_points_only),
          pick(opt.closure_decided_points, we.closure_decided_points,
               opt.cooperation.closure_alignment.decided_points_only),
          mission.bump_away,
          mission.visited_radius,
          mission.recent_hits_s,
          pick(opt.calibrate_distance_scale, we.calibrate_distance_scale, true),
          pick(opt.stereo_distance_scale, we.stereo_distance_scale, false),
          pick(opt.odometry_distance_scale, we.odometry_distance_scale, 0.0),
          mission.passage_width,
          mission.planning.margin,
          mission.planner.preferred_margin,
          closures,
          pick(opt.post_gate_m, we.post_gate_m, opt.cooperation.post_gate_m),
          pick(opt.manhattan_sigma_deg, we.manhattan_sigma_deg,
               opt.cooperation.manhattan_sigma_rad * 180.0 / M_PI),
          pick(opt.wall_heading_gain, we.wall_heading_gain, 0.0),
          pick(opt.closure_scans, we.closure_scans, opt.cooperation.closure_scans),
          mission.frontiers.look_again_gain,
          mission.max_linear_accel};
      WallHeadingConfig headings;
      headings.gain = settings->wall_heading_gain;
      r.headings = WallHeadingTracker(headings);
      mission.max_sorties = cooperative ? opt.max_sorties : 1;
      r.mission = std::make_unique<MissionAgent>(spec.start, mission);
      if (cooperative) {
        CooperationConfig cooperation = opt.cooperation;
        cooperation.closure_shape = settings->shaped_closures;
        cooperation.closure_alignment.seen_points_only = settings->closure_seen_points;
        cooperation.closure_alignment.decided_points_only = settings->closure_decided_points;
        cooperation.setClosureKinds(closures);  // checked above (options) or on loading
        cooperation.post_gate_m = settings->post_gate_m;
        cooperation.manhattan_sigma_rad = settings->manhattan_sigma_deg * M_PI / 180.0;
        cooperation.closure_scans = settings->closure_scans;
        // A distance scale calibrated beforehand (neither learnt from the sorties'
        // corrections nor measured by the cameras as the mission goes) is held by each
        // sortie's correction: the home-base fix cannot see it. (With the cameras' scale, one
        // mission's figure spreads 0.6 points, and the corrections still fit their own.)
        const bool scale_from_sorties =
            settings->calibrate_distance_scale && !settings->stereo_distance_scale;
        cooperation.correction.fit_distance_scale =
            settings->calibrate_distance_scale || settings->stereo_distance_scale;
        r.coop = std::make_unique<HomeBaseCooperation>(
            spec.name, nominalHomeBase(world), world.home_base.arm_length, &*live, cooperation);
        r.calibrate = opt.calibrate_odometry;
        // With the scale from stereo, the sorties' corrections do not also move it.
        r.stereo_scale = settings->stereo_distance_scale;
        r.calibration = OdometryCalibration(scale_from_sorties);
        r.calibration.setDistanceScale(settings->odometry_distance_scale);
        r.sortie_scale = r.calibration.bias().distance_scale;
      }
    }
    r.result.name = spec.name;
    r.last_true = spec.start;
    r.home = spec.start;
    runs.push_back(std::move(r));
  }

  const double control_dt = 1.0 / world.control_rate;
  if (opt.sensing_rate && !(*opt.sensing_rate > 0.0 && *opt.sensing_rate <= 60.0))
    throw std::invalid_argument("--sensing-rate: expected a rate in (0, 60] Hz");
  const double sense_dt = 1.0 / opt.sensing_rate.value_or(world.sensing_rate);
  std::optional<RecordingWriter> recorder;
  if (!opt.record_dir.empty()) {
    RecordingInfo info;
    info.source = "simulator";
    info.world = world.name;
    info.world_file = opt.world_file;
    info.seed = opt.seed;
    info.sensing_rate = opt.sensing_rate.value_or(world.sensing_rate);
    info.control_rate = world.control_rate;
    info.map = limits;
    recorder.emplace(opt.record_dir, info);
    for (RobotRun& r : runs)
      r.recording = recorder->addRobot(r.result.name, r.mapper_description,
                                       sim.spec(r.driver->index()).start);
  }
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const GridU8 floor = sim::floorMask(world, limits);
  for (RobotRun& r : runs)
    r.truth = sim::trueOccupancy(world, limits, sim.description(r.driver->index()).swept_height);
  const GridU8& shared_truth = tallestRobot(runs).truth;
  const Eigen::Vector2d home_position = world.robots.front().start.translation();
  std::vector<TimelineSample> timeline;
  double next_sample = 0.0;
  // Coverage and error now: the shared map's (or all robots' maps together) and each robot's.
  auto sample = [&](double t) {
    TimelineSample out;
    out.t = t;
    std::optional<OccupancyGrid> merged;
    if (live) merged = live->publishedGrid();
    for (RobotRun& r : runs) {
      const Pose2 truth = sim.truePose(r.driver->index());
      const Pose2 estimate = r.mapper->estimate(r.odo);
      out.robot_error_m.push_back(std::hypot(truth.x - estimate.x, truth.y - estimate.y));
      out.robot_coverage.push_back(
          computeMapMetrics(r.mapper->grid(), r.truth, home_position, &floor).coverage);
      if (!live) {  // without sharing: what the robots have seen together
        if (!merged)
          merged.emplace(r.mapper->grid());
        else
          mergeSeen(*merged, r.mapper->grid());
      }
    }
    out.shared_coverage = computeMapMetrics(*merged, shared_truth, home_position, &floor).coverage;
    return out;
  };
  RunTiming timing;
  double next_sense = 0.0, next_progress = 0.0;
  const bool progress = opt.progress && ::isatty(2);
  while (true) {
    const double t = sim.time();
    const bool sense = t + 1e-9 >= next_sense;
    if (sense) next_sense += sense_dt;
    bool all_done = true;
    for (RobotRun& r : runs) {
      const int i = r.driver->index();
      r.odo = r.calibrate ? r.calibration.calibrate(r.driver->odometry()) : r.driver->odometry();
      if (sense) {
        std::optional<TrinocularFrame> frame;
        cv::Mat depth;
        const auto render_start = Clock::now();
        if (opt.frame_observer) {
          frame = sim.capture(i, &depth);
          opt.frame_observer(r.result.name, *frame, depth);
        } else {
          frame = r.driver->captureFrame();
        }
        timing.render_s += seconds(render_start, Clock::now());
        if (frame) {
          const MotionSegment segment = r.turn_steps + r.straight_steps == 0 ? MotionSegment::kStop
                                        : r.turn_steps > r.straight_steps
                                            ? MotionSegment::kTurn
                                            : MotionSegment::kStraight;
          r.turn_steps = r.straight_steps = 0;
          r.raw.push_back(frame->odometry);
          if (r.calibrate) frame->odometry = r.calibration.calibrate(frame->odometry);
          if (runs.size() > 1 && opt.teammate_mask_m > 0.0) {
            // Teammates report where they are: what this robot sees of them is not mapped.
            r.mapper->setTeammates(teammateReports(runs, r), opt.teammate_mask_m);
          }
          r.latest = &r.mapper->process(*frame, segment);
          trackWhileDriving(r);
          if (recorder) recorder->addFrame(r.recording, *frame, segment);
          ++r.result.frames;
        }
      }
      r.result.groundtruth.push_back({t, sim.truePose(i)});
      r.result.odometry.push_back({t, r.driver->odometry()});
      r.result.estimate.push_back({t, r.mapper->estimate(r.odo)});
      // Drift experiments steer by the true pose (as a person driving the route would), so
      // the path is the intended one and odometry only records it.
      const Pose2 steer = opt.steer_by_truth ? sim.truePose(i) : r.result.estimate.back().pose;
      if (r.mission && runs.size() > 1) {
        // Teammates report where they believe they are (their estimates share the map frame).
        std::vector<Eigen::Vector2d> goals;
        for (const RobotRun& o : runs)
          if (&o != &r && o.mission)
            if (const std::optional<Eigen::Vector2d> g = o.mission->explorationGoal())
              goals.push_back(*g);
        r.mission->setTeammates(teammateReports(runs, r), &r == &runs.front());
        if (opt.coordinate) r.mission->setTeammateGoals(goals);
      }
      const RobotStatus status = r.driver->status();
      const MotionCommand cmd = r.mission ? r.mission->update(t, steer, r.mapper->grid(), r.latest,
                                                              status.bumped, status.bump_bearing)
                                          : r.follower->update(steer, t);
      r.latest = nullptr;
      if (r.coop && r.mission->phase() == MissionPhase::kAtHome)
        endSortie(r, *live, t, opt.reapproach_m, opt.track_shared_map);
      r.driver->command(cmd);
      if (recorder)
        recorder->addControl(r.recording, t, r.result.odometry.back().pose, cmd,
                             r.result.groundtruth.back().pose);
      const MotionSegment segment = segmentOf(cmd);
      r.turn_steps += segment == MotionSegment::kTurn;
      r.straight_steps += segment == MotionSegment::kStraight;
      // A robot without a route stays put for the whole run.
      all_done = all_done &&
                 (r.mission ? r.mission->done() : r.follower->done() && !sim.spec(i).route.empty());
    }
    if (t + 1e-9 >= next_sample) {
      next_sample += opt.timeline_period_s;
      timeline.push_back(sample(t));
    }
    if (progress && t >= next_progress) {
      drawProgress(t, opt.duration);
      next_progress += 1.0;
    }
    if (t >= opt.duration || (all_done && sense)) break;
    const auto physics_start = Clock::now();
    sim.advance(control_dt);
    timing.physics_s += seconds(physics_start, Clock::now());
    for (RobotRun& r : runs) {
      const Pose2 p = sim.truePose(r.driver->index());
      r.result.path_length_m += std::hypot(p.x - r.last_true.x, p.y - r.last_true.y);
      r.last_true = p;
      const std::vector<sim::ContactEvent>& log = sim.contactLog(r.driver->index());
      for (size_t k = r.result.contacts.size(); k < log.size(); ++k)
        r.result.contacts.push_back({log[k].time, sim::toString(log[k].kind), log[k].point, p,
                                     r.mission ? toString(r.mission->phase()) : "route"});
    }
  }
  if (progress) std::fprintf(stderr, "\n");

  if (timeline.empty() || timeline.back().t < sim.time()) timeline.push_back(sample(sim.time()));
  RunResult result;
  result.sim_time_s = sim.time();
  result.timing = timing;
  result.cooperative = cooperative;
  result.mission_settings = settings;
  result.timeline = std::move(timeline);
  auto firstReaching = [&](double coverage) {
    for (const TimelineSample& s : result.timeline)
      if (s.shared_coverage >= coverage) return s.t;
    return -1.0;
  };
  result.time_to_50_s = firstReaching(0.5);
  result.time_to_75_s = firstReaching(0.75);
  result.time_to_90_s = firstReaching(0.9);
  for (const RobotRun& r : runs) {
    result.timing.stereo_s += r.mapper->timing().stereo_s;
    result.timing.mapping_s += r.mapper->timing().mapping_s;
  }
  for (RobotRun& r : runs) {
    const int i = r.driver->index();
    const Pose2 truth = sim.truePose(i), odo = r.driver->odometry();
    r.result.collisions = r.driver->status().contact_events;
    const sim::ContactCounts contacts = sim.contactCounts(i);
    r.result.collisions_static = contacts.static_world;
    r.result.collisions_people = contacts.people;
    r.result.collisions_robots = contacts.robots;
    r.result.route_complete = r.mission ? r.mission->done() : r.follower->done();
    if (r.mission) {
      r.result.mission_phase = toString(r.mission->phase());
      r.result.exploration_complete = r.mission->explorationComplete();
      r.result.goals_reached = r.mission->goalsReached();
      r.result.goals_failed = r.mission->goalsFailed();
      r.result.safety_stops = r.mission->safetyStops();
      r.result.early_returns = r.mission->earlyReturns();
      r.result.mission_event = r.mission->lastEvent();
    }
    if (r.calibrate) r.result.calibration = r.calibration.bias();
    r.result.traverse = r.mapper->traverse();
    r.result.odometry_error_m = std::hypot(truth.x - odo.x, truth.y - odo.y);
    r.result.odometry_error_deg = std::abs(wrapAngle(truth.theta - odo.theta)) * 180.0 / M_PI;
    if (r.coop) {
      for (const SortieReport& rep : r.coop->reports()) {
        ++r.result.sorties;
        r.result.sorties_fixed += rep.fixed;
        r.result.sorties_posted += rep.posted;
      }
      r.result.corrected = r.coop->corrected();
    }
    r.result.map =
        computeMapMetrics(r.mapper->grid(), r.truth, sim.spec(i).start.translation(), &floor);
    r.result.grid = r.mapper->grid();
    result.robots.push_back(r.result);
    if (recorder) recorder->setTruthOccupancy(r.recording, r.truth);
  }
  if (recorder) {
    recorder->setFloor(floor);
    recorder->finish();
  }
  if (cooperative) {
    SharedMapResult& shared = result.shared_map;
    shared.protocol_grid = live->publishedGrid();
    shared.naive_grid = naiveSharedMap(limits, runs, published);
    for (const RobotRun& r : runs) {
      shared.posts_accepted += r.result.sorties_posted;
      if (r.result.sorties_posted > 0) shared.posted.push_back(r.result.name);
      for (const SortieReport& rep : r.coop->reports())
        if (!rep.posted)
          shared.refused.push_back(r.result.name + " sortie " + std::to_string(rep.sortie) + ": " +
                                   rep.method);
    }
    shared.protocol = computeMapMetrics(*shared.protocol_grid, shared_truth, home_position, &floor);
    shared.imported = computeMapMetrics(live->grid(), shared_truth, home_position, &floor);
    shared.naive = computeMapMetrics(*shared.naive_grid, shared_truth, home_position, &floor);
    shared.computed = true;
  } else if (opt.share_maps) {
    // The paper's correction (the heading-drift model, no closures) unless --closures says.
    result.shared_map =
        shareMaps(world, limits, floor, runs, opt.closures.value_or("none"), published);
  }
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.real_time_factor = result.wall_time_s > 0 ? result.sim_time_s / result.wall_time_s : 0.0;
  if (!opt.out_dir.empty()) writeOutputs(opt, world, result, runs, floor);
  return result;
}

}  // namespace coopmap

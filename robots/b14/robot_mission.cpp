#include "robots/b14/robot_mission.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <thread>

#include "core/agent/robot_agent.h"
#include "core/agent/route_follower.h"
#include "core/calibration/rig_calibration.h"
#include "core/io/yaml_reader.h"
#include "core/sharing/shared_map.h"
#include "robots/b14/b14_robot.h"
#include "robots/rflex/serial_port.h"
#include "robots/robot_model.h"

namespace coopmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

volatile std::sig_atomic_t g_interrupted = 0;

void onSignal(int) { g_interrupted = 1; }

// Catches SIGINT and SIGTERM while alive, so a Ctrl-C ends the route with a safe stop.
class SignalGuard {
 public:
  SignalGuard() {
    g_interrupted = 0;
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~SignalGuard() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

std::string posePhrase(const Pose2& p) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.3f m, %.3f m, %.1f deg)", p.x, p.y, p.theta / kDeg);
  return b;
}

void sleepSeconds(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

}  // namespace

RobotRunConfig loadRobotRunConfig(const std::string& path) {
  namespace fs = std::filesystem;
  RobotRunConfig c;
  c.file = path;
  const YamlField root = YamlField::loadFile(path);
  if (!root.isMap()) root.fail("a mapping with 'model' and 'serial'");
  root.allowOnly({"model", "serial", "rflex", "route", "cameras", "mission", "shared_map",
                  "control_rate", "max_duration"});
  auto relative = [&](const std::string& p) {
    fs::path q(p);
    return (q.is_relative() ? fs::path(path).parent_path() / q : q).string();
  };

  const YamlField model = root["model"];
  fs::path model_path(model.asString());
  if (model_path.is_relative()) model_path = fs::path(path).parent_path() / model_path;
  if (!fs::is_regular_file(model_path))
    model.fail("an existing robot model file (relative paths start at the config's folder)");
  c.model_file = model_path.string();
  c.description = loadRobotModel(c.model_file).description;

  const YamlField serial = root["serial"];
  serial.allowOnly({"device", "baud"});
  c.rflex.device = serial["device"].asString();
  if (c.rflex.device.empty()) serial["device"].fail("a serial device path");
  if (const auto baud = serial.get("baud")) {
    const std::string expected = "a baud rate: 9600, 19200, 38400, 57600, 115200 or 230400";
    if (!baud->isScalar()) baud->fail(expected);
    const std::string text = baud->asString();
    int value = 0;
    try {
      size_t used = 0;
      value = std::stoi(text, &used);
      if (used != text.size()) value = 0;
    } catch (const std::exception&) {
      value = 0;
    }
    if (!SerialPort::supportedBaud(value)) baud->fail(expected);
    c.rflex.baud = value;
  }

  if (const auto r = root.get("rflex")) {
    r->allowOnly({"distance_ticks_per_m", "angle_ticks_per_rad", "report_period",
                  "watchdog_timeout", "startup_timeout", "write_timeout"});
    RflexConfig& x = c.rflex;
    const std::string ticks = "a positive number of encoder ticks";
    x.distance_ticks_per_m = optionalDouble(*r, "distance_ticks_per_m", x.distance_ticks_per_m, 1.0,
                                            1e8, ticks + " per metre");
    x.angle_ticks_per_rad = optionalDouble(*r, "angle_ticks_per_rad", x.angle_ticks_per_rad, 1.0,
                                           1e8, ticks + " per radian");
    x.report_period =
        optionalDouble(*r, "report_period", x.report_period, 0.005, 1.0, "seconds in [0.005, 1]");
    x.watchdog_timeout = optionalDouble(*r, "watchdog_timeout", x.watchdog_timeout, 0.02, 10.0,
                                        "seconds in [0.02, 10]");
    x.startup_timeout =
        optionalDouble(*r, "startup_timeout", x.startup_timeout, 0.1, 60.0, "seconds in [0.1, 60]");
    x.write_timeout =
        optionalDouble(*r, "write_timeout", x.write_timeout, 0.01, 10.0, "seconds in [0.01, 10]");
    if (x.watchdog_timeout <= x.report_period)
      (*r)["watchdog_timeout"].fail("more than report_period (" + std::to_string(x.report_period) +
                                    " s)");
  }
  try {
    c.rflex.validate();
  } catch (const std::invalid_argument& e) {
    throw ConfigError(path + ": " + e.what());
  }

  if (const auto route = root.get("route")) {
    route->allowOnly({"waypoints", "linear_speed", "angular_speed", "heading_tolerance_deg",
                      "arrive_tolerance", "heading_gain", "control_rate", "max_duration"});
    RouteConfig& rc = c.route_config;
    const RobotDescription& d = c.description;
    rc.linear_speed = optionalDouble(*route, "linear_speed", std::min(rc.linear_speed, 0.3), 0.01,
                                     d.max_linear_speed, "m/s up to the model's maximum speed");
    rc.angular_speed =
        optionalDouble(*route, "angular_speed", std::min(rc.angular_speed, 0.5), 0.01,
                       d.max_angular_speed, "rad/s up to the model's maximum turn rate");
    rc.heading_tolerance =
        optionalDouble(*route, "heading_tolerance_deg", rc.heading_tolerance / kDeg, 0.1, 45.0,
                       "degrees in [0.1, 45]") *
        kDeg;
    rc.arrive_tolerance = optionalDouble(*route, "arrive_tolerance", rc.arrive_tolerance, 0.005,
                                         2.0, "metres in [0.005, 2]");
    rc.heading_gain =
        optionalDouble(*route, "heading_gain", rc.heading_gain, 0.1, 20.0, "a gain in [0.1, 20]");
    c.control_rate =
        optionalDouble(*route, "control_rate", c.control_rate, 1.0, 100.0, "Hz in [1, 100]");
    c.max_duration = optionalDouble(*route, "max_duration", c.max_duration, 0.0, 86400.0,
                                    "seconds in [0, 86400] (0: no limit)");
    const YamlField wps = (*route)["waypoints"];
    for (const YamlField& w : wps.elements()) c.route.push_back(parseWaypoint(w));
    if (c.route.empty()) wps.fail("at least one waypoint");
  }

  if (const auto mission = root.get("mission")) {
    if (root.has("route")) root["route"].failMessage("a config has a route or a mission, not both");
    if (!root.has("cameras")) mission->failMessage("a mission needs the cameras (`cameras:`)");
    c.mission = readAgentConfig(*mission);
    const YamlField cameras = root["cameras"];
    cameras.allowOnly({"sources", "calibration", "rectified"});
    const std::vector<YamlField> sources = cameras["sources"].elements();
    if (sources.size() != 3)
      cameras["sources"].fail("three sources: reference, horizontal, vertical");
    for (size_t k = 0; k < 3; ++k) {
      const std::string source = sources[k].asString();
      // A device number stays as it is; a file, video or image sequence is found beside the
      // config file.
      const bool device =
          !source.empty() && source.find_first_not_of("0123456789") == std::string::npos;
      c.camera_sources[k] = device ? source : relative(source);
    }
    const bool rectified = cameras.has("rectified") && cameras["rectified"].asBool();
    if (rectified == cameras.has("calibration"))
      cameras.failMessage(
          "expected either 'calibration' (raw cameras, rectified by coopmap) or 'rectified: "
          "true' (the sources give rectified images of the model's rig)");
    if (!rectified) c.camera_calibration = relative(cameras["calibration"].asString());
    if (root.has("shared_map")) c.shared_map_dir = relative(root["shared_map"].asString());
    c.control_rate =
        optionalDouble(root, "control_rate", c.control_rate, 1.0, 100.0, "Hz in [1, 100]");
    c.max_duration = optionalDouble(root, "max_duration", c.max_duration, 0.0, 864000.0,
                                    "seconds in [0, 864000] (0: until the mission is done)");
  } else if (root.has("cameras")) {
    root["cameras"].failMessage("cameras without a mission (`mission:`) would see for nothing");
  }
  return c;
}

namespace {

// The mission on the B-14: its agent on the base and the cameras, on the wall clock.
int runMission(const RobotCommandOptions& o, const RobotRunConfig& c, std::FILE* out,
               RobotMissionResult* result) {
  SignalGuard signals;
  std::unique_ptr<TrinocularCamera> cameras =
      c.camera_calibration.empty()
          ? std::make_unique<TrinocularCamera>(c.camera_sources, c.description.rig)
          : std::make_unique<TrinocularCamera>(c.camera_sources,
                                               readRigCalibration(c.camera_calibration));
  B14Robot robot(std::make_unique<RflexRobot>(c.rflex, c.description), std::move(cameras),
                 c.description);
  const AgentConfig& mission = *c.mission;
  std::optional<LocalSharedMap> shared;
  if (mission.setup.mode == AgentSetup::Mode::kExplore)
    shared.emplace(mission.setup.map, OccupancyConfig{}, c.shared_map_dir);
  RobotAgent agent(robot, mission.setup, mission.settings, shared ? &*shared : nullptr);
  RobotMissionResult r;
  r.name = mission.setup.name;
  const double period = 1.0 / c.control_rate;
  auto next = std::chrono::steady_clock::now();
  size_t logged = 0;
  std::string event;
  if (!o.quiet)
    std::fprintf(out, "rflex %s: %s mission of %s\n", c.rflex.device.c_str(),
                 toString(mission.setup.mode), mission.setup.name.c_str());
  int code = 0;
  std::string why;
  while (true) {
    if (const auto fault = robot.base().fault()) {
      robot.command(MotionCommand::stop());
      throw RflexError(*fault);
    }
    if (g_interrupted) {
      code = 130;
      why = "interrupted: stop sent";
      break;
    }
    if (c.max_duration > 0.0 && robot.now() > c.max_duration) {
      why = "max_duration reached: stop sent";
      break;
    }
    agent.step();
    r.odometry.push_back({robot.now(), robot.odometry()});
    for (; logged < agent.log().size(); ++logged)
      if (!o.quiet) std::fprintf(out, "%s\n", agent.log()[logged].c_str());
    // What the mission decides, as it changes: for whoever watches the robot.
    if (const MissionAgent* m = agent.mission(); m && m->lastEvent() != event) {
      event = m->lastEvent();
      if (!o.quiet) std::fprintf(out, "%.1f s: %s\n", robot.now(), event.c_str());
    }
    if (agent.done()) {
      why = "mission done (" + agent.phase() + ")";
      break;
    }
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(period));
    std::this_thread::sleep_until(next);
  }
  robot.command(MotionCommand::stop());
  sleepSeconds(2.0 * period);
  for (; logged < agent.log().size(); ++logged)
    std::fprintf(out, "%s\n", agent.log()[logged].c_str());
  std::fprintf(out, "%s after %.1f s: %d frames, odometry %s\n", why.c_str(), robot.now(),
               agent.frames(), posePhrase(robot.odometry()).c_str());
  r.frames = agent.frames();
  r.log = agent.log();
  r.traverse = agent.mapper().traverse();
  r.grid = agent.mapper().grid();
  if (agent.startFix() && agent.startFix()->ok()) r.odometry_in_map = agent.startFix()->correction;
  if (result) *result = std::move(r);
  return code;
}

}  // namespace

int runRobotCommand(const RobotCommandOptions& o, std::FILE* out, RobotMissionResult* mission) {
  const RobotRunConfig c = loadRobotRunConfig(o.config);
  if (!o.dry_run && c.route.empty() && !c.mission)
    throw ConfigError(o.config +
                      ": nothing to do (add a mission with its cameras, or route.waypoints, or "
                      "use --dry-run to only check the base)");
  RflexConfig rflex = c.rflex;
  rflex.enable_motion = !o.dry_run;
  const RobotDescription& d = c.description;

  if (o.dry_run) {
    RflexRobot robot(rflex, d);  // throws when the controller does not answer
    sleepSeconds(std::min(0.5, 5.0 * rflex.report_period));  // a few more reports
    if (const auto fault = robot.fault()) throw RflexError(*fault);
    const RflexStats s = robot.stats();
    const RobotStatus st = robot.status();
    std::fprintf(out,
                 "rflex %s at %d baud: controller answering, odometry reports every %.3f s\n"
                 "  encoders: translation %d ticks, rotation %d ticks; controller clock %.3f s\n"
                 "  bumper: %s (%llu digital I/O reports)\n"
                 "  packets: %llu good, %llu garbage bytes, %llu bad checksums, %llu malformed\n"
                 "  robot: %s (%s): radius %.3f m, limits %.2f m/s %.2f rad/s\n",
                 rflex.device.c_str(), rflex.baud, rflex.report_period, s.translation_ticks,
                 s.rotation_ticks, s.controller_time_ms * 1e-3, st.bumped ? "pressed" : "clear",
                 static_cast<unsigned long long>(s.dio_reports),
                 static_cast<unsigned long long>(s.decoder.packets),
                 static_cast<unsigned long long>(s.decoder.garbage_bytes),
                 static_cast<unsigned long long>(s.decoder.bad_checksums),
                 static_cast<unsigned long long>(s.decoder.malformed), d.model.c_str(),
                 c.model_file.c_str(), d.body_radius, d.max_linear_speed, d.max_angular_speed);
    std::fprintf(
        out, "  route: %zu waypoints\ndry run: configuration and controller OK, nothing moved\n",
        c.route.size());
    return 0;
  }

  if (c.mission) {
    RobotRunConfig enabled = c;
    enabled.rflex = rflex;
    return runMission(o, enabled, out, mission);
  }
  SignalGuard signals;
  RflexRobot robot(rflex, d);
  RobotInterface& iface = robot;  // the agent sees only the robot interface
  RouteFollower follower(c.route, c.route_config);
  const double period = 1.0 / c.control_rate;
  auto next = std::chrono::steady_clock::now();
  Pose2 last = iface.odometry();
  double path = 0.0;
  size_t reached = 0;
  if (!o.quiet)
    std::fprintf(out, "rflex %s: following %zu waypoints\n", rflex.device.c_str(), c.route.size());
  while (true) {
    if (const auto fault = robot.fault()) throw RflexError(*fault);
    const Pose2 pose = iface.odometry();
    path += (pose.translation() - last.translation()).norm();
    last = pose;
    if (g_interrupted) {
      iface.command(MotionCommand::stop());
      std::fprintf(out, "interrupted: stop sent at odometry %s after %.2f m\n",
                   posePhrase(pose).c_str(), path);
      return 130;
    }
    if (iface.status().bumped) {
      iface.command(MotionCommand::stop());
      throw std::runtime_error("the base bumped into something at odometry " + posePhrase(pose) +
                               ": stopped");
    }
    const double t = iface.now();
    if (c.max_duration > 0.0 && t > c.max_duration) {
      iface.command(MotionCommand::stop());
      throw std::runtime_error("route not finished within max_duration (" +
                               std::to_string(c.max_duration) + " s): stopped at waypoint " +
                               std::to_string(follower.nextWaypoint() + 1));
    }
    const MotionCommand cmd = follower.update(pose, t);
    while (reached < follower.nextWaypoint()) {
      ++reached;
      if (!o.quiet)
        std::fprintf(out, "waypoint %zu/%zu reached at %.1f s, odometry %s\n", reached,
                     c.route.size(), t, posePhrase(pose).c_str());
    }
    if (follower.done()) {
      iface.command(MotionCommand::stop());
      sleepSeconds(2.0 * period);
      std::fprintf(out, "route done: %zu waypoints in %.1f s, %.2f m by odometry, ending at %s\n",
                   c.route.size(), iface.now(), path, posePhrase(iface.odometry()).c_str());
      return 0;
    }
    iface.command(cmd);
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(period));
    std::this_thread::sleep_until(next);
  }
}

}  // namespace coopmap

#include "sim/runner/replay_run.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include "core/agent/mapper.h"
#include "core/agent/robot_agent.h"
#include "core/io/atomic_file.h"
#include "core/io/json_writer.h"
#include "core/io/robot_outputs.h"
#include "core/sharing/shared_map.h"
#include "core/sharing/team.h"
#include "robots/replay/replay_robot.h"

namespace coopmap {
namespace {

double pathLength(const std::vector<StampedPose2>& poses) {
  double length = 0.0;
  for (size_t i = 1; i < poses.size(); ++i)
    length +=
        std::hypot(poses[i].pose.x - poses[i - 1].pose.x, poses[i].pose.y - poses[i - 1].pose.y);
  return length;
}

void writeMetrics(const ReplayOptions& o, const ReplayResult& result) {
  JsonWriter j;
  j.beginObject();
  j.value("recording", o.recording).value("format_version", result.info.version);
  j.value("source", result.info.source);
  j.value("world", result.info.world).value("world_file", result.info.world_file);
  j.value("seed", static_cast<unsigned long long>(result.info.seed));
  j.value("wall_time_s", result.wall_time_s);
  j.beginObject("robots");
  for (const ReplayRobotResult& r : result.robots) {
    j.beginObject(r.name);
    j.value("frames", r.frames).value("duration_s", r.duration_s);
    j.value("odometry_path_length_m", r.odometry_path_length_m);
    if (r.path_length_m) j.value("path_length_m", *r.path_length_m);
    if (r.odometry_error_m)
      j.value("odometry_error_m", *r.odometry_error_m)
          .value("odometry_error_deg", *r.odometry_error_deg);
    if (r.map) {
      j.beginObject("map");
      j.value("wall_recall", r.map->wall_recall);
      j.value("false_occupied_rate", r.map->false_occupied_rate);
      j.value("coverage", r.map->coverage);
      j.endObject();
    }
    j.endObject();
  }
  j.endObject();
  j.endObject();
  writeFileAtomic(o.out_dir + "/metrics.json", j.str());
}

}  // namespace

namespace {

// Version 1: the frames through a mapper with the default configuration, in order.
void mapAlone(std::vector<std::unique_ptr<ReplayRobot>>& robots, const RecordingInfo& info,
              std::vector<ReplayRobotResult>& out) {
  for (size_t k = 0; k < robots.size(); ++k) {
    ReplayRobot& robot = *robots[k];
    Mapper mapper(robot.description(), info.map, MapperConfig{});
    mapper.setRobotName(robot.recording().name);
    RobotInterface& iface = robot;  // the core sees only the robot interface
    while (const std::optional<TrinocularFrame> frame = iface.captureFrame())
      mapper.process(*frame, robot.lastSegment());
    out[k].traverse = mapper.traverse();
    out[k].grid = mapper.grid();
  }
}

// Version 2: the agents of the live run, stepped at its control stamps in its order, with a
// shared map and a team channel again when they had them.
void runAgents(std::vector<std::unique_ptr<ReplayRobot>>& robots, const RecordingInfo& info,
               std::vector<ReplayRobotResult>& out) {
  std::optional<LocalSharedMap> shared;
  if (info.shared_map) shared.emplace(info.map, OccupancyConfig{});
  LocalTeamChannel team;
  std::vector<std::unique_ptr<RobotAgent>> agents;
  for (const std::unique_ptr<ReplayRobot>& robot : robots) {
    const AgentConfig& c = *robot->recording().agent;
    agents.push_back(std::make_unique<RobotAgent>(*robot, c.setup, c.settings,
                                                  shared ? &*shared : nullptr, &team));
  }
  const size_t steps = robots.front()->recording().odometry.size();
  for (const std::unique_ptr<ReplayRobot>& robot : robots)
    if (robot->recording().odometry.size() != steps)
      throw std::runtime_error(robot->recording().dir + "/odometry.csv: " +
                               std::to_string(robot->recording().odometry.size()) +
                               " control steps, " + robots.front()->recording().name + "'s has " +
                               std::to_string(steps) + ": the robots were not recorded together");
  for (size_t j = 0; j < steps; ++j)
    for (size_t k = 0; k < robots.size(); ++k) {
      const RobotRecording& rec = robots[k]->recording();
      robots[k]->advanceTo(rec.odometry[j].stamp);
      if (rec.agent->setup.mode == AgentSetup::Mode::kDriven)
        agents[k]->stepDriven(rec.commands.at(j).command);
      else
        agents[k]->step();
    }
  for (size_t k = 0; k < robots.size(); ++k) {
    if (robots[k]->framesLeft() > 0)
      throw std::runtime_error(robots[k]->recording().dir + "/frames.csv: the agent took " +
                               std::to_string(agents[k]->frames()) + " of the " +
                               std::to_string(robots[k]->frameCount()) +
                               " frames: they were not taken on its sensing schedule");
    out[k].traverse = agents[k]->mapper().traverse();
    out[k].grid = agents[k]->mapper().grid();
    out[k].log = agents[k]->log();
    if (const std::optional<StartFix>& fix = agents[k]->startFix(); fix && fix->ok())
      out[k].odometry_in_map = fix->correction;
  }
}

}  // namespace

ReplayResult runReplay(const ReplayOptions& o) {
  const auto wall_start = std::chrono::steady_clock::now();
  ReplayResult result;
  result.info = readRecordingInfo(o.recording);
  const RecordingInfo& info = result.info;
  // Every table first, so a broken one is reported before any mapping.
  std::vector<RobotRecording> recordings;
  for (const RecordedRobotInfo& r : info.robots)
    recordings.push_back(readRobotRecording(o.recording, info, r));
  const std::optional<GridU8> floor = readRecordedFloor(o.recording, info);

  std::vector<std::unique_ptr<ReplayRobot>> robots;
  for (const RobotRecording& rec : recordings) robots.push_back(std::make_unique<ReplayRobot>(rec));
  result.robots.resize(robots.size());
  if (info.version >= 2)
    runAgents(robots, info, result.robots);
  else
    mapAlone(robots, info, result.robots);

  for (size_t k = 0; k < recordings.size(); ++k) {
    const RobotRecording& rec = recordings[k];
    ReplayRobotResult& r = result.robots[k];
    r.name = rec.name;
    r.frames = static_cast<int>(rec.frames.size());
    if (!rec.frames.empty()) r.duration_s = rec.frames.back().stamp - rec.frames.front().stamp;
    r.odometry = rec.odometry;
    // The ground truth in the map frame, as the live run wrote it.
    const Pose2 X_MW =
        info.robots[k].map_in_world ? info.robots[k].map_in_world->inverse() : Pose2();
    r.groundtruth = rec.groundtruth;
    for (StampedPose2& p : r.groundtruth) p.pose = X_MW * p.pose;
    r.odometry_path_length_m = pathLength(r.odometry);
    if (!r.groundtruth.empty()) {
      r.path_length_m = pathLength(r.groundtruth);
      if (!r.odometry.empty() && info.robots[k].start) {
        const Pose2 truth = info.robots[k].start->inverse() * rec.groundtruth.back().pose;
        const Pose2 odo = r.odometry.back().pose;
        r.odometry_error_m = std::hypot(truth.x - odo.x, truth.y - odo.y);
        r.odometry_error_deg = std::abs(wrapAngle(truth.theta - odo.theta)) * 180.0 / M_PI;
      }
    }
    const std::optional<Pose2>& start = info.robots[k].start;
    if (rec.truth_occupancy && start)
      r.map = computeMapMetrics(*r.grid, *rec.truth_occupancy, (X_MW * *start).translation(),
                                floor ? &*floor : nullptr);
  }
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  if (!o.out_dir.empty()) {
    std::filesystem::create_directories(o.out_dir);
    for (size_t k = 0; k < result.robots.size(); ++k) {
      const ReplayRobotResult& r = result.robots[k];
      const RobotRecording& rec = recordings[k];
      writeRobotOutputs(o.out_dir, {r.name, info.world, &*r.grid, &r.groundtruth, &r.odometry,
                                    rec.truth_occupancy ? &*rec.truth_occupancy : nullptr,
                                    &r.traverse, r.odometry_in_map});
    }
    writeMetrics(o, result);
  }
  return result;
}

}  // namespace coopmap

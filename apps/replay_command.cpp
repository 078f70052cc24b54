#include "apps/replay_command.h"

#include <chrono>
#include <cmath>
#include <filesystem>

#include "apps/run_outputs.h"
#include "core/agent/mapper.h"
#include "core/io/atomic_file.h"
#include "core/io/json_writer.h"
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
  j.value("seed", static_cast<long long>(result.info.seed));
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

  for (size_t k = 0; k < recordings.size(); ++k) {
    ReplayRobot robot(recordings[k]);  // a copy: the tables are small, the images on disk
    const RobotRecording& rec = robot.recording();
    // The live run's mapper: the recorded description, the recorded map, the default config.
    Mapper mapper(robot.description(), info.map, MapperConfig{});
    mapper.setRobotName(rec.name);
    RobotInterface& iface = robot;  // the core sees only the robot interface
    while (const std::optional<TrinocularFrame> frame = iface.captureFrame())
      mapper.process(*frame, robot.lastSegment());

    ReplayRobotResult r;
    r.name = rec.name;
    r.frames = robot.frameCount();
    if (!rec.frames.empty()) r.duration_s = rec.frames.back().stamp - rec.frames.front().stamp;
    r.odometry = rec.odometry;
    r.groundtruth = rec.groundtruth;
    r.odometry_path_length_m = pathLength(r.odometry);
    if (!r.groundtruth.empty()) {
      r.path_length_m = pathLength(r.groundtruth);
      if (!r.odometry.empty()) {
        const Pose2 truth = r.groundtruth.back().pose, odo = r.odometry.back().pose;
        r.odometry_error_m = std::hypot(truth.x - odo.x, truth.y - odo.y);
        r.odometry_error_deg = std::abs(wrapAngle(truth.theta - odo.theta)) * 180.0 / M_PI;
      }
    }
    const std::optional<Pose2>& start = info.robots[k].start;
    if (rec.truth_occupancy && start)
      r.map = computeMapMetrics(mapper.grid(), *rec.truth_occupancy, start->translation(),
                                floor ? &*floor : nullptr);
    r.traverse = mapper.traverse();
    r.grid = mapper.grid();
    result.robots.push_back(std::move(r));
  }
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  if (!o.out_dir.empty()) {
    std::filesystem::create_directories(o.out_dir);
    for (size_t k = 0; k < result.robots.size(); ++k) {
      const ReplayRobotResult& r = result.robots[k];
      const RobotRecording& rec = recordings[k];
      writeRobotOutputs(o.out_dir,
                        {r.name, info.world, &*r.grid, &r.groundtruth, &r.odometry,
                         rec.truth_occupancy ? &*rec.truth_occupancy : nullptr, &r.traverse});
    }
    writeMetrics(o, result);
  }
  return result;
}

}  // namespace coopmap

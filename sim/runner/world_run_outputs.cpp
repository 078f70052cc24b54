#include "sim/runner/world_run_outputs.h"

#include <filesystem>
#include <string>
#include <vector>

#include "core/agent/agent_settings.h"
#include "core/io/atomic_file.h"
#include "core/io/json_writer.h"
#include "core/io/robot_outputs.h"
#include "core/io/tum.h"
#include "core/mapping/map_io.h"
#include "sim/runner/run_report.h"

namespace coopmap {

void writeRunOutputs(const std::string& dir, const RunResult& result) {
  std::filesystem::create_directories(dir);
  const GridU8& floor = result.floor;
  for (const RobotRunResult& r : result.robots)
    writeRobotOutputs(dir, {r.name, result.world, &*r.grid, &r.groundtruth, &r.odometry, &r.truth,
                            &r.traverse, r.odometry_in_map});
  if (result.cooperative)
    for (const RobotRunResult& r : result.robots) {
      writeTum(dir + "/trajectory_" + r.name + "_estimate.tum", r.estimate,
               "coopmap pose estimate of " + r.name +
                   " (odometry, corrected at each home-base fix; map frame) in world " +
                   result.world);
      writeTum(dir + "/trajectory_" + r.name + "_corrected.tum", r.corrected,
               "coopmap corrected traverse of " + r.name +
                   " (radial maps posted to the shared map; map frame) in world " + result.world);
    }
  writeTimelineCsv(dir + "/timeline.csv", result);
  const SharedMapResult& shared = result.shared_map;
  if (shared.computed) {
    writeRosMap(*shared.protocol_grid, dir, "shared_map");
    writeMapPng(dir + "/shared_map.png", *shared.protocol_grid, {});
    writeRosMap(*shared.naive_grid, dir, "shared_map_naive");
    writeMapPng(dir + "/shared_map_naive.png", *shared.naive_grid, {});
    const GridU8& truth = result.shared_truth;
    writeFileAtomic(dir + "/shared_map_evaluation.png",
                    encodeEvaluationPng(*shared.protocol_grid, truth, 3, &floor));
    writeFileAtomic(dir + "/shared_map_naive_evaluation.png",
                    encodeEvaluationPng(*shared.naive_grid, truth, 3, &floor));
  }
  JsonWriter j;
  j.beginObject();
  j.value("world", result.world).value("world_file", result.world_file);
  if (shared.computed) {
    auto metrics = [&](const char* key, const MapMetrics& m) {
      j.beginObject(key);
      j.value("wall_recall", m.wall_recall).value("false_occupied_rate", m.false_occupied_rate);
      j.value("coverage", m.coverage);
      j.beginObject("false_occupied_by_distance");
      for (int b = 0; b < MapMetrics::kDistanceBands; ++b)
        j.value(MapMetrics::kDistanceBandNames[b], m.false_occupied_by_distance[b]);
      j.endObject();
      if (std::string(key) == "shared_map") {
        j.value("posts_accepted", shared.posts_accepted);
        j.value("published_band", result.published_band);
        j.beginObject("imported");  // the shared grid the robots import, at their band
        j.value("wall_recall", shared.imported.wall_recall);
        j.value("false_occupied_rate", shared.imported.false_occupied_rate);
        j.endObject();
        std::string posted, refused;
        for (const std::string& r : shared.posted) posted += (posted.empty() ? "" : ", ") + r;
        for (const std::string& r : shared.refused) refused += (refused.empty() ? "" : "; ") + r;
        j.value("posted", posted).value("refused", refused);
      }
      j.endObject();
    };
    metrics("shared_map", shared.protocol);
    metrics("shared_map_naive", shared.naive);
  }
  j.value("seed", static_cast<unsigned long long>(result.seed));
  {
    int collisions = 0;
    bool complete = !result.robots.empty();
    for (const RobotRunResult& r : result.robots) {
      collisions += r.collisions;
      complete = complete && r.exploration_complete;
    }
    j.value("collisions", collisions);
    if (result.explore) j.value("exploration_complete", complete);
    j.value("cooperative", result.cooperative);
    j.value("time_to_50_percent_coverage_s", result.time_to_50_s);
    j.value("time_to_75_percent_coverage_s", result.time_to_75_s);
    j.value("time_to_90_percent_coverage_s", result.time_to_90_s);
  }
  j.beginObject("settings");
  result.settings.visit(
      [&](const SettingInfo& info, const auto& value) { j.value(info.name, value); });
  j.endObject();
  j.value("sim_time_s", result.sim_time_s).value("wall_time_s", result.wall_time_s);
  j.value("real_time_factor", result.real_time_factor);
  j.beginObject("timing_s");
  j.value("physics", result.timing.physics_s).value("render", result.timing.render_s);
  j.value("stereo", result.timing.stereo_s).value("mapping", result.timing.mapping_s);
  j.endObject();
  j.beginObject("robots");
  for (const RobotRunResult& r : result.robots) {
    j.beginObject(r.name);
    j.value("path_length_m", r.path_length_m).value("collisions", r.collisions);
    j.beginObject("collisions_with");
    j.value("static_world", r.collisions_static).value("people", r.collisions_people);
    j.value("robots", r.collisions_robots);
    j.endObject();
    j.value("frames", r.frames).value("route_complete", r.route_complete);
    j.value("phase", r.phase).value("placed", r.placed);
    if (r.start_fix_error)
      j.value("start_fix_error_m", r.start_fix_error->error_m)
          .value("start_fix_error_deg", r.start_fix_error->error_deg);
    if (r.placed_error)
      j.value("placed_error_m", r.placed_error->error_m)
          .value("placed_error_deg", r.placed_error->error_deg);
    if (result.explore) {
      j.beginObject("mission");
      j.value("exploration_complete", r.exploration_complete);
      j.value("goals_reached", r.goals_reached).value("goals_failed", r.goals_failed);
      j.value("safety_stops", r.safety_stops)
          .value("early_returns", r.early_returns)
          .value("last_event", r.mission_event);
      j.value("sorties", r.sorties).value("sorties_fixed", r.sorties_fixed);
      j.value("sorties_posted", r.sorties_posted);
      std::string log;
      for (const std::string& line : r.log) log += (log.empty() ? "" : "; ") + line;
      j.value("log", log);
      j.beginArray("fix_errors");
      for (const FixError& e : r.fix_errors) {
        j.beginObject();
        j.value("sortie", e.sortie).value("t", e.stamp);
        j.value("error_m", e.error_m).value("error_deg", e.error_deg);
        j.endObject();
      }
      j.endArray();
      j.beginObject("odometry_calibration");
      j.value("heading_drift_rad_per_m", r.calibration.heading_drift)
          .value("turn_scale", r.calibration.turn_scale)
          .value("distance_scale", r.calibration.distance_scale);
      j.endObject();
      j.endObject();
    }
    j.beginObject("phases");
    for (const PhaseTime& p : r.phases) {
      j.beginObject(p.phase);
      j.value("time_s", p.time_s).value("driving_s", p.driving_s);
      j.value("turning_s", p.turning_s).value("path_m", p.path_m);
      j.endObject();
    }
    j.endObject();
    j.beginArray("contacts");
    for (const ContactRecord& c : r.contacts) {
      j.beginObject();
      j.value("t", c.t).value("with", c.with).value("x", c.point.x()).value("y", c.point.y());
      j.value("robot_x", c.robot.x).value("robot_y", c.robot.y).value("phase", c.phase);
      j.endObject();
    }
    j.endArray();
    j.value("odometry_error_m", r.odometry_error_m)
        .value("odometry_error_deg", r.odometry_error_deg);
    j.beginObject("map");
    j.value("wall_recall", r.map.wall_recall);
    j.value("false_occupied_rate", r.map.false_occupied_rate);
    j.value("coverage", r.map.coverage);
    j.endObject();
    j.endObject();
  }
  j.endObject();
  j.endObject();
  writeFileAtomic(dir + "/metrics.json", j.str());
  writeRunReport(dir, result);
}

}  // namespace coopmap

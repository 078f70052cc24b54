// Writes a run's outputs to opt.out_dir: per-robot maps and trajectories, the shared maps
// and their evaluation images, timeline.csv, metrics.json and report.html.
#include <filesystem>
#include <string>
#include <vector>

#include "apps/robot_run.h"
#include "apps/run_outputs.h"
#include "apps/run_report.h"
#include "core/io/atomic_file.h"
#include "core/io/json_writer.h"
#include "core/io/tum.h"
#include "core/mapping/map_io.h"

namespace coopmap::run_detail {

// `floor`: the drivable floor over the run's map limits (what the metrics score).
void writeOutputs(const RunOptions& opt, const sim::World& world, const RunResult& result,
                  const std::vector<RobotRun>& runs, const GridU8& floor) {
  std::filesystem::create_directories(opt.out_dir);
  for (const RobotRun& r : runs)
    writeRobotOutputs(opt.out_dir,
                      {r.result.name, world.name, &r.mapper->grid(), &r.result.groundtruth,
                       &r.result.odometry, &r.truth, &r.mapper->traverse()});
  if (result.cooperative)
    for (const RobotRunResult& r : result.robots) {
      writeTum(opt.out_dir + "/trajectory_" + r.name + "_estimate.tum", r.estimate,
               "coopmap pose estimate of " + r.name +
                   " (odometry, corrected at each home-base "
                   "fix) in world " +
                   world.name);
      writeTum(opt.out_dir + "/trajectory_" + r.name + "_corrected.tum", r.corrected,
               "coopmap corrected traverse of " + r.name +
                   " (radial maps posted to the shared "
                   "map) in world " +
                   world.name);
    }
  writeTimelineCsv(opt.out_dir + "/timeline.csv", result);
  const SharedMapResult& shared = result.shared_map;
  if (shared.computed) {
    writeRosMap(*shared.protocol_grid, opt.out_dir, "shared_map");
    writeMapPng(opt.out_dir + "/shared_map.png", *shared.protocol_grid, {});
    writeRosMap(*shared.naive_grid, opt.out_dir, "shared_map_naive");
    writeMapPng(opt.out_dir + "/shared_map_naive.png", *shared.naive_grid, {});
    if (!runs.empty()) {
      const GridU8& truth = tallestRobot(runs).truth;
      writeFileAtomic(opt.out_dir + "/shared_map_evaluation.png",
                      encodeEvaluationPng(*shared.protocol_grid, truth, 3, &floor));
      writeFileAtomic(opt.out_dir + "/shared_map_naive_evaluation.png",
                      encodeEvaluationPng(*shared.naive_grid, truth, 3, &floor));
    }
  }
  JsonWriter j;
  j.beginObject();
  j.value("world", world.name).value("world_file", opt.world_file);
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
        j.value("published_band", opt.published_band);
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
  j.value("seed", static_cast<long long>(opt.seed));
  {
    int collisions = 0;
    bool complete = !result.robots.empty();
    for (const RobotRunResult& r : result.robots) {
      collisions += r.collisions;
      complete = complete && r.exploration_complete;
    }
    j.value("collisions", collisions);
    if (opt.explore) j.value("exploration_complete", complete);
    j.value("cooperative", result.cooperative);
    j.value("time_to_50_percent_coverage_s", result.time_to_50_s);
    j.value("time_to_75_percent_coverage_s", result.time_to_75_s);
    j.value("time_to_90_percent_coverage_s", result.time_to_90_s);
  }
  if (const auto& m = result.mission_settings) {
    j.beginObject("mission_settings");
    j.value("sortie_budget_m", m->sortie_budget_m);
    j.value("first_sortie_budget_m", m->first_sortie_budget_m);
    j.value("safety_distance", m->safety_distance).value("slow_distance", m->slow_distance);
    j.value("fringe_clearance", m->fringe_clearance).value("goal_clearance", m->goal_clearance);
    j.value("doorway_width", m->doorway_width);
    j.value("retry_frontiers", m->retry_frontiers).value("floor_edge_depth", m->floor_edge_depth);
    j.value("beyond_support", m->beyond_support);
    j.value("shaped_closures", m->shaped_closures).value("bump_away", m->bump_away);
    j.value("closure_seen_points", m->closure_seen_points);
    j.value("closure_decided_points", m->closure_decided_points);
    j.value("visited_radius", m->visited_radius).value("recent_hits_s", m->recent_hits_s);
    j.value("calibrate_distance_scale", m->calibrate_distance_scale);
    j.value("stereo_distance_scale", m->stereo_distance_scale);
    j.value("odometry_distance_scale", m->odometry_distance_scale);
    j.value("passage_width", m->passage_width).value("planning_margin", m->planning_margin);
    j.value("preferred_margin", m->preferred_margin).value("closures", m->closures);
    j.value("post_gate_m", m->post_gate_m).value("manhattan_sigma_deg", m->manhattan_sigma_deg);
    j.value("wall_heading_gain", m->wall_heading_gain).value("closure_scans", m->closure_scans);
    j.value("look_again_gain", m->look_again_gain).value("max_linear_accel", m->max_linear_accel);
    j.endObject();
  }
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
    if (!r.mission_phase.empty()) {
      j.beginObject("mission");
      j.value("phase", r.mission_phase).value("exploration_complete", r.exploration_complete);
      j.value("goals_reached", r.goals_reached).value("goals_failed", r.goals_failed);
      j.value("safety_stops", r.safety_stops)
          .value("early_returns", r.early_returns)
          .value("last_event", r.mission_event);
      j.value("sorties", r.sorties).value("sorties_fixed", r.sorties_fixed);
      j.value("sorties_posted", r.sorties_posted);
      std::string log;
      for (const std::string& line : r.sortie_log) log += (log.empty() ? "" : "; ") + line;
      j.value("sortie_log", log);
      j.beginObject("odometry_calibration");
      j.value("heading_drift_rad_per_m", r.calibration.heading_drift)
          .value("turn_scale", r.calibration.turn_scale)
          .value("distance_scale", r.calibration.distance_scale);
      j.endObject();
      j.endObject();
    }
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
  writeFileAtomic(opt.out_dir + "/metrics.json", j.str());
  writeRunReport(opt, world.name, result, runs.empty() ? nullptr : &tallestRobot(runs).truth);
}

}  // namespace coopmap::run_detail

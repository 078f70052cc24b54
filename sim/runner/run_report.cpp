#include "sim/runner/run_report.h"

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/io/atomic_file.h"
#include "sim/runner/report_html.h"

namespace coopmap {

namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

// report.html: the run on one page.
void writeRunReport(const std::string& dir, const RunResult& result) {
  ReportData d;
  d.title = result.world + ", seed " + std::to_string(result.seed);
  auto row = [&](const std::string& k, const std::string& v) { d.summary.emplace_back(k, v); };
  row("world file", result.world_file);
  row("robots", std::to_string(result.robots.size()));
  row("mode", !result.explore      ? "scripted routes"
              : result.cooperative ? "autonomous, cooperative: sorties of " +
                                         fixed(result.settings.sortie_budget_m, 0) +
                                         " m, home-base protocol after each"
                                   : "autonomous, one sortie");
  row("simulated time",
      fixed(result.sim_time_s, 1) + " s (" + fixed(result.real_time_factor, 1) + "x real time)");
  int collisions = 0;
  for (const RobotRunResult& r : result.robots) collisions += r.collisions;
  int with_static = 0, with_people = 0, with_robots = 0;
  for (const RobotRunResult& r : result.robots) {
    with_static += r.collisions_static;
    with_people += r.collisions_people;
    with_robots += r.collisions_robots;
  }
  row("collisions", std::to_string(collisions) + " (walls and furniture " +
                        std::to_string(with_static) + ", people " + std::to_string(with_people) +
                        ", robots " + std::to_string(with_robots) + ")");
  if (result.explore) {
    bool complete = true;
    for (const RobotRunResult& r : result.robots) complete = complete && r.exploration_complete;
    row("exploration complete", complete ? "yes" : "no");
  }
  auto reached = [&](double t) { return t >= 0 ? fixed(t, 0) + " s" : std::string("not reached"); };
  row("time to 50 / 75 / 90 % coverage", reached(result.time_to_50_s) + " / " +
                                             reached(result.time_to_75_s) + " / " +
                                             reached(result.time_to_90_s));
  const SharedMapResult& shared = result.shared_map;
  if (shared.computed) {
    auto metrics = [&](const MapMetrics& m) {
      return "wall_recall " + fixed(m.wall_recall, 3) + ", false_occupied_rate " +
             fixed(m.false_occupied_rate, 4) + ", coverage " + fixed(m.coverage, 3);
    };
    row("shared map (home-base protocol, " + std::to_string(shared.posts_accepted) + " posts)",
        metrics(shared.protocol));
    row("shared map, naive sharing", metrics(shared.naive));
    row("shared map as the robots import it (their maps' band)",
        "wall_recall " + fixed(shared.imported.wall_recall, 3) + ", false_occupied_rate " +
            fixed(shared.imported.false_occupied_rate, 4));
    std::string refused;
    for (const std::string& r : shared.refused) refused += (refused.empty() ? "" : "; ") + r;
    if (!refused.empty()) row("not shared", refused);
  }
  for (const RobotRunResult& r : result.robots) {
    row(r.name + ": own map", "wall_recall " + fixed(r.map.wall_recall, 3) +
                                  ", false_occupied_rate " + fixed(r.map.false_occupied_rate, 4) +
                                  ", coverage " + fixed(r.map.coverage, 3) + ", path " +
                                  fixed(r.path_length_m, 1) + " m");
    for (const std::string& line : r.log) row(r.name, line);
    std::vector<StampedPose2> odometry = r.odometry;
    for (StampedPose2& p : odometry) p.pose = r.odometry_in_map * p.pose;
    d.robots.push_back({r.name, r.groundtruth, std::move(odometry), r.corrected});
  }
  d.truth = &result.shared_truth;
  d.limits = result.shared_truth.limits;
  if (shared.computed) {
    d.images.push_back({"Shared map: home-base protocol", "shared_map.png"});
    d.images.push_back({"Shared map: naive sharing (every radial map at its odometry pose)",
                        "shared_map_naive.png"});
  }
  for (const RobotRunResult& r : result.robots) {
    d.images.push_back({r.name + "'s map (truth green, odometry red)", "map_" + r.name + ".png"});
    d.images.push_back({r.name + "'s map against the truth", "map_" + r.name + "_evaluation.png"});
  }
  ReportSeries shared_coverage{result.cooperative ? "shared map" : "all robots' maps together", {}};
  std::vector<ReportSeries> coverage(result.robots.size()), error(result.robots.size());
  for (size_t k = 0; k < result.robots.size(); ++k) {
    coverage[k].name = result.robots[k].name + "'s map";
    error[k].name = result.robots[k].name;
  }
  for (const TimelineSample& s : result.timeline) {
    shared_coverage.points.emplace_back(s.t, s.shared_coverage);
    for (size_t k = 0; k < s.robot_coverage.size(); ++k) {
      coverage[k].points.emplace_back(s.t, s.robot_coverage[k]);
      error[k].points.emplace_back(s.t, s.robot_error_m[k]);
    }
  }
  d.coverage.push_back(std::move(shared_coverage));
  for (ReportSeries& c : coverage) d.coverage.push_back(std::move(c));
  d.error = std::move(error);
  d.coverage_note =
      "Share of the true free area reachable from the start that the map has "
      "seen, every " +
      fixed(result.timeline_period_s, 0) + " s." +
      (result.cooperative ? " The shared map grows when a robot posts a sortie "
                            "corrected at the home base."
                          : "");
  d.error_note =
      "Distance between each robot's pose estimate (odometry, corrected at each "
      "home-base fix) and its true pose.";
  writeReport(dir, d);
}

void writeTimelineCsv(const std::string& path, const RunResult& result) {
  std::string csv = "t_s,shared_coverage";
  for (const RobotRunResult& r : result.robots)
    csv += "," + r.name + "_coverage," + r.name + "_error_m";
  csv += "\n";
  char buf[64];
  for (const TimelineSample& s : result.timeline) {
    std::snprintf(buf, sizeof buf, "%.2f,%.4f", s.t, s.shared_coverage);
    csv += buf;
    for (size_t k = 0; k < s.robot_coverage.size(); ++k) {
      std::snprintf(buf, sizeof buf, ",%.4f,%.4f", s.robot_coverage[k], s.robot_error_m[k]);
      csv += buf;
    }
    csv += "\n";
  }
  writeFileAtomic(path, csv);
}

}  // namespace coopmap

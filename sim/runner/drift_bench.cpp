#include "sim/runner/drift_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/correction/home_return.h"
#include "core/correction/trajectory_error.h"
#include "core/io/atomic_file.h"
#include "core/mapping/map_io.h"
#include "core/mapping/map_metrics.h"
#include "robots/robot_model.h"
#include "sim/runner/world_run.h"
#include "sim/world/ground_truth.h"
#include "sim/world/world.h"

namespace coopmap {

namespace {

constexpr const char* kTruthModel = "ground-truth";

double degrees(double rad) { return rad * 180.0 / M_PI; }

// The trajectory's pose at a stamp (the sample at or just before it).
Pose2 poseAt(const std::vector<StampedPose2>& t, double stamp) {
  auto it = std::upper_bound(t.begin(), t.end(), stamp + 1e-9,
                             [](double s, const StampedPose2& p) { return s < p.stamp; });
  return it == t.begin() ? t.front().pose : std::prev(it)->pose;
}

std::vector<StampedPose2> stamped(const TraverseLog& log, const std::vector<Pose2>& poses) {
  std::vector<StampedPose2> out(poses.size());
  for (size_t i = 0; i < poses.size(); ++i) out[i] = {log.entries[i].scan.stamp, poses[i]};
  return out;
}

cv::Mat labelled(const OccupancyGrid& grid, const std::vector<TrajectoryOverlay>& overlays,
                 const std::string& label) {
  const std::string png = encodeMapPng(grid, overlays, 1);
  cv::Mat img =
      cv::imdecode(cv::Mat(1, static_cast<int>(png.size()), CV_8U, const_cast<char*>(png.data())),
                   cv::IMREAD_COLOR);
  cv::Mat out(img.rows + 24, img.cols, CV_8UC3, cv::Scalar(255, 255, 255));
  img.copyTo(out(cv::Rect(0, 24, img.cols, img.rows)));
  cv::putText(out, label, {6, 17}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  return out;
}

struct Stat {
  double mean = 0.0, sd = 0.0;
  int n = 0;
};
Stat stat(const std::vector<double>& v) {
  Stat s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= v.size();
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(s.sd / (v.size() - 1)) : 0.0;
  return s;
}

std::string pm(const Stat& s, int digits) {
  char b[64];
  std::snprintf(b, sizeof(b), "%.*f ± %.*f", digits, s.mean, digits, s.sd);
  return b;
}

std::string markdown(const DriftBenchOptions& o, const std::vector<DriftRow>& rows) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const DriftRow*>> by_model;
  int seeds = 0, failed = 0;
  std::vector<double> path, odo_m, odo_deg, home_m, home_deg;
  uint64_t last_seed = 0;
  for (const DriftRow& r : rows) {
    const bool first_of_seed = seeds == 0 || r.seed != last_seed;
    if (first_of_seed) {
      ++seeds;
      last_seed = r.seed;
      if (r.status != "ok") ++failed;
    }
    if (r.status != "ok") continue;
    if (!by_model.count(r.model)) order.push_back(r.model);
    by_model[r.model].push_back(&r);
    if (first_of_seed) {
      path.push_back(r.path_length_m);
      odo_m.push_back(r.odometry_error_m);
      odo_deg.push_back(r.odometry_error_deg);
      home_m.push_back(r.home_error_m * 100.0);
      home_deg.push_back(r.home_error_deg);
    }
  }
  std::ostringstream md;
  md << "# Drift-error benchmark\n\n"
     << "World `" << o.world_file << "`, odometry `" << o.odometry << "`, camera noise "
     << (o.camera_noise ? "on" : "off") << "; " << seeds << " seeds from " << o.first_seed << " ("
     << failed << " without a home-base fix). Mean ± standard deviation over seeds.\n\n"
     << "| | paper (one run) | coopmap |\n|---|---|---|\n"
     << "| traverse length (m) | ~82 | " << pm(stat(path), 1) << " |\n"
     << "| odometry error at home base (m) | 2.64 | " << pm(stat(odo_m), 2) << " |\n"
     << "| odometry error at home base (deg) | 25.4 | " << pm(stat(odo_deg), 1) << " |\n"
     << "| home-base fix error (cm) | — | " << pm(stat(home_m), 1) << " |\n"
     << "| home-base fix error (deg) | — | " << pm(stat(home_deg), 2) << " |\n\n"
     << "| model | paper | final error (cm) | ATE RMSE (m) | ATE max (m) | ATE, scale aligned (m) "
        "| "
        "heading RMSE (deg) | drift (%) | drift (deg/m) | wall_recall | false_occupied_rate | "
        "correct (ms) | rebuild (ms) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto paper = [](const std::string& m) -> std::string {
    if (m == "none") return "2.64 m, 25.4° (Fig. 6a)";
    if (m == "uniform") return "the assumption of §4.1";
    if (m == "turns-and-straights") return "corridors not straightened (Fig. 6b)";
    if (m == kTruthModel) return "—";
    return "— (new)";
  };
  for (const std::string& m : order) {
    const auto& rs = by_model[m];
    auto col = [&](auto f) {
      std::vector<double> v;
      for (const DriftRow* r : rs) v.push_back(f(*r));
      return stat(v);
    };
    md << "| " << m << " | " << paper(m) << " | "
       << pm(col([](const DriftRow& r) { return r.final_error_m * 100; }), 1) << " | "
       << pm(col([](const DriftRow& r) { return r.ate_rmse_m; }), 3) << " | "
       << pm(col([](const DriftRow& r) { return r.ate_max_m; }), 3) << " | "
       << pm(col([](const DriftRow& r) { return r.ate_scale_aligned_m; }), 3) << " | "
       << pm(col([](const DriftRow& r) { return r.heading_rmse_deg; }), 2) << " | "
       << pm(col([](const DriftRow& r) { return r.drift_percent; }), 2) << " | "
       << pm(col([](const DriftRow& r) { return r.drift_deg_per_m; }), 3) << " | "
       << pm(col([](const DriftRow& r) { return r.wall_recall; }), 3) << " | "
       << pm(col([](const DriftRow& r) { return r.false_occupied_rate; }), 4) << " | "
       << pm(col([](const DriftRow& r) { return r.correct_ms; }), 2) << " | "
       << pm(col([](const DriftRow& r) { return r.rebuild_ms; }), 1) << " |\n";
  }
  md << "\nfinal error: corrected pose at the home-base fix against the true pose. ATE: "
        "position error of every corrected scan pose, no alignment (the home base fixes the "
        "frame); scale aligned: after the best uniform scaling about the start (a distance-scale "
        "error does not show at the home base of a closed loop). drift: KITTI-style relative error "
        "over sub-paths of 5, 10, 20 and 40 m. "
        "Maps are rebuilt from the traverse log with the corrected poses; `ground-truth` "
        "rebuilds them with the true poses (the best these scans allow).\n";
  return md.str();
}

}  // namespace

std::string formatDriftCsv(const std::vector<DriftRow>& rows) {
  std::ostringstream csv;
  csv << "seed,model,status,path_length_m,odometry_error_m,odometry_error_deg,home_error_m,"
         "home_error_deg,final_error_m,final_error_deg,ate_rmse_m,ate_max_m,"
         "ate_scale_aligned_m,heading_rmse_deg,"
         "drift_percent,drift_deg_per_m,wall_recall,false_occupied_rate,correct_ms,rebuild_ms,"
         "bias_heading_drift,bias_turn_scale,bias_distance_scale,iterations,fix_method\n";
  for (const DriftRow& r : rows) {
    char b[1024];
    std::snprintf(b, sizeof(b),
                  "%llu,%s,\"%s\",%.3f,%.4f,%.3f,%.4f,%.3f,%.4f,%.3f,%.4f,%.4f,%.4f,%.3f,%.3f,%.4f,"
                  "%.4f,%.5f,%.3f,%.3f,%.6f,%.6f,%.6f,%d,\"%s\"\n",
                  static_cast<unsigned long long>(r.seed), r.model.c_str(), r.status.c_str(),
                  r.path_length_m, r.odometry_error_m, r.odometry_error_deg, r.home_error_m,
                  r.home_error_deg, r.final_error_m, r.final_error_deg, r.ate_rmse_m, r.ate_max_m,
                  r.ate_scale_aligned_m, r.heading_rmse_deg, r.drift_percent, r.drift_deg_per_m,
                  r.wall_recall, r.false_occupied_rate, r.correct_ms, r.rebuild_ms,
                  r.bias.heading_drift, r.bias.turn_scale, r.bias.distance_scale, r.iterations,
                  r.fix_method.c_str());
    csv << b;
  }
  return csv.str();
}

DriftBenchResult runDriftBench(const DriftBenchOptions& o) {
  if (o.seeds < 1) throw std::invalid_argument("--seeds: expected at least 1");
  if (o.models.empty()) throw std::invalid_argument("--models: expected at least one model");
  const sim::World world = sim::loadWorld(o.world_file);
  if (world.home_base.corners.size() != 2)
    throw std::invalid_argument(o.world_file + ": the drift benchmark needs a home_base");
  if (world.robots.empty()) throw std::invalid_argument(o.world_file + ": no robots");
  const RobotModel model = loadRobotModel(world.robots[0].model_file);
  sim::OdometryConfig odometry_model = model.odometry;
  if (o.odometry != "drifting") {
    const auto preset = model.odometry_presets.find(o.odometry);
    if (preset == model.odometry_presets.end())
      throw std::invalid_argument("--odometry: no preset '" + o.odometry + "' in " +
                                  world.robots[0].model_file);
    odometry_model = preset->second;
  }
  // The robot maps in the home base's frame (it places itself there by its first look).
  const HomeBaseDesign design;
  const Pose2 X_WM = sim::mapFrameInWorld(world, design);
  const MapLimits limits = sim::worldMapLimits(world, 0.5, X_WM);
  const GridU8 truth_map = sim::trueOccupancy(world, limits, model.description.swept_height, X_WM);
  const GridU8 floor = sim::floorMask(world, limits, X_WM);
  const Eigen::Vector2d start = X_WM.inverse() * world.robots[0].start.translation();
  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };

  DriftBenchResult result;
  for (int k = 0; k < o.seeds; ++k) {
    const uint64_t seed = o.first_seed + k;
    RunOptions run;
    run.world_file = o.world_file;
    run.seed = seed;
    run.robots = 1;
    run.odometry = o.odometry;
    run.camera_noise = o.camera_noise;
    run.steer_by_truth = true;  // the intended path; odometry only records it
    run.duration = 3600.0;
    const RunResult r = runWorld(run);
    const RobotRunResult& robot = r.robots[0];
    const TraverseLog& log = robot.traverse;
    std::vector<Pose2> truth(log.entries.size()), odometry(log.entries.size());
    for (size_t i = 0; i < log.entries.size(); ++i) {
      truth[i] = poseAt(robot.groundtruth, log.entries[i].scan.stamp);
      odometry[i] = log.entries[i].scan.odometry;
    }

    DriftRow base;
    base.seed = seed;
    base.path_length_m = robot.path_length_m;
    std::optional<HomeReturn> ret;
    std::optional<OccupancyGrid> reference;
    HomeBaseProtocol protocol =
        runHomeBaseProtocol(log, design.visibleCorners(), design.arm_length);
    ret = protocol.result;
    reference = std::move(protocol.reference);
    if (ret->status != HomeReturnStatus::kOk) base.status = toString(ret->status);
    if (!robot.placed) base.status = "not placed at its start by the home base";
    base.fix_method = protocol.method;
    size_t at = log.entries.empty() ? 0 : log.entries.size() - 1;
    if (base.status == "ok") {
      at = ret->observation.entry;
      const Pose2& fix = ret->observation.pose;
      base.home_error_m = std::hypot(fix.x - truth[at].x, fix.y - truth[at].y);
      base.home_error_deg = std::abs(degrees(wrapAngle(fix.theta - truth[at].theta)));
    }
    if (!log.entries.empty()) {
      base.odometry_error_m =
          std::hypot(odometry[at].x - truth[at].x, odometry[at].y - truth[at].y);
      base.odometry_error_deg = std::abs(degrees(wrapAngle(odometry[at].theta - truth[at].theta)));
    }

    const std::string seed_dir = o.out_dir + "/seeds/" + std::to_string(seed);
    if (!o.out_dir.empty()) {
      std::filesystem::create_directories(seed_dir);
      writeTum(seed_dir + "/trajectory_groundtruth.tum", stamped(log, truth),
               "coopmap drift benchmark: ground truth at each scan, seed " + std::to_string(seed));
      writeTum(seed_dir + "/trajectory_odometry.tum", stamped(log, odometry),
               "coopmap drift benchmark: odometry at each scan, seed " + std::to_string(seed));
    }
    std::vector<cv::Mat> panels;
    auto evaluate = [&](const std::string& name, const std::vector<Pose2>& poses, DriftRow row) {
      const auto t0 = Clock::now();
      const OccupancyGrid grid = rebuildMap(log, poses, limits);
      row.rebuild_ms = ms(t0, Clock::now());
      row.model = name;
      const MapMetrics mm = computeMapMetrics(grid, truth_map, start, &floor);
      row.wall_recall = mm.wall_recall;
      row.false_occupied_rate = mm.false_occupied_rate;
      const TrajectoryError te = trajectoryError(poses, truth);
      row.ate_rmse_m = te.ate_rmse_m;
      row.ate_max_m = te.ate_max_m;
      row.ate_scale_aligned_m = te.ate_scale_aligned_m;
      row.heading_rmse_deg = te.heading_rmse_deg;
      row.drift_percent = te.drift_percent;
      row.drift_deg_per_m = te.drift_deg_per_m;
      row.final_error_m = std::hypot(poses[at].x - truth[at].x, poses[at].y - truth[at].y);
      row.final_error_deg = std::abs(degrees(wrapAngle(poses[at].theta - truth[at].theta)));
      if (!o.out_dir.empty()) {
        // (The uncorrected and true poses are already trajectory_{odometry,groundtruth}.)
        if (name != "none" && name != kTruthModel)
          writeTum(seed_dir + "/trajectory_" + name + ".tum", stamped(log, poses),
                   "coopmap drift benchmark: " + name + " poses at each scan, seed " +
                       std::to_string(seed));
        panels.push_back(
            labelled(grid, {{stamped(log, truth), 0, 160, 0}, {stamped(log, poses), 0, 0, 230}},
                     name + ": wall_recall " + std::to_string(mm.wall_recall).substr(0, 5) +
                         ", ATE " + std::to_string(te.ate_rmse_m).substr(0, 5) + " m"));
      }
      result.rows.push_back(row);
    };

    if (base.status != "ok" || log.entries.size() < 2) {
      for (CorrectionModel m : o.models) {
        DriftRow row = base;
        row.model = toString(m);
        result.rows.push_back(row);
      }
    } else {
      for (CorrectionModel m : o.models) {
        CorrectionConfig config;
        config.model = m;
        // The robot knows its own odometry's random errors (its robot file's preset).
        config.odometry.linear_per_sqrt_m = std::max(odometry_model.linear_noise, 0.002);
        config.odometry.heading_per_sqrt_m = std::max(odometry_model.heading_noise, 0.0005);
        config.odometry.angular_per_sqrt_rad = std::max(odometry_model.angular_noise, 0.001);
        const auto t0 = Clock::now();
        const CorrectionResult c = correctTraverse(log, ret->observation, config);
        DriftRow row = base;
        row.correct_ms = ms(t0, Clock::now());
        if (!c.ok) {
          row.status = "correction failed: " + c.message;
          row.model = toString(m);
          result.rows.push_back(row);
          continue;
        }
        row.bias = c.bias;
        row.iterations = c.iterations;
        evaluate(toString(m), c.poses, row);
      }
      evaluate(kTruthModel, truth, base);
    }
    if (!o.out_dir.empty() && !panels.empty()) {
      cv::Mat strip;
      cv::hconcat(panels, strip);
      std::vector<uchar> png;
      cv::imencode(".png", strip, png);
      writeFileAtomic(seed_dir + "/maps.png", std::string(png.begin(), png.end()));
    }
    if (o.progress) {
      std::fprintf(stderr, "seed %llu: path %.1f m, odometry error %.2f m %.1f deg, %s",
                   static_cast<unsigned long long>(seed), base.path_length_m, base.odometry_error_m,
                   base.odometry_error_deg, base.status.c_str());
      for (const DriftRow& row : result.rows)
        if (row.seed == seed && row.status == "ok")
          std::fprintf(stderr, "; %s ATE %.3f m", row.model.c_str(), row.ate_rmse_m);
      std::fprintf(stderr, "\n");
    }
  }
  result.markdown = markdown(o, result.rows);
  if (!o.out_dir.empty()) {
    writeFileAtomic(o.out_dir + "/drift.csv", formatDriftCsv(result.rows));
    writeFileAtomic(o.out_dir + "/drift.md", result.markdown);
  }
  return result;
}

}  // namespace coopmap

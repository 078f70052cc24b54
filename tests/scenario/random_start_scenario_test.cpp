// Scenario: robots placed anywhere the home base is in view find where they stand from
// their first look at it (nothing else tells them), and the two-robot mission from such
// starts maps the lab as well as from the starts the world file gives.
//
// The starts, fixed by this rule before any result: run k (k = 1..20) draws both robots'
// starts from std::mt19937_64 seeded with k: distance from the home base's middle uniform in
// [1, 2.5] m, bearing from the home base's axis uniform in [-30, 30] degrees, heading uniform
// in [-25, 25] degrees from facing the home base's middle; eric is drawn again (up to 100
// times) while within 1 m of jose. The run's own seed is k.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "sim/runner/world_run.h"
#include "sim/world/ground_truth.h"
#include "sim/world/world.h"
#include "tests/support/test_world.h"

namespace coopmap {
namespace {

constexpr int kRuns = 20;

struct Start {
  double x = 0.0, y = 0.0, heading = 0.0;  // world frame, m and rad
};

// A start `distance` from the home base's middle at `bearing` from its axis, turned
// `heading` from facing the middle; the home base in `world` (its corners face the robots).
Start startAt(const sim::World& world, double distance, double bearing, double heading) {
  const auto& c = world.home_base.corners;
  const Eigen::Vector2d mid = 0.5 * (c[0].position + c[1].position);
  const double axis = c[0].heading + bearing;  // from the middle towards the robots
  const Eigen::Vector2d at = mid + distance * Eigen::Vector2d(std::cos(axis), std::sin(axis));
  const double facing = std::atan2(mid.y() - at.y(), mid.x() - at.x());
  return {at.x(), at.y(), facing + heading};
}

// The lab with its two robots at the starts of run k (see the rule above).
test_support::TestWorldFile labWithStarts(int k, Start* jose, Start* eric) {
  const std::string lab_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml";
  const sim::World world = sim::loadWorld(lab_file);
  std::mt19937_64 rng(static_cast<uint64_t>(k));
  std::uniform_real_distribution<double> distance(1.0, 2.5), angle(-1.0, 1.0);
  constexpr double kDeg = M_PI / 180.0;
  auto draw = [&] {
    return startAt(world, distance(rng), 30 * kDeg * angle(rng), 25 * kDeg * angle(rng));
  };
  *jose = draw();
  *eric = draw();
  for (int tries = 0; tries < 100 && std::hypot(eric->x - jose->x, eric->y - jose->y) < 1.0;
       ++tries)
    *eric = draw();
  std::ifstream in(lab_file);
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  yaml = yaml.substr(0, yaml.find("\nrobots:"));
  auto robot = [](const char* name, const Start& s) {
    char b[300];
    std::snprintf(b, sizeof b,
                  "  - name: %s\n    model: %s/robots/b14/b14.yaml\n    start: {position: [%.4f, "
                  "%.4f], heading_deg: %.3f}\n",
                  name, COOPMAP_SOURCE_DIR, s.x, s.y, s.heading / kDeg);
    return std::string(b);
  };
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("coopmap_test_random_start_" + std::to_string(::getpid()) + ".yaml"))
                               .string();
  std::ofstream(path) << yaml << "\nrobots:\n" << robot("jose", *jose) << robot("eric", *eric);
  return test_support::TestWorldFile(path);
}

TEST(RandomStartScenarioTest, RobotsFindTheirStartsAndMapTheLabFromThem) {
  int starts = 0, good_starts = 0, good_maps = 0;
  for (int k = 1; k <= kRuns; ++k) {
    Start jose, eric;
    const test_support::TestWorldFile world = labWithStarts(k, &jose, &eric);
    RunOptions o;
    o.world_file = world.path();
    o.seed = static_cast<uint64_t>(k);
    o.explore = true;
    o.duration = 900.0;
    const RunResult r = runWorld(o);
    ASSERT_EQ(r.robots.size(), 2u);
    int contacts = 0;
    std::string line;
    for (const RobotRunResult& robot : r.robots) {
      contacts += robot.collisions;
      ++starts;
      char b[200];
      if (robot.start_fix_error) {
        const FixError& e = *robot.start_fix_error;
        good_starts += e.error_m <= 0.03 && e.error_deg <= 0.75;
        std::snprintf(b, sizeof b, " %s start %.1f cm %.2f deg", robot.name.c_str(),
                      100.0 * e.error_m, e.error_deg);
      } else {
        std::snprintf(b, sizeof b, " %s not placed (%s)", robot.name.c_str(),
                      robot.log.empty() ? "" : robot.log.back().c_str());
      }
      line += b;
    }
    const MapMetrics& m = r.shared_map.protocol;
    const bool good = r.shared_map.computed && m.wall_recall >= 0.95 &&
                      m.false_occupied_rate <= 0.01 && m.coverage >= 0.90 && contacts == 0;
    good_maps += good;
    if (!good)  // how the robots' missions went, for whoever reads the failure
      for (const RobotRunResult& robot : r.robots)
        for (const std::string& l : robot.log)
          std::printf("  %s %s\n", robot.name.c_str(), l.substr(0, 160).c_str());
    std::printf(
        "run %2d: jose (%.2f, %.2f, %.0f deg) eric (%.2f, %.2f, %.0f deg):%s; shared "
        "wall_recall %.3f FOR %.4f coverage %.3f, %d contacts%s\n",
        k, jose.x, jose.y, jose.heading * 180 / M_PI, eric.x, eric.y, eric.heading * 180 / M_PI,
        line.c_str(), m.wall_recall, m.false_occupied_rate, m.coverage, contacts,
        good ? "" : "  <- short of the bars");
  }
  std::printf("starts within 3 cm and 0.75 deg: %d of %d; runs meeting the map bars: %d of %d\n",
              good_starts, starts, good_maps, kRuns);
  EXPECT_GE(good_starts, (9 * starts + 9) / 10);
  EXPECT_GE(good_maps, (9 * kRuns + 9) / 10);
}

}  // namespace
}  // namespace coopmap

// The exploration benchmark's own code that runs no world: its options, reading a run's
// metrics.json, the CSV and the summary's statistics.
#include "sim/runner/explore_bench.h"

#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/yaml_reader.h"

namespace coopmap {
namespace {

// A metrics.json as `coopmap run` writes it, cut to the keys the benchmark reads and a few
// it does not.
const char* kCooperativeMetrics = R"({
  "world": "office",
  "shared_map": {
    "wall_recall": 0.962,
    "false_occupied_rate": 0.0041,
    "coverage": 0.931,
    "false_occupied_by_distance": {"2": 0.003, "3": 0.001}
  },
  "seed": 3,
  "collisions": 2,
  "exploration_complete": true,
  "cooperative": true,
  "time_to_50_percent_coverage_s": 410,
  "time_to_75_percent_coverage_s": 800,
  "time_to_90_percent_coverage_s": -1,
  "robots": {
    "jose": {
      "phase": "done",
      "mission": {"last_event": "home: \"nothing left\", done"},
      "phases": {
        "look at home": {"time_s": 30, "driving_s": 0, "turning_s": 28, "path_m": 0.1},
        "explore": {"time_s": 100, "driving_s": 60, "turning_s": 30, "path_m": 18}
      },
      "contacts": [{"t": 12.5, "with": "person"}],
      "map": {"wall_recall": 0.5, "false_occupied_rate": 0.2, "coverage": 0.4}
    },
    "eric": {
      "phase": "returning",
      "mission": {"last_event": "budget spent"},
      "phases": {
        "explore": {"time_s": 120, "driving_s": 70, "turning_s": 40, "path_m": 20}
      },
      "contacts": [],
      "map": {"wall_recall": 0.6, "false_occupied_rate": 0.1, "coverage": 0.3}
    }
  }
}
)";

TEST(ExploreBenchTest, ReadsTheSharedMapOfACooperativeRun) {
  ExploreRow row;
  readExploreMetrics(kCooperativeMetrics, "runs/3/metrics.json", row);
  EXPECT_DOUBLE_EQ(row.coverage, 0.931);
  EXPECT_DOUBLE_EQ(row.wall_recall, 0.962);
  EXPECT_DOUBLE_EQ(row.false_occupied_rate, 0.0041);
  EXPECT_DOUBLE_EQ(row.time_to_50_s, 410.0);
  EXPECT_DOUBLE_EQ(row.time_to_90_s, -1.0);
  EXPECT_EQ(row.contacts, 2);
  EXPECT_TRUE(row.exploration_complete);
  EXPECT_EQ(row.map_picture, "shared_map_evaluation.png");
  ASSERT_EQ(row.endings.size(), 2u);
  EXPECT_EQ(row.endings[0].robot, "jose");
  EXPECT_EQ(row.endings[0].phase, "done");
  EXPECT_EQ(row.endings[0].reason, "home: \"nothing left\", done");
  EXPECT_EQ(row.endings[1].robot, "eric");
  EXPECT_EQ(row.endings[1].phase, "returning");
  // Both robots' phase times, summed by phase in the order first met.
  ASSERT_EQ(row.phases.size(), 2u);
  EXPECT_EQ(row.phases[0].phase, "look at home");
  EXPECT_DOUBLE_EQ(row.phases[0].turning_s, 28.0);
  EXPECT_EQ(row.phases[1].phase, "explore");
  EXPECT_DOUBLE_EQ(row.phases[1].time_s, 220.0);
  EXPECT_DOUBLE_EQ(row.phases[1].driving_s, 130.0);
  EXPECT_DOUBLE_EQ(row.phases[1].turning_s, 70.0);
  EXPECT_DOUBLE_EQ(row.phases[1].path_m, 38.0);
}

TEST(ExploreBenchTest, SaysWhereTheRobotsTimeWent) {
  ExploreBenchOptions o;
  o.out_dir = "out";
  ExploreRow a, b;
  a.seed = 1;
  b.seed = 2;
  a.phases = {{"explore", 300.0, 200.0, 90.0, 60.0}, {"return", 100.0, 80.0, 20.0, 24.0}};
  b.phases = {{"explore", 100.0, 50.0, 40.0, 15.0}};
  const std::string md = formatExploreMarkdown(o, {a, b});
  // 500 s of robot time: explore 400 s (250 driving, 130 turning, 20 standing).
  EXPECT_NE(md.find("| explore | 80.0 % | 50.0 % | 26.0 % | 4.0 % | 75 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| return | 20.0 % | 16.0 % | 4.0 % | 0.0 % | 24 |"), std::string::npos) << md;
}

TEST(ExploreBenchTest, ReadsTheRobotsOwnMapWithoutASharedOne) {
  std::string text = kCooperativeMetrics;
  text.replace(text.find("\"cooperative\": true"), 19, "\"cooperative\": false");
  ExploreRow row;
  readExploreMetrics(text, "m.json", row);
  EXPECT_DOUBLE_EQ(row.coverage, 0.4);
  EXPECT_DOUBLE_EQ(row.wall_recall, 0.5);
  EXPECT_EQ(row.map_picture, "map_jose_evaluation.png");
}

TEST(ExploreBenchTest, NamesAMissingKey) {
  std::string text = kCooperativeMetrics;
  text.replace(text.find("\"collisions\""), 12, "\"bumps\"");
  ExploreRow row;
  try {
    readExploreMetrics(text, "runs/3/metrics.json", row);
    FAIL() << "a metrics.json without collisions was read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("runs/3/metrics.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'collisions'"), std::string::npos) << e.what();
  }
}

TEST(ExploreBenchTest, QuartilesInterpolateBetweenOrderStatistics) {
  const Quartiles q = quartiles({4.0, 1.0, 3.0, 2.0});
  EXPECT_DOUBLE_EQ(q.q1, 1.75);
  EXPECT_DOUBLE_EQ(q.median, 2.5);
  EXPECT_DOUBLE_EQ(q.q3, 3.25);
  const Quartiles odd = quartiles({0.9, 0.1, 0.5, 0.7, 0.3});
  EXPECT_DOUBLE_EQ(odd.q1, 0.3);
  EXPECT_DOUBLE_EQ(odd.median, 0.5);
  EXPECT_DOUBLE_EQ(odd.q3, 0.7);
  const Quartiles one = quartiles({0.42});
  EXPECT_DOUBLE_EQ(one.q1, 0.42);
  EXPECT_DOUBLE_EQ(one.q3, 0.42);
  const Quartiles none = quartiles({});
  EXPECT_DOUBLE_EQ(none.median, 0.0);
}

ExploreRow row(uint64_t seed, double coverage, double recall, double false_occupied, int contacts) {
  ExploreRow r;
  r.seed = seed;
  r.family = "loop";
  r.robots = 1;
  r.coverage = coverage;
  r.wall_recall = recall;
  r.false_occupied_rate = false_occupied;
  r.contacts = contacts;
  r.endings = {{"jose", "done", "came home"}};
  r.map_picture = "shared_map_evaluation.png";
  return r;
}

TEST(ExploreBenchTest, CsvQuotesReasonsAndLeavesAFailedRunsScoresEmpty) {
  ExploreRow ok = row(4, 0.95, 0.97, 0.002, 0);
  ok.endings[0].reason = "said \"stop\", then stopped";
  ok.run_seed = 4;
  ExploreRow failed = row(5, 0.0, 0.0, 0.0, 0);
  failed.run_seed = 105;  // run with --run-seed-offset 100
  failed.failed = true;
  failed.endings = {{"jose", "failed", "coopmap: error: disk full"}};
  const std::string csv = formatExploreCsv({ok, failed});
  EXPECT_EQ(csv,
            "seed,run_seed,family,floor_area_m2,robots,coverage,time_to_50_s,time_to_90_s,"
            "wall_recall,false_occupied_rate,contacts,robot1,ending1,reason1,exploration_"
            "complete,wall_time_s\n"
            "4,4,loop,0.0,1,0.9500,-1,-1,0.9700,0.00200,0,jose,done,\"said \"\"stop\"\", "
            "then stopped\",false,0.0\n"
            "5,105,loop,0.0,1,,,,,,,jose,failed,\"coopmap: error: disk full\",false,0.0\n");
}

TEST(ExploreBenchTest, SummaryCountsTargetsAndListsTheWorstFirst) {
  ExploreBenchOptions o;
  o.first_seed = 1;
  o.count = 7;
  o.robots = 1;
  std::vector<ExploreRow> rows = {
      row(1, 0.95, 0.96, 0.005, 0),  // meets all four
      row(2, 0.81, 0.96, 0.005, 0),  // coverage short
      row(3, 0.95, 0.90, 0.005, 0),  // wall recall short
      row(4, 0.95, 0.96, 0.020, 0),  // false-occupied high
      row(5, 0.95, 0.96, 0.005, 1),  // a contact
      row(6, 0.10, 0.50, 0.050, 3),  // worst
      row(7, 0.0, 0.0, 0.0, 0),      // failed
  };
  rows[6].failed = true;
  rows[6].endings = {{"jose", "failed", "killed by signal 6"}};
  // Ended "exploration complete": with 19 % of the floor unseen (too early), with 5 % (not).
  rows[1].endings = {{"jose", "done", "exploration complete: 2 frontiers, none reachable"}};
  rows[0].endings = {{"jose", "done", "exploration complete: no frontier left"}};
  const std::string md = formatExploreMarkdown(o, rows);
  EXPECT_NE(md.find("6 runs finished, 1 failed"), std::string::npos) << md;
  EXPECT_NE(md.find("| coverage >= 0.90 | 4 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| wall_recall >= 0.95 | 4 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| false_occupied_rate <= 0.01 | 4 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| no contact | 4 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| all four | 1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| no robot ends \"exploration complete\" with more than 5 % of the floor "
                    "unseen | 5 |"),
            std::string::npos)
      << md;
  // Coverage 0.10, 0.81, 0.95 x4: quartiles over the six that ran.
  EXPECT_NE(md.find("| coverage | 0.845 | 0.950 | 0.950 |"), std::string::npos) << md;
  // Five worst: 6, 2, then the first three of the ties in seed order; not seed 5 nor the
  // failed one.
  const size_t s6 = md.find("| 6 | loop"), s2 = md.find("| 2 | loop"), s4 = md.find("| 4 | loop");
  ASSERT_NE(s6, std::string::npos) << md;
  EXPECT_LT(s6, s2);
  EXPECT_LT(s2, s4);
  EXPECT_EQ(md.find("| 5 | loop"), std::string::npos) << md;
  EXPECT_NE(md.find("[map](runs/6/shared_map_evaluation.png), [events](runs/6.events)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- seed 7: killed by signal 6 ([log](runs/7.log))"), std::string::npos) << md;
}

TEST(ExploreBenchTest, ValidateNamesTheBadOption) {
  auto message = [](auto change) {
    ExploreBenchOptions o;
    o.out_dir = "out";
    change(o);
    try {
      o.validate();
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message([](ExploreBenchOptions&) {}), "accepted");
  EXPECT_EQ(message([](ExploreBenchOptions& o) { o.robots = 3; }),
            "--robots: expected 1 or 2, got 3");
  EXPECT_EQ(message([](ExploreBenchOptions& o) { o.count = 0; }),
            "--count: expected at least 1, got 0");
  EXPECT_EQ(message([](ExploreBenchOptions& o) { o.duration = 0.0; }),
            "--duration: expected a positive number of seconds, got 0");
  EXPECT_EQ(message([](ExploreBenchOptions& o) { o.jobs = 0; }),
            "--jobs: expected at least 1, got 0");
  EXPECT_EQ(message([](ExploreBenchOptions& o) { o.out_dir.clear(); }),
            "--out: expected an output folder, none given");
  EXPECT_EQ(message([](ExploreBenchOptions& o) {
              o.first_seed = 10;
              o.count = 5;
              o.run_seed_offset = std::numeric_limits<uint64_t>::max() - 13;
            }),
            "--run-seed-offset: 18446744073709551602 added to seeds up to 14 would pass "
            "18446744073709551615");
}

}  // namespace
}  // namespace coopmap

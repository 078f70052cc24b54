#include "sim/runner/explore_bench.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include "core/io/atomic_file.h"
#include "core/io/yaml_reader.h"
#include "sim/world/world_generator.h"

extern char** environ;

namespace coopmap {

namespace {

// The targets explore.md counts worlds against.
constexpr double kCoverageTarget = 0.90;
constexpr double kWallRecallTarget = 0.95;
constexpr double kFalseOccupiedTarget = 0.01;
constexpr int kWorstShown = 5;
// A robot that ends "exploration complete" with more of the reachable floor unseen than this
// share ended too early.
constexpr double kUnseenAtCompletion = 0.05;

std::string number(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

std::string csvQuote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return q + '"';
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The last non-blank line of a file ("" if none or unreadable), leaving out the command
// line's hint after an option error (the error is the line before it).
std::string lastLine(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line, last;
  while (std::getline(in, line)) {
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    const size_t cr = line.find_last_of('\r');  // a progress bar's last redraw
    if (cr != std::string::npos) line = line.substr(cr + 1);
    if (!line.empty() && line != "Run with --help for more information.") last = line;
  }
  return last;
}

// Runs `argv` (argv[0] the program) with stdin on /dev/null, stdout into `out` and stderr
// into `log`; returns "" when it exits 0, else what went wrong.
std::string runChild(const std::vector<std::string>& args, const std::string& out,
                     const std::string& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int error = posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (error != 0) return "cannot start " + args[0] + ": " + std::strerror(error);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return std::string("waitpid: ") + std::strerror(errno);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  const std::string how = WIFEXITED(status)
                              ? "exit status " + std::to_string(WEXITSTATUS(status))
                              : "killed by signal " + std::to_string(WTERMSIG(status));
  const std::string last = lastLine(log);
  return last.empty() ? how : last;
}

std::string seconds(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// One world: generated, run in a child, scored from its metrics.json.
ExploreRow runOne(const ExploreBenchOptions& o, uint64_t seed, std::mutex& generate_mutex) {
  ExploreRow row;
  row.seed = seed;
  row.run_seed = seed + o.run_seed_offset;
  row.robots = o.robots;
  const std::string name = std::to_string(seed);
  const std::string world_file = o.out_dir + "/worlds/world_" + name + ".yaml";
  const std::string run_dir = o.out_dir + "/runs/" + name;
  const std::string log = o.out_dir + "/runs/" + name + ".log";
  const std::string events = o.out_dir + "/runs/" + name + ".events";
  std::vector<std::string> robot_names;
  auto fail = [&](const std::string& reason) {
    row.failed = true;
    row.endings.clear();
    for (int i = 0; i < o.robots; ++i)
      row.endings.push_back(
          {i < static_cast<int>(robot_names.size()) ? robot_names[i] : "", "failed", reason});
    return row;
  };
  try {
    std::lock_guard<std::mutex> lock(generate_mutex);
    sim::WorldGeneratorOptions gen;
    gen.seed = seed;
    gen.out_file = world_file;
    const sim::GeneratedWorld world = sim::generateWorld(gen);
    row.family = world.family;
    row.floor_area_m2 = world.floor_area;
    writeFileAtomic(world_file, world.yaml);
    const YamlField robots = YamlField::loadString(world.yaml, world_file)["robots"];
    for (const YamlField& r : robots.elements()) robot_names.push_back(r["name"].asString());
  } catch (const std::exception& e) {
    std::ofstream(log) << "world generation: " << e.what() << "\n";
    return fail(std::string("world generation: ") + e.what());
  }
  const std::string run_seed = std::to_string(row.run_seed);
  std::vector<std::string> args = {
      o.program,           "run",       world_file, "--seed", run_seed, "--duration",
      seconds(o.duration), "--explore", "--events", "--out",  run_dir};
  if (o.robots == 1) args.insert(args.end(), {"--robots", "1"});
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const std::string error = runChild(args, events, log);
  row.wall_time_s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!error.empty()) return fail(error);
  const std::string metrics = run_dir + "/metrics.json";
  try {
    readExploreMetrics(readText(metrics), metrics, row);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return row;
}

}  // namespace

int processorCount() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

void ExploreBenchOptions::validate() const {
  if (count < 1) throw ConfigError("--count: expected at least 1, got " + std::to_string(count));
  if (static_cast<uint64_t>(count - 1) > std::numeric_limits<uint64_t>::max() - first_seed)
    throw ConfigError("--count: seeds from --first-seed " + std::to_string(first_seed) +
                      " would pass 18446744073709551615");
  const uint64_t last_seed = first_seed + static_cast<uint64_t>(count - 1);
  if (last_seed > std::numeric_limits<uint64_t>::max() - run_seed_offset)
    throw ConfigError("--run-seed-offset: " + std::to_string(run_seed_offset) +
                      " added to seeds up to " + std::to_string(last_seed) +
                      " would pass 18446744073709551615");
  if (robots != 1 && robots != 2)
    throw ConfigError("--robots: expected 1 or 2, got " + std::to_string(robots));
  if (!std::isfinite(duration) || duration <= 0.0)
    throw ConfigError("--duration: expected a positive number of seconds, got " +
                      seconds(duration));
  if (jobs < 1) throw ConfigError("--jobs: expected at least 1, got " + std::to_string(jobs));
  if (out_dir.empty()) throw ConfigError("--out: expected an output folder, none given");
}

void readExploreMetrics(const std::string& text, const std::string& file, ExploreRow& row) {
  const YamlField root = YamlField::loadString(text, file);
  const YamlField robots = root["robots"];
  const std::vector<std::string> names = robots.keys();
  if (names.empty()) robots.fail("at least one robot");
  const std::optional<YamlField> shared = root.get("shared_map");
  const bool cooperative = root["cooperative"].asBool() && shared;
  const YamlField scored = cooperative ? *shared : robots[names.front()]["map"];
  row.coverage = scored["coverage"].asDouble();
  row.wall_recall = scored["wall_recall"].asDouble();
  row.false_occupied_rate = scored["false_occupied_rate"].asDouble();
  row.map_picture =
      cooperative ? "shared_map_evaluation.png" : "map_" + names.front() + "_evaluation.png";
  row.time_to_50_s = root["time_to_50_percent_coverage_s"].asDouble();
  row.time_to_90_s = root["time_to_90_percent_coverage_s"].asDouble();
  row.contacts = root["collisions"].asInt(0, std::numeric_limits<int>::max());
  const std::optional<YamlField> complete = root.get("exploration_complete");
  row.exploration_complete = complete && complete->asBool();
  row.endings.clear();
  for (const std::string& name : names) {
    const YamlField robot = robots[name];
    ExploreEnding e{name, robot["phase"].asString(), ""};
    if (const auto mission = robot.get("mission"))
      if (const auto event = mission->get("last_event")) e.reason = event->asString();
    row.endings.push_back(e);
    if (const auto phases = robot.get("phases"))
      for (const std::string& phase : phases->keys()) {
        const YamlField p = (*phases)[phase];
        phaseNamed(row.phases, phase) += {phase, p["time_s"].asDouble(0.0, 1e12, "seconds"),
                                          p["driving_s"].asDouble(0.0, 1e12, "seconds"),
                                          p["turning_s"].asDouble(0.0, 1e12, "seconds"),
                                          p["path_m"].asDouble(0.0, 1e12, "metres")};
      }
  }
}

Quartiles quartiles(std::vector<double> v) {
  Quartiles q;
  if (v.empty()) return q;
  std::sort(v.begin(), v.end());
  auto at = [&](double p) {
    const double x = p * (v.size() - 1);
    const size_t i = static_cast<size_t>(std::floor(x));
    const size_t j = std::min(i + 1, v.size() - 1);
    return v[i] + (x - i) * (v[j] - v[i]);
  };
  q.q1 = at(0.25);
  q.median = at(0.5);
  q.q3 = at(0.75);
  return q;
}

std::string formatExploreCsv(const std::vector<ExploreRow>& rows) {
  int max_robots = 0;
  for (const ExploreRow& r : rows)
    max_robots = std::max({max_robots, r.robots, static_cast<int>(r.endings.size())});
  std::ostringstream csv;
  csv << "seed,run_seed,family,floor_area_m2,robots,coverage,time_to_50_s,time_to_90_s,"
         "wall_recall,false_occupied_rate,contacts";
  for (int i = 1; i <= max_robots; ++i) csv << ",robot" << i << ",ending" << i << ",reason" << i;
  csv << ",exploration_complete,wall_time_s\n";
  for (const ExploreRow& r : rows) {
    csv << r.seed << "," << r.run_seed << "," << r.family << "," << number(r.floor_area_m2, 1)
        << "," << r.robots;
    if (r.failed)  // no scores
      csv << ",,,,,,";
    else
      csv << "," << number(r.coverage, 4) << "," << number(r.time_to_50_s, 0) << ","
          << number(r.time_to_90_s, 0) << "," << number(r.wall_recall, 4) << ","
          << number(r.false_occupied_rate, 5) << "," << r.contacts;
    for (int i = 0; i < max_robots; ++i) {
      const ExploreEnding e =
          i < static_cast<int>(r.endings.size()) ? r.endings[i] : ExploreEnding{};
      csv << "," << e.robot << "," << e.phase << "," << csvQuote(e.reason);
    }
    csv << "," << (r.exploration_complete ? "true" : "false") << "," << number(r.wall_time_s, 1)
        << "\n";
  }
  return csv.str();
}

std::string formatExploreMarkdown(const ExploreBenchOptions& o,
                                  const std::vector<ExploreRow>& rows) {
  std::vector<const ExploreRow*> ran;
  std::vector<double> coverage, recall, false_occupied;
  int failed = 0, meet_coverage = 0, meet_recall = 0, meet_false = 0, meet_contacts = 0,
      meet_all = 0, meet_completion = 0;
  for (const ExploreRow& r : rows) {
    if (r.failed) {
      ++failed;
      continue;
    }
    ran.push_back(&r);
    coverage.push_back(r.coverage);
    recall.push_back(r.wall_recall);
    false_occupied.push_back(r.false_occupied_rate);
    const bool c = r.coverage >= kCoverageTarget, w = r.wall_recall >= kWallRecallTarget,
               f = r.false_occupied_rate <= kFalseOccupiedTarget, k = r.contacts == 0;
    meet_coverage += c;
    meet_recall += w;
    meet_false += f;
    meet_contacts += k;
    meet_all += c && w && f && k;
    const bool early = std::any_of(r.endings.begin(), r.endings.end(), [&](const ExploreEnding& e) {
      return e.reason.find("exploration complete") != std::string::npos &&
             r.coverage < 1.0 - kUnseenAtCompletion;
    });
    meet_completion += !early;
  }
  const int n = static_cast<int>(ran.size());
  std::ostringstream md;
  md << "# Exploration benchmark\n\n"
     << rows.size() << " generated worlds, seeds " << o.first_seed << "-"
     << o.first_seed + static_cast<uint64_t>(o.count) - 1 << "; " << o.robots
     << (o.robots == 1 ? " robot" : " robots") << " exploring for at most " << number(o.duration, 0)
     << " s on the default settings"
     << (o.run_seed_offset ? ", each run's seed the world's + " + std::to_string(o.run_seed_offset)
                           : std::string())
     << ". " << n << " runs finished, " << failed
     << " failed. Scores of the shared map when the robots shared one, else of the "
     << "robot's own map.\n\n"
     << "| | first quartile | median | third quartile |\n|---|---|---|---|\n";
  auto line = [&](const char* name, const std::vector<double>& v, int digits) {
    const Quartiles q = quartiles(v);
    md << "| " << name << " | " << number(q.q1, digits) << " | " << number(q.median, digits)
       << " | " << number(q.q3, digits) << " |\n";
  };
  line("coverage", coverage, 3);
  line("wall_recall", recall, 3);
  line("false_occupied_rate", false_occupied, 4);
  md << "\n| target | worlds meeting it (of " << n << ") |\n|---|---|\n"
     << "| coverage >= " << number(kCoverageTarget, 2) << " | " << meet_coverage << " |\n"
     << "| wall_recall >= " << number(kWallRecallTarget, 2) << " | " << meet_recall << " |\n"
     << "| false_occupied_rate <= " << number(kFalseOccupiedTarget, 2) << " | " << meet_false
     << " |\n"
     << "| no contact | " << meet_contacts << " |\n"
     << "| all four | " << meet_all << " |\n"
     << "| no robot ends \"exploration complete\" with more than "
     << number(100.0 * kUnseenAtCompletion, 0) << " % of the floor unseen | " << meet_completion
     << " |\n";

  // Where the robots' time went, over every run that finished.
  std::vector<PhaseTime> phases;
  double robot_time = 0.0;
  for (const ExploreRow* r : ran)
    for (const PhaseTime& p : r->phases) {
      phaseNamed(phases, p.phase) += p;
      robot_time += p.time_s;
    }
  if (robot_time > 0.0) {
    auto share = [&](double s) { return number(100.0 * s / robot_time, 1) + " %"; };
    md << "\n## Where the robots' time went\n\n"
       << "Shares of all robots' time in all runs; driving and turning in place from the "
          "robots' true motion.\n\n"
       << "| phase | time | driving | turning in place | standing | path (m) |\n"
          "|---|---|---|---|---|---|\n";
    for (const PhaseTime& p : phases)
      md << "| " << p.phase << " | " << share(p.time_s) << " | " << share(p.driving_s) << " | "
         << share(p.turning_s) << " | " << share(p.time_s - p.driving_s - p.turning_s) << " | "
         << number(p.path_m, 0) << " |\n";
  }

  std::vector<const ExploreRow*> worst = ran;
  std::stable_sort(worst.begin(), worst.end(), [](const ExploreRow* a, const ExploreRow* b) {
    return a->coverage < b->coverage;
  });
  if (static_cast<int>(worst.size()) > kWorstShown) worst.resize(kWorstShown);
  md << "\n## Least coverage\n\n"
     << "| seed | family | floor (m^2) | coverage | 50 % at (s) | 90 % at (s) | wall_recall | "
        "false_occupied_rate | contacts | endings | complete | map |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto endings = [](const ExploreRow& r) {
    std::string s;
    for (const ExploreEnding& e : r.endings) {
      std::string reason = e.reason;
      std::replace(reason.begin(), reason.end(), '|', '/');
      s += (s.empty() ? "" : "; ") + e.robot + ": " + e.phase +
           (reason.empty() ? "" : " (" + reason + ")");
    }
    return s;
  };
  for (const ExploreRow* r : worst) {
    const std::string seed = std::to_string(r->seed);
    md << "| " << seed << " | " << r->family << " | " << number(r->floor_area_m2, 1) << " | "
       << number(r->coverage, 3) << " | " << number(r->time_to_50_s, 0) << " | "
       << number(r->time_to_90_s, 0) << " | " << number(r->wall_recall, 3) << " | "
       << number(r->false_occupied_rate, 4) << " | " << r->contacts << " | " << endings(*r) << " | "
       << (r->exploration_complete ? "yes" : "no") << " | [map](runs/" << seed << "/"
       << r->map_picture << "), [events](runs/" << seed << ".events) |\n";
  }
  if (failed > 0) {
    md << "\n## Failed runs\n\n";
    for (const ExploreRow& r : rows)
      if (r.failed)
        md << "- seed " << r.seed << ": "
           << (r.endings.empty() ? std::string("failed") : r.endings.front().reason)
           << " ([log](runs/" << r.seed << ".log))\n";
  }
  md << "\nEvery world's row: explore.csv; the world files: worlds/; each run's folder: "
        "runs/<seed>/. One world again: `coopmap run worlds/world_<seed>.yaml --seed <seed>"
     << (o.run_seed_offset ? " + " + std::to_string(o.run_seed_offset) : std::string())
     << " --duration " << seconds(o.duration) << " --explore"
     << (o.robots == 1 ? " --robots 1" : "") << " --out DIR`.\n";
  return md.str();
}

ExploreBenchResult runExploreBench(const ExploreBenchOptions& o) {
  o.validate();
  try {
    std::filesystem::create_directories(o.out_dir + "/worlds");
    std::filesystem::create_directories(o.out_dir + "/runs");
    const std::string probe = o.out_dir + "/.explore_bench_probe";
    writeFileAtomic(probe, "");
    std::filesystem::remove(probe);
  } catch (const std::exception& e) {
    throw ConfigError("--out: expected a writable folder: " + std::string(e.what()));
  }

  ExploreBenchResult result;
  std::mutex generate_mutex, rows_mutex;
  std::atomic<int> next{0};
  std::exception_ptr error;  // the first output that could not be written
  auto worker = [&] {
    for (int k = next++; k < o.count; k = next++) {
      try {
        ExploreRow row = runOne(o, o.first_seed + static_cast<uint64_t>(k), generate_mutex);
        std::lock_guard<std::mutex> lock(rows_mutex);
        if (o.progress) {
          if (row.failed)
            std::fprintf(stderr, "seed %llu (%s): failed, %.1f s wall: %s\n",
                         static_cast<unsigned long long>(row.seed), row.family.c_str(),
                         row.wall_time_s, row.endings.empty() ? "" : row.endings[0].reason.c_str());
          else
            std::fprintf(stderr, "seed %llu (%s): coverage %.3f, %.1f s wall\n",
                         static_cast<unsigned long long>(row.seed), row.family.c_str(),
                         row.coverage, row.wall_time_s);
        }
        const auto at =
            std::lower_bound(result.rows.begin(), result.rows.end(), row.seed,
                             [](const ExploreRow& r, uint64_t seed) { return r.seed < seed; });
        result.rows.insert(at, std::move(row));
        // The rows so far, so that an interrupted benchmark keeps what it finished.
        writeFileAtomic(o.out_dir + "/explore.csv", formatExploreCsv(result.rows));
      } catch (...) {
        std::lock_guard<std::mutex> lock(rows_mutex);
        if (!error) error = std::current_exception();
        next = o.count;
      }
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < std::min(o.jobs, o.count); ++j) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
  result.markdown = formatExploreMarkdown(o, result.rows);
  writeFileAtomic(o.out_dir + "/explore.md", result.markdown);
  return result;
}

}  // namespace coopmap

#include "sim/runner/team_speedup.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/io/yaml_reader.h"
#include "sim/runner/explore_bench.h"

namespace coopmap {

namespace {

namespace fs = std::filesystem;

struct TeamRun {
  std::string world;
  double time_to_90_s = -1.0;
};

// Seed -> the run's metrics.json path, for every runs/<seed>/ of a benchmark output.
std::map<uint64_t, fs::path> runsOf(const std::string& dir) {
  const fs::path runs = fs::path(dir) / "runs";
  std::error_code ec;
  if (!fs::is_directory(runs, ec))
    throw ConfigError(dir + ": expected the output of `coopmap bench explore` (a runs/ folder)");
  std::map<uint64_t, fs::path> found;
  for (const fs::directory_entry& e : fs::directory_iterator(runs)) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory() || name.empty() ||
        !std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    found[std::stoull(name)] = e.path() / "metrics.json";
  }
  return found;
}

std::optional<TeamRun> readRun(const fs::path& metrics, int robots) {
  std::ifstream in(metrics, std::ios::binary);
  if (!in) return std::nullopt;  // the run failed: no metrics
  std::stringstream text;
  text << in.rdbuf();
  ExploreRow row;
  readExploreMetrics(text.str(), metrics.string(), row);
  if (static_cast<int>(row.endings.size()) != robots)
    throw ConfigError(metrics.string() + ": expected a run of " + std::to_string(robots) +
                      (robots == 1 ? " robot" : " robots") + ", got " +
                      std::to_string(row.endings.size()));
  return TeamRun{YamlField::loadString(text.str(), metrics.string())["world"].asString(),
                 row.time_to_90_s};
}

std::string timeText(double s) {
  if (s < 0.0) return "never";
  char b[32];
  std::snprintf(b, sizeof b, "%.0f", s);
  return b;
}

}  // namespace

int TeamSpeedup::twoSooner() const {
  return static_cast<int>(std::count_if(worlds.begin(), worlds.end(),
                                        [](const TeamSpeedupWorld& w) { return w.twoSooner(); }));
}

std::optional<double> TeamSpeedup::medianSpeedup() const {
  std::vector<double> ratios;
  for (const TeamSpeedupWorld& w : worlds)
    if (w.two_s > 0.0 && w.one_s >= 0.0) ratios.push_back(w.one_s / w.two_s);
  if (ratios.empty()) return std::nullopt;
  return quartiles(ratios).median;
}

TeamSpeedup compareTeams(const std::string& two_dir, const std::string& one_dir) {
  const std::map<uint64_t, fs::path> two = runsOf(two_dir), one = runsOf(one_dir);
  TeamSpeedup out;
  for (const auto& [seed, metrics] : two) {
    const auto other = one.find(seed);
    const std::optional<TeamRun> a = readRun(metrics, 2);
    const std::optional<TeamRun> b = other == one.end() ? std::nullopt : readRun(other->second, 1);
    if (!a || !b) {
      out.unmatched.push_back(seed);
      continue;
    }
    if (a->world != b->world)
      throw ConfigError(other->second.string() + ": world '" + b->world + "', but " +
                        metrics.string() + " ran '" + a->world + "'");
    out.worlds.push_back({seed, a->world, a->time_to_90_s, b->time_to_90_s});
  }
  for (const auto& [seed, metrics] : one)
    if (!two.count(seed)) out.unmatched.push_back(seed);
  std::sort(out.unmatched.begin(), out.unmatched.end());
  return out;
}

std::string formatTeamSpeedup(const TeamSpeedup& c, const std::string& two_dir,
                              const std::string& one_dir) {
  std::ostringstream md;
  md << "# Two robots against one\n\n"
     << "Two robots: " << two_dir << "; one robot: " << one_dir << ".\n\n";
  const int n = static_cast<int>(c.worlds.size());
  char line[160];
  std::snprintf(line, sizeof line, "Two robots reached 90 %% coverage sooner in %d of %d worlds",
                c.twoSooner(), n);
  md << line;
  if (n > 0) {
    std::snprintf(line, sizeof line, " (%.0f %%)", 100.0 * c.twoSooner() / n);
    md << line;
  }
  md << ".";
  if (const std::optional<double> s = c.medianSpeedup()) {
    int both = 0;
    for (const TeamSpeedupWorld& w : c.worlds) both += w.two_s > 0.0 && w.one_s >= 0.0;
    std::snprintf(line, sizeof line,
                  " Median speed-up (one robot's time over two robots') %.2f, over the %d %s "
                  "where both reached it.",
                  *s, both, both == 1 ? "world" : "worlds");
    md << line;
  }
  md << "\n";
  if (!c.unmatched.empty()) {
    md << "\nNot compared (in one output only, or a run that failed):";
    for (uint64_t seed : c.unmatched) md << " " << seed;
    md << ".\n";
  }
  md << "\n| seed | world | two robots: 90 % after (s) | one robot (s) | speed-up |\n"
     << "|---|---|---|---|---|\n";
  for (const TeamSpeedupWorld& w : c.worlds) {
    std::string speedup = "-";
    if (w.two_s > 0.0 && w.one_s >= 0.0) {
      std::snprintf(line, sizeof line, "%.2f", w.one_s / w.two_s);
      speedup = line;
    }
    md << "| " << w.seed << " | " << w.world << " | " << timeText(w.two_s) << " | "
       << timeText(w.one_s) << " | " << speedup << " |\n";
  }
  return md.str();
}

}  // namespace coopmap

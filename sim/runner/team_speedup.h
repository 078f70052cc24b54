// Two robots against one on the same worlds (issue 44): two `coopmap bench explore` outputs
// of the same seeds, one run with two robots and one with one, compared world by world on
// when the map first covered 90 % of the reachable floor.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace coopmap {

// One world both outputs ran. Times in s; -1: 90 % never reached.
struct TeamSpeedupWorld {
  uint64_t seed = 0;
  std::string world;  // the world's name in its metrics.json
  double two_s = -1.0, one_s = -1.0;
  // Two robots reached 90 % and one robot did not, or did later.
  bool twoSooner() const { return two_s >= 0.0 && (one_s < 0.0 || two_s < one_s); }
};

struct TeamSpeedup {
  std::vector<TeamSpeedupWorld> worlds;  // by seed
  // Seeds in one output only, or whose run left no metrics.json (a failed run).
  std::vector<uint64_t> unmatched;
  int twoSooner() const;
  // one_s / two_s over the worlds where both reached 90 %; none when there is no such world.
  std::optional<double> medianSpeedup() const;
};

// Reads runs/<seed>/metrics.json of every seed under `two_dir` and `one_dir`. Throws
// ConfigError naming the file when a metrics.json cannot be read, when a run has the wrong
// number of robots, or when the same seed names different worlds in the two outputs; and
// naming the folder when it holds no runs/.
TeamSpeedup compareTeams(const std::string& two_dir, const std::string& one_dir);

// The comparison as Markdown: the count of worlds where two robots were sooner, the median
// speed-up, and a row per world.
std::string formatTeamSpeedup(const TeamSpeedup& comparison, const std::string& two_dir,
                              const std::string& one_dir);

}  // namespace coopmap

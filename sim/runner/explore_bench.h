// The exploration benchmark (issue 44): generated buildings the robots have never seen
// (world_generator.h), one per seed, each explored by the robots on their default settings,
// each run scored against its truth. Per world: coverage and when it reached 50 % and 90 %,
// wall recall, false-occupied rate, contacts, how each robot's mission ended; then the
// distribution over the worlds and the worst of them.
//
// Each world runs in a child process, `<program> run WORLD --explore --quiet --out DIR`, the
// command a person would type to look at one world again: the renderer holds one OpenGL
// context per process, so runs in parallel need processes, and a run that crashes takes only
// its own row. The parent reads the child's metrics.json (docs/formats.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/runner/phase_time.h"

namespace coopmap {

// The processors of this machine (at least 1): the default number of children at once.
int processorCount();

struct ExploreBenchOptions {
  uint64_t first_seed = 1;  // worlds of seeds first_seed .. first_seed + count - 1
  int count = 1;
  // Each world's run takes the seed world seed + run_seed_offset (every random choice of
  // the run: camera and odometry noise, people's walks). 0: the world's own seed; another
  // offset runs the same worlds again with other noise, which measures how far a build's
  // scores move from run to run on the same worlds.
  uint64_t run_seed_offset = 0;
  int robots = 2;               // 1: jose alone; 2: jose and eric
  double duration = 2400.0;     // s of simulated time per world at most
  int jobs = processorCount();  // children at once
  // explore.csv, explore.md, worlds/world_<seed>.yaml, runs/<seed>/, runs/<seed>.log (the
  // run's stderr) and runs/<seed>.events (its stdout: the mission events and the summary).
  std::string out_dir;
  std::string program = "/proc/self/exe";  // the coopmap program the children run
  bool progress = false;                   // a line per finished world on stderr

  // Throws ConfigError naming the option (as the command line spells it) and the bad value.
  void validate() const;
};

// One robot's end of a run.
struct ExploreEnding {
  std::string robot;
  std::string phase;   // the agent's phase at the end ("done": came home); "failed"
  std::string reason;  // the mission's last event; for a failed run, the log's last line
};

// One world.
struct ExploreRow {
  uint64_t seed = 0;      // the world's
  uint64_t run_seed = 0;  // the run's: seed + run_seed_offset
  std::string family;
  double floor_area_m2 = 0.0;
  int robots = 0;
  bool failed = false;  // the child exited non-zero or wrote no readable metrics.json
  // The shared map's scores when the robots shared one, else the (single) robot's own map.
  double coverage = 0.0;
  double time_to_50_s = -1.0, time_to_90_s = -1.0;  // s; -1: never
  double wall_recall = 0.0, false_occupied_rate = 0.0;
  int contacts = 0;  // contacts of all robots
  std::vector<ExploreEnding> endings;
  bool exploration_complete = false;
  double wall_time_s = 0.0;       // the child's, start to exit
  std::string map_picture;        // the scored map's picture, relative to the output folder
  std::vector<PhaseTime> phases;  // all robots' together, by phase (first entered first)
};

struct ExploreBenchResult {
  std::vector<ExploreRow> rows;  // by seed
  std::string markdown;          // explore.md
};

// Runs the benchmark. Throws ConfigError for bad options or an --out that cannot be written
// (before any world is generated or run). A world that cannot be generated or whose run fails
// gives a failed row; the others go on.
ExploreBenchResult runExploreBench(const ExploreBenchOptions& options);

// A finished child's row fields from its metrics.json text (`file` names it in messages):
// the scores, contacts, endings, exploration_complete, map_picture and the phases' times
// (when the file has them). Throws ConfigError when a key it needs is missing or malformed.
void readExploreMetrics(const std::string& text, const std::string& file, ExploreRow& row);

// The CSV text of the rows (header first); free text quoted, inner quotes doubled.
std::string formatExploreCsv(const std::vector<ExploreRow>& rows);

// explore.md: the distribution over the worlds that ran, how many meet each target, where
// the robots' time went (phase by phase), and the five worlds of least coverage with links to
// their map pictures.
std::string formatExploreMarkdown(const ExploreBenchOptions& options,
                                  const std::vector<ExploreRow>& rows);

// The quartiles of a sample: {first quartile, median, third quartile}, linearly interpolated
// between order statistics (numpy's default); all 0 for an empty sample.
struct Quartiles {
  double q1 = 0.0, median = 0.0, q3 = 0.0;
};
Quartiles quartiles(std::vector<double> values);

}  // namespace coopmap

// What a run writes for people: report.html (sim/runner/report_html.h) and timeline.csv.
#pragma once

#include <string>

#include "core/mapping/grid.h"
#include "sim/runner/world_run.h"

namespace coopmap {

// report.html (and trajectories.png) in `dir`: the summary, the trajectories over the true
// occupancy the shared map is measured against, coverage and error over time, the maps.
void writeRunReport(const std::string& dir, const RunResult& result);

// The run's timeline (t, shared coverage, each robot's coverage and position error) as CSV,
// written atomically.
void writeTimelineCsv(const std::string& path, const RunResult& result);

}  // namespace coopmap

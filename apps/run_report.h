// What a run writes for people: report.html (apps/report_html.h) and timeline.csv.
#pragma once

#include <string>

#include "apps/run_world.h"
#include "core/mapping/grid.h"

namespace coopmap {

// report.html (and trajectories.png) in opt.out_dir: the summary, the trajectories over
// `truth` (the true occupancy the shared map is measured against; null: none), coverage and
// error over time, the maps.
void writeRunReport(const RunOptions& opt, const std::string& world_name, const RunResult& result,
                    const GridU8* truth);

// The run's timeline (t, shared coverage, each robot's coverage and position error) as CSV,
// written atomically.
void writeTimelineCsv(const std::string& path, const RunResult& result);

}  // namespace coopmap

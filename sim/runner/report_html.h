// report.html: one self-contained page a person opens after a run — summary table, the
// trajectories over the true map, coverage and error plots (inline SVG), the maps.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/io/tum.h"
#include "core/mapping/grid.h"
#include "sim/runner/svg_plot.h"

namespace coopmap {

// One robot's trajectories, in the world frame of the true map.
struct ReportRobot {
  std::string name;
  std::vector<StampedPose2> groundtruth, odometry, corrected;  // any may be empty
};

// A map to show; `file` is a PNG name relative to the out dir.
struct ReportImage {
  std::string caption, file;
};

// Everything on the page; pointers are borrowed for the call.
struct ReportData {
  std::string title;                                         // e.g. "lab_corridor, seed 1"
  std::vector<std::pair<std::string, std::string>> summary;  // key/value rows of the summary
  std::vector<ReportRobot> robots;
  const GridU8* truth = nullptr;          // true occupancy (nonzero = occupied); null: white canvas
  MapLimits limits;                       // of truth; width 0: truth->limits
  std::vector<ReportImage> images;        // maps to show (shared map, per-robot maps, naive map...)
  std::vector<ReportSeries> coverage;     // coverage over time (fraction 0..1)
  std::vector<ReportSeries> error;        // position error over time (m)
  std::string coverage_note, error_note;  // one-line captions under the plots
  int map_scale = 0;  // trajectories.png pixels per map cell; 0: up to 4, longer side <= 1200 px
};

// Escapes & < > " ' for HTML text and attribute values.
std::string escapeHtml(const std::string& text);

// Renders the true map (free white, walls grey, north up, `data.map_scale` px per cell) with
// every robot's trajectories — each robot its own colour; truth solid, odometry dashed,
// corrected dotted; a circle at the start, a dot at each end — and a legend column (robots,
// line styles, a scale bar) right of the map. The map occupies the top-left
// width*scale x height*scale pixels. Returns PNG bytes. Without truth the canvas covers
// `limits`, or else the poses with a 1 m margin. Throws std::invalid_argument when truth and
// limits disagree, map_scale is outside 0..16 or there is nothing to draw.
std::string encodeTrajectoriesPng(const ReportData& data);

// Writes OUT/trajectories.png (encodeTrajectoriesPng; skipped when there is neither truth,
// limits nor a pose) and then OUT/report.html, each atomically. OUT must exist.
// Throws std::runtime_error naming the file on failure.
void writeReport(const std::string& out_dir, const ReportData& data);

}  // namespace coopmap

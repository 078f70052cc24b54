// Where a robot stands when it starts: its first look at the home base (a turn in place,
// section 4 of the paper) against the home base as designed. The map frame is the home
// base's: its two corners' designed geometry is all a robot is told, so this fix is what
// places the robot's odometry frame in the map frame (X_MO). Robots may start anywhere the
// home base is in view.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/correction/home_return.h"
#include "core/correction/traverse_log.h"
#include "core/localization/home_base.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

// The home base drawn as its arms' surfaces (each arm a solid box, home_base.h) in a grid of
// `resolution` around it, for dense alignment: occupied and seen where a surface passes
// within half a cell of the cell's centre, unknown elsewhere, so that points seen on a surface
// lie on occupied cells' centres, not half a cell off them. With `viewpoint` (map frame),
// only the faces turned towards it: an arm is as thick as a few cells, and points of its
// near face would fit its far face as well.
OccupancyGrid homeBaseModelGrid(const HomeBaseDesign& design, double resolution,
                                const std::optional<Eigen::Vector2d>& viewpoint = std::nullopt);

enum class StartFixStatus { kOk, kNoTurn, kHomeBaseNotFound, kAlignmentFailed };
const char* toString(StartFixStatus s);

struct StartFix {
  StartFixStatus status = StartFixStatus::kNoTurn;
  std::string method;        // how the fix was found, or why there is none, for people
  Pose2 correction;          // X_MO: the log's (odometry) frame placed in the map frame
  size_t entry = 0;          // the radial map the fix is for (the middle of the view used)
  size_t turn_begin = 0;     // the first radial map of the turn in place (the look)
  Pose2 pose;                // the robot's pose at `entry`, map frame
  std::vector<size_t> view;  // the entries the fix was made from (one stretch of the turn)
  int points = 0;            // obstacle points aligned to the designed home base
  double inlier_share = 0.0;
  bool ok() const { return status == StartFixStatus::kOk; }
};

// Localizes the start of a log (odometry frame) against the designed home base. The turn in
// place the log ends with (the look; a log of the look alone at the start) is mapped; every corner
// found in that map near the start is tried as either of the home base's corners (they look alike,
// and a view may show only one of them whole), and the placement of the design that puts most of
// the turn's obstacle points on the arms' surfaces, both L's among them, is the home base. Then the
// longest run of the turn's entries facing it (the first one when two are as long: a turn that
// starts facing the home base comes back to it drifted by the turn) is aligned on its own to the
// faces of the design turned towards the robot: every point of the arms pins the pose, where
// the paper's fix is only as good as two corner fits. `config` gives the local map and the
// corner fits (HomeReturnConfig).
StartFix localizeStart(const TraverseLog& log, const HomeBaseDesign& design,
                       const HomeReturnConfig& config = {});

}  // namespace coopmap

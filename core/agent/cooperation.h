// One robot's side of the paper's cooperation (section 4): at the end of every sortie the
// robot is back at the home base and has looked at it; it localizes there, corrects the
// sortie's traverse, posts the corrected radial maps to the shared map, and imports the
// shared map before it goes again. Uncorrected data is never shared. Robot-agnostic: it
// works on traverse logs, the same from the simulator, a recording or a real robot.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/correction/drift_correction.h"
#include "core/correction/home_return.h"
#include "core/correction/traverse_log.h"
#include "core/io/tum.h"
#include "core/localization/manhattan.h"
#include "core/localization/scan_alignment.h"
#include "core/sharing/shared_map.h"

namespace coopmap {

struct CooperationConfig {
  HomeReturnConfig home_return;
  CorrectionConfig correction;  // heading-drift by default
  // A fix that moves the robot farther than this (m) or turns it more than this (rad) from
  // where it believed it was is not trusted (the home base was mistaken for something else).
  // (The robot's move: from its pose on the sortie's odometry at the fix to the fix's.)
  double max_fix_jump_m = 3.0;
  double max_fix_jump_rad = 0.6;
  double max_disagreement_m = 0.3;
  // Beyond the paper: once the shared map has data, stretches of the corrected sortie
  // (closure_scans radial maps every closure_stride entries) are aligned to it, and those
  // that fit (inlier share >= closure_min_inliers; an alignment that would move the map's
  // origin, by the home base, at most closure_max_m and turn at most closure_max_rad from
  // where the home-base correction put them: see mapClosures) become loop closures of a
  // pose-graph correction: the sortie is made to agree with what is already shared. Off by
  // default: closures place scans by stereo alignments, which carry stereo's own errors; with
  // exact odometry the shared map has the fewest false obstacles without closures of either
  // kind, and with drifting, calibrated odometry closures to the shared map add false
  // obstacles for little gain in walls found, and the home-base fixes that follow are farther
  // off the truth (measured: docs/experiments/2026-11-lab-exploration.md).
  bool closures = false;
  int closure_scans = 6;
  int closure_stride = 9;
  double closure_min_inliers = 0.7;
  double closure_max_m = 0.5;
  double closure_max_rad = 0.1;
  double closure_sigma_xy = 0.05;     // m, 1-sigma of a closure
  double closure_sigma_theta = 0.02;  // rad
  // Shaped closures: a closure constrains a position only in the directions its alignment
  // pins down; along the weak direction the sigma grows as sqrt(strong / weak information),
  // up to closure_max_sigma_m. Round (off), every closure pins the position in all directions
  // alike: in a straight corridor, where an alignment can slide along the walls, that moves
  // whole stretches. Off by default: on the lab, whose alignments see corners, it measured
  // no better; the agents turn it on (core/agent/agent_settings.h;
  // measured in docs/experiments/2026-12-building-settings.md).
  bool closure_shape = false;
  double closure_max_sigma_m = 5.0;
  // Closures within the sortie too (beyond the paper): stretches of each half aligned to
  // the other half's map, leaving self_closure_gap entries out either side of the middle.
  // On by default: with drifting odometry the maps are about as good as without, and the
  // home-base fixes that follow, on calibrated odometry, come closest to the truth of the
  // three choices (measured with the closures above).
  bool self_closures = true;
  int self_closure_gap = 60;
  AlignmentConfig closure_alignment;
  // Before posting: the last home_check_scans radial maps (the look at home) at their
  // corrected poses must put at least this share of their obstacle points on the shared
  // map's obstacles (when it has data there): a wrong fix shows as a home that does not look
  // like the shared map's home, and is not shared.
  double min_home_agreement = 0.5;
  int home_check_scans = 30;
  // Beyond the paper: the home base's two corners look alike from places their spacing
  // apart, and a fix can land on the wrong one, metres off, with enough of the look on the
  // shared map's obstacles to pass the check above. The shared map knows more of home than
  // the reference look: the look, placed by the fix, is also scored at placements up to
  // rival_search_m away (at least rival_min_shift_m off, turned up to rival_max_turn_rad).
  // When one fits better by rival_margin (share of points within a cell of an obstacle), the
  // fix moves there (aligned from it) or, when that alignment fails or leaves the places
  // searched, is not trusted (measured: docs/experiments/2026-12-shared-maps-and-fix-check.md).
  // 0: off.
  double rival_search_m = 2.0;
  double rival_min_shift_m = 0.5;
  // 12 degrees: a fix on the wrong corner can be several degrees off in heading too, and a
  // search that turns less leaves its true place outside the places searched, so the fix is
  // not trusted and its robot stops, lost (measured:
  // docs/experiments/2026-12-shared-maps-and-fix-check.md).
  double rival_max_turn_rad = 12.0 * M_PI / 180.0;
  double rival_margin = 0.1;
  // Beyond the paper: before posting, the corrected sortie's stretches (closure_scans radial
  // maps each, end to end) are aligned to the shared map once more, and a stretch the
  // alignment would move farther than post_gate_m (or turn more than post_gate_rad) at its
  // middle is withheld: the shared map says the correction misplaced it, and posting it would
  // draw its walls where there are none and clear free space through real ones. Stretches
  // that do not align (new territory, too few points) are posted. 0: off, everything posted
  // (the default here and the agents'; measured in docs/experiments/2026-12-building-settings.md).
  double post_gate_m = 0.0;
  double post_gate_rad = M_PI;
  // Beyond the paper: headings from the building's walls (manhattanTurn). Each stretch of the
  // corrected sortie (closure_scans radial maps every closure_stride entries) whose walls
  // show a turn from the axes of `manhattan` gives the pose graph a heading observation of
  // 1-sigma manhattan_sigma_rad at its middle (position free). Only for worlds whose walls
  // run along two perpendicular axes. 0: off (the default here; the agents turn it on,
  // core/agent/agent_settings.h). There the walls a robot sees give its heading absolutely,
  // wherever it is, so the corrected sorties keep closer to the truth in heading and across
  // the corridors, and the shared map finds more walls with fewer false obstacles (measured:
  // docs/experiments/2026-12-building-settings.md). The position is left free by an
  // xy_information of ~0 (PoseObservation has no heading-only kind).
  double manhattan_sigma_rad = 0.0;
  ManhattanConfig manhattan;
  // Passes of the walls' headings: each after the first finds them again on the poses the
  // one before corrected, and is kept when it found more. The walls' turn is searched
  // within manhattan.search_rad of the axes, so a sortie whose first correction is further
  // off gets few headings where it needs them and stays off in heading all along; found
  // again on the corrected poses, the walls hold it, and the shared map finds more walls
  // (measured: docs/experiments/2026-12-building-sessions-25-34.md).
  int manhattan_passes = 3;
  // Beyond the paper: a robot's map frame is its home base's as its first look placed it, a
  // few tenths of a degree and a centimetre or two off the design for a look from afar, and
  // each robot's off in its own way; far from home two robots' walls part by that turn. The
  // first sortie a robot posts to a shared map that holds its teammates' data is aligned to
  // it whole (one rigid motion, turning at most team_frame_max_rad and moving the home base
  // at most team_frame_max_m; at least team_frame_min_points obstacle points, of which
  // team_frame_min_inliers on the map's obstacles): the robot takes the team's frame, with its
  // registration and reference of the home base. Off: each robot keeps its own.
  bool join_team_frame = false;
  double team_frame_max_m = 0.15;
  double team_frame_max_rad = 3.0 * M_PI / 180.0;
  int team_frame_min_points = 500;
  double team_frame_min_inliers = 0.7;
  void validate() const;  // throws std::invalid_argument naming the field

  // The loop closures by name: "none", "self" (within the sortie), "shared" (to the shared
  // map) or "both" (`coopmap run --closures`, a world's `closures`).
  std::string closureKinds() const;
  // Sets closures and self_closures from such a name; false (nothing changed) for another.
  bool setClosureKinds(const std::string& name);
};

// How a sortie's end at the home base went (SortieReport::method has the details).
enum class SortieStatus {
  kFixed,             // localized at the home base and the traverse corrected
  kNoEntries,         // no radial maps in the sortie
  kNotLocalized,      // the look at the home base gave no fix
  kFixOnReference,    // the fix fell on a reference scan, not on the return turn
  kFixJumps,          // the fix moves the robot farther than one sortie drifts
  kRivalPlacement,    // the look fits the shared map better elsewhere
  kDisagrees,         // the fix is far from where the first fix sent the robot
  kCorrectionFailed,  // the traverse could not be corrected on the fix
  kHomeUnlike,        // corrected, home does not look like the shared map's there: not shared
};
const char* toString(SortieStatus s);

struct SortieReport {
  int sortie = 0;      // 1 for the first
  double stamp = 0.0;  // s: the last entry of the sortie
  size_t entries = 0;  // radial maps in the sortie
  SortieStatus status = SortieStatus::kNotLocalized;
  bool fixed() const { return status == SortieStatus::kFixed; }
  std::string method;            // how it was localized, or why not
  Pose2 correction;              // X_M,estimate: what the fix did to the robot's estimate
  Pose2 fix;                     // the robot's pose in the map frame at the fix
  double fix_stamp = 0.0;        // s: when (the radial map the fix is for)
  bool posted = false;           // the corrected traverse was accepted by the shared map
  PostResult post;               // what the shared map said
  int closures = 0;              // stretches aligned to the shared map (pose-graph closures)
  size_t withheld = 0;           // radial maps left out of the post (post_gate_m)
  double home_agreement = -1.0;  // share of the look's points on the shared map (-1: none)
  double fix_moved_m = 0.0;      // how far the shared map moved the fix (rival check), or 0
  uint64_t map_version = 0;      // of the shared map imported afterwards
  // The rigid motion that took the robot's map frame into the team's (join_team_frame),
  // already in `correction` and `fix`; identity unless this sortie joined.
  Pose2 team_frame;
  // The systematic odometry errors the correction fitted (of the odometry the sortie ran
  // on), and the distance driven: for online odometry calibration.
  OdometryBias bias;
  double length_m = 0.0;
};

// Heading observations from the walls (CooperationConfig::manhattan_sigma_rad): stretches
// of `scans` radial maps every `stride` entries, placed at `poses`, whose hits within
// max_range (m) look turned from the axes of `config`; each observes the heading at its
// middle entry, turned back, with 1-sigma sigma_rad, and leaves the position free. Throws
// std::invalid_argument when the pose count differs from the log's or scans, stride < 1.
std::vector<PoseObservation> manhattanHeadings(const TraverseLog& log,
                                               const std::vector<Pose2>& poses, int scans,
                                               int stride, double max_range, double sigma_rad,
                                               const ManhattanConfig& config = {});

// Loop closures of a corrected traverse against the aligner's map (the shared map, or the
// sortie's other half): stretches of closure_scans entries every closure_stride within
// entries [from, to), each placed at `corrected` and aligned; a fit (closure_min_inliers of
// its points on the map's obstacles, moving the map's origin at most closure_max_m and
// turning it at most closure_max_rad) observes the pose of its middle entry (closure_sigma_*,
// shaped by the alignment with closure_shape). With `estimate` (the robot's live estimate
// at each entry, held by the walls' headings while it drove), each stretch is also placed
// on its own odometry where the estimate had its middle, and the better fit of the two (the
// larger share of points on the map's obstacles) is taken: one home-base fix cannot tell a
// long sortie's heading drift from the rest and can leave its far end well off, where the
// estimate, held by the walls, stays close, and many more stretches fit from there (measured:
// docs/experiments/2026-12-building-settings.md). Throws std::invalid_argument when a pose
// list's length differs from the log's.
std::vector<PoseObservation> mapClosures(const TraverseLog& log,
                                         const std::vector<Pose2>& corrected,
                                         const ScanAligner& aligner,
                                         const CooperationConfig& config, size_t from, size_t to,
                                         const std::vector<Pose2>* estimate = nullptr);

// The entries of a corrected traverse whose stretch the aligner's map says is misplaced.
// The traverse is cut into stretches of `scans` entries, end to end (a shorter rest joins
// the last); each is aligned, at `poses`, to the map, and its entries are flagged when the
// alignment fits (at least `min_inliers` of its points on the map's obstacles) and would move
// the stretch's middle pose farther than `max_m` or turn it more than `max_rad`.
std::vector<bool> misplacedEntries(const TraverseLog& log, const std::vector<Pose2>& poses,
                                   const ScanAligner& aligner, int scans, double min_inliers,
                                   double max_m, double max_rad);

// The best other place for points (map frame) on the aligner's map, by the share of the
// points within a cell of an obstacle: shifts of at least `min_shift_m` and at most
// `search_m` combined with turns about `pivot` of up to `max_turn_rad`, searched coarse to
// fine (0.1 m and 2 degree steps, then half those about the best). `here` is the points'
// score where they are.
struct RivalPlacement {
  Pose2 correction;    // where the best other place puts the points: correction * point
  double score = 0.0;  // its score
  double here = 0.0;   // the score of the points where they are
};
RivalPlacement rivalPlacement(const ScanAligner& aligner,
                              const std::vector<Eigen::Vector2d>& points,
                              const Eigen::Vector2d& pivot, double search_m, double min_shift_m,
                              double max_turn_rad);

class HomeBaseCooperation {
 public:
  // `nominal`: the home base as designed (map frame); `shared`: the shared-map service
  // (not owned; must outlive this).
  HomeBaseCooperation(std::string robot, const HomeBase& nominal, double arm_length,
                      SharedMapService* shared, const CooperationConfig& config = {});

  // The sortie's traverse: its entries in the robot's map-frame estimate, ending with the
  // turn at the home base (the first sortie starts with the look at the home base, which
  // registers it). Localizes, corrects, posts; returns what happened. Afterwards the robot
  // applies `correction` to its estimate and imports the shared map (SharedMapService::
  // snapshot), whether or not its post went in.
  // With `expected`: where the robot should be at the fix (it drove to its start by a
  // first fix); a fix farther than max_disagreement_m from it is not trusted. With
  // `estimate` (the robot's live estimate at each entry, map frame), the closures to the
  // shared map also try each stretch where the estimate had it (see mapClosures). Entries
  // before `look_from` are never part of the look (the return turn): a robot that looked
  // again where it stood would otherwise see what hid the home base at its earlier look.
  //
  // `located`: what locate() found for this very sortie, look and expectation (the robot
  // accepted that fix): taken over instead of localizing again.
  struct Located;
  SortieReport endSortie(const TraverseLog& sortie,
                         const std::optional<Eigen::Vector2d>& expected = std::nullopt,
                         const std::vector<Pose2>* estimate = nullptr, size_t look_from = 0,
                         const Located* located = nullptr);
  // Localizes only (nothing posted, nothing registered): where is the robot now? For a
  // robot that came back away from its start: it drives to the start by this fix and
  // looks again, so that endSortie sees the home base as the reference scans did. With
  // `expected`, the same trust check as endSortie's: before endSortie, it tells whether the
  // look after driving there agrees with the first (when not, one of the two was wrong).
  // The report is `rep` of the result.
  struct Located {
    SortieReport rep;
    PoseObservation observation;               // in the sortie's entries, when rep.fixed()
    std::optional<HomeBaseProtocol> protocol;  // the first sortie's registration
    // What it was located from: endSortie takes it over only for the same.
    size_t entries = 0, look_from = 0;
    std::optional<Eigen::Vector2d> expected;
    uint64_t shared_version = 0;
  };
  Located locate(const TraverseLog& sortie,
                 const std::optional<Eigen::Vector2d>& expected = std::nullopt,
                 size_t look_from = 0) const;

  const std::vector<SortieReport>& reports() const { return reports_; }
  // Every entry of the sorties posted so far at its corrected pose (map frame), in order.
  const std::vector<StampedPose2>& corrected() const { return corrected_; }
  // The registered home base (after the first sortie): the robot's own, or the nominal one.
  const HomeBase& home() const { return home_; }

 private:
  std::string robot_;
  HomeBase nominal_, home_;
  double arm_length_;
  SharedMapService* shared_;
  CooperationConfig config_;
  TraverseLog reference_log_;  // the first sortie's look at the home base (exact poses)
  std::optional<OccupancyGrid> reference_;
  std::vector<SortieReport> reports_;
  std::vector<StampedPose2> corrected_;
  // The shared map as it is now, prepared for alignment once per sortie (no aligner before
  // the first post).
  struct SharedView {
    SharedView(const SharedMapService& shared, const AlignmentConfig& config);
    SharedView(const SharedView&) = delete;
    SharedView& operator=(const SharedView&) = delete;
    std::optional<OccupancyGrid> map;
    std::optional<ScanAligner> aligner;  // over *map
    uint64_t version = 0;                // of the snapshot
  };
  Located locateSortie(const TraverseLog& sortie, const SharedView& view, size_t look_from) const;
  // The rival check (CooperationConfig::rival_search_m) of a located sortie's fix against
  // the shared map: true when it stands, possibly moved (noted in the report's method); false
  // when it is not trusted.
  bool checkRival(const TraverseLog& sortie, const ScanAligner& shared, Located& l) const;
  // Not trusted (noted in the method) when the fix is farther than max_disagreement_m from
  // where the robot was expected.
  void checkExpected(SortieReport& rep, const std::optional<Eigen::Vector2d>& expected) const;
  // Takes the team's frame (CooperationConfig::join_team_frame): aligns the corrected sortie
  // (`poses`) to the shared map and, when it fits, moves the poses, the report's fix and
  // correction, and the registration and reference of the home base by the alignment.
  void joinTeamFrame(const TraverseLog& sortie, const ScanAligner& aligner,
                     std::vector<Pose2>& poses, SortieReport& rep);
  bool joined_ = false;  // the team's frame was taken (or the first post found none)
  uint64_t next_post_ = 1;
};

}  // namespace coopmap

#include "apps/run_mission_options.h"

#include <optional>
#include <string>

namespace coopmap {

namespace {

// A number option that sets `target` when given.
CLI::Option* setting(CLI::App& cmd, const std::string& name, std::optional<double>& target,
                     const std::string& help) {
  return cmd.add_option_function<double>(
      name, [&target](const double& v) { target = v; }, help);
}

// Two flags, one turning `target` on, the other off; not both.
void onOff(CLI::App& cmd, const std::string& on, const std::string& on_help, const std::string& off,
           const std::string& off_help, std::optional<bool>& target) {
  CLI::Option* yes = cmd.add_flag_callback(
      on, [&target] { target = true; }, on_help);
  cmd.add_flag_callback(
         off, [&target] { target = false; }, off_help)
      ->excludes(yes);
}

}  // namespace

void addMissionSettingOptions(CLI::App& cmd, RunOptions& run) {
  setting(cmd, "--sortie-budget", run.sortie_budget_m,
          "With --explore: metres of a sortie before the robot goes home to be localized, "
          "share its corrected traverse and import the shared map [default: the world's "
          "mission settings, else 25]")
      ->check(CLI::PositiveNumber);
  setting(cmd, "--first-sortie-budget", run.first_sortie_budget_m,
          "With --explore and sorties: metres of the first sortie (0: --sortie-budget); a "
          "short first one calibrates the odometry near home before long ones [default: the "
          "world's mission settings, else 0]")
      ->check(CLI::NonNegativeNumber);
  setting(cmd, "--safety-distance", run.safety_distance,
          "With --explore: m from the cameras; an obstacle ahead nearer than this stops the "
          "robot [default: the world's, else 0.30]")
      ->check(CLI::PositiveNumber);
  setting(cmd, "--slow-distance", run.slow_distance,
          "With --explore: m; an obstacle ahead nearer than this slows the robot (0: never) "
          "[default: the world's, else 0]")
      ->check(CLI::NonNegativeNumber);
  setting(cmd, "--fringe-clearance", run.fringe_clearance,
          "With --explore: m; uncertain cells this far from obstacles, joined to unseen ones, "
          "make frontiers when no other frontier has a goal (0: off) [default: the world's, "
          "else 0]")
      ->check(CLI::NonNegativeNumber);
  setting(cmd, "--doorway-width", run.doorway_width,
          "With --explore and --fringe-clearance: m; uncertain cells between two obstacles at "
          "most this far apart (a door seen obliquely) count as unseen however near the "
          "obstacles (0: off) [default: the world's, else 0]")
      ->check(CLI::NonNegativeNumber);
  setting(cmd, "--floor-edge-depth", run.floor_edge_depth,
          "m; a camera column that matches nothing but sees the floor end nearer than this "
          "depth has met a textureless wall there (0: off) [default: the world's, else 0]")
      ->check(CLI::Range(0.0, 5.0));
  cmd.add_option_function<int>(
         "--beyond-support", [&run](const int& v) { run.beyond_support = v; },
         "Pixels of a camera column, beyond the range and agreeing, that see it free to the "
         "range (1: any one; a textureless wall seen at a grazing angle gives stray far "
         "mismatches) [default: the world's, else 1]")
      ->check(CLI::Range(1, 100));
  setting(cmd, "--goal-clearance", run.goal_clearance,
          "With --explore: m; frontier goals this far from anything blocked are preferred (0: "
          "the nearest free cell) [default: the world's, else 0]")
      ->check(CLI::NonNegativeNumber);
  onOff(cmd, "--retry-frontiers",
        "With --explore and sorties: frontiers whose goals failed send the robot home to share "
        "and try again next sortie, rather than end exploration; reached goals are not tried "
        "again [default: the world's, else off]",
        "--no-retry-frontiers",
        "With --explore: end exploration when no frontier goal is left this sortie",
        run.retry_frontiers);
  onOff(cmd, "--bump-away",
        "With --explore: after a bump, back off away from where the base was touched and map "
        "the obstacle at that bearing (the simulator's bump panels say where) [default: the "
        "world's, else off]",
        "--bump-back",
        "With --explore: after a bump, back off against the command and map the obstacle "
        "ahead",
        run.bump_away);
  setting(cmd, "--passage-width", run.passage_width,
          "With --explore and several robots: m; where the way ahead passes between obstacles "
          "nearer together than this (a door), a robot waits while a teammate nearer to it "
          "goes through (0: off) [default: the world's, else 0]")
      ->check(CLI::Range(0.0, 5.0));
  setting(cmd, "--max-linear-accel", run.max_linear_accel,
          "With --explore: m/s^2; the mission speeds up no faster than this (the wheels slip "
          "where the floor grips less than the base's acceleration needs; 0: as the base does) "
          "[default: the world's, else 0]")
      ->check(CLI::Range(0.0, 10.0));
  setting(cmd, "--visited-radius", run.visited_radius,
          "With --explore: m either side of the path driven kept free in planning (0: the "
          "robot's radius) [default: the world's, else 0]")
      ->check(CLI::Range(0.0, 1.0));
  setting(cmd, "--recent-hits", run.recent_hits_s,
          "With --explore: seconds; what the cameras saw that long ago or less (within 2 m) "
          "blocks the robot's planning whatever its map holds there (0: off) [default: the "
          "world's, else 0]")
      ->check(CLI::Range(0.0, 600.0));
  setting(cmd, "--margin", run.planning_margin,
          "With --explore: metres kept clear around the robot's body in planning, room for "
          "the estimate's drift [default: the world's, else 0.05]")
      ->check(CLI::Range(0.0, 1.0));
  setting(cmd, "--preferred-margin", run.preferred_margin,
          "With --explore: metres beyond the body the paths keep from walls where the map "
          "leaves room (a door only as wide as the robot needs is still passed, through its "
          "middle; 0: off) [default: the world's, else 0]")
      ->check(CLI::Range(0.0, 2.0));
  setting(cmd, "--post-gate", run.post_gate_m,
          "With --explore: metres; a stretch of a corrected sortie that the shared map would "
          "move farther than this is not posted (it was misplaced; 0: off) [default: the "
          "world's, else 0]")
      ->check(CLI::Range(0.0, 2.0));
  setting(cmd, "--manhattan", run.manhattan_sigma_deg,
          "With --explore: degrees; in a building whose walls run along the map's axes, each "
          "stretch of a sortie whose walls look turned from them gives its correction a "
          "heading of this 1-sigma (0: off) [default: the world's, else 0]")
      ->check(CLI::Range(0.0, 10.0));
  setting(cmd, "--wall-heading", run.wall_heading_gain,
          "With --explore: a share in [0, 1]; in a building whose walls run along the map's "
          "axes, every few radial maps the robot's estimate is turned back by this share of "
          "the turn of the walls it sees from the axes (0: off) [default: the world's, else "
          "0]")
      ->check(CLI::Range(0.0, 1.0));
  cmd.add_option_function<int>(
         "--closure-scans", [&run](const int& v) { run.closure_scans = v; },
         "With --explore: radial maps per stretch of a sortie's correction: each stretch "
         "aligned to the shared map (a loop closure), each giving a heading from the walls, "
         "each the post gate checks [default: the world's, else 6]")
      ->check(CLI::Range(1, 100));
  cmd.add_option_function<int>(
         "--look-again", [&run](const int& v) { run.look_again_gain = v; },
         "With --explore and --retry-frontiers: never-observed cells; once no frontier is left "
         "to go to, a frontier whose goal was reached but that still has this many is gone to "
         "once more, to turn a full circle there (0: off) [default: the world's, else 0]")
      ->check(CLI::Range(0, 10000));
  onOff(cmd, "--scale-calibration",
        "With --explore: the online odometry calibration includes the distance scale the "
        "sorties' loop closures find [default: the world's, else on]",
        "--no-scale-calibration",
        "With --explore: calibrate heading drift and turn scale only (a home-base fix does "
        "not observe the distance scale)",
        run.calibrate_distance_scale);
  onOff(cmd, "--stereo-scale",
        "With --explore: the odometry calibration takes its distance scale from stereo (radial "
        "maps 1-1.5 m apart on straight stretches, aligned) and each sortie is rescaled to it "
        "before its correction [default: the world's, else off]",
        "--no-stereo-scale", "With --explore: no distance scale from stereo",
        run.stereo_distance_scale);
  setting(cmd, "--odometry-scale", run.odometry_distance_scale,
          "With --explore: the odometry's distance scale calibrated beforehand (the fraction by "
          "which it over-counts distance; `coopmap stereo-scale` measures it over runs' logs): "
          "the calibration starts from it [default: the world's, else 0]")
      ->check(CLI::Range(-0.05, 0.05));
  onOff(cmd, "--shaped-closures",
        "With --explore and closures: a closure pins its position only in the directions its "
        "alignment pins down (along a straight corridor's walls it is left loose) [default: "
        "the world's, else off]",
        "--round-closures",
        "With --explore and closures: each closure pins its position in every direction alike",
        run.shaped_closures);
  onOff(cmd, "--closure-seen-points",
        "With --explore: the sorties' alignments to the shared map (closures, post gate) "
        "leave out points where the map saw nothing, but for those just behind a surface it "
        "saw (past a mapped wall's end they pull a stretch back onto it) [default: the "
        "world's, else off]",
        "--closure-near-points",
        "With --explore: those alignments use every point near the map's obstacles",
        run.closure_seen_points);
  onOff(cmd, "--closure-decided-points",
        "With --explore: those alignments also leave out points in cells the map saw but is "
        "unsure of, neither free nor occupied (a wall's far part seen weakly pulled stretches "
        "back along it) [default: the world's, else off]",
        "--closure-undecided-points",
        "With --explore: those alignments also judge points in cells the map is unsure of",
        run.closure_decided_points);
}

}  // namespace coopmap

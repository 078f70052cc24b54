// The settings a robot's agent is run with, each declared once below: name, unit, range,
// default and one line of help. YAML keys (a settings file, a recording's agent.yaml) and
// command-line flags (snake_case key = --kebab-case flag) are derived from this table, and
// the agent turns the settings into its components' configurations (RobotAgent).
#pragma once

#include <string>
#include <vector>

namespace coopmap {

class YamlField;

// One setting's declaration. Numbers must lie in [min, max]; a string setting with `choices`
// (separated by '|') must be one of them.
struct SettingInfo {
  const char* name;
  const char* unit;  // "m", "s", "deg", "m/s^2", "Hz", "" for none
  const char* help;
  double min = 0.0;
  double max = 0.0;
  const char* choices = nullptr;
};

struct AgentSettings {
  // What takes a robot out and brings it home.
  double sortie_budget_m = 40.0;
  double first_sortie_budget_m = 10.0;
  double sortie_budget_s = 400.0;
  int max_sorties = 12;
  // Safety.
  double safety_distance = 0.45;
  double slow_distance = 1.0;
  double max_linear_accel = 0.4;
  bool bump_away = true;
  // Exploration.
  double fringe_clearance = 0.3;
  double doorway_width = 1.2;
  bool retry_frontiers = true;
  double visited_radius = 0.09;
  double recent_hits_s = 4.0;
  double planning_margin = 0.12;
  double preferred_margin = 0.3;
  // Teammates.
  bool coordinate = true;
  double passage_width = 1.2;
  double teammate_mask_m = 0.8;
  // Perception.
  double sensing_rate = 3.0;
  double floor_edge_depth = 1.5;
  int beyond_support = 3;
  // Localization, correction and sharing.
  double reapproach_m = 0.1;
  std::string closures = "none";
  bool shaped_closures = true;
  bool closure_seen_points = true;
  int closure_scans = 18;
  double manhattan_sigma_deg = 0.6;
  double wall_heading_gain = 0.5;
  // Odometry calibration.
  bool calibrate_odometry = true;
  bool calibrate_distance_scale = false;
  bool stereo_distance_scale = false;
  double odometry_distance_scale = 0.0;

  // Calls v(info, field) for every setting, in the order above; field is a double, int, bool
  // or std::string.
  template <typename Self, typename Visitor>
  static void visitAll(Self& s, Visitor&& v);
  template <typename Visitor>
  void visit(Visitor&& v) {
    visitAll(*this, v);
  }
  template <typename Visitor>
  void visit(Visitor&& v) const {
    visitAll(*this, v);
  }
  // Throws std::invalid_argument naming the first setting out of its range.
  void validate() const;
  bool operator==(const AgentSettings&) const = default;
};

// The declarations, in table order.
std::vector<SettingInfo> agentSettingInfos();

// Sets the settings a YAML mapping names (others keep their values); throws ConfigError
// naming the file, line and key for an unknown key or a bad value. `other_keys` are keys
// the caller reads itself, passed over here.
void readAgentSettings(const YamlField& mapping, AgentSettings& settings,
                       const std::vector<std::string>& other_keys = {});
// Sets one setting from text (a command-line value); throws std::invalid_argument
// "--kebab-name: expected ..., got '...'" for a bad value, or naming an unknown setting.
void setAgentSetting(AgentSettings& settings, const std::string& name, const std::string& value);
// The settings as a YAML mapping, one `name: value` per line (doubles to 17 digits, so they
// read back exactly), `indent` spaces before each.
std::string agentSettingsYaml(const AgentSettings& settings, int indent = 0);
// "--kebab-case" for a snake_case name.
std::string settingFlag(const std::string& name);
// The reference of every setting (docs/settings.md): a Markdown table of names, flags,
// defaults, ranges and help.
std::string agentSettingsMarkdown();

template <typename Self, typename Visitor>
void AgentSettings::visitAll(Self& s, Visitor&& v) {
  constexpr double kBig = 1e6;
  v(SettingInfo{"sortie_budget_m", "m",
                "metres driven before a sortie goes home to be localized, share its corrected "
                "traverse and import the shared map",
                0.1, kBig},
    s.sortie_budget_m);
  v(SettingInfo{"first_sortie_budget_m", "m",
                "metres of the first sortie (0: sortie_budget_m); a short first one calibrates "
                "the odometry near home",
                0.0, kBig},
    s.first_sortie_budget_m);
  v(SettingInfo{"sortie_budget_s", "s",
                "seconds of a sortie before it goes home (a robot whose wheels slip gets nowhere)",
                1.0, kBig},
    s.sortie_budget_s);
  v(SettingInfo{"max_sorties", "", "sorties at most; 1: explore once and share after the run", 1,
                10000},
    s.max_sorties);
  v(SettingInfo{"safety_distance", "m",
                "an obstacle ahead nearer than this to the cameras stops the robot", 0.05, 5.0},
    s.safety_distance);
  v(SettingInfo{"slow_distance", "m",
                "an obstacle ahead nearer than this slows the robot (0: never)", 0.0, 10.0},
    s.slow_distance);
  v(SettingInfo{"max_linear_accel", "m/s^2",
                "speeding up no faster than this keeps the grip on slippery floors (0: as the "
                "base does)",
                0.0, 10.0},
    s.max_linear_accel);
  v(SettingInfo{"bump_away", "",
                "after a bump, back off away from where the base was touched and map the "
                "obstacle at that bearing (off: straight back, obstacle ahead)"},
    s.bump_away);
  v(SettingInfo{"fringe_clearance", "m",
                "uncertain cells this far from obstacles, joined to unseen ones, make frontiers "
                "when no other frontier has a goal (0: off)",
                0.0, 5.0},
    s.fringe_clearance);
  v(SettingInfo{"doorway_width", "m",
                "with fringe_clearance: uncertain cells between two obstacles at most this far "
                "apart (a door seen obliquely) count as unseen (0: off)",
                0.0, 5.0},
    s.doorway_width);
  v(SettingInfo{"retry_frontiers", "",
                "frontiers whose goals failed send the robot home to share and try again next "
                "sortie, rather than end exploration"},
    s.retry_frontiers);
  v(SettingInfo{"visited_radius", "m",
                "the strip either side of the path driven kept free in planning (0: the robot's "
                "radius)",
                0.0, 1.0},
    s.visited_radius);
  v(SettingInfo{"recent_hits_s", "s",
                "what the cameras saw this recently (within 2 m) blocks planning whatever the map "
                "holds there (0: off)",
                0.0, 600.0},
    s.recent_hits_s);
  v(SettingInfo{"planning_margin", "m",
                "kept clear around the robot's body in planning: room for the estimate's drift",
                0.0, 1.0},
    s.planning_margin);
  v(SettingInfo{"preferred_margin", "m",
                "beyond the body, paths keep this from walls where the map leaves room (0: off)",
                0.0, 2.0},
    s.preferred_margin);
  v(SettingInfo{"coordinate", "",
                "frontiers near teammates' goals are worth less, and a robot whose own part is "
                "explored goes home to share it (off: each explores as if alone)"},
    s.coordinate);
  v(SettingInfo{"passage_width", "m",
                "where the way ahead passes between obstacles nearer together than this (a door), "
                "a robot waits while a nearer teammate goes through (0: off)",
                0.0, 5.0},
    s.passage_width);
  v(SettingInfo{"teammate_mask_m", "m",
                "returns within this of where a teammate reports itself are the teammate and are "
                "not logged or shared (0: logged like the world)",
                0.0, 2.0},
    s.teammate_mask_m);
  v(SettingInfo{"sensing_rate", "Hz", "trinocular frames per second (the paper: 3)", 0.1, 60.0},
    s.sensing_rate);
  v(SettingInfo{"floor_edge_depth", "m",
                "a camera column that matches nothing but sees the floor end nearer than this "
                "has met a textureless wall there (0: off)",
                0.0, 5.0},
    s.floor_edge_depth);
  v(SettingInfo{"beyond_support", "",
                "pixels of a column beyond the range, agreeing, that see it free to the range "
                "(1: any one)",
                1, 100},
    s.beyond_support);
  v(SettingInfo{"reapproach_m", "m",
                "back farther than this from its start by the first fix, a robot drives there "
                "and looks at the home base again",
                0.0, 10.0},
    s.reapproach_m);
  v(SettingInfo{"closures", "",
                "the loop closures of each sortie's correction: none, within the sortie (self), "
                "to the shared map (shared), or both",
                0.0, 0.0, "none|self|shared|both"},
    s.closures);
  v(SettingInfo{"shaped_closures", "",
                "a closure pins its position only in the directions its alignment pins down"},
    s.shaped_closures);
  v(SettingInfo{"closure_seen_points", "",
                "the sorties' alignments to the shared map leave out points where the map saw "
                "nothing (but just behind a surface it saw)"},
    s.closure_seen_points);
  v(SettingInfo{"closure_scans", "",
                "radial maps per stretch of a sortie's correction (closures, wall headings)", 1,
                100},
    s.closure_scans);
  v(SettingInfo{"manhattan_sigma_deg", "deg",
                "walls along the map frame's axes give each stretch of a sortie's correction a "
                "heading of this 1-sigma (0: off)",
                0.0, 10.0},
    s.manhattan_sigma_deg);
  v(SettingInfo{"wall_heading_gain", "",
                "while driving, the estimate is turned back by this share of the walls' turn from "
                "the map frame's axes (0: off)",
                0.0, 1.0},
    s.wall_heading_gain);
  v(SettingInfo{"calibrate_odometry", "",
                "calibrate the odometry online with the systematic errors the home-base fixes "
                "find (off: every sortie on raw odometry)"},
    s.calibrate_odometry);
  v(SettingInfo{"calibrate_distance_scale", "",
                "that calibration includes the distance scale the sorties' corrections find"},
    s.calibrate_distance_scale);
  v(SettingInfo{"stereo_distance_scale", "",
                "the calibration takes its distance scale from stereo along straight stretches"},
    s.stereo_distance_scale);
  v(SettingInfo{"odometry_distance_scale", "",
                "the odometry's distance over-count calibrated beforehand (coopmap stereo-scale): "
                "the calibration starts from it",
                -0.05, 0.05},
    s.odometry_distance_scale);
}

}  // namespace coopmap

// The agents' settings table: read from YAML and from command-line text, checked against
// each setting's declared range, written back exactly.
#include "core/agent/agent_settings.h"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/io/yaml_reader.h"

namespace coopmap {
namespace {

AgentSettings read(const std::string& yaml) {
  AgentSettings s;
  readAgentSettings(YamlField::loadString(yaml, "s.yaml"), s);
  return s;
}

std::string errorOf(const std::string& yaml) {
  try {
    read(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(AgentSettingsTest, EverySettingIsReadFromYaml) {
  const AgentSettings m = read(
      "{first_sortie_budget_m: 11, safety_distance: 0.5, slow_distance: 1.1, fringe_clearance: "
      "0.35, doorway_width: 1.1, retry_frontiers: false, floor_edge_depth: "
      "1.4, beyond_support: 2, shaped_closures: false, bump_away: false, visited_radius: 0.1, "
      "max_linear_accel: 0.3, calibrate_distance_scale: true, stereo_distance_scale: true, "
      "passage_width: 1.3, odometry_distance_scale: 0.012, sortie_budget_m: 30, "
      "planning_margin: 0.2, preferred_margin: 0.25, closures: both, "
      "recent_hits_s: 8, manhattan_sigma_deg: 0.7, wall_heading_gain: 0.4, closure_scans: 12, "
      "closure_seen_points: false}");
  EXPECT_EQ(m.first_sortie_budget_m, 11.0);
  EXPECT_EQ(m.safety_distance, 0.5);
  EXPECT_EQ(m.slow_distance, 1.1);
  EXPECT_EQ(m.fringe_clearance, 0.35);
  EXPECT_EQ(m.doorway_width, 1.1);
  EXPECT_EQ(m.retry_frontiers, false);
  EXPECT_EQ(m.floor_edge_depth, 1.4);
  EXPECT_EQ(m.beyond_support, 2);
  EXPECT_EQ(m.shaped_closures, false);
  EXPECT_EQ(m.bump_away, false);
  EXPECT_EQ(m.visited_radius, 0.1);
  EXPECT_EQ(m.max_linear_accel, 0.3);
  EXPECT_EQ(m.calibrate_distance_scale, true);
  EXPECT_EQ(m.stereo_distance_scale, true);
  EXPECT_EQ(m.odometry_distance_scale, 0.012);
  EXPECT_EQ(m.passage_width, 1.3);
  EXPECT_EQ(m.sortie_budget_m, 30.0);
  EXPECT_EQ(m.planning_margin, 0.2);
  EXPECT_EQ(m.preferred_margin, 0.25);
  EXPECT_EQ(m.closures, "both");
  EXPECT_EQ(m.recent_hits_s, 8.0);
  EXPECT_EQ(m.manhattan_sigma_deg, 0.7);
  EXPECT_EQ(m.wall_heading_gain, 0.4);
  EXPECT_EQ(m.closure_scans, 12);
  EXPECT_EQ(m.closure_seen_points, false);
  // What a file does not name keeps its value.
  EXPECT_EQ(read("{safety_distance: 0.5}").sortie_budget_s, AgentSettings{}.sortie_budget_s);
}

// A recording's agent.yaml written before a setting was removed still reads when the setting
// held its old default (off); any other value cannot be honoured and is refused by name.
TEST(AgentSettingsTest, RemovedSettingsReadOnlyAtTheirOldDefault) {
  EXPECT_EQ(read("{post_gate_m: 0, track_shared_map: false, look_again_gain: 0, "
                 "safety_distance: 0.5}")
                .safety_distance,
            0.5);
  const std::string e = errorOf("{sortie_budget_m: 30, post_gate_m: 0.25}");
  EXPECT_NE(e.find("post_gate_m"), std::string::npos) << e;
  EXPECT_NE(e.find("no longer has"), std::string::npos) << e;
  EXPECT_NE(errorOf("{track_shared_map: true}").find("track_shared_map"), std::string::npos);
}

TEST(AgentSettingsTest, WrittenSettingsReadBackExactly) {
  AgentSettings s;
  s.odometry_distance_scale = 0.01 / 3.0;  // no short decimal
  s.closures = "shared";
  s.beyond_support = 5;
  s.bump_away = false;
  EXPECT_EQ(read(agentSettingsYaml(s)), s);
}

TEST(AgentSettingsTest, BadValuesNameTheLineTheSettingAndTheRange) {
  std::string e = errorOf("{safety_distance: -1}");
  EXPECT_NE(e.find("s.yaml:1:19: safety_distance: expected a number in [0.05, 5] m, got '-1'"),
            std::string::npos)
      << e;
  e = errorOf("max_linear_accel: -0.3\n");
  EXPECT_NE(e.find("max_linear_accel: expected a number in [0, 10] m/s^2, got '-0.3'"),
            std::string::npos)
      << e;
  e = errorOf("{closure_scans: 2.5}");
  EXPECT_NE(e.find("closure_scans: expected an integer in [1, 100], got '2.5'"), std::string::npos)
      << e;
  e = errorOf("{bump_away: sometimes}");
  EXPECT_NE(e.find("bump_away: expected true or false, got 'sometimes'"), std::string::npos) << e;
  e = errorOf("{closures: all}");
  EXPECT_NE(e.find("closures: expected one of none, self, shared or both, got 'all'"),
            std::string::npos)
      << e;
  e = errorOf("{budget: 3}");
  EXPECT_NE(e.find("budget: unknown setting (known: sortie_budget_m,"), std::string::npos) << e;
}

TEST(AgentSettingsTest, CommandLineValuesAreCheckedAsFlags) {
  AgentSettings s;
  setAgentSetting(s, "sortie_budget_m", "12.5");
  EXPECT_EQ(s.sortie_budget_m, 12.5);
  setAgentSetting(s, "closures", "self");
  EXPECT_EQ(s.closures, "self");
  setAgentSetting(s, "bump_away", "false");
  EXPECT_FALSE(s.bump_away);
  try {
    setAgentSetting(s, "safety_distance", "far");
    ADD_FAILURE() << "a bad value was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--safety-distance: expected"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(setAgentSetting(s, "no_such_setting", "1"), std::invalid_argument);
  EXPECT_EQ(settingFlag("sortie_budget_m"), "--sortie-budget-m");
}

TEST(AgentSettingsTest, TheReferenceInDocsIsTheTables) {
  std::ifstream in(std::string(COOPMAP_SOURCE_DIR) + "/docs/settings.md");
  ASSERT_TRUE(in) << "docs/settings.md is missing";
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), agentSettingsMarkdown())
      << "docs/settings.md is stale: build/apps/coopmap settings --markdown > docs/settings.md";
  for (const SettingInfo& info : agentSettingInfos())
    EXPECT_NE(text.str().find(std::string("| `") + info.name + "` |"), std::string::npos)
        << info.name;
}

}  // namespace
}  // namespace coopmap

#include "core/agent/mission_config.h"

#include <stdexcept>
#include <string>

namespace coopmap {

void MissionConfig::validate() const {
  auto positive = [](const char* field, double v) {
    if (!(v > 0.0))
      throw std::invalid_argument(std::string("mission config: field '") + field +
                                  "': expected a positive number, got " + std::to_string(v));
  };
  positive("budget_m", budget_m);
  positive("budget_s", budget_s);
  positive("replan_period_s", replan_period_s);
  positive("safety_distance", safety_distance);
  positive("safety_half_angle", safety_half_angle);
  positive("look_turn_rate", look_turn_rate);
  positive("goal_timeout_factor", goal_timeout_factor);
  positive("backoff_s", backoff_s);
  positive("escape_radius", escape_radius);
  positive("team_distance", team_distance);
  positive("team_half_angle", team_half_angle);
  positive("team_wait_s", team_wait_s);
  positive("team_radius", team_radius);
  positive("team_close", team_close);
  positive("look_from_m", look_from_m);
  positive("bump_radius", bump_radius);
  positive("max_home_detour", max_home_detour);
  positive("home_retry_s", home_retry_s);
  // field, whether its value is good, what is expected, the value
  auto require = [](const char* field, bool ok, const char* expected, double v) {
    if (!ok)
      throw std::invalid_argument(std::string("mission config: field '") + field + "': expected " +
                                  expected + ", got " + std::to_string(v));
  };
  require("max_linear_accel", max_linear_accel >= 0.0, "a number >= 0 (0: the base's)",
          max_linear_accel);
  require("slow_distance", slow_distance >= 0.0, "a number >= 0 (0: off)", slow_distance);
  require("slow_fraction", slow_fraction > 0.0 && slow_fraction <= 1.0, "a number in (0, 1]",
          slow_fraction);
  require("recent_hits_s", recent_hits_s >= 0.0, "a number >= 0 (0: off)", recent_hits_s);
  positive("recent_hits_range", recent_hits_range);
  require("recent_hits_support", recent_hits_support >= 1, "at least 1", recent_hits_support);
  require("first_budget_m", first_budget_m >= 0.0, "a number >= 0 (0: budget_m)", first_budget_m);
  require("bump_width", bump_width >= 0.0, "a number >= 0", bump_width);
  require("passage_width", passage_width >= 0.0, "a number >= 0 (0: off)", passage_width);
  positive("passage_lookahead", passage_lookahead);
  positive("passage_radius", passage_radius);
  positive("passage_wait_s", passage_wait_s);
  require("visited_radius", visited_radius >= 0.0, "a number >= 0 (0: the robot's radius)",
          visited_radius);
  require("claimed_return_factor", claimed_return_factor >= 0.0 && claimed_return_factor <= 1.0,
          "a number in [0, 1]", claimed_return_factor);
  require("min_sortie_m", min_sortie_m >= 0.0, "a number >= 0", min_sortie_m);
  require("look_wait_s", look_wait_s >= 0.0, "a number >= 0", look_wait_s);
  require("trail_after_waits", trail_after_waits >= 0, "a number >= 0 (0: never)",
          trail_after_waits);
  auto atLeastOne = [](const char* field, int v) {
    if (v < 1)
      throw std::invalid_argument(std::string("mission config: field '") + field +
                                  "': expected at least 1, got " + std::to_string(v));
  };
  atLeastOne("firm_log_odds", firm_log_odds);
  atLeastOne("max_sortie_bumps", max_sortie_bumps);
  atLeastOne("max_return_bumps", max_return_bumps);
  atLeastOne("max_sorties", max_sorties);
  frontiers.validate();
  planner.validate();
  planning.validate();
  route.validate();
}

}  // namespace coopmap

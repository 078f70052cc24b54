// A robot's agent configuration (its setup and settings, robot_agent.h) as YAML: what a real
// robot's config file states under `mission:`, and what a recording keeps beside each robot's
// stream (agent.yaml) so that a replay runs the very same agent.
//
//   name: jose
//   mode: explore                 # route | explore | driven
//   seed: 1                       # the path planner's
//   priority: true                # right of way over teammates
//   map: {origin: [-3.3, -2.0], resolution: 0.05, width: 220, height: 180}   # map frame
//   home_base:                    # the home base as designed (defines the map frame); absent:
//     corners:                    # coopmap's standard one; `none`: the map frame is the start
//       - {position: [0, -0.7], heading_deg: 180}
//       - {position: [0, 0.7], heading_deg: 180}
//     arm_length: 0.6
//     thickness: 0.04
//   route: [[1.0, 0.0], {at: [0.0, 0.0], spin: true}]   # mode route, map frame
//   settings: {sortie_budget_m: 25, ...}                  # agent_settings.h; absent: defaults
//
// Angles may be given in radians (heading_rad, face_rad, spin_rate_rad) instead of degrees:
// the writer does, with 17 significant digits, so that every number reads back exactly.
#pragma once

#include <string>

#include "core/agent/agent_settings.h"
#include "core/agent/robot_agent.h"
#include "core/io/yaml_reader.h"

namespace coopmap {

struct AgentConfig {
  AgentSetup setup;
  AgentSettings settings;
};

// Reads a configuration mapping (keys above; `name` and `map` required, the rest optional).
// Throws ConfigError naming the file, line and field.
AgentConfig readAgentConfig(const YamlField& mapping);
// The home base as designed, from a mapping {corners: [2 x {position, heading_deg}],
// arm_length, thickness}.
HomeBaseDesign readHomeBaseDesign(const YamlField& mapping);
// The configuration as YAML text, every number exact.
std::string agentConfigYaml(const AgentConfig& config);

}  // namespace coopmap

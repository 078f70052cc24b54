// Generated worlds (issue 44): office-like buildings a robot team has never seen, written as
// world files (world.h) in the style of worlds/lab.yaml. A building is one of four families:
//   corridor  rooms off one or both sides of a straight corridor
//   lt        an L or a T of corridors with rooms along them
//   loop      a corridor loop with rooms inside and outside it
//   open      an open plan with partitions and furniture islands, rooms along one side
// Each has 100-600 m^2 of floor, walls 0.1 m thick, doorways 0.9-1.2 m between wall ends
// (some with open door panels), desks, cabinets and tables clear of the doorways, textured
// walls (some low-texture plaster), one or two people walking the corridors, one or two
// slippery floor patches, and a start room holding the standard home base with the two
// robots jose and eric before it. Every world passes checkWorldExplorable (world_checks.h)
// before it is returned; a world that fails is drawn again (the next attempt of the same
// seed), so the same options always give the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace coopmap::sim {

struct WorldGeneratorOptions {
  uint64_t seed = 1;
  std::string family;          // one of worldFamilies(); empty: drawn from the seed
  std::optional<double> area;  // m^2 of floor in [kMinArea, kMaxArea]; empty: from the seed
  // Where the world file will be written: the robot model path is written relative to its
  // folder, and the world is loaded as that file to check it. Need not exist.
  std::string out_file = "world.yaml";
  // The robot model file; empty: robots/b14/b14.yaml of the source tree.
  std::string robot_model;

  static constexpr double kMinArea = 100.0, kMaxArea = 600.0;

  // Throws ConfigError naming the option (as the command line spells it) and what it expects.
  void validate() const;
};

struct GeneratedWorld {
  std::string yaml;         // the world file's text
  std::string family;       // the family built
  double area = 0.0;        // m^2 asked for (given or drawn)
  double floor_area = 0.0;  // m^2, the union of the floor rectangles
  int rooms = 0;            // rooms, the start room included (not corridors or the open plan)
  int doors = 0;            // doorways
  int attempt = 0;          // 0 for the first draw; more when earlier draws failed a check
};

// The families the generator builds, in the order the seed draws them.
const std::vector<std::string>& worldFamilies();

// Builds a world. Throws ConfigError for bad options, std::runtime_error if none of the
// seed's attempts passes the checks.
GeneratedWorld generateWorld(const WorldGeneratorOptions& options);

}  // namespace coopmap::sim

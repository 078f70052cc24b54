// The building the world generator lays out (sim/world/world_generator.cpp) before it is
// written as a world file (generated_world_yaml.cpp): zones on a grid of decimetres, their
// doorways, walls, furniture, the home base, the robots' starts, people and floor patches.
// Private to the generator.
#pragma once

#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sim/world/world.h"

namespace coopmap::sim::generated {

// The layout is drawn on a grid of decimetres: every wall line and doorway edge lies on it.
constexpr double kDm = 0.1;
constexpr double kHalfWall = 0.05;  // m, walls are 0.1 m thick, centred on the zone boundaries

// A rectangle of the layout grid, in dm.
struct Rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// A rectangle in metres.
struct Box2 {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  Box2 grown(double m) const { return {x0 - m, y0 - m, x1 + m, y1 + m}; }
};

inline Box2 metres(const Rect& r) { return {r.x0 * kDm, r.y0 * kDm, r.x1 * kDm, r.y1 * kDm}; }

// A band of rooms beside a corridor, split into rooms along x (along_x) or y.
struct Strip {
  Rect r;
  bool along_x = true;
  bool start = false;  // holds the start room
};

// A family's shape at one scale: the corridors (one zone, or the open plan) and room strips.
struct Plan {
  std::vector<Rect> corridors;
  std::vector<Strip> strips;
  bool open_plan = false;
  bool ring = false;  // the corridors form a loop
  Rect aisle;         // open plan: the band kept clear for walking
  std::string shape;  // for the header comment
};

enum class ZoneKind { kCorridor, kRoom, kOpen };
struct Zone {
  ZoneKind kind = ZoneKind::kRoom;
  std::vector<Rect> rects;
};

// A doorway: the wall edges [from, to) (dm) of a grid line removed between zones a and b.
struct Doorway {
  int a = 0, b = 0;
  bool vertical = false;  // on a line x = line
  int line = 0, from = 0, to = 0;
  bool panel = false;  // an open door panel is declared
  Eigen::Vector2d centre() const {
    const double mid = 0.5 * (from + to) * kDm;
    return vertical ? Eigen::Vector2d(line * kDm, mid) : Eigen::Vector2d(mid, line * kDm);
  }
  double width() const { return (to - from) * kDm; }
};

struct Layout {
  std::vector<Zone> zones;
  std::vector<Doorway> doors;
  int start_room = -1;
  int start_door = -1;
  int rooms = 0;
};

struct Furniture {
  Box2 footprint;
  double height = 0.75;
  std::string texture, label;
};

// Every draw of a world happens in this order: the shape, the scale, the rooms and doors,
// the home base, furniture, textures, people and floor patches.
struct Building {
  Plan plan;
  Layout layout;
  std::vector<WallSpec> walls;
  std::vector<std::pair<WallSpec, std::string>> partitions;
  std::vector<Furniture> furniture;
  HomeBaseSpec home_base;
  std::vector<std::pair<std::string, Pose2>> robots;
  std::vector<PersonSpec> people;
  std::vector<SurfaceSpec> surfaces;
  double floor_area = 0.0;
};

// The world file of a building: `header` (comment lines) first, then the world, the robots'
// model at `model` (as the file should name it).
std::string worldYaml(const Building& b, const std::string& header, const std::string& family,
                      uint64_t seed, const std::string& model);

// A number as the world files write it: at most 3 decimals, no trailing zeros.
std::string num(double v);

// Uniform draws from std::mt19937_64 words, the same on every platform.
class Draw {
 public:
  explicit Draw(uint64_t seed) : engine_(seed) {}
  double uniform(double a, double b) {
    return a + (b - a) * static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  }
  int integer(int a, int b) {  // in [a, b]
    if (b < a) throw std::logic_error("world generator: empty range drawn");
    return a + static_cast<int>(engine_() % static_cast<uint64_t>(b - a + 1));
  }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }

 private:
  std::mt19937_64 engine_;
};

// What stands in the building once its zones and doors are laid out
// (generated_contents.cpp), each drawn from `d` in this order:
// the home base and the robots in the start room (false: the room has no place for them)...
bool placeStart(Building& b, Draw& d);
// ... then the places furniture keeps clear of (doorways, the home base, the starts) ...
std::vector<Box2> keepOuts(const Building& b);
// ... furniture in a room ...
void furnishRoom(Building& b, const Rect& room, const std::vector<Box2>& keep_out, Draw& d);
// ... furniture islands and partitions in the open plan ...
void furnishOpenPlan(Building& b, const std::vector<Box2>& keep_out, Draw& d);
// ... and, after the walls, people walking and slippery floor patches.
void addPeopleAndPatches(Building& b, Draw& d);

}  // namespace coopmap::sim::generated

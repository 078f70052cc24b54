// The world model: what a world file (YAML) describes.
#pragma once

#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/agent/route_follower.h"
#include "core/geometry/pose2.h"

namespace coopmap::sim {

enum class TextureType { kNoise, kBricks, kPosters, kUniform };

// A procedural grey texture, tiled over surfaces in world units.
struct TextureSpec {
  std::string name;
  TextureType type = TextureType::kNoise;
  double tile = 1.0;       // m covered by one repeat of the texture
  double feature = 0.05;   // m, size of the smallest pattern features
  double mean = 128.0;     // grey level
  double contrast = 50.0;  // grey-level amplitude of the pattern
  uint64_t seed = 0;       // derived from the world seed and the name unless given
};

// A solid, axis-aligned-in-its-own-frame box standing on the floor (or raised by z0).
struct SolidBox {
  Eigen::Vector2d center{0.0, 0.0};     // m, world
  Eigen::Vector3d size{1.0, 1.0, 1.0};  // m: length along yaw, width, height
  double yaw = 0.0;                     // rad
  double z0 = 0.0;                      // m, bottom above the floor
  std::string texture;
  std::string kind;  // "wall", "box", "door", "home_base" (for people and tools)
};

struct WallSpec {
  Eigen::Vector2d from{0.0, 0.0}, to{1.0, 0.0};
  double thickness = 0.1;
  double height = 2.5;
  std::string texture;
};

struct DoorSpec {
  Eigen::Vector2d center{0.0, 0.0};
  double width = 0.9;
  double yaw = 0.0;  // direction along the doorway
  bool open = true;  // at the start
  std::string texture;
  std::vector<std::pair<double, bool>> schedule;  // (time s, open) changes, in time order

  bool openAt(double t) const;
  bool scheduled() const { return !schedule.empty(); }
  SolidBox panel() const;  // the closed door's box
};

// The home-base landmark: two L-shaped corners. Each corner's arms leave its vertex at
// heading +/- 45 degrees, so `heading` points into the corner's concave side.
struct HomeBaseSpec {
  struct Corner {
    Eigen::Vector2d position{0.0, 0.0};
    double heading = 0.0;
  };
  std::vector<Corner> corners;  // exactly two
  double arm_length = 0.6;
  double thickness = 0.04;
  double height = 1.2;
  std::string texture;
};

// A person walking a path at a steady speed (a kinematic body: it pushes, it is not pushed).
// A person waits for robots: they pause while a robot stands ahead of them and near (see
// yieldsTo), so where they are depends on their "walked time", the seconds they have spent
// walking since start_time; the simulator keeps it.
struct PersonSpec {
  std::string name;
  double radius = 0.25;               // m
  double height = 1.7;                // m
  double speed = 1.2;                 // m/s
  double start_time = 0;              // s: stands at the path's start until then
  bool loop = false;                  // walk the path again and again; else stop at its end
  double yield_distance = 1.0;        // m of free space kept to a robot ahead; 0: never waits
  std::vector<Eigen::Vector2d> path;  // at least two points

  // Half-angle of "ahead" (rad): a robot within 75 degrees of the walking direction.
  static constexpr double kYieldHalfAngle = 75.0 * std::numbers::pi / 180.0;

  // A place on the path: where the person stands and the unit direction they walk in
  // there (the current segment's; zero where walking on would not move them: at the end
  // of a path that does not loop, or at speed 0). World frame, m.
  struct Place {
    Eigen::Vector2d position{0.0, 0.0};
    Eigen::Vector2d direction{0.0, 0.0};
  };
  // Where the person is after walking for `walked` seconds (pauses not counted).
  Place placeAtWalked(double walked) const;
  Eigen::Vector2d positionAtWalked(double walked) const { return placeAtWalked(walked).position; }
  // Where the person stands at time t (s) if nothing ever made them wait.
  Eigen::Vector2d positionAt(double t) const;
  // True if a robot (centre `robot`, m, world; radius `robot_radius`, m) makes the person
  // wait at walked time `walked`: its centre is within yield_distance + radius +
  // robot_radius of the person's and within kYieldHalfAngle of the walking direction.
  bool yieldsTo(double walked, const Eigen::Vector2d& robot, double robot_radius) const;
};

// A floor patch whose wheel-floor friction replaces the robot's own (tile, a wet or dusty
// patch): less friction, more slip.
struct SurfaceSpec {
  std::string name;
  Eigen::Vector2d min{0.0, 0.0}, max{1.0, 1.0};  // m, axis-aligned rectangle
  double traction_mu = 0.8;
  bool contains(const Eigen::Vector2d& p) const {
    return p.x() >= min.x() && p.y() >= min.y() && p.x() <= max.x() && p.y() <= max.y();
  }
};

// A planar checkerboard target (for camera calibration): squares_x x squares_y squares, the
// top-left one black, inside a white border; single-sided. Its board frame B is OpenCV's:
// origin at the board's centre, x along a row (to the right seen from the front), y down a
// column, z into the board. At yaw = pitch = roll = 0 it stands upright facing world +x; then
// it turns by `yaw` about world z, tilts by `pitch` about its own x (positive brings the top
// edge towards the viewer), and turns by `roll` about its own z.
struct TargetSpec {
  Eigen::Vector3d center{0.0, 0.0, 1.0};      // m, world
  int squares_x = 10, squares_y = 7;          // squares along a row, along a column
  double square = 0.04;                       // m, side of a square
  double border = 1.0;                        // white border width, in squares
  double yaw = 0.0, pitch = 0.0, roll = 0.0;  // rad
  double black = 20.0, white = 235.0;         // grey levels of the print

  // Rotation R_WB of the board frame in the world.
  Eigen::Matrix3d rotation() const;
  // Inner corner (i, j) in the world (m): i = 0..squares_x-2 along a row, j down a column,
  // in the order cv::findChessboardCorners reports an upright board's corners.
  Eigen::Vector3d cornerInWorld(int i, int j) const;
};

struct RobotSpec {
  std::string name;
  std::string model_file;  // resolved path of the robot model YAML
  Pose2 start;
  std::vector<Waypoint> route;
};

// An axis-aligned rectangle of floor (m).
struct FloorArea {
  Eigen::Vector2d min, max;
};

struct World {
  std::string name;
  std::string file;  // where it was loaded from
  uint64_t seed = 1;
  // The floor's bounding rectangle; the floor itself is `floor_areas` (rectangles, e.g. the
  // rooms and corridors of a building), or all of the bounding rectangle if that is empty.
  Eigen::Vector2d floor_min{0.0, 0.0}, floor_max{10.0, 8.0};
  std::vector<FloorArea> floor_areas;
  std::string floor_texture;
  std::map<std::string, TextureSpec> textures;
  std::vector<WallSpec> walls;
  std::vector<SolidBox> boxes;
  std::vector<DoorSpec> doors;
  HomeBaseSpec home_base;
  std::vector<RobotSpec> robots;
  std::vector<PersonSpec> people;
  std::vector<SurfaceSpec> surfaces;
  std::vector<TargetSpec> targets;  // drawn by the renderer only: they take no physical space
  double map_resolution = 0.05;     // m per cell for maps and ground truth
  double physics_rate = 200.0;      // Hz
  double control_rate = 20.0;       // Hz

  // The floor's rectangles: `floor_areas`, or the bounding rectangle if that is empty.
  std::vector<FloorArea> floorRects() const;
  // Whether p lies on the floor (edges included).
  bool onFloor(const Eigen::Vector2d& p) const;

  // Every solid that never moves, as boxes: walls, furniture, doors that stay closed,
  // home-base arms.
  std::vector<SolidBox> solids() const;
  // Solids that come and go: the doors on a schedule that are closed at time t (s).
  std::vector<SolidBox> doorsClosedAt(double t) const;
};

// Loads a world file. Errors (ConfigError) name the file, line and field.
World loadWorld(const std::string& path);
// Parses world text; `file` names it in messages and anchors relative paths.
World parseWorld(const std::string& text, const std::string& file);

}  // namespace coopmap::sim

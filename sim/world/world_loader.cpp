#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/agent/cooperation.h"
#include "core/agent/route_follower.h"
#include "core/io/yaml_reader.h"
#include "core/robot/robot_interface.h"
#include "sim/world/world.h"
#include "sim/world/world_checks.h"

namespace coopmap::sim {

namespace {

// m, as messages write it.
std::string formatMetres(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f m", v);
  return b;
}

// The body radius a robot model file gives (body.radius); the description's default where
// the file has none (the model's own loader checks the file in full).
double bodyRadiusOf(const std::string& model_file) {
  const YamlField model = YamlField::loadFile(model_file);
  if (const auto body = model.get("body"))
    if (const auto radius = body->get("radius"))
      return radius->asDouble(0.05, 2.0, "a radius in [0.05, 2] m");
  return RobotDescription{}.body_radius;
}
constexpr double kDeg = M_PI / 180.0;

uint64_t fnv1a(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

TextureSpec parseTexture(const YamlField& f, const std::string& name, uint64_t world_seed) {
  f.allowOnly({"type", "tile", "feature", "mean", "contrast", "seed"});
  TextureSpec t;
  t.name = name;
  const std::string type = f["type"].asEnum({"noise", "bricks", "posters", "uniform"});
  t.type = type == "noise"     ? TextureType::kNoise
           : type == "bricks"  ? TextureType::kBricks
           : type == "posters" ? TextureType::kPosters
                               : TextureType::kUniform;
  t.tile = optionalDouble(f, "tile", t.tile, 0.05, 100.0, "a tile size in [0.05, 100] m");
  t.feature =
      optionalDouble(f, "feature", t.feature, 0.005, t.tile, "a feature size in [0.005 m, tile]");
  t.mean = optionalDouble(f, "mean", t.mean, 0.0, 255.0, "a grey level in [0, 255]");
  t.contrast = optionalDouble(f, "contrast", t.contrast, 0.0, 127.0, "a contrast in [0, 127]");
  t.seed = f.has("seed") ? static_cast<uint64_t>(f["seed"].asInt(0, 1 << 30))
                         : world_seed * 0x9E3779B97F4A7C15ull ^ fnv1a(name);
  return t;
}

std::string textureRef(const YamlField& parent, const World& w, const std::string& fallback) {
  if (!parent.has("texture")) {
    if (fallback.empty()) parent.failMessage("missing required field 'texture'");
    return fallback;
  }
  const YamlField f = parent["texture"];
  const std::string name = f.asString();
  if (!w.textures.count(name)) {
    std::string known;
    for (const auto& [k, v] : w.textures) known += (known.empty() ? "" : ", ") + k;
    f.fail("the name of a texture declared under 'textures' (" + known + ")");
  }
  return name;
}

Pose2 parseStart(const YamlField& f) {
  f.allowOnly({"position", "heading_deg"});
  const Eigen::Vector2d p = f["position"].asVector2();
  const double h =
      f.has("heading_deg") ? f["heading_deg"].asDouble(-360, 360, "degrees in [-360, 360]") : 0.0;
  return {p.x(), p.y(), wrapAngle(h * kDeg)};
}

bool inside(const World& w, const Eigen::Vector2d& p) { return w.onFloor(p); }

FloorArea parseFloorArea(const YamlField& f) {
  const FloorArea a{f["min"].asVector2(), f["max"].asVector2()};
  if (!(a.max.x() > a.min.x() && a.max.y() > a.min.y()))
    f["max"].fail("a corner above and to the right of 'min'");
  return a;
}
}  // namespace

bool DoorSpec::openAt(double t) const {
  bool state = open;
  for (const auto& [at, opened] : schedule)
    if (at <= t) state = opened;
  return state;
}

SolidBox DoorSpec::panel() const {
  SolidBox b;
  b.center = center;
  b.size = {width, 0.05, 2.0};
  b.yaw = yaw;
  b.texture = texture;
  b.kind = "door";
  return b;
}

std::vector<SolidBox> World::doorsClosedAt(double t) const {
  std::vector<SolidBox> out;
  for (const DoorSpec& door : doors)
    if (door.scheduled() && !door.openAt(t)) out.push_back(door.panel());
  return out;
}

std::vector<FloorArea> World::floorRects() const {
  if (!floor_areas.empty()) return floor_areas;
  return {FloorArea{floor_min, floor_max}};
}

bool World::onFloor(const Eigen::Vector2d& p) const {
  for (const FloorArea& a : floorRects())
    if (p.x() >= a.min.x() && p.y() >= a.min.y() && p.x() <= a.max.x() && p.y() <= a.max.y())
      return true;
  return false;
}

std::vector<SolidBox> World::solids() const {
  std::vector<SolidBox> out;
  for (const WallSpec& wall : walls) {
    const Eigen::Vector2d d = wall.to - wall.from;
    SolidBox b;
    b.center = 0.5 * (wall.from + wall.to);
    b.size = {d.norm() + wall.thickness, wall.thickness, wall.height};  // overlapping ends
    b.yaw = std::atan2(d.y(), d.x());
    b.texture = wall.texture;
    b.kind = "wall";
    out.push_back(b);
  }
  for (const SolidBox& box : boxes) out.push_back(box);
  for (const DoorSpec& door : doors)
    if (!door.open && !door.scheduled()) out.push_back(door.panel());
  const HomeBaseSpec& hb = home_base;
  for (const HomeBaseSpec::Corner& c : hb.corners) {
    for (double side : {-1.0, 1.0}) {
      const double a = c.heading + side * M_PI / 4.0;
      const Eigen::Vector2d dir(std::cos(a), std::sin(a));
      SolidBox b;
      // The arm's outer face passes through the vertex; the arm extends arm_length.
      b.center = c.position + dir * (0.5 * hb.arm_length);
      b.size = {hb.arm_length + hb.thickness, hb.thickness, hb.height};
      b.yaw = a;
      b.texture = hb.texture;
      b.kind = "home_base";
      out.push_back(b);
    }
  }
  return out;
}

PersonSpec::Place PersonSpec::placeAtWalked(double walked) const {
  if (path.size() < 2) return {path.empty() ? Eigen::Vector2d::Zero() : path.front(), {0.0, 0.0}};
  double length = 0.0;
  for (size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  double s = std::max(0.0, walked) * speed;
  if (loop) {
    const double lap = length + (path.back() - path.front()).norm();
    s = lap > 0.0 ? std::fmod(s, lap) : 0.0;
  } else if (s >= length) {
    return {path.back(), {0.0, 0.0}};
  }
  // Along the path, closing it back to the start when looping.
  const size_t segments = loop ? path.size() : path.size() - 1;
  for (size_t i = 0; i < segments; ++i) {
    const Eigen::Vector2d& a = path[i];
    const Eigen::Vector2d& b = path[(i + 1) % path.size()];
    const double seg = (b - a).norm();
    if (seg > 0.0 && (s < seg || i + 1 == segments)) {
      const Eigen::Vector2d direction =
          speed > 0.0 ? Eigen::Vector2d((b - a) / seg) : Eigen::Vector2d::Zero();
      return {a + (b - a) * std::min(1.0, s / seg), direction};
    }
    s -= seg;
  }
  return {path.back(), {0.0, 0.0}};
}

Eigen::Vector2d PersonSpec::positionAt(double t) const {
  return positionAtWalked(std::max(0.0, t - start_time));
}

bool PersonSpec::yieldsTo(double walked, const Eigen::Vector2d& robot, double robot_radius) const {
  if (!(yield_distance > 0.0)) return false;
  const Place here = placeAtWalked(walked);
  if (here.direction.isZero()) return false;  // not walking: nothing to wait for
  const Eigen::Vector2d d = robot - here.position;
  const double reach = yield_distance + radius + robot_radius;
  const double dist = d.norm();
  if (dist > reach) return false;
  return dist == 0.0 || d.dot(here.direction) >= dist * std::cos(kYieldHalfAngle);
}

Eigen::Matrix3d TargetSpec::rotation() const {
  // Upright and facing +x: board x = world y, board y = -world z, board z = -world x.
  Eigen::Matrix3d upright;
  upright << 0, 0, -1, 1, 0, 0, 0, -1, 0;
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  const double cr = std::cos(roll), sr = std::sin(roll);
  Eigen::Matrix3d Rz, Rx, Rn;
  Rz << cy, -sy, 0, sy, cy, 0, 0, 0, 1;
  Rx << 1, 0, 0, 0, cp, -sp, 0, sp, cp;
  Rn << cr, -sr, 0, sr, cr, 0, 0, 0, 1;
  return Rz * upright * Rx * Rn;
}

Eigen::Vector3d TargetSpec::cornerInWorld(int i, int j) const {
  const Eigen::Vector3d p_B((i + 1 - 0.5 * squares_x) * square, (j + 1 - 0.5 * squares_y) * square,
                            0.0);
  return center + rotation() * p_B;
}

World parseWorld(const std::string& text, const std::string& file) {
  const YamlField root = YamlField::loadString(text, file);
  root.allowOnly({"name", "seed", "floor", "simulation", "textures", "walls", "boxes", "doors",
                  "home_base", "robots", "people", "surfaces", "targets", "mission"});
  World w;
  w.file = file;
  w.name = root["name"].asString();
  if (const auto mission = root.get("mission"))
    mission->failMessage(
        "a world describes the world, not how robots run in it: `coopmap run` follows the "
        "robots' routes where the world gives them and explores otherwise (--routes, "
        "--explore), and the robots' settings are given with `coopmap run --settings FILE` or "
        "as flags");
  if (root.has("seed")) w.seed = static_cast<uint64_t>(root["seed"].asInt(0, 1 << 30));

  const YamlField textures = root["textures"];
  for (const std::string& name : textures.keys())
    w.textures[name] = parseTexture(textures[name], name, w.seed);

  const YamlField floor = root["floor"];
  // Either one rectangle (min, max) or the rectangles of rooms and corridors (areas).
  floor.allowOnly({"min", "max", "areas", "texture"});
  if (floor.has("areas") == (floor.has("min") || floor.has("max")))
    floor.failMessage(
        "expected either 'min' and 'max' (one rectangle) or 'areas' (a list of "
        "{min, max} rectangles)" +
        std::string(floor.has("areas") ? ", not both" : ""));
  if (floor.has("areas")) {
    const YamlField areas = floor["areas"];
    const std::vector<YamlField> items =
        areas.isSequence() ? areas.elements() : std::vector<YamlField>{};
    if (items.empty()) areas.fail("a non-empty list of {min, max} rectangles");
    for (const YamlField& item : items) {
      item.allowOnly({"min", "max"});
      w.floor_areas.push_back(parseFloorArea(item));
    }
    w.floor_min = w.floor_areas.front().min;
    w.floor_max = w.floor_areas.front().max;
    for (const FloorArea& a : w.floor_areas) {
      w.floor_min = w.floor_min.cwiseMin(a.min);
      w.floor_max = w.floor_max.cwiseMax(a.max);
    }
  } else {
    const FloorArea a = parseFloorArea(floor);
    w.floor_min = a.min;
    w.floor_max = a.max;
  }
  w.floor_texture = textureRef(floor, w, "");

  if (const auto sim = root.get("simulation")) {
    sim->allowOnly({"map_resolution", "physics_rate", "control_rate"});
    w.map_resolution = optionalDouble(*sim, "map_resolution", w.map_resolution, 0.01, 1.0,
                                      "a cell size in [0.01, 1] m");
    w.physics_rate = optionalDouble(*sim, "physics_rate", w.physics_rate, 50.0, 2000.0,
                                    "a rate in [50, 2000] Hz");
    w.control_rate =
        optionalDouble(*sim, "control_rate", w.control_rate, 1.0, 200.0, "a rate in [1, 200] Hz");
  }
  // The maps cover the floor at map_resolution: their size is checked before any is made.
  {
    const Eigen::Vector2d cells = (w.floor_max - w.floor_min) / w.map_resolution;
    const std::string problem = mapSizeProblem(std::ceil(cells.x()), std::ceil(cells.y()));
    char resolution[32];
    std::snprintf(resolution, sizeof resolution, "%g", w.map_resolution);
    if (!problem.empty())
      floor.failMessage(std::string("the floor at map_resolution ") + resolution + " m: expected " +
                        problem);
  }

  for (const YamlField& f : root["walls"].elements()) {
    f.allowOnly({"from", "to", "thickness", "height", "texture"});
    WallSpec wall;
    wall.from = f["from"].asVector2();
    wall.to = f["to"].asVector2();
    if ((wall.to - wall.from).norm() < 1e-3) f["to"].fail("a point different from 'from'");
    wall.thickness =
        optionalDouble(f, "thickness", wall.thickness, 0.01, 2.0, "a positive thickness up to 2 m");
    wall.height = optionalDouble(f, "height", wall.height, 0.05, 20.0, "a height in [0.05, 20] m");
    wall.texture = textureRef(f, w, "");
    w.walls.push_back(wall);
  }
  if (const auto boxes = root.get("boxes")) {
    for (const YamlField& f : boxes->elements()) {
      f.allowOnly({"center", "size", "yaw_deg", "z0", "texture"});
      SolidBox b;
      b.center = f["center"].asVector2();
      b.size = f["size"].asVector3();
      if (!(b.size.minCoeff() > 0.0))
        f["size"].fail("three positive sizes [length, width, height]");
      b.yaw = optionalDouble(f, "yaw_deg", 0.0, -360, 360, "degrees in [-360, 360]") * kDeg;
      b.z0 = optionalDouble(f, "z0", 0.0, 0.0, 10.0, "a height in [0, 10] m");
      b.texture = textureRef(f, w, "");
      b.kind = "box";
      if (!inside(w, b.center)) f["center"].fail("a point on the floor");
      w.boxes.push_back(b);
    }
  }
  if (const auto doors = root.get("doors")) {
    for (const YamlField& f : doors->elements()) {
      f.allowOnly({"center", "width", "yaw_deg", "open", "texture", "schedule"});
      DoorSpec d;
      d.center = f["center"].asVector2();
      d.width = optionalDouble(f, "width", d.width, 0.3, 5.0, "a width in [0.3, 5] m");
      d.yaw = optionalDouble(f, "yaw_deg", 0.0, -360, 360, "degrees in [-360, 360]") * kDeg;
      if (f.has("open")) d.open = f["open"].asBool();
      d.texture = textureRef(f, w, w.walls.empty() ? "" : w.walls.front().texture);
      if (const auto schedule = f.get("schedule")) {
        double last = -1.0;
        for (const YamlField& e : schedule->elements()) {
          e.allowOnly({"at", "open"});
          const double at = e["at"].asDouble(0.0, 1e7, "a time >= 0 s");
          if (at <= last) e["at"].fail("a time after the previous change");
          last = at;
          d.schedule.push_back({at, e["open"].asBool()});
        }
      }
      // The door fills its doorway, no more: its leaf may not reach into a wall's run (the
      // walls' square end caps, half a thickness past their ends, may touch it).
      const Eigen::Vector2d along(std::cos(d.yaw), std::sin(d.yaw));
      for (const WallSpec& wall : w.walls) {
        const Eigen::Vector2d run = wall.to - wall.from, u = run.normalized();
        double deepest = 0.0;
        for (double t = -0.5 * d.width; t <= 0.5 * d.width; t += 0.005) {
          const Eigen::Vector2d q = d.center + t * along - wall.from;
          const double s = q.dot(u);
          if (std::abs(q.x() * u.y() - q.y() * u.x()) < 0.5 * wall.thickness && s > 0.0 &&
              s < run.norm())
            deepest = std::max(deepest, std::min(s, run.norm() - s));
        }
        if (deepest > 0.01)
          f["width"].failMessage(
              "a door no wider than its doorway: " + formatMetres(d.width) + " wide at (" +
              formatMetres(d.center.x()) + ", " + formatMetres(d.center.y()) + "), it reaches " +
              formatMetres(deepest) + " into the wall from (" + formatMetres(wall.from.x()) + ", " +
              formatMetres(wall.from.y()) + ") to (" + formatMetres(wall.to.x()) + ", " +
              formatMetres(wall.to.y()) + ")");
      }
      w.doors.push_back(d);
    }
  }

  // Optional: without one, robots map in their own start frames.
  if (const auto home = root.get("home_base")) {
    const YamlField& hb = *home;
    hb.allowOnly({"corners", "arm_length", "thickness", "height", "texture"});
    const auto corners = hb["corners"].elements();
    if (corners.size() != 2) hb["corners"].fail("exactly 2 corners");
    for (const YamlField& c : corners) {
      c.allowOnly({"position", "heading_deg"});
      HomeBaseSpec::Corner corner;
      corner.position = c["position"].asVector2();
      corner.heading = c["heading_deg"].asDouble(-360, 360, "degrees in [-360, 360]") * kDeg;
      if (!inside(w, corner.position)) c["position"].fail("a point on the floor");
      w.home_base.corners.push_back(corner);
    }
    w.home_base.arm_length = optionalDouble(hb, "arm_length", w.home_base.arm_length, 0.2, 3.0,
                                            "a length in [0.2, 3] m");
    w.home_base.thickness = optionalDouble(hb, "thickness", w.home_base.thickness, 0.01, 0.5,
                                           "a thickness in [0.01, 0.5] m");
    w.home_base.height =
        optionalDouble(hb, "height", w.home_base.height, 0.3, 3.0, "a height in [0.3, 3] m");
    w.home_base.texture = textureRef(hb, w, "");
  }

  if (const auto surfaces = root.get("surfaces")) {
    for (const YamlField& f : surfaces->elements()) {
      f.allowOnly({"name", "min", "max", "traction_mu"});
      SurfaceSpec sp;
      sp.name = f["name"].asString();
      sp.min = f["min"].asVector2();
      sp.max = f["max"].asVector2();
      if (!(sp.max.x() > sp.min.x() && sp.max.y() > sp.min.y()))
        f["max"].fail("a corner above and to the right of 'min'");
      sp.traction_mu = f["traction_mu"].asDouble(0.01, 3.0, "a friction coefficient in [0.01, 3]");
      w.surfaces.push_back(sp);
    }
  }
  if (const auto people = root.get("people")) {
    for (const YamlField& f : people->elements()) {
      f.allowOnly(
          {"name", "radius", "height", "speed", "start_time", "loop", "yield_distance", "path"});
      PersonSpec p;
      p.name = f["name"].asString();
      p.radius = optionalDouble(f, "radius", p.radius, 0.1, 1.0, "a radius in [0.1, 1] m");
      p.height = optionalDouble(f, "height", p.height, 0.5, 2.5, "a height in [0.5, 2.5] m");
      p.speed = optionalDouble(f, "speed", p.speed, 0.0, 3.0, "a walking speed in [0, 3] m/s");
      p.start_time = optionalDouble(f, "start_time", 0.0, 0.0, 1e6, "a time >= 0 s");
      if (f.has("loop")) p.loop = f["loop"].asBool();
      p.yield_distance = optionalDouble(f, "yield_distance", p.yield_distance, 0.0, 100.0,
                                        "a distance in [0, 100] m (0: never waits for robots)");
      const auto points = f["path"].elements();
      if (points.size() < 2) f["path"].fail("a list of at least 2 points");
      for (const YamlField& pt : points) {
        p.path.push_back(pt.asVector2());
        if (!inside(w, p.path.back())) pt.fail("a point on the floor");
      }
      w.people.push_back(std::move(p));
    }
  }

  if (const auto targets = root.get("targets")) {
    for (const YamlField& f : targets->elements()) {
      f.allowOnly({"center", "squares", "square", "border", "yaw_deg", "pitch_deg", "roll_deg"});
      TargetSpec t;
      t.center = f["center"].asVector3();
      const YamlField squares = f["squares"];
      const auto counts = squares.elements();
      if (counts.size() != 2) squares.fail("[squares along a row, squares along a column]");
      t.squares_x = counts[0].asInt(3, 100);
      t.squares_y = counts[1].asInt(3, 100);
      t.square = f["square"].asDouble(0.001, 1.0, "a square side in [0.001, 1] m");
      t.border = optionalDouble(f, "border", t.border, 0.0, 10.0, "a border in [0, 10] squares");
      t.yaw = optionalDouble(f, "yaw_deg", 0.0, -360, 360, "degrees in [-360, 360]") * kDeg;
      t.pitch = optionalDouble(f, "pitch_deg", 0.0, -89, 89, "degrees in [-89, 89]") * kDeg;
      t.roll = optionalDouble(f, "roll_deg", 0.0, -360, 360, "degrees in [-360, 360]") * kDeg;
      w.targets.push_back(t);
    }
  }

  const std::filesystem::path base = std::filesystem::path(file).parent_path();
  std::set<std::string> names;
  std::vector<double> radii;  // of the robots loaded so far
  const auto robots = root["robots"].elements();
  if (robots.empty()) root["robots"].fail("at least one robot");
  for (const YamlField& f : robots) {
    f.allowOnly({"name", "model", "start", "route"});
    RobotSpec r;
    r.name = f["name"].asString();
    if (r.name.empty() ||
        r.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
      f["name"].fail("a name of lower-case letters, digits, '_' or '-'");
    if (!names.insert(r.name).second) f["name"].fail("a name not used by another robot");
    const std::string model = f["model"].asString();
    r.model_file = (base / model).lexically_normal().string();
    if (!std::filesystem::exists(r.model_file))
      f["model"].fail("the path of a robot model file relative to the world file (" + r.model_file +
                      " does not exist)");
    r.start = parseStart(f["start"]);
    if (!inside(w, r.start.translation())) f["start"].fail("a start position on the floor");
    // Where the robot's body stands, nothing else may: no solid, no other robot.
    const double radius = bodyRadiusOf(r.model_file);
    const Eigen::Vector2d at = r.start.translation();
    for (const SolidBox& solid : w.solids())
      if (solid.kind != "door" && distanceToFootprint(solid, at) < radius)
        f["start"].failMessage("the robot's body (radius " + formatMetres(radius) + ") at (" +
                               formatMetres(at.x()) + ", " + formatMetres(at.y()) +
                               ") overlaps a " + solid.kind + " of the world");
    for (size_t k = 0; k < w.robots.size(); ++k)
      if ((w.robots[k].start.translation() - at).norm() < radius + radii[k])
        f["start"].failMessage(
            "the robot's body overlaps " + w.robots[k].name + "'s at its start (" +
            formatMetres((w.robots[k].start.translation() - at).norm()) +
            " apart, their radii add up to " + formatMetres(radius + radii[k]) + ")");
    radii.push_back(radius);
    if (const auto route = f.get("route"))
      for (const YamlField& wp : route->elements()) {
        r.route.push_back(parseWaypoint(wp));
        if (!inside(w, r.route.back().position)) wp.fail("a waypoint on the floor");
      }
    w.robots.push_back(std::move(r));
  }
  return w;
}

World loadWorld(const std::string& path) {
  std::ifstream probe(path);
  if (!probe) throw ConfigError(path + ": cannot open world file");
  std::stringstream ss;
  ss << probe.rdbuf();
  return parseWorld(ss.str(), path);
}

}  // namespace coopmap::sim

// A generated building written as a world file (docs/formats.md), in the style of worlds/.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sim/world/generated_building.h"

namespace coopmap::sim::generated {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}
namespace {

std::string point(const Eigen::Vector2d& p) { return "[" + num(p.x()) + ", " + num(p.y()) + "]"; }
double degrees(double rad) { return rad * 180.0 / M_PI; }

}  // namespace

std::string worldYaml(const Building& b, const std::string& header, const std::string& family,
                      uint64_t seed, const std::string& model) {
  const Layout& l = b.layout;
  int panels = 0;
  for (const Doorway& dw : l.doors) panels += dw.panel;
  std::ostringstream o;
  o << header;
  char buf[256];
  std::snprintf(buf, sizeof buf, "# An office building (family %s) of %.0f m^2: %s.\n",
                family.c_str(), b.floor_area, b.plan.shape.c_str());
  o << buf;
  std::snprintf(buf, sizeof buf,
                "# %d rooms, %d doorways (%d with an open door panel); jose and eric start in "
                "a room\n",
                l.rooms, static_cast<int>(l.doors.size()), panels);
  o << buf;
  o << "# before the home base. The robot model path is relative to this file's folder.\n"
       "# Units: metres; angles in keys ending _deg.\n";
  o << "name: generated_" << family << "_" << seed << "\n";
  o << "seed: " << seed % (1u << 30) << "\n";
  o << "\n";
  o << "simulation:\n  map_resolution: 0.05\n  physics_rate: 200\n  control_rate: 20\n\n";
  o << "textures:\n"
       "  carpet:  {type: noise,   tile: 2.0, feature: 0.03, mean: 105, contrast: 30}\n"
       "  brick:   {type: bricks,  tile: 2.0, feature: 0.02, mean: 120, contrast: 55}\n"
       "  poster:  {type: posters, tile: 2.5, feature: 0.04, mean: 128, contrast: 70}\n"
       "  plaster: {type: uniform, tile: 2.0, feature: 0.10, mean: 190, contrast: 4}   # low "
       "texture\n"
       "  wood:    {type: noise,   tile: 1.0, feature: 0.02, mean: 140, contrast: 55}\n"
       "  metal:   {type: noise,   tile: 1.0, feature: 0.04, mean: 100, contrast: 45}\n"
       "  landmark: {type: posters, tile: 1.0, feature: 0.02, mean: 128, contrast: 80}\n\n";

  o << "# The floor: each room and corridor to the outer faces of its walls.\n";
  o << "floor:\n  texture: carpet\n  areas:\n";
  int room_number = 0;
  for (size_t z = 0; z < l.zones.size(); ++z) {
    const Zone& zone = l.zones[z];
    std::string what = zone.kind == ZoneKind::kOpen       ? "open plan"
                       : zone.kind == ZoneKind::kCorridor ? "corridor"
                                                          : "room " + std::to_string(++room_number);
    if (static_cast<int>(z) == l.start_room) what += " (start room)";
    for (const Rect& r : zone.rects) {
      const Box2 m = metres(r).grown(kHalfWall);
      o << "    - {min: " << point({m.x0, m.y0}) << ", max: " << point({m.x1, m.y1}) << "}   # "
        << what << "\n";
    }
  }

  o << "\nwalls:\n";
  for (const WallSpec& w : b.walls)
    o << "  - {from: " << point(w.from) << ", to: " << point(w.to)
      << ", thickness: " << num(w.thickness) << ", height: " << num(w.height)
      << ", texture: " << w.texture << "}\n";
  for (const auto& [w, label] : b.partitions)
    o << "  - {from: " << point(w.from) << ", to: " << point(w.to)
      << ", thickness: " << num(w.thickness) << ", height: " << num(w.height)
      << ", texture: " << w.texture << "}   # " << label << "\n";

  if (panels > 0) {
    o << "\n# Doorways with a door panel, standing open (the others are plain openings).\n";
    o << "doors:\n";
    for (const Doorway& dw : l.doors)
      if (dw.panel)
        o << "  - {center: " << point(dw.centre()) << ", width: " << num(dw.width())
          << ", yaw_deg: " << (dw.vertical ? 90 : 0) << ", open: true}\n";
  }

  if (!b.furniture.empty()) {
    o << "\nboxes:\n";
    for (const Furniture& f : b.furniture) {
      const Box2& m = f.footprint;
      o << "  - {center: " << point({0.5 * (m.x0 + m.x1), 0.5 * (m.y0 + m.y1)}) << ", size: ["
        << num(m.x1 - m.x0) << ", " << num(m.y1 - m.y0) << ", " << num(f.height)
        << "], texture: " << f.texture << "}   # " << f.label << "\n";
    }
  }

  o << "\n# Slippery floor: patches with less wheel friction than the robot's own.\n";
  o << "surfaces:\n";
  for (const SurfaceSpec& s : b.surfaces)
    o << "  - {name: " << s.name << ", min: " << point(s.min) << ", max: " << point(s.max)
      << ", traction_mu: " << num(s.traction_mu) << "}\n";

  o << "\n# People walking the corridors, to and fro (they wait for a robot ahead of them).\n";
  o << "people:\n";
  for (const PersonSpec& p : b.people) {
    o << "  - {name: " << p.name << ", radius: " << num(p.radius) << ", speed: " << num(p.speed)
      << ", start_time: " << num(p.start_time) << ", loop: true, path: [";
    for (size_t k = 0; k < p.path.size(); ++k) o << (k ? ", " : "") << point(p.path[k]);
    o << "]}\n";
  }

  o << "\n# The standard home base: two L corners 1.4 m apart opening towards the robots.\n";
  o << "home_base:\n  corners:\n";
  for (const auto& c : b.home_base.corners)
    o << "    - {position: " << point(c.position) << ", heading_deg: " << num(degrees(c.heading))
      << "}\n";
  o << "  arm_length: " << num(b.home_base.arm_length)
    << "\n  thickness: " << num(b.home_base.thickness) << "\n  height: " << num(b.home_base.height)
    << "\n  texture: landmark\n";

  o << "\nrobots:\n";
  for (const auto& [name, start] : b.robots)
    o << "  - name: " << name << "\n    model: " << model
      << "\n    start: {position: " << point(start.translation())
      << ", heading_deg: " << num(degrees(start.theta)) << "}\n";
  return o.str();
}

}  // namespace coopmap::sim::generated

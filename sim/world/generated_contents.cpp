// What stands in a generated building (generated_building.h): the home base and the robots'
// starts, furniture, people and slippery floor patches.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sim/world/generated_building.h"

namespace coopmap::sim::generated {

namespace {

double gap(const Box2& a, const Box2& b) {
  const double dx = std::max({0.0, a.x0 - b.x1, b.x0 - a.x1});
  const double dy = std::max({0.0, a.y0 - b.y1, b.y0 - a.y1});
  return std::hypot(dx, dy);
}
bool overlaps(const Box2& a, const Box2& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

bool fits(const Box2& box, const std::vector<Box2>& keep_out, const std::vector<Box2>& placed,
          double spacing) {
  for (const Box2& k : keep_out)
    if (overlaps(box, k)) return false;
  for (const Box2& p : placed)
    if (gap(box, p) < spacing) return false;
  return true;
}

}  // namespace

// Places the home base and the robots in the start room: the robots' backs to the wall
// opposite the room's door, the home base between them and the door, its corners 1.4 m
// apart opening towards them. Each robot stands 1.6-2.4 m from the home base's middle, 18-26
// degrees off its axis, facing the middle, well inside both corners' openings.
bool placeStart(Building& b, Draw& d) {
  const Layout& l = b.layout;
  if (l.start_room < 0 || l.start_door < 0) return false;
  const Rect& room = l.zones[l.start_room].rects[0];
  const Doorway& door = l.doors[l.start_door];
  Eigen::Vector2d f;  // from the back wall towards the door
  if (door.vertical)
    f = {door.line == room.x0 ? -1.0 : 1.0, 0.0};
  else
    f = {0.0, door.line == room.y0 ? -1.0 : 1.0};
  const Eigen::Vector2d lat(-f.y(), f.x());
  const Box2 m = metres(room);
  const Eigen::Vector2d centre(0.5 * (m.x0 + m.x1), 0.5 * (m.y0 + m.y1));
  const double depth = std::abs(f.x()) * (m.x1 - m.x0) + std::abs(f.y()) * (m.y1 - m.y0) - 0.1;
  const double width = std::abs(lat.x()) * (m.x1 - m.x0) + std::abs(lat.y()) * (m.y1 - m.y0) - 0.1;
  const Eigen::Vector2d back = centre - f * (0.5 * depth);  // on the back wall's face

  const double a = d.uniform(18.0, 26.0) * M_PI / 180.0;
  const double r_min = std::max({1.6, 0.85 / (std::cos(a) - std::sin(a)), 0.55 / std::sin(a)});
  const double u_robots = d.uniform(0.85, 1.1);
  const double r_max = std::min(2.4, (depth - 1.3 - u_robots) / std::cos(a));
  if (r_max < r_min) return false;
  const double r = d.uniform(r_min, std::min(r_max, std::max(r_min, 2.3)));
  const double slack = std::min(0.3, 0.5 * width - 1.14 - 0.8);
  const double v = slack > 0.0 ? d.uniform(-slack, slack) : 0.0;
  if (0.5 * width - std::abs(v) - r * std::sin(a) < 0.6) return false;

  const Eigen::Vector2d middle = back + f * (u_robots + r * std::cos(a)) + lat * v;
  b.home_base.arm_length = 0.6;
  b.home_base.thickness = 0.04;
  b.home_base.height = 1.2;
  b.home_base.texture = "landmark";
  const double facing = std::atan2(-f.y(), -f.x());
  b.home_base.corners = {{middle - 0.7 * lat, facing}, {middle + 0.7 * lat, facing}};
  for (const auto& [name, side] : {std::pair{"jose", -1.0}, std::pair{"eric", 1.0}}) {
    const Eigen::Vector2d p = middle - f * (r * std::cos(a)) + lat * (side * r * std::sin(a));
    const Eigen::Vector2d to = middle - p;
    b.robots.push_back({name, Pose2(p.x(), p.y(), std::atan2(to.y(), to.x()))});
  }
  return true;
}

// Furniture keeps clear of doorways (1.6 m on both sides of each) and of the home base and
// the robots' starts.
std::vector<Box2> keepOuts(const Building& b) {
  std::vector<Box2> out;
  for (const Doorway& dw : b.layout.doors) {
    const Eigen::Vector2d c = dw.centre();
    const double half = 0.5 * dw.width() + 0.4, deep = 1.6;
    out.push_back(dw.vertical ? Box2{c.x() - deep, c.y() - half, c.x() + deep, c.y() + half}
                              : Box2{c.x() - half, c.y() - deep, c.x() + half, c.y() + deep});
  }
  Box2 start{1e9, 1e9, -1e9, -1e9};
  auto include = [&](const Eigen::Vector2d& p) {
    start = {std::min(start.x0, p.x()), std::min(start.y0, p.y()), std::max(start.x1, p.x()),
             std::max(start.y1, p.y())};
  };
  for (const auto& c : b.home_base.corners) include(c.position);
  for (const auto& robot : b.robots) include(robot.second.translation());
  out.push_back(start.grown(1.2));
  return out;
}

// Desks and cabinets against a room's walls, tables in its middle, 0.9 m or more apart.
void furnishRoom(Building& b, const Rect& room, const std::vector<Box2>& keep_out, Draw& d) {
  const Box2 face = metres(room).grown(-kHalfWall - 0.02);
  const double area = (face.x1 - face.x0) * (face.y1 - face.y0);
  const int wanted = std::clamp(static_cast<int>(area / 8.0), 1, 6);
  std::vector<Box2> placed;
  for (int attempt = 0, n = 0; attempt < 40 && n < wanted; ++attempt) {
    const int kind = d.integer(0, 9);
    Furniture f;
    double length, deep;
    if (kind < 5) {
      length = d.uniform(1.2, 1.8), deep = d.uniform(0.6, 0.8), f.height = 0.75;
      f.texture = "wood", f.label = "desk";
    } else if (kind < 8) {
      length = d.uniform(0.8, 1.2), deep = d.uniform(0.4, 0.6), f.height = d.uniform(1.6, 2.0);
      f.texture = d.chance(0.5) ? "metal" : "poster", f.label = "cabinet";
    } else {
      length = d.uniform(1.2, 2.0), deep = d.uniform(0.8, 1.0), f.height = 0.75;
      f.texture = "wood", f.label = "table";
    }
    const int side = d.integer(0, 3);  // wall: south, north, west, east; table: orientation
    const bool along_x = side < 2;
    const double sx = along_x ? length : deep, sy = along_x ? deep : length;
    const double inset = f.label == "table" ? 1.0 : 0.0;
    const double x_lo = face.x0 + inset, x_hi = face.x1 - inset - sx;
    const double y_lo = face.y0 + inset, y_hi = face.y1 - inset - sy;
    if (x_hi < x_lo || y_hi < y_lo) continue;
    double x = d.uniform(x_lo, x_hi), y = d.uniform(y_lo, y_hi);
    if (f.label != "table") {
      if (side == 0) y = face.y0;
      if (side == 1) y = face.y1 - sy;
      if (side == 2) x = face.x0;
      if (side == 3) x = face.x1 - sx;
    }
    f.footprint = {x, y, x + sx, y + sy};
    if (!fits(f.footprint, keep_out, placed, 0.9)) continue;
    placed.push_back(f.footprint);
    b.furniture.push_back(f);
    ++n;
  }
}

// Furniture islands (desk blocks, cabinets) and free-standing partitions in the open plan,
// 1.2 m or more from its walls, from each other and from the walking aisle.
void furnishOpenPlan(Building& b, const std::vector<Box2>& keep_out, Draw& d) {
  const Box2 open = metres(b.plan.corridors[0]).grown(-kHalfWall - 1.2);
  std::vector<Box2> blocked = keep_out;
  blocked.push_back(metres(b.plan.aisle).grown(0.6));
  const double area = (open.x1 - open.x0) * (open.y1 - open.y0);
  const int wanted = std::clamp(static_cast<int>(area / 12.0), 2, 14);
  std::vector<Box2> placed;
  for (int attempt = 0, n = 0; attempt < 120 && n < wanted; ++attempt) {
    const int kind = d.integer(0, 9);
    const bool along_x = d.chance(0.5);
    double length, deep;
    if (kind < 5)
      length = d.uniform(2.4, 3.6), deep = d.uniform(1.4, 1.8);
    else if (kind < 7)
      length = d.uniform(1.2, 1.8), deep = 0.5;
    else
      length = d.uniform(1.5, 3.0), deep = 0.1;
    const double sx = along_x ? length : deep, sy = along_x ? deep : length;
    if (open.x1 - sx < open.x0 || open.y1 - sy < open.y0) continue;
    const double x = d.uniform(open.x0, open.x1 - sx), y = d.uniform(open.y0, open.y1 - sy);
    const Box2 footprint{x, y, x + sx, y + sy};
    if (!fits(footprint, blocked, placed, 1.2)) continue;
    placed.push_back(footprint);
    ++n;
    if (kind >= 7) {
      WallSpec wall;
      wall.thickness = 0.1;
      wall.height = 1.6;
      wall.texture = d.chance(0.5) ? "plaster" : "poster";
      const double t = 0.5 * wall.thickness;  // wall solids reach past their ends by this
      wall.from = along_x ? Eigen::Vector2d(x + t, y + t) : Eigen::Vector2d(x + t, y + t);
      wall.to = along_x ? Eigen::Vector2d(x + sx - t, y + t) : Eigen::Vector2d(x + t, y + sy - t);
      b.partitions.push_back({wall, "partition"});
      continue;
    }
    Furniture f;
    f.footprint = footprint;
    f.height = kind < 5 ? 0.75 : 1.4;
    f.texture = kind < 5 ? "wood" : "metal";
    f.label = kind < 5 ? "desk island" : "cabinets";
    b.furniture.push_back(f);
  }
}

// People walk a corridor's length 0.45 m off its centre line (the loop: around it), back and
// forth; slippery patches lie across corridors.
void addPeopleAndPatches(Building& b, Draw& d) {
  const Plan& p = b.plan;
  std::vector<std::vector<Eigen::Vector2d>> walks;
  const double offset = 0.45;
  if (p.ring) {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -(1 << 30), y1 = -(1 << 30);
    for (const Rect& r : p.corridors)
      x0 = std::min(x0, r.x0), y0 = std::min(y0, r.y0), x1 = std::max(x1, r.x1),
      y1 = std::max(y1, r.y1);
    const Rect& c = p.corridors[0];
    const double half = 0.5 * std::min(c.x1 - c.x0, c.y1 - c.y0) * kDm;
    for (double sign : {-1.0, 1.0}) {
      const double in = half + sign * offset;
      walks.push_back({{x0 * kDm + in, y0 * kDm + in},
                       {x1 * kDm - in, y0 * kDm + in},
                       {x1 * kDm - in, y1 * kDm - in},
                       {x0 * kDm + in, y1 * kDm - in}});
    }
  } else {
    for (const Rect& c : p.open_plan ? std::vector<Rect>{p.aisle} : p.corridors) {
      const Box2 m = metres(c);
      const bool along_x = m.x1 - m.x0 >= m.y1 - m.y0;
      for (double sign : {-1.0, 1.0}) {
        if (along_x) {
          const double y = 0.5 * (m.y0 + m.y1) + sign * offset;
          walks.push_back({{m.x0 + 0.8, y}, {m.x1 - 0.8, y}});
        } else {
          const double x = 0.5 * (m.x0 + m.x1) + sign * offset;
          walks.push_back({{x, m.y0 + 0.8}, {x, m.y1 - 0.8}});
        }
      }
    }
  }
  const int people = d.chance(0.5) ? 2 : 1;
  const char* names[] = {"ana", "ben"};
  int first_walk = -1;
  for (int k = 0; k < people; ++k) {
    int walk = d.integer(0, static_cast<int>(walks.size()) - 1);
    if (walk == first_walk) walk = (walk + 1) % static_cast<int>(walks.size());
    first_walk = walk;
    PersonSpec person;
    person.name = names[k];
    person.radius = 0.22;
    person.speed = std::round(d.uniform(0.7, 1.1) * 10.0) / 10.0;
    person.start_time = 5.0 * d.integer(3, 8);
    person.loop = true;
    person.path = walks[static_cast<size_t>(walk)];
    if (d.chance(0.5)) std::reverse(person.path.begin(), person.path.end());
    b.people.push_back(person);
  }

  const int patches = d.chance(0.5) ? 2 : 1;
  const std::vector<Rect>& lanes = p.open_plan ? std::vector<Rect>{p.aisle} : p.corridors;
  const std::pair<const char*, double> kinds[] = {
      {"polished_tiles", 0.05}, {"wet_floor", 0.15}, {"dust", 0.3}};
  for (int k = 0; k < patches; ++k) {
    const Box2 m =
        metres(lanes[static_cast<size_t>(d.integer(0, static_cast<int>(lanes.size()) - 1))])
            .grown(-kHalfWall);
    const bool along_x = m.x1 - m.x0 >= m.y1 - m.y0;
    const double length = d.uniform(1.5, 3.0);
    const double span = (along_x ? m.x1 - m.x0 : m.y1 - m.y0) - length;
    if (span <= 0.0) continue;
    const double at = (along_x ? m.x0 : m.y0) + d.uniform(0.0, span);
    const auto& [name, mu] = kinds[d.integer(0, 2)];
    SurfaceSpec s;
    s.name = std::string(name) + "_" + std::to_string(k + 1);
    s.traction_mu = mu;
    s.min = along_x ? Eigen::Vector2d(at, m.y0) : Eigen::Vector2d(m.x0, at);
    s.max = along_x ? Eigen::Vector2d(at + length, m.y1) : Eigen::Vector2d(m.x1, at + length);
    b.surfaces.push_back(s);
  }
}

}  // namespace coopmap::sim::generated

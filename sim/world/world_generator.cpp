#include "sim/world/world_generator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <Eigen/Core>

#include "core/io/yaml_reader.h"
#include "sim/world/generated_building.h"
#include "sim/world/world.h"
#include "sim/world/world_checks.h"

namespace coopmap::sim {

namespace {

using namespace generated;

constexpr int kAttempts = 64;

uint64_t splitmix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Area (m^2) of the union of the zone rectangles grown to the walls' outer faces, on a
// 0.05 m raster (exact: every edge lies on it).
double floorArea(const std::vector<Rect>& rects) {
  if (rects.empty()) return 0.0;
  int x0 = rects[0].x0, y0 = rects[0].y0, x1 = rects[0].x1, y1 = rects[0].y1;
  for (const Rect& r : rects) {
    x0 = std::min(x0, r.x0), y0 = std::min(y0, r.y0);
    x1 = std::max(x1, r.x1), y1 = std::max(y1, r.y1);
  }
  const int w = 2 * (x1 - x0) + 2, h = 2 * (y1 - y0) + 2;  // half-dm cells
  std::vector<uint8_t> cells(static_cast<size_t>(w) * h, 0);
  for (const Rect& r : rects)
    for (int j = 2 * (r.y0 - y0); j < 2 * (r.y1 - y0) + 2; ++j)
      for (int i = 2 * (r.x0 - x0); i < 2 * (r.x1 - x0) + 2; ++i)
        cells[static_cast<size_t>(j) * w + i] = 1;
  size_t n = 0;
  for (uint8_t c : cells) n += c;
  return static_cast<double>(n) * 0.0025;
}

std::vector<Rect> planRects(const Plan& p) {
  std::vector<Rect> all = p.corridors;
  for (const Strip& s : p.strips) all.push_back(s.r);
  return all;
}

// The smallest length (dm) in [lo, hi] whose plan has at least `target` m^2 of floor, or the
// one below it if that is nearer.
template <typename MakePlan>
Plan planForArea(const MakePlan& make, int lo, int hi, double target) {
  auto area = [&](int length) { return floorArea(planRects(make(length))); };
  int a = lo, b = hi;
  while (a < b) {
    const int m = (a + b) / 2;
    if (area(m) >= target)
      b = m;
    else
      a = m + 1;
  }
  if (a > lo && target - area(a - 1) < area(a) - target) --a;
  return make(a);
}

// A strip of rooms needs at least this length (dm); shorter ones are left out of the plan.
constexpr int kMinStrip = 30;
void addStrip(Plan& p, Rect r, bool along_x, bool start = false) {
  if ((along_x ? r.x1 - r.x0 : r.y1 - r.y0) >= kMinStrip) p.strips.push_back({r, along_x, start});
}

Plan corridorFamily(Draw& d, double target) {
  const int cw = d.integer(18, 24), south = d.integer(48, 60), north = d.integer(40, 60);
  bool two = d.chance(0.6);
  const double one_sided = target / ((cw + south) * kDm);
  if (!two && one_sided > 45.0) two = true;
  if (two && target / ((cw + south + north) * kDm) < 9.0) two = false;
  auto make = [=](int length) {
    Plan p;
    p.corridors = {{0, 0, length, cw}};
    addStrip(p, {0, -south, length, 0}, true, true);
    if (two) addStrip(p, {0, cw, length, cw + north}, true);
    char buf[96];
    std::snprintf(buf, sizeof buf, "a %.1f m corridor with rooms on %s", cw * kDm,
                  two ? "both sides" : "one side");
    p.shape = buf;
    return p;
  };
  return planForArea(make, 50, 1200, target);
}

Plan ltFamily(Draw& d, double target) {
  const int cw = d.integer(18, 24), south = d.integer(48, 60), north = d.integer(40, 60);
  const int side = d.integer(40, 60);
  const bool tee = d.chance(0.5);
  const double ratio = d.uniform(0.5, 1.0), junction = d.uniform(0.35, 0.65);
  const bool north_left = d.chance(0.8), north_right = d.chance(0.8);
  const bool left = d.chance(0.8), right = d.chance(0.7);
  auto make = [=](int la) {
    Plan p;
    const int lb = std::max(30, static_cast<int>(std::lround(ratio * la)));
    const int bx = tee ? static_cast<int>(std::lround(junction * la)) : la - cw;
    p.corridors = {{0, 0, la, cw}, {bx, cw, bx + cw, cw + lb}};
    addStrip(p, {0, -south, la, 0}, true, true);
    if (north_left) addStrip(p, {0, cw, bx, cw + north}, true);
    if (tee && north_right) addStrip(p, {bx + cw, cw, la, cw + north}, true);
    if (left) addStrip(p, {bx - side, north_left ? cw + north : cw, bx, cw + lb}, false);
    if (right) {
      const int y0 = tee ? (north_right ? cw + north : cw) : 0;
      addStrip(p, {bx + cw, y0, bx + cw + side, cw + lb}, false);
    }
    char buf[96];
    std::snprintf(buf, sizeof buf, "an %s of %.1f m corridors with rooms along them",
                  tee ? "T" : "L", cw * kDm);
    p.shape = buf;
    return p;
  };
  return planForArea(make, 60, 900, target);
}

Plan loopFamily(Draw& d, double target) {
  const int cw = d.integer(18, 22), inner = d.integer(40, 55), south = d.integer(48, 60);
  const int north = d.integer(40, 55);
  const int rows = target >= 280.0 ? 2 : 1;
  const bool north_rooms = target >= 350.0 && d.chance(0.6);
  const int h = 2 * cw + rows * inner;
  auto make = [=](int w) {
    Plan p;
    p.ring = true;
    p.corridors = {{0, 0, w, cw}, {0, h - cw, w, h}, {0, cw, cw, h - cw}, {w - cw, cw, w, h - cw}};
    for (int k = 0; k < rows; ++k)
      addStrip(p, {cw, cw + k * inner, w - cw, cw + (k + 1) * inner}, true);
    addStrip(p, {0, -south, w, 0}, true, true);
    if (north_rooms) addStrip(p, {0, h, w, h + north}, true);
    char buf[96];
    std::snprintf(buf, sizeof buf, "a %.1f m corridor loop with rooms inside and outside it",
                  cw * kDm);
    p.shape = buf;
    return p;
  };
  return planForArea(make, 2 * cw + kMinStrip, 900, target);
}

Plan openFamily(Draw& d, double target) {
  const int depth = d.integer(80, 140), south = d.integer(48, 60), north = d.integer(40, 55);
  const bool north_rooms = target >= 350.0 && d.chance(0.5);
  const int aisle = d.integer(30, depth - 50);
  auto make = [=](int w) {
    Plan p;
    p.open_plan = true;
    p.corridors = {{0, 0, w, depth}};
    p.aisle = {0, aisle, w, aisle + 20};
    addStrip(p, {0, -south, w, 0}, true, true);
    if (north_rooms) addStrip(p, {0, depth, w, depth + north}, true);
    p.shape = "an open plan with partitions and furniture islands, rooms along its side";
    return p;
  };
  return planForArea(make, 80, 900, target);
}

// Mirrors and turns the plan (x -> -x, y -> -y, x <-> y) so the start room and corridors
// face any way.
Rect transformed(Rect r, bool flip_x, bool flip_y, bool swap) {
  if (flip_x) r = {-r.x1, r.y0, -r.x0, r.y1};
  if (flip_y) r = {r.x0, -r.y1, r.x1, -r.y0};
  if (swap) r = {r.y0, r.x0, r.y1, r.x1};
  return r;
}
void transform(Plan& p, Draw& d) {
  const bool fx = d.chance(0.5), fy = d.chance(0.5), sw = d.chance(0.5);
  for (Rect& r : p.corridors) r = transformed(r, fx, fy, sw);
  for (Strip& s : p.strips) {
    s.r = transformed(s.r, fx, fy, sw);
    if (sw) s.along_x = !s.along_x;
  }
  p.aisle = transformed(p.aisle, fx, fy, sw);
  // Shift so that the building starts at (0, 0).
  int x0 = p.corridors[0].x0, y0 = p.corridors[0].y0;
  for (const Rect& r : planRects(p)) x0 = std::min(x0, r.x0), y0 = std::min(y0, r.y0);
  auto shift = [&](Rect& r) { r = {r.x0 - x0, r.y0 - y0, r.x1 - x0, r.y1 - y0}; };
  for (Rect& r : p.corridors) shift(r);
  for (Strip& s : p.strips) shift(s.r);
  shift(p.aisle);
}

// Splits `length` (dm) into room widths in [lo, hi], the first at least first_lo; a piece too
// short to split further stays whole (up to first_lo + lo) or joins the one before.
std::vector<int> partition(Draw& d, int length, int lo, int hi, int first_lo) {
  std::vector<int> out;
  int left = length;
  while (left > 0) {
    const int lo_here = out.empty() ? first_lo : lo;
    if (left <= hi || left < lo_here + lo) {
      if (left < lo && !out.empty())
        out.back() += left;
      else
        out.push_back(left);
      break;
    }
    const int w = d.integer(lo_here, std::min(hi, left - lo));
    out.push_back(w);
    left -= w;
  }
  return out;
}

// Adds a doorway 0.9-1.2 m wide (between wall ends) on the longest boundary zones a and b
// share, at least 0.5 m from its ends. False if they share none long enough.
bool addDoor(Layout& l, int a, int b, Draw& d) {
  const int width = d.integer(9, 12);
  Doorway best;
  int best_length = 0;
  for (const Rect& ra : l.zones[a].rects)
    for (const Rect& rb : l.zones[b].rects) {
      if (ra.x1 == rb.x0 || ra.x0 == rb.x1) {
        const int from = std::max(ra.y0, rb.y0), to = std::min(ra.y1, rb.y1);
        if (to - from > best_length)
          best = {a, b, true, ra.x1 == rb.x0 ? ra.x1 : ra.x0, from, to}, best_length = to - from;
      }
      if (ra.y1 == rb.y0 || ra.y0 == rb.y1) {
        const int from = std::max(ra.x0, rb.x0), to = std::min(ra.x1, rb.x1);
        if (to - from > best_length)
          best = {a, b, false, ra.y1 == rb.y0 ? ra.y1 : ra.y0, from, to}, best_length = to - from;
      }
    }
  if (best_length < width + 10) return false;
  best.from += 5 + d.integer(0, best_length - width - 10);
  best.to = best.from + width;
  best.panel = d.chance(0.5);
  l.doors.push_back(best);
  return true;
}

Layout realize(const Plan& p, Draw& d) {
  Layout l;
  l.zones.push_back({p.open_plan ? ZoneKind::kOpen : ZoneKind::kCorridor, p.corridors});
  for (const Strip& s : p.strips) {
    const Rect& r = s.r;
    const std::vector<int> widths =
        partition(d, s.along_x ? r.x1 - r.x0 : r.y1 - r.y0, 36, 65, s.start ? 48 : 36);
    const int depth = s.along_x ? r.y1 - r.y0 : r.x1 - r.x0;
    std::vector<int> wide;  // rooms big enough to hold the home base
    int at = s.along_x ? r.x0 : r.y0;
    const int first = static_cast<int>(l.zones.size());
    for (size_t k = 0; k < widths.size(); ++k) {
      const Rect room =
          s.along_x ? Rect{at, r.y0, at + widths[k], r.y1} : Rect{r.x0, at, r.x1, at + widths[k]};
      at += widths[k];
      if (widths[k] >= 48 && depth >= 48) wide.push_back(static_cast<int>(l.zones.size()));
      l.zones.push_back({ZoneKind::kRoom, {room}});
      ++l.rooms;
    }
    if (s.start && !wide.empty())
      l.start_room = wide[static_cast<size_t>(d.integer(0, static_cast<int>(wide.size()) - 1))];
    for (int z = first; z < static_cast<int>(l.zones.size()); ++z) {
      const size_t doors_before = l.doors.size();
      const bool to_corridor = addDoor(l, z, 0, d);
      if (!to_corridor && z > first) addDoor(l, z, z - 1, d);
      if (z == l.start_room && l.doors.size() > doors_before)
        l.start_door = static_cast<int>(doors_before);
      if (to_corridor && z > first && d.chance(0.25)) addDoor(l, z, z - 1, d);
    }
  }
  return l;
}

// Walls along every boundary between different zones (or a zone and the outside), less the
// doorways, merged into straight runs. Each pair of zones draws its wall texture once.
std::vector<WallSpec> wallsOf(const Layout& l, double height, Draw& d) {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  for (const Zone& z : l.zones)
    for (const Rect& r : z.rects) {
      x0 = std::min(x0, r.x0), y0 = std::min(y0, r.y0);
      x1 = std::max(x1, r.x1), y1 = std::max(y1, r.y1);
    }
  const int w = x1 - x0, h = y1 - y0;
  std::vector<int> id(static_cast<size_t>(w) * h, 0);
  for (size_t z = 0; z < l.zones.size(); ++z)
    for (const Rect& r : l.zones[z].rects)
      for (int j = r.y0; j < r.y1; ++j)
        for (int i = r.x0; i < r.x1; ++i) {
          int& cell = id[static_cast<size_t>(j - y0) * w + (i - x0)];
          if (cell != 0) throw std::logic_error("world generator: zones overlap");
          cell = static_cast<int>(z) + 1;
        }
  auto zoneAt = [&](int i, int j) {
    if (i < x0 || j < y0 || i >= x1 || j >= y1) return 0;
    return id[static_cast<size_t>(j - y0) * w + (i - x0)];
  };
  std::set<std::tuple<bool, int, int>> open;
  for (const Doorway& dw : l.doors)
    for (int k = dw.from; k < dw.to; ++k) open.insert({dw.vertical, dw.line, k});

  std::map<std::pair<int, int>, std::string> textures;
  auto textureOf = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = textures.find(key);
    if (it != textures.end()) return it->second;
    const bool corridor = (a > 0 && l.zones[a - 1].kind != ZoneKind::kRoom) ||
                          (b > 0 && l.zones[b - 1].kind != ZoneKind::kRoom);
    const double u = d.uniform(0.0, 1.0);
    const std::string t = u < (corridor ? 0.35 : 0.2) ? "plaster" : u < 0.65 ? "brick" : "poster";
    return textures[key] = t;
  };

  std::vector<WallSpec> walls;
  auto emit = [&](bool vertical, int line, int from, int to, int a, int b) {
    WallSpec wall;
    wall.from = vertical ? Eigen::Vector2d(line * kDm, from * kDm)
                         : Eigen::Vector2d(from * kDm, line * kDm);
    wall.to =
        vertical ? Eigen::Vector2d(line * kDm, to * kDm) : Eigen::Vector2d(to * kDm, line * kDm);
    wall.thickness = 2 * kHalfWall;
    wall.height = height;
    wall.texture = textureOf(a, b);
    walls.push_back(wall);
  };
  for (int vertical = 1; vertical >= 0; --vertical) {
    const int lines_from = vertical ? x0 : y0, lines_to = vertical ? x1 : y1;
    const int along_from = vertical ? y0 : x0, along_to = vertical ? y1 : x1;
    for (int line = lines_from; line <= lines_to; ++line) {
      int run = 0, pa = 0, pb = 0;
      bool in_run = false;
      for (int k = along_from; k <= along_to; ++k) {
        int a = 0, b = 0;
        bool wall = false;
        if (k < along_to) {
          a = vertical ? zoneAt(line - 1, k) : zoneAt(k, line - 1);
          b = vertical ? zoneAt(line, k) : zoneAt(k, line);
          wall = a != b && !open.count({vertical != 0, line, k});
        }
        const bool same = wall && in_run && std::minmax(a, b) == std::minmax(pa, pb);
        if (in_run && !same) {
          emit(vertical != 0, line, run, k, pa, pb);
          in_run = false;
        }
        if (wall && !in_run) run = k, pa = a, pb = b, in_run = true;
      }
    }
  }
  return walls;
}

Building build(const std::string& family, double target, Draw& d) {
  Building b;
  b.plan = family == "corridor" ? corridorFamily(d, target)
           : family == "lt"     ? ltFamily(d, target)
           : family == "loop"   ? loopFamily(d, target)
                                : openFamily(d, target);
  b.floor_area = floorArea(planRects(b.plan));
  transform(b.plan, d);
  b.layout = realize(b.plan, d);
  if (!placeStart(b, d)) return b;
  const std::vector<Box2> keep_out = keepOuts(b);
  for (size_t z = 1; z < b.layout.zones.size(); ++z)
    furnishRoom(b, b.layout.zones[z].rects[0], keep_out, d);
  if (b.plan.open_plan) furnishOpenPlan(b, keep_out, d);
  b.walls = wallsOf(b.layout, std::round(d.uniform(2.4, 3.0) * 10.0) / 10.0, d);
  // At least one long low-texture wall: the stereo's hardest case.
  if (std::none_of(b.walls.begin(), b.walls.end(),
                   [](const WallSpec& w) { return w.texture == "plaster"; })) {
    auto longest =
        std::max_element(b.walls.begin(), b.walls.end(), [](const auto& x, const auto& y) {
          return (x.to - x.from).norm() < (y.to - y.from).norm();
        });
    longest->texture = "plaster";
  }
  addPeopleAndPatches(b, d);
  return b;
}

}  // namespace

const std::vector<std::string>& worldFamilies() {
  static const std::vector<std::string> families = {"corridor", "lt", "loop", "open"};
  return families;
}

void WorldGeneratorOptions::validate() const {
  const auto& families = worldFamilies();
  if (!family.empty() && std::find(families.begin(), families.end(), family) == families.end()) {
    std::string known;
    for (const std::string& f : families) known += (known.empty() ? "" : ", ") + f;
    throw ConfigError("--family: expected one of " + known + ", got '" + family + "'");
  }
  if (area && !(*area >= kMinArea && *area <= kMaxArea))
    throw ConfigError("--area: expected a floor area in [" + num(kMinArea) + ", " + num(kMaxArea) +
                      "] m^2, got " + num(*area));
  if (out_file.empty()) throw ConfigError("--out: expected the path of the world file to write");
}

GeneratedWorld generateWorld(const WorldGeneratorOptions& options) {
  options.validate();
  namespace fs = std::filesystem;
  // Family and area are always drawn, so that giving the drawn ones changes nothing else.
  Draw first(splitmix(options.seed));
  const auto& families = worldFamilies();
  const std::string drawn_family =
      families[static_cast<size_t>(first.integer(0, static_cast<int>(families.size()) - 1))];
  const double drawn_area = 10.0 * first.integer(10, 60);
  GeneratedWorld out;
  out.family = options.family.empty() ? drawn_family : options.family;
  out.area = options.area ? *options.area : drawn_area;

  const fs::path model = fs::absolute(options.robot_model.empty()
                                          ? fs::path(COOPMAP_SOURCE_DIR) / "robots/b14/b14.yaml"
                                          : fs::path(options.robot_model))
                             .lexically_normal();
  const fs::path folder = fs::absolute(options.out_file).lexically_normal().parent_path();
  const fs::path relative = model.lexically_relative(folder);
  const std::string model_text = relative.empty() ? model.string() : relative.string();

  std::string command = "coopmap world generate --seed " + std::to_string(options.seed);
  if (!options.family.empty()) command += " --family " + options.family;
  if (options.area) command += " --area " + num(*options.area);
  std::string header = "# Generated by `" + command + "`\n#";
  std::string drawn;
  if (options.family.empty()) drawn = "family " + out.family;
  if (!options.area) drawn += (drawn.empty() ? "area " : " and area ") + num(out.area) + " m^2";
  if (!drawn.empty()) header += " (" + drawn + " drawn from the seed)";
  header +=
      (drawn.empty() ? " The" : "; the") + std::string(" same command writes the same bytes.\n");

  // Keep the floor inside the allowed range when aiming at its ends.
  const double target = std::clamp(out.area, 103.0, 597.0);
  std::string last_failure;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    Draw d(splitmix(options.seed ^ splitmix(static_cast<uint64_t>(attempt) + 1)));
    const Building b = build(out.family, target, d);
    if (b.robots.empty()) {
      last_failure = "no room for the home base";
      continue;
    }
    if (b.floor_area < WorldGeneratorOptions::kMinArea ||
        b.floor_area > WorldGeneratorOptions::kMaxArea ||
        std::abs(b.floor_area - out.area) > 0.1 * out.area) {
      last_failure = "floor area " + num(b.floor_area) + " m^2";
      continue;
    }
    const std::string yaml = worldYaml(b, header, out.family, options.seed, model_text);
    try {
      const World world = parseWorld(yaml, options.out_file);
      const WorldCheckResult check = checkWorldExplorable(world);
      if (!check.ok()) {
        last_failure = check.detail;
        continue;
      }
    } catch (const ConfigError& e) {
      last_failure = e.what();
      continue;
    }
    out.yaml = yaml;
    out.floor_area = b.floor_area;
    out.rooms = b.layout.rooms;
    out.doors = static_cast<int>(b.layout.doors.size());
    out.attempt = attempt;
    return out;
  }
  throw std::runtime_error("world generator: no world of seed " + std::to_string(options.seed) +
                           " passed its checks in " + std::to_string(kAttempts) +
                           " attempts (last: " + last_failure + ")");
}

}  // namespace coopmap::sim

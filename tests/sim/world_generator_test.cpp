// Generated worlds: every family's worlds for seeds 1-30 load, have 100-600 m^2 of floor,
// and pass this test's own reachability, start and home-base checks (a raster and line
// tests of their own, not the generator's); the same options give the same bytes.
#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/yaml_reader.h"
#include "sim/world/world.h"
#include "sim/world/world_generator.h"

namespace coopmap::sim {
namespace {

namespace fs = std::filesystem;

constexpr double kRadius = 0.25, kMargin = 0.05;

// A folder of its own per test, so generated files can be loaded as files.
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("coopmap_world_generator_test_" + name);
  fs::create_directories(dir);
  return dir;
}

GeneratedWorld generate(uint64_t seed, const std::string& family, const fs::path& dir,
                        std::optional<double> area = std::nullopt) {
  WorldGeneratorOptions o;
  o.seed = seed;
  o.family = family;
  o.area = area;
  o.out_file = (dir / ("w" + std::to_string(seed) + ".yaml")).string();
  return generateWorld(o);
}

World writeAndLoad(const GeneratedWorld& g, const fs::path& file) {
  std::ofstream(file) << g.yaml;
  return loadWorld(file.string());
}

// The box's footprint corners, counter-clockwise.
std::vector<Eigen::Vector2d> corners(const SolidBox& b) {
  const Eigen::Vector2d u(std::cos(b.yaw), std::sin(b.yaw)), v(-u.y(), u.x());
  const double hx = 0.5 * b.size.x(), hy = 0.5 * b.size.y();
  return {b.center - hx * u - hy * v, b.center + hx * u - hy * v, b.center + hx * u + hy * v,
          b.center - hx * u + hy * v};
}

double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Distance from p to the footprint polygon: 0 inside, else to its nearest edge.
double distanceTo(const SolidBox& b, const Eigen::Vector2d& p) {
  const auto c = corners(b);
  bool inside = true;
  double d = 1e9;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d e = c[(k + 1) % 4] - c[k], q = p - c[k];
    if (e.x() * q.y() - e.y() * q.x() < 0.0) inside = false;
    d = std::min(d, segmentDistance(p, c[k], c[(k + 1) % 4]));
  }
  return inside ? 0.0 : d;
}

bool segmentsCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  auto side = [](const Eigen::Vector2d& o, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    const Eigen::Vector2d u = p - o, v = q - o;
    return u.x() * v.y() - u.y() * v.x();
  };
  return side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0;
}

// Whether the open segment a-b enters the footprint: crosses an edge or ends inside.
bool blocks(const SolidBox& box, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const auto c = corners(box);
  for (int k = 0; k < 4; ++k)
    if (segmentsCross(a, b, c[k], c[(k + 1) % 4])) return true;
  return distanceTo(box, a) == 0.0 || distanceTo(box, b) == 0.0;
}

double unionArea(const World& w) {
  const double cell = 0.05;
  int n = 0;
  for (double y = w.floor_min.y() + 0.5 * cell; y < w.floor_max.y(); y += cell)
    for (double x = w.floor_min.x() + 0.5 * cell; x < w.floor_max.x(); x += cell)
      n += w.onFloor({x, y});
  return n * cell * cell;
}

// Free floor cells (0.1 m from everything beyond the robot's radius and margin) that an
// 8-connected search from the starts does not reach.
int unreachableCells(const World& w) {
  const double cell = 0.05, inflate = kRadius + kMargin;
  const int nx = static_cast<int>((w.floor_max.x() - w.floor_min.x()) / cell) + 1;
  const int ny = static_cast<int>((w.floor_max.y() - w.floor_min.y()) / cell) + 1;
  auto centre = [&](int i, int j) {
    return Eigen::Vector2d(w.floor_min.x() + (i + 0.5) * cell, w.floor_min.y() + (j + 0.5) * cell);
  };
  std::vector<char> free(static_cast<size_t>(nx) * ny, 0);
  const std::vector<SolidBox> solids = w.solids();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d p = centre(i, j);
      if (!w.onFloor(p)) continue;
      bool clear = true;
      for (const SolidBox& s : solids)
        if ((p - s.center).norm() < 0.5 * s.size.head<2>().norm() + inflate &&
            distanceTo(s, p) <= inflate) {
          clear = false;
          break;
        }
      free[static_cast<size_t>(j) * nx + i] = clear;
    }
  std::deque<std::pair<int, int>> queue;
  std::vector<char> seen(free.size(), 0);
  for (const RobotSpec& r : w.robots) {
    const int i = static_cast<int>((r.start.x - w.floor_min.x()) / cell);
    const int j = static_cast<int>((r.start.y - w.floor_min.y()) / cell);
    if (free[static_cast<size_t>(j) * nx + i]) {
      seen[static_cast<size_t>(j) * nx + i] = 1;
      queue.push_back({i, j});
    }
  }
  while (!queue.empty()) {
    const auto [i, j] = queue.front();
    queue.pop_front();
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int a = i + di, b = j + dj;
        if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
        const size_t k = static_cast<size_t>(b) * nx + a;
        if (free[k] && !seen[k]) seen[k] = 1, queue.push_back({a, b});
      }
  }
  int unreached = 0;
  for (size_t k = 0; k < free.size(); ++k) unreached += free[k] && !seen[k];
  return unreached;
}

void expectExplorable(const World& w, const std::string& what) {
  SCOPED_TRACE(what);
  for (const RobotSpec& r : w.robots) EXPECT_TRUE(r.route.empty()) << r.name << ": they explore";
  const double area = unionArea(w);
  EXPECT_GE(area, 100.0);
  EXPECT_LE(area, 600.0);

  // The standard home base and two robots before it.
  ASSERT_EQ(w.home_base.corners.size(), 2u);
  const auto& hb = w.home_base;
  EXPECT_NEAR((hb.corners[0].position - hb.corners[1].position).norm(), 1.4, 1e-9);
  EXPECT_NEAR(hb.corners[0].heading, hb.corners[1].heading, 1e-9);
  EXPECT_EQ(hb.arm_length, 0.6);
  EXPECT_EQ(hb.thickness, 0.04);
  EXPECT_EQ(hb.height, 1.2);
  ASSERT_EQ(w.robots.size(), 2u);
  EXPECT_EQ(w.robots[0].name, "jose");
  EXPECT_EQ(w.robots[1].name, "eric");
  EXPECT_GE((w.robots[0].start.translation() - w.robots[1].start.translation()).norm(), 1.0);
  const Eigen::Vector2d middle = 0.5 * (hb.corners[0].position + hb.corners[1].position);
  const std::vector<SolidBox> solids = w.solids();
  for (const RobotSpec& r : w.robots) {
    EXPECT_TRUE(fs::exists(r.model_file)) << r.model_file;
    const Eigen::Vector2d p = r.start.translation();
    const double d = (middle - p).norm();
    EXPECT_GE(d, 1.0);
    EXPECT_LE(d, 2.5);
    const Eigen::Vector2d facing(std::cos(r.start.theta), std::sin(r.start.theta));
    EXPECT_GT(facing.dot((middle - p).normalized()), std::cos(M_PI / 36)) << r.name;
    for (const SolidBox& s : solids)
      EXPECT_GE(distanceTo(s, p), kRadius + 0.1) << r.name << " near a " << s.kind;
    // Each corner's vertex in view: inside its L's opening and no wall, box or door between.
    for (const auto& c : hb.corners) {
      const Eigen::Vector2d heading(std::cos(c.heading), std::sin(c.heading));
      EXPECT_GT(heading.dot((p - c.position).normalized()), std::cos(M_PI / 4)) << r.name;
      const Eigen::Vector2d target = c.position + 0.06 * heading;
      for (const SolidBox& s : solids) {
        if (s.kind == "home_base") continue;
        EXPECT_FALSE(blocks(s, p, target))
            << r.name << ": a " << s.kind << " at " << s.center.transpose() << " hides a corner";
      }
    }
  }

  // Doorways, people, slippery patches, textures.
  for (const DoorSpec& d : w.doors) {
    EXPECT_GE(d.width, 0.9 - 1e-9);
    EXPECT_LE(d.width, 1.2 + 1e-9);
    EXPECT_TRUE(d.open);
  }
  EXPECT_GE(w.people.size(), 1u);
  EXPECT_LE(w.people.size(), 2u);
  EXPECT_GE(w.surfaces.size(), 1u);
  EXPECT_LE(w.surfaces.size(), 2u);
  for (const SurfaceSpec& s : w.surfaces) EXPECT_LT(s.traction_mu, 0.5);
  EXPECT_TRUE(std::any_of(w.walls.begin(), w.walls.end(), [&](const WallSpec& x) {
    return w.textures.at(x.texture).contrast < 10;
  })) << "no low-texture wall";
  EXPECT_FALSE(w.boxes.empty());

  EXPECT_EQ(unreachableCells(w), 0);
}

class WorldGeneratorFamilyTest : public ::testing::TestWithParam<std::string> {};

TEST_P(WorldGeneratorFamilyTest, Seeds1To30AreExplorable) {
  const std::string family = GetParam();
  const fs::path dir = scratch(family);
  for (uint64_t seed = 1; seed <= 30; ++seed) {
    const GeneratedWorld g = generate(seed, family, dir);
    EXPECT_EQ(g.family, family);
    EXPECT_GE(g.floor_area, 100.0);
    EXPECT_LE(g.floor_area, 600.0);
    EXPECT_NEAR(g.floor_area, g.area, 0.1 * g.area);
    EXPECT_GE(g.rooms, family == "open" ? 1 : 2);  // the open plan's start room may be alone
    const World w = writeAndLoad(g, dir / ("w" + std::to_string(seed) + ".yaml"));
    expectExplorable(w, family + " seed " + std::to_string(seed));
  }
  fs::remove_all(dir);
}

TEST_P(WorldGeneratorFamilyTest, SameOptionsSameBytesOtherSeedsOtherWorlds) {
  const fs::path dir = scratch(GetParam() + "_determinism");
  const std::string a = generate(7, GetParam(), dir).yaml;
  EXPECT_EQ(a, generate(7, GetParam(), dir).yaml);
  EXPECT_NE(a, generate(8, GetParam(), dir).yaml);
  EXPECT_NE(a, generate(7, GetParam(), dir, 250.0).yaml);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Families, WorldGeneratorFamilyTest,
                         ::testing::Values("corridor", "lt", "loop", "open"),
                         [](const auto& info) { return info.param; });

TEST(WorldGeneratorTest, AreaIsTheOneAskedFor) {
  const fs::path dir = scratch("area");
  for (double area : {100.0, 600.0}) {
    const GeneratedWorld g = generate(3, "corridor", dir, area);
    EXPECT_EQ(g.area, area);
    const World w = writeAndLoad(g, dir / "w.yaml");
    EXPECT_NEAR(unionArea(w), area, 0.1 * area);
    EXPECT_GE(unionArea(w), 100.0);
    EXPECT_LE(unionArea(w), 600.0);
  }
  fs::remove_all(dir);
}

TEST(WorldGeneratorTest, WithoutAFamilyTheSeedPicksOne) {
  const fs::path dir = scratch("drawn");
  std::set<std::string> drawn;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const GeneratedWorld g = generate(seed, "", dir);
    drawn.insert(g.family);
    // Naming the drawn family and area changes nothing but the header's command line.
    const GeneratedWorld named = generate(seed, g.family, dir, g.area);
    EXPECT_EQ(g.yaml.substr(g.yaml.find("\nname:")), named.yaml.substr(named.yaml.find("\nname:")));
  }
  EXPECT_EQ(drawn.size(), worldFamilies().size());
  fs::remove_all(dir);
}

// Each family's structure: the corridor family one corridor (its people walk one axis), the
// L/T two corridors across each other, the loop a closed walk around it, the open plan a
// wide open floor with free-standing partitions lower than the walls.
TEST(WorldGeneratorTest, FamiliesDifferInStructure) {
  const fs::path dir = scratch("structure");
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    auto load = [&](const std::string& family) {
      return writeAndLoad(generate(seed, family, dir), dir / (family + ".yaml"));
    };
    auto widest = [](const World& w) {
      double best = 0.0;
      for (const FloorArea& a : w.floor_areas)
        best = std::max(best, std::min(a.max.x() - a.min.x(), a.max.y() - a.min.y()));
      return best;
    };
    auto lowWalls = [](const World& w) {
      return std::count_if(w.walls.begin(), w.walls.end(),
                           [](const WallSpec& x) { return x.height < 2.0; });
    };
    const World corridor = load("corridor"), lt = load("lt"), loop = load("loop"),
                open = load("open");
    // Rooms and corridors are at most 6.6 m across; the open plan is wider.
    EXPECT_LT(widest(corridor), 6.7);
    EXPECT_LT(widest(lt), 6.7);
    EXPECT_GT(widest(open), 7.9);
    EXPECT_EQ(lowWalls(corridor) + lowWalls(lt) + lowWalls(loop), 0);
    EXPECT_GT(lowWalls(open), 0);
    // Only the loop's people walk a closed round of four corners.
    EXPECT_TRUE(std::any_of(loop.people.begin(), loop.people.end(),
                            [](const PersonSpec& p) { return p.path.size() == 4; }));
    for (const World* w : {&corridor, &lt, &open})
      for (const PersonSpec& p : w->people) EXPECT_EQ(p.path.size(), 2u);
    // The corridor family's corridor runs one way; the L/T's two corridors run both ways.
    auto corridorAxes = [](const World& w) {
      std::set<int> axes;
      for (const FloorArea& a : w.floor_areas) {
        const double dx = a.max.x() - a.min.x(), dy = a.max.y() - a.min.y();
        if (std::min(dx, dy) < 2.6) axes.insert(dx > dy ? 0 : 1);  // rooms are 3 m or more
      }
      return axes.size();
    };
    EXPECT_EQ(corridorAxes(corridor), 1u);
    EXPECT_EQ(corridorAxes(lt), 2u);
  }
  fs::remove_all(dir);
}

TEST(WorldGeneratorTest, BadOptionsNameTheOption) {
  auto errorOf = [](const WorldGeneratorOptions& o) {
    try {
      generateWorld(o);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  WorldGeneratorOptions o;
  o.family = "maze";
  EXPECT_EQ(errorOf(o), "--family: expected one of corridor, lt, loop, open, got 'maze'");
  o.family = "";
  o.area = 50.0;
  EXPECT_EQ(errorOf(o), "--area: expected a floor area in [100, 600] m^2, got 50");
  o.area.reset();
  o.out_file = "";
  EXPECT_EQ(errorOf(o), "--out: expected the path of the world file to write");
}

}  // namespace
}  // namespace coopmap::sim

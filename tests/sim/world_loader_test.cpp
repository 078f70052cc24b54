// World files: the shipped worlds load, and broken files are reported with the file,
// the line and the field, and what was expected.
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>

#include "core/io/yaml_reader.h"
#include "sim/world/world.h"

namespace coopmap::sim {
namespace {

const std::string kSrc = COOPMAP_SOURCE_DIR;

// A minimal valid world; tests break one line of it.
std::string minimal() {
  return "name: t\n"                                                     // 1
         "textures:\n"                                                   // 2
         "  a: {type: noise, tile: 1.0}\n"                               // 3
         "floor: {min: [0, 0], max: [5, 4], texture: a}\n"               // 4
         "walls:\n"                                                      // 5
         "  - {from: [0, 0], to: [5, 0], thickness: 0.1, texture: a}\n"  // 6
         "home_base:\n"                                                  // 7
         "  corners:\n"                                                  // 8
         "    - {position: [1, 1], heading_deg: 0}\n"                    // 9
         "    - {position: [1, 2], heading_deg: 0}\n"                    // 10
         "  texture: a\n"                                                // 11
         "robots:\n"                                                     // 12
         "  - name: r1\n"                                                // 13
         "    model: " +
         kSrc +
         "/robots/b14/b14.yaml\n"                            // 14
         "    start: {position: [2, 2], heading_deg: 90}\n"  // 15
         "    route: [[3, 3], {at: [4, 3], spin: true}]\n";  // 16
}

std::string replaceLine(const std::string& text, int line, const std::string& with) {
  std::string out;
  std::istringstream in(text);
  std::string l;
  for (int n = 1; std::getline(in, l); ++n) out += (n == line ? with : l) + "\n";
  return out;
}

std::string errorOf(const std::string& text) {
  try {
    parseWorld(text, "w.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(WorldLoaderTest, MinimalWorldLoads) {
  const World w = parseWorld(minimal(), "w.yaml");
  EXPECT_EQ(w.name, "t");
  ASSERT_EQ(w.robots.size(), 1u);
  EXPECT_NEAR(w.robots[0].start.theta, M_PI / 2, 1e-12);
  ASSERT_EQ(w.robots[0].route.size(), 2u);
  EXPECT_TRUE(w.robots[0].route[1].spin);
  // One wall and two L corners of two arms each.
  EXPECT_EQ(w.solids().size(), 1u + 4u);
}

TEST(WorldLoaderTest, ShippedWorldsLoad) {
  for (const char* f : {"/worlds/lab.yaml", "/worlds/lab_corridor.yaml"}) {
    const World w = loadWorld(kSrc + f);
    EXPECT_FALSE(w.robots.empty()) << f;
    EXPECT_EQ(w.home_base.corners.size(), 2u) << f;
  }
}

// How robots run and with what settings is the command's choice, not the world's.
TEST(WorldLoaderTest, HowRobotsRunIsNoPartOfAWorld) {
  for (const char* mission :
       {"mission: explore\n", "mission: {mode: explore, safety_distance: 0.4}\n"}) {
    const std::string e = errorOf(mission + minimal());
    EXPECT_NE(e.find("w.yaml:1:10: mission: a world describes the world, not how robots run in "
                     "it"),
              std::string::npos)
        << e;
  }
}

TEST(WorldLoaderTest, NegativeThicknessNamesLineAndField) {
  const std::string e = errorOf(
      replaceLine(minimal(), 6, "  - {from: [0, 0], to: [5, 0], thickness: -0.1, texture: a}"));
  EXPECT_EQ(e,
            "w.yaml:6:43: walls[0].thickness: expected a positive thickness up to 2 m, got '-0.1'");
}

TEST(WorldLoaderTest, UnknownTextureListsTheDeclaredOnes) {
  const std::string e = errorOf(
      replaceLine(minimal(), 6, "  - {from: [0, 0], to: [5, 0], thickness: 0.1, texture: marble}"));
  EXPECT_EQ(e,
            "w.yaml:6:57: walls[0].texture: expected the name of a texture declared under "
            "'textures' (a), got 'marble'");
}

TEST(WorldLoaderTest, MissingFieldIsNamed) {
  const std::string e = errorOf(replaceLine(minimal(), 15, ""));
  EXPECT_EQ(e, "w.yaml:13:5: robots[0]: missing required field 'robots[0].start'");
}

TEST(WorldLoaderTest, TypoInKeyIsCaught) {
  const std::string e = errorOf(replaceLine(minimal(), 1, "nmae: t"));
  EXPECT_NE(e.find("w.yaml:1:1: nmae: unknown field 'nmae'"), std::string::npos) << e;
}

TEST(WorldLoaderTest, WrongCornerCount) {
  const std::string e = errorOf(replaceLine(minimal(), 10, ""));
  EXPECT_EQ(e, "w.yaml:9:5: home_base.corners: expected exactly 2 corners, got a list");
}

// Where a robot's body stands at the start nothing else may: a wall, a box, another robot.
TEST(WorldLoaderTest, StartsThatOverlapAreRefused) {
  const std::string in_wall =
      errorOf(replaceLine(minimal(), 15, "    start: {position: [2, 0.2], heading_deg: 90}"));
  EXPECT_EQ(in_wall,
            "w.yaml:15:12: robots[0].start: the robot's body (radius 0.18 m) at (2.00 m, 0.20 m) "
            "overlaps a wall of the world");
  const std::string two = minimal() + "  - name: r2\n    model: " + kSrc +
                          "/robots/b14/b14.yaml\n"
                          "    start: {position: [2.2, 2], heading_deg: 90}\n";
  EXPECT_EQ(errorOf(two),
            "w.yaml:19:12: robots[1].start: the robot's body overlaps r1's at its start (0.20 m "
            "apart, their radii add up to 0.36 m)");
  const std::string apart = minimal() + "  - name: r2\n    model: " + kSrc +
                            "/robots/b14/b14.yaml\n"
                            "    start: {position: [3, 2], heading_deg: 90}\n";
  EXPECT_EQ(errorOf(apart), "(no error)");
}

// A door fills its doorway, no more: a leaf reaching into the walls beside the gap is refused.
TEST(WorldLoaderTest, DoorsWiderThanTheirDoorwayAreRefused) {
  // A wall along y = 0 from x = 0 to 5 with a gap from 2 to 3 for a door.
  const std::string walls =
      "  - {from: [0, 0], to: [2, 0], thickness: 0.1, texture: a}\n"
      "  - {from: [3, 0], to: [5, 0], thickness: 0.1, texture: a}\n"
      "doors:\n"
      "  - {center: [2.5, 0], width: ";
  const std::string fits = replaceLine(minimal(), 6, walls + "1.0}");
  EXPECT_EQ(errorOf(fits), "(no error)");
  const std::string wide = replaceLine(minimal(), 6, walls + "1.4}");
  EXPECT_EQ(errorOf(wide),
            "w.yaml:9:31: doors[0].width: a door no wider than its doorway: 1.40 m wide at "
            "(2.50 m, 0.00 m), it reaches 0.20 m into the wall from (0.00 m, 0.00 m) to (2.00 "
            "m, 0.00 m)");
  // Across a wall (a door in the wrong place) is refused too.
  const std::string across = replaceLine(
      minimal(), 6, walls + "1.0, yaw_deg: 90}\n  - {center: [1, 0], width: 0.8, yaw_deg: 90}");
  EXPECT_NE(errorOf(across).find("doors[1].width: a door no wider than its doorway"),
            std::string::npos)
      << errorOf(across);
}

TEST(WorldLoaderTest, WaypointOffTheFloor) {
  const std::string e = errorOf(replaceLine(minimal(), 16, "    route: [[3, 3], [9, 3]]"));
  EXPECT_EQ(e, "w.yaml:16:21: robots[0].route[1]: expected a waypoint on the floor, got a list");
}

TEST(WorldLoaderTest, WaypointFacesAHeadingWithinItsOwnTolerance) {
  const World w = parseWorld(
      replaceLine(minimal(), 16,
                  "    route: [{at: [3, 3], within: 0.01, face_deg: -90, wait: 2, spin: true}]"),
      "w.yaml");
  ASSERT_EQ(w.robots[0].route.size(), 1u);
  const auto& wp = w.robots[0].route[0];
  ASSERT_TRUE(wp.face.has_value());
  EXPECT_NEAR(*wp.face, -M_PI / 2, 1e-12);
  EXPECT_EQ(wp.arrive_tolerance, 0.01);
  EXPECT_EQ(wp.wait, 2.0);
  EXPECT_EQ(errorOf(replaceLine(minimal(), 16, "    route: [{at: [3, 3], within: 0}]")),
            "w.yaml:16:34: robots[0].route[0].within: expected metres in [0.001, 10], got '0'");
}

// A building's floor is its rooms and corridors: an L of two rectangles here.
TEST(WorldLoaderTest, FloorOfRoomsAndCorridorsIsTheirRectangles) {
  const std::string l_shape =
      "floor:\n"
      "  texture: a\n"
      "  areas:\n"
      "    - {min: [0, 0], max: [5, 4]}\n"
      "    - {min: [4, 4], max: [5, 9]}\n";
  std::string text = replaceLine(minimal(), 4, l_shape);
  const World w = parseWorld(text, "w.yaml");
  ASSERT_EQ(w.floor_areas.size(), 2u);
  EXPECT_EQ(w.floor_min, Eigen::Vector2d(0, 0));
  EXPECT_EQ(w.floor_max, Eigen::Vector2d(5, 9));
  EXPECT_TRUE(w.onFloor({4.5, 8.0}));
  EXPECT_TRUE(w.onFloor({1.0, 1.0}));
  EXPECT_FALSE(w.onFloor({1.0, 8.0}));  // inside the bounding box, off the floor

  // A waypoint in the corner the L leaves out is off the floor.
  EXPECT_NE(errorOf(replaceLine(text, 21, "    route: [[1, 6]]")).find("a waypoint on the floor"),
            std::string::npos)
      << errorOf(replaceLine(text, 21, "    route: [[1, 6]]"));
  // Both forms at once, an empty list and an upside-down rectangle are refused by line.
  const std::string both = errorOf(replaceLine(text, 5, "  texture: a\n  min: [0, 0]"));
  EXPECT_NE(both.find("w.yaml:5:3: floor:"), std::string::npos) << both;
  EXPECT_NE(both.find("either 'min' and 'max'"), std::string::npos) << both;
  const std::string empty = errorOf(replaceLine(minimal(), 4, "floor: {texture: a, areas: []}"));
  EXPECT_NE(empty.find("a non-empty list"), std::string::npos) << empty;
  const std::string flipped = errorOf(replaceLine(text, 8, "    - {min: [4, 9], max: [5, 4]}"));
  EXPECT_NE(flipped.find("w.yaml:8"), std::string::npos) << flipped;
  EXPECT_NE(flipped.find("above and to the right"), std::string::npos) << flipped;
}

TEST(WorldLoaderTest, MissingModelFileIsReported) {
  const std::string e = errorOf(replaceLine(minimal(), 14, "    model: nowhere/b14.yaml"));
  EXPECT_NE(e.find("w.yaml:14:12: robots[0].model: expected the path of a robot model file"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("nowhere/b14.yaml does not exist"), std::string::npos) << e;
}

TEST(WorldLoaderTest, SyntaxErrorNamesTheLine) {
  const std::string e = errorOf(replaceLine(minimal(), 4, "floor: {min: [0, 0], max: [5, 4"));
  EXPECT_EQ(e.rfind("w.yaml:", 0), 0u) << e;
  EXPECT_NE(e.find("YAML syntax error"), std::string::npos) << e;
}

TEST(WorldLoaderTest, MissingFile) {
  try {
    loadWorld("/nonexistent/world.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/world.yaml: cannot open world file");
  }
}

}  // namespace
}  // namespace coopmap::sim

namespace coopmap::sim {
namespace {

TEST(WorldLoaderTest, PeopleWalkTheirPaths) {
  const World w = parseWorld(
      minimal() +
          "people:\n  - {name: ann, speed: 1.0, start_time: 1.0, path: [[1, 1], [4, 1], [4, 3]]}\n",
      "w.yaml");
  ASSERT_EQ(w.people.size(), 1u);
  const PersonSpec& p = w.people[0];
  EXPECT_EQ(p.positionAt(0.5), Eigen::Vector2d(1, 1));  // waits for its start time
  EXPECT_TRUE(p.positionAt(3.0).isApprox(Eigen::Vector2d(3, 1)));
  EXPECT_TRUE(p.positionAt(5.0).isApprox(Eigen::Vector2d(4, 2)));
  EXPECT_EQ(p.positionAt(60.0), Eigen::Vector2d(4, 3));  // stays at the end
}

TEST(WorldLoaderTest, PersonYieldDistanceIsRead) {
  const World w = parseWorld(minimal() +
                                 "people:\n"
                                 "  - {name: ann, path: [[1, 1], [4, 1]]}\n"
                                 "  - {name: bob, yield_distance: 0, path: [[1, 1], [4, 1]]}\n"
                                 "  - {name: cid, yield_distance: 2.5, path: [[1, 1], [4, 1]]}\n",
                             "w.yaml");
  ASSERT_EQ(w.people.size(), 3u);
  EXPECT_EQ(w.people[0].yield_distance, 1.0);  // the default
  EXPECT_EQ(w.people[1].yield_distance, 0.0);  // never waits
  EXPECT_EQ(w.people[2].yield_distance, 2.5);
}

TEST(WorldLoaderTest, PersonYieldDistanceMustNotBeNegative) {
  const std::string e = errorOf(
      minimal() + "people:\n  - {name: ann, yield_distance: -0.5, path: [[1, 1], [4, 1]]}\n");
  EXPECT_EQ(e,
            "w.yaml:18:33: people[0].yield_distance: expected a distance in [0, 100] m (0: never "
            "waits for robots), got '-0.5'");
}

TEST(WorldLoaderTest, PersonPathNeedsTwoPoints) {
  const std::string e = errorOf(minimal() + "people:\n  - {name: ann, path: [[1, 1]]}\n");
  EXPECT_EQ(e, "w.yaml:18:23: people[0].path: expected a list of at least 2 points, got a list");
}

}  // namespace
}  // namespace coopmap::sim

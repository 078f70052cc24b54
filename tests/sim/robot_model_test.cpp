#include "robots/robot_model.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "core/io/yaml_reader.h"

namespace coopmap {
namespace {

const std::string kB14 = std::string(COOPMAP_SOURCE_DIR) + "/robots/b14/b14.yaml";

TEST(RobotModelTest, B14MatchesThePaper) {
  const RobotModel m = loadRobotModel(kB14);
  const RobotDescription& d = m.description;
  EXPECT_NEAR(d.body_radius, 0.178, 1e-9);  // 14-inch cylinder
  EXPECT_EQ(d.rig.intrinsics.width, 160);
  EXPECT_EQ(d.rig.intrinsics.height, 120);
  // 90 degree horizontal field of view.
  EXPECT_NEAR(2.0 * std::atan(0.5 * d.rig.intrinsics.width / d.rig.intrinsics.fx), M_PI / 2, 1e-9);
  EXPECT_NEAR(d.rig.referenceBaseline(), 0.10, 1e-9);
  EXPECT_NEAR(d.rig.vertical_offset.norm(), 0.10, 1e-9);
  EXPECT_FALSE(m.odometry.perfect);
}

std::string errorOf(const std::string& from, const std::string& to) {
  std::ifstream in(kB14);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  try {
    parseRobotModel(text, "b14.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RobotModelTest, BadValuesAreNamed) {
  EXPECT_NE(errorOf("hfov_deg: 90", "hfov_deg: 200")
                .find("cameras.hfov_deg: expected a field of view in [10, 170] degrees, got '200'"),
            std::string::npos);
  EXPECT_NE(errorOf("horizontal_offset: [0.10, 0.0, 0.0]", "horizontal_offset: [0.10, 0.02, 0.0]")
                .find("cameras.horizontal_offset: expected [b, 0, 0]"),
            std::string::npos);
  EXPECT_NE(
      errorOf("preset: drifting", "preset: wobbly")
          .find("simulation.odometry.preset: expected one of: perfect, drifting, got 'wobbly'"),
      std::string::npos);
  const std::string e = errorOf("radius: 0.178", "radius: big");
  EXPECT_EQ(e.rfind("b14.yaml:", 0), 0u) << e;
  EXPECT_NE(e.find("body.radius: expected a number, got 'big'"), std::string::npos) << e;
}

}  // namespace
}  // namespace coopmap

namespace coopmap {
namespace {

TEST(RobotModelTest, OdometryPresetsByName) {
  const RobotModel m = loadRobotModel(kB14);
  ASSERT_TRUE(m.odometry_presets.count("default"));
  ASSERT_TRUE(m.odometry_presets.count("utias_robot1"));
  EXPECT_NEAR(m.odometry_presets.at("utias_robot1").heading_drift, 0.072574, 1e-9);
  EXPECT_EQ(m.odometry_presets.at("default").heading_drift, m.odometry.heading_drift);
  const std::string e = errorOf("    utias_robot2:", "    perfect:");
  EXPECT_NE(e.find("'perfect' is a reserved preset name"), std::string::npos) << e;
}

}  // namespace
}  // namespace coopmap

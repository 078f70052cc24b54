#include "core/io/yaml_reader.h"

#include <gtest/gtest.h>

namespace coopmap {
namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(YamlReaderTest, WrongTypeNamesFileLineFieldAndValue) {
  const YamlField root = YamlField::loadString("a: 1\nb:\n  c: fast\n", "cfg.yaml");
  const std::string m = messageOf([&] { root["b"]["c"].asDouble(); });
  EXPECT_EQ(m, "cfg.yaml:3:6: b.c: expected a number, got 'fast'");
}

TEST(YamlReaderTest, MissingFieldNamesTheParentLine) {
  const YamlField root = YamlField::loadString("a: 1\nb:\n  c: 2\n", "cfg.yaml");
  const std::string m = messageOf([&] { root["b"]["d"]; });
  EXPECT_EQ(m, "cfg.yaml:3:3: b: missing required field 'b.d'");
}

TEST(YamlReaderTest, ListElementsAreIndexed) {
  const YamlField root = YamlField::loadString("xs:\n  - [1, 2]\n  - [1, two]\n", "cfg.yaml");
  const auto xs = root["xs"].elements();
  EXPECT_EQ(xs[0].asVector2(), Eigen::Vector2d(1, 2));
  EXPECT_EQ(messageOf([&] { xs[1].asVector2(); }),
            "cfg.yaml:3:9: xs[1][1]: expected a number, got 'two'");
}

TEST(YamlReaderTest, RangeAndEnumAndUnknownKeys) {
  const YamlField root = YamlField::loadString("n: 7\nmode: sideways\nspeeed: 1\n", "cfg.yaml");
  EXPECT_EQ(messageOf([&] { root["n"].asInt(0, 5); }),
            "cfg.yaml:1:4: n: expected an integer in [0, 5], got '7'");
  EXPECT_EQ(messageOf([&] {
              root["mode"].asEnum({"up", "down"});
            }),
            "cfg.yaml:2:7: mode: expected one of: up, down, got 'sideways'");
  EXPECT_EQ(messageOf([&] {
              root.allowOnly({"n", "mode", "speed"});
            }),
            "cfg.yaml:3:1: speeed: unknown field 'speeed' (expected one of: n, mode, speed)");
}

TEST(YamlReaderTest, SyntaxErrorNamesLine) {
  const std::string m = messageOf([] { YamlField::loadString("a: [1, 2\nb: 3\n", "bad.yaml"); });
  EXPECT_EQ(m.rfind("bad.yaml:", 0), 0u) << m;
  EXPECT_NE(m.find("YAML syntax error"), std::string::npos) << m;
}

// A key given twice would be read as whichever yaml-cpp kept: refused, at any depth.
TEST(YamlReaderTest, AKeyGivenTwiceIsRefused) {
  EXPECT_EQ(messageOf([] { YamlField::loadString("a: 1\nb: 2\na: 3\n", "cfg.yaml"); }),
            "cfg.yaml:3:1: key 'a' given twice in one mapping");
  EXPECT_EQ(messageOf([] { YamlField::loadString("xs:\n  - {x: 1, y: 2, x: 3}\n", "cfg.yaml"); }),
            "cfg.yaml:2:18: key 'x' given twice in one mapping");
  EXPECT_EQ(messageOf([] { YamlField::loadString("a: {x: 1}\nb: {x: 1}\n", "cfg.yaml"); }),
            "(no error)");
}

TEST(YamlReaderTest, MissingFileIsReported) {
  EXPECT_EQ(messageOf([] { YamlField::loadFile("/nonexistent/w.yaml"); }),
            "/nonexistent/w.yaml: cannot open file");
}

}  // namespace
}  // namespace coopmap

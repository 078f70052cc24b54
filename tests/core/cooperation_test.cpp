// The cooperation layer's guards: bad configuration, a sortie without radial maps, and a
// sortie that cannot be localized are reported and nothing reaches the shared map.
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/agent/cooperation.h"

namespace coopmap {
namespace {

HomeBase homeBase() {
  HomeBase h;
  h.first.position = {2.8, 0.8};
  h.first.heading = M_PI;
  h.second.position = {2.8, 2.2};
  h.second.heading = M_PI;
  return h;
}

MapLimits limits() { return MapLimits::covering({0, 0}, {10, 8}, 0.05); }

TEST(CooperationTest, BadConfigurationNamesTheField) {
  LocalSharedMap shared(limits(), OccupancyConfig{});
  CooperationConfig c;
  c.max_fix_jump_m = 0.0;
  try {
    HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared, c);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_fix_jump_m"), std::string::npos) << e.what();
  }
  c = CooperationConfig{};
  c.closure_min_inliers = 1.5;
  EXPECT_THROW(HomeBaseCooperation("jose", homeBase(), 0.6, &shared, c), std::invalid_argument);
  EXPECT_THROW(HomeBaseCooperation("jose", homeBase(), 0.6, nullptr), std::invalid_argument);
}

TEST(CooperationTest, EmptySortieIsReportedAndNothingIsPosted) {
  LocalSharedMap shared(limits(), OccupancyConfig{});
  HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared);
  TraverseLog log;
  log.robot = "jose";
  const SortieReport r = coop.endSortie(log);
  EXPECT_FALSE(r.fixed);
  EXPECT_FALSE(r.posted);
  EXPECT_EQ(r.sortie, 1);
  EXPECT_NE(r.method.find("no radial maps"), std::string::npos) << r.method;
  EXPECT_EQ(shared.version(), 0u);
  EXPECT_EQ(coop.reports().size(), 1u);
  EXPECT_TRUE(coop.corrected().empty());
}

TEST(CooperationTest, SortieWithoutAHomeBaseInViewIsNotShared) {
  // A robot that turned in place in an empty world: no corners, no reference obstacles.
  LocalSharedMap shared(limits(), OccupancyConfig{});
  HomeBaseCooperation coop("jose", homeBase(), 0.6, &shared);
  TraverseLog log;
  log.robot = "jose";
  for (int i = 0; i < 40; ++i) {
    TraverseEntry e;
    e.segment = MotionSegment::kTurn;
    e.scan.stamp = i / 3.0;
    e.scan.odometry = Pose2(1.5, 1.5, wrapAngle(i * 0.2));
    RadialReading miss;
    miss.kind = RadialKind::kBeyond;
    miss.range = 3.0;
    e.scan.readings.assign(20, miss);
    log.entries.push_back(e);
  }
  const SortieReport first = coop.locate(log);
  EXPECT_FALSE(first.fixed);
  EXPECT_TRUE(coop.reports().empty()) << "locate records nothing";
  const SortieReport r = coop.endSortie(log);
  EXPECT_FALSE(r.fixed);
  EXPECT_FALSE(r.posted);
  EXPECT_EQ(shared.version(), 0u);
}

}  // namespace
}  // namespace coopmap

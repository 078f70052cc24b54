// report.html and trajectories.png from a small synthetic run.
#include "sim/runner/report_html.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "core/io/atomic_file.h"

namespace coopmap {
namespace {

namespace fs = std::filesystem;

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string freshDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("coopmap_report_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// A 60 x 40 grid at 0.1 m from (-1, -2): a wall along the bottom row and one column at ix 30.
GridU8 truthGrid() {
  MapLimits lim;
  lim.resolution = 0.1;
  lim.origin = Eigen::Vector2d(-1.0, -2.0);
  lim.width = 60;
  lim.height = 40;
  GridU8 g(lim, 0);
  for (int ix = 0; ix < 60; ++ix) g.at(ix, 0) = 1;
  for (int iy = 0; iy < 40; ++iy) g.at(30, iy) = 1;
  return g;
}

std::vector<StampedPose2> line(double x0, double y0, double x1, double y1, int n) {
  std::vector<StampedPose2> poses;
  for (int i = 0; i < n; ++i) {
    const double f = static_cast<double>(i) / (n - 1);
    poses.push_back({1.0 * i, Pose2(x0 + f * (x1 - x0), y0 + f * (y1 - y0), 0.0)});
  }
  return poses;
}

ReportData syntheticRun(const GridU8& truth) {
  ReportData d;
  d.title = "synthetic & small, seed 1";
  d.summary = {{"world", "synthetic"}, {"robots", "2"}, {"odometry end error", "<0.5 m"}};
  d.robots = {{"jose", line(-0.5, -1.5, 1.5, 1.0, 8), line(-0.5, -1.5, 1.8, 1.3, 8), {}},
              {"maria", line(2.5, -1.0, 4.5, 1.5, 6), line(2.5, -1.0, 4.0, 1.9, 6),
               line(2.5, -1.0, 4.4, 1.6, 6)}};
  d.truth = &truth;
  d.limits = truth.limits;
  d.images = {{"Shared map (home-base protocol)", "map_shared.png"},
              {"jose's map", "map_jose.png"}};
  d.coverage = {{"jose", {{0, 0.0}, {10, 0.4}, {20, 0.7}, {30, 0.95}}},
                {"shared map", {{0, 0.0}, {10, 0.6}, {20, 0.92}, {30, 0.99}}}};
  d.error = {{"jose odometry", {{0, 0.0}, {10, 0.2}, {20, 0.5}, {30, 0.8}}}};
  d.coverage_note = "Fraction of the true free space seen.";
  d.error_note = "Distance from the true position.";
  return d;
}

TEST(ReportHtmlTest, PageHoldsTitleSeriesImagesAndEscapedSummary) {
  const GridU8 truth = truthGrid();
  const std::string dir = freshDir("page");
  writeReport(dir, syntheticRun(truth));
  const std::string html = readFile(dir + "/report.html");
  EXPECT_NE(html.find("<h1>synthetic &amp; small, seed 1</h1>"), std::string::npos);
  for (const char* name : {"jose", "shared map", "jose odometry", "maria"})
    EXPECT_NE(html.find(name), std::string::npos) << name;
  EXPECT_EQ(count(html, "<svg"), 2u);  // coverage and error
  EXPECT_EQ(count(html, "</svg>"), 2u);
  for (const char* file : {"map_shared.png", "map_jose.png", "trajectories.png"})
    EXPECT_NE(html.find("src=\"" + std::string(file) + "\""), std::string::npos) << file;
  EXPECT_NE(html.find("<th scope=\"row\">odometry end error</th><td>&lt;0.5 m</td>"),
            std::string::npos);
  EXPECT_EQ(html.find("<0.5 m"), std::string::npos);
  EXPECT_NE(html.find(">90 %</text>"), std::string::npos);
  EXPECT_NE(html.find("Fraction of the true free space seen."), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  // Robots table: maria's corrected path ends 0.1 m x 0.1 m from the truth.
  EXPECT_NE(html.find("0.14 m, 0.0&deg;"), std::string::npos);
  // Written atomically: no temp files left.
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
}

TEST(ReportHtmlTest, TrajectoriesPngIsTheTrueMapAtScaleWithALegendBeside) {
  const GridU8 truth = truthGrid();
  const std::string dir = freshDir("png");
  ReportData d = syntheticRun(truth);
  d.map_scale = 3;
  writeReport(dir, d);
  const cv::Mat img = cv::imread(dir + "/trajectories.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_GT(img.cols, 60 * 3);  // the map, then the legend column
  EXPECT_GE(img.rows, 40 * 3);
  // North up: the bottom wall row (iy 0) is the map's last pixel rows; walls grey.
  EXPECT_EQ(img.at<cv::Vec3b>(40 * 3 - 2, 10 * 3 + 1), cv::Vec3b(80, 80, 80));
  EXPECT_EQ(img.at<cv::Vec3b>(20 * 3 + 1, 30 * 3 + 1), cv::Vec3b(80, 80, 80));
  EXPECT_EQ(img.at<cv::Vec3b>(4 * 3 + 1, 10 * 3 + 1), cv::Vec3b(255, 255, 255));  // (10, 35)
  // jose's ground truth (first colour, BGR 178 114 0) passes through its midpoint.
  const Pose2 mid(0.5, -0.25, 0.0);
  const int px = static_cast<int>((mid.x + 1.0) / 0.1 * 3),
            py = static_cast<int>((40 - (mid.y + 2.0) / 0.1) * 3);
  bool blue = false;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const cv::Vec3b c = img.at<cv::Vec3b>(py + dy, px + dx);
      blue |= c[0] > 150 && c[2] < 60;
    }
  EXPECT_TRUE(blue);
  // The legend column holds ink.
  const cv::Mat legend = img(cv::Rect(60 * 3 + 1, 0, img.cols - 60 * 3 - 1, img.rows));
  EXPECT_LT(cv::mean(legend)[0], 254.0);
}

TEST(ReportHtmlTest, AutomaticScaleIsFourPixelsPerCellForASmallMap) {
  const GridU8 truth = truthGrid();
  ReportData d = syntheticRun(truth);
  d.map_scale = 0;
  const std::string png = encodeTrajectoriesPng(d);
  const cv::Mat img =
      cv::imdecode(std::vector<unsigned char>(png.begin(), png.end()), cv::IMREAD_COLOR);
  ASSERT_GE(img.rows, 40 * 4);
  EXPECT_EQ(img.at<cv::Vec3b>(40 * 4 - 2, 10 * 4 + 2), cv::Vec3b(80, 80, 80));  // bottom wall
  EXPECT_EQ(img.at<cv::Vec3b>(40 * 4 - 6, 10 * 4 + 2), cv::Vec3b(255, 255, 255));
}

TEST(ReportHtmlTest, EmptyAndSinglePointSeriesAreShownWithoutCrashing) {
  const GridU8 truth = truthGrid();
  const std::string dir = freshDir("sparse");
  ReportData d = syntheticRun(truth);
  d.coverage = {{"nothing yet", {}}, {"one sample", {{5.0, 0.3}}}};
  d.error = {{"empty", {}}};
  writeReport(dir, d);
  const std::string html = readFile(dir + "/report.html");
  EXPECT_NE(html.find("nothing yet (no data)"), std::string::npos);
  EXPECT_NE(html.find("empty (no data)"), std::string::npos);
  EXPECT_EQ(count(html, "<circle"), 1u);  // the single point, as a dot
}

TEST(ReportHtmlTest, NonFiniteValuesBreakTheLine) {
  PlotAxes axes;
  axes.y_label = "error";
  const std::string svg =
      renderSvgPlot({{"gappy", {{0, 1.0}, {1, 2.0}, {2, NAN}, {3, 1.5}, {4, 1.0}}}}, axes);
  EXPECT_EQ(count(svg, "<polyline class=\"series\""), 2u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(ReportHtmlTest, CoverageAxisIsInPercentWithTheReferenceLine) {
  PlotAxes axes;
  axes.y_label = "coverage";
  axes.y_percent = true;
  axes.y_max = 1.0;
  axes.reference = {{0.9, "90 %"}};
  const std::string svg = renderSvgPlot({{"a", {{0, 0.1}, {600, 0.5}}}}, axes);
  EXPECT_NE(svg.find(">100 %</text>"), std::string::npos);
  EXPECT_NE(svg.find(">0 %</text>"), std::string::npos);
  EXPECT_NE(svg.find(">600</text>"), std::string::npos);  // the last time tick
  EXPECT_EQ(count(svg, "<line class=\"ref\""), 1u);
}

TEST(ReportHtmlTest, EscapesEveryHtmlSpecialCharacter) {
  EXPECT_EQ(escapeHtml("a<b>&\"c\"'d'"), "a&lt;b&gt;&amp;&quot;c&quot;&#39;d&#39;");
}

TEST(ReportHtmlTest, UnwritableOutDirThrowsNamingTheFile) {
  const GridU8 truth = truthGrid();
  const std::string dir = freshDir("missing") + "/not/there";
  try {
    writeReport(dir, syntheticRun(truth));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/trajectories.png"), std::string::npos) << e.what();
  }
}

TEST(ReportHtmlTest, TruthThatDisagreesWithItsLimitsIsRejected) {
  GridU8 truth = truthGrid();
  truth.cells.resize(100);
  try {
    encodeTrajectoriesPng(syntheticRun(truth));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("100 cells"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("60 x 40"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace coopmap

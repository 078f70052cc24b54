#include "sim/runner/report_html.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/atomic_file.h"
#include "sim/runner/report_style.h"

namespace coopmap {
namespace {

using namespace report_style;

cv::Scalar bgr(const Rgb& c) { return cv::Scalar(c.b, c.g, c.r); }

// ---- trajectories.png --------------------------------------------------------------------

MapLimits canvasLimits(const ReportData& d) {
  if (d.truth) {
    const MapLimits lim = d.limits.width > 0 ? d.limits : d.truth->limits;
    if (lim.width <= 0 || lim.height <= 0 || d.truth->cells.size() != lim.size())
      throw std::invalid_argument("report: the true map has " +
                                  std::to_string(d.truth->cells.size()) + " cells, its limits " +
                                  std::to_string(lim.width) + " x " + std::to_string(lim.height));
    return lim;
  }
  if (d.limits.width > 0 && d.limits.height > 0) return d.limits;
  Eigen::Vector2d lo(std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const ReportRobot& r : d.robots)
    for (const auto* traj : {&r.groundtruth, &r.odometry, &r.corrected})
      for (const StampedPose2& p : *traj)
        if (p.pose.translation().allFinite()) {
          lo = lo.cwiseMin(p.pose.translation());
          hi = hi.cwiseMax(p.pose.translation());
        }
  if (!(lo.x() <= hi.x()))
    throw std::invalid_argument("report: no true map, no limits and no pose to draw");
  // 5 cm cells, coarser when the poses span more than 100 m.
  const double resolution = std::max(0.05, (hi - lo).maxCoeff() / 2000.0);
  return MapLimits::covering(lo - Eigen::Vector2d(1, 1), hi + Eigen::Vector2d(1, 1), resolution);
}

// Draws a polyline solid (off <= 0) or with an on/off pattern in pixels along its length.
void drawPattern(cv::Mat& img, const std::vector<cv::Point2d>& pts, const cv::Scalar& colour,
                 int thickness, double on, double off) {
  constexpr int kShift = 4;  // sub-pixel bits
  auto fixed = [](const cv::Point2d& p) {
    return cv::Point(static_cast<int>(std::lround(p.x * (1 << kShift))),
                     static_cast<int>(std::lround(p.y * (1 << kShift))));
  };
  bool drawing = true;
  double left = on;
  for (size_t i = 1; i < pts.size(); ++i) {
    const cv::Point2d a = pts[i - 1], d = pts[i] - pts[i - 1];
    const double len = std::hypot(d.x, d.y);
    if (off <= 0.0) {
      cv::line(img, fixed(a), fixed(pts[i]), colour, thickness, cv::LINE_AA, kShift);
      continue;
    }
    for (double pos = 0.0; pos < len;) {
      const double step = std::min(left, len - pos);
      if (drawing)
        cv::line(img, fixed(a + d * (pos / len)), fixed(a + d * ((pos + step) / len)), colour,
                 thickness, cv::LINE_AA, kShift);
      pos += step;
      left -= step;
      if (left <= 1e-9) {
        drawing = !drawing;
        left = drawing ? on : off;
      }
    }
  }
}

struct LineStyle {
  const char* label;
  double on, off;  // in line thicknesses; off 0: solid
};
constexpr LineStyle kTruthStyle{"ground truth", 1, 0};
constexpr LineStyle kOdometryStyle{"odometry", 4, 2.5};
constexpr LineStyle kCorrectedStyle{"corrected", 0.01, 3};

bool anyCorrected(const ReportData& d) {
  return std::any_of(d.robots.begin(), d.robots.end(),
                     [](const ReportRobot& r) { return !r.corrected.empty(); });
}

bool hasPoses(const ReportData& d) {
  return std::any_of(d.robots.begin(), d.robots.end(), [](const ReportRobot& r) {
    return !r.groundtruth.empty() || !r.odometry.empty() || !r.corrected.empty();
  });
}

}  // namespace

std::string escapeHtml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string encodeTrajectoriesPng(const ReportData& data) {
  if (data.map_scale < 0 || data.map_scale > 16)
    throw std::invalid_argument("report: map_scale must be 0 (automatic) to 16, got " +
                                std::to_string(data.map_scale));
  const MapLimits lim = canvasLimits(data);
  const int s = data.map_scale > 0 ? data.map_scale
                                   : std::clamp(1200 / std::max(lim.width, lim.height), 1, 4);
  const int map_w = lim.width * s, map_h = lim.height * s;
  // Lines, markers and legend grow with images over 1200 px, which are shown shrunk.
  const double ui = std::max(1.0, std::max(map_w, map_h) / 1200.0);
  auto px = [&](double v) { return static_cast<int>(std::lround(v * ui)); };
  const int t = px(2);  // line thickness
  const bool corrected = anyCorrected(data);

  // Legend column: robots by colour, line styles, markers, a scale bar.
  constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
  const double font_scale = 0.45 * ui;
  const int font_t = px(1), pad = px(10), row = px(20), sample = px(34), gap = px(8);
  const cv::Scalar ink(40, 40, 40);
  std::vector<std::string> texts;
  for (const ReportRobot& r : data.robots) texts.push_back(r.name);
  texts.insert(texts.end(),
               {kTruthStyle.label, kOdometryStyle.label, kCorrectedStyle.label, "start", "end"});
  int text_w = 0;
  for (const std::string& text : texts) {
    int base = 0;
    text_w = std::max(text_w, cv::getTextSize(text, kFont, font_scale, font_t, &base).width);
  }
  double bar_m = 0.1;  // the longest "nice" length up to 120 legend pixels
  for (const double m : {0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0})
    if (m / lim.resolution * s <= 120.0 * ui) bar_m = m;
  const int bar_px = static_cast<int>(std::lround(bar_m / lim.resolution * s));
  const int legend_w = pad + std::max(sample + gap + text_w, bar_px) + pad;
  // Rows: robots, gap, line styles, gap, start, end, scale bar, its length.
  const int rows = static_cast<int>(data.robots.size()) + 1 + (corrected ? 3 : 2) + 1 + 2 + 2;
  const int legend_h = 2 * pad + rows * row;

  cv::Mat img(std::max(map_h, legend_h), map_w + legend_w, CV_8UC3, cv::Scalar(255, 255, 255));
  if (data.truth)
    for (int iy = 0; iy < lim.height; ++iy)
      for (int ix = 0; ix < lim.width; ++ix)
        if (data.truth->at(ix, iy))
          img(cv::Rect(ix * s, (lim.height - 1 - iy) * s, s, s)).setTo(cv::Scalar(80, 80, 80));
  cv::rectangle(img, cv::Rect(0, 0, map_w, map_h), cv::Scalar(180, 180, 180), 1);

  auto toPixel = [&](const Pose2& p) {  // as encodeMapPng: north up; far off the map clamped
    constexpr double kFar = 1e5;
    return cv::Point2d(
        std::clamp((p.x - lim.origin.x()) / lim.resolution * s, -kFar, kFar),
        std::clamp((lim.height - (p.y - lim.origin.y()) / lim.resolution) * s, -kFar, kFar));
  };
  const int start_r = 3 * t, end_r = t + px(1);
  for (size_t i = 0; i < data.robots.size(); ++i) {
    const ReportRobot& r = data.robots[i];
    const cv::Scalar colour = bgr(paletteColour(i));
    const std::pair<const std::vector<StampedPose2>*, LineStyle> layers[] = {
        {&r.groundtruth, kTruthStyle},
        {&r.odometry, kOdometryStyle},
        {&r.corrected, kCorrectedStyle}};
    bool started = false;
    for (const auto& [traj, style] : layers) {
      std::vector<cv::Point2d> pts;
      pts.reserve(traj->size());
      for (const StampedPose2& p : *traj)
        if (p.pose.translation().allFinite()) pts.push_back(toPixel(p.pose));
      if (pts.empty()) continue;
      if (!std::exchange(started, true))
        cv::circle(img, pts.front(), start_r, colour, font_t, cv::LINE_AA);
      drawPattern(img, pts, colour, t, style.on * t, style.off * t);
      cv::circle(img, pts.back(), end_r, colour, cv::FILLED, cv::LINE_AA);
    }
  }

  // The legend; each row's sample is centred on y + row / 2.
  int y = pad;
  const int x0 = map_w + pad, xt = x0 + sample + gap, mid = row / 2;
  auto label = [&](const std::string& text) {
    cv::putText(img, text, cv::Point(xt, y + px(14)), kFont, font_scale, ink, font_t, cv::LINE_AA);
    y += row;
  };
  for (size_t i = 0; i < data.robots.size(); ++i) {
    cv::rectangle(img, cv::Rect(x0, y + px(5), sample, px(10)), bgr(paletteColour(i)), cv::FILLED);
    label(data.robots[i].name);
  }
  y += row;
  std::vector<LineStyle> styles = {kTruthStyle, kOdometryStyle};
  if (corrected) styles.push_back(kCorrectedStyle);
  for (const LineStyle& style : styles) {
    drawPattern(img, {cv::Point2d(x0, y + mid), cv::Point2d(x0 + sample, y + mid)}, ink, t,
                style.on * t, style.off * t);
    label(style.label);
  }
  y += row;
  cv::circle(img, cv::Point(x0 + sample / 2, y + mid), start_r, ink, font_t, cv::LINE_AA);
  label("start");
  cv::circle(img, cv::Point(x0 + sample / 2, y + mid), end_r, ink, cv::FILLED, cv::LINE_AA);
  label("end");
  cv::line(img, cv::Point(x0, y + mid), cv::Point(x0 + bar_px, y + mid), ink, t);
  for (const int x : {x0, x0 + bar_px})
    cv::line(img, cv::Point(x, y + mid - px(5)), cv::Point(x, y + mid + px(5)), ink, font_t);
  y += row;
  cv::putText(img, format(bar_m < 1.0 ? "%.1f m" : "%.0f m", bar_m), cv::Point(x0, y + px(14)),
              kFont, font_scale, ink, font_t, cv::LINE_AA);

  std::vector<unsigned char> buf;
  if (!cv::imencode(".png", img, buf)) throw std::runtime_error("OpenCV could not encode a PNG");
  return std::string(buf.begin(), buf.end());
}

namespace {

// ---- the page -----------------------------------------------------------------------------

// The pose of `truth` nearest in time to `t`; truth must not be empty.
const Pose2& nearestInTime(const std::vector<StampedPose2>& truth, double t) {
  const auto it = std::lower_bound(truth.begin(), truth.end(), t,
                                   [](const StampedPose2& p, double s) { return p.stamp < s; });
  if (it == truth.begin()) return it->pose;
  if (it == truth.end() || t - (it - 1)->stamp < it->stamp - t) return (it - 1)->pose;
  return it->pose;
}

// "1.23 m, 4.5°": where `traj` ends against the truth at that time; "–" without either.
std::string endError(const std::vector<StampedPose2>& traj,
                     const std::vector<StampedPose2>& truth) {
  if (traj.empty() || truth.empty()) return "&ndash;";
  const Pose2& end = traj.back().pose;
  const Pose2& ref = nearestInTime(truth, traj.back().stamp);
  return format("%.2f m, ", std::hypot(end.x - ref.x, end.y - ref.y)) +
         format("%.1f&deg;", std::abs(wrapAngle(end.theta - ref.theta)) * 180.0 / M_PI);
}

std::string robotRows(const ReportData& d, bool corrected) {
  std::string rows;
  for (size_t i = 0; i < d.robots.size(); ++i) {
    const ReportRobot& r = d.robots[i];
    const std::vector<StampedPose2>& path = r.groundtruth.empty() ? r.odometry : r.groundtruth;
    double length = 0.0;
    for (size_t k = 1; k < path.size(); ++k)
      length +=
          std::hypot(path[k].pose.x - path[k - 1].pose.x, path[k].pose.y - path[k - 1].pose.y);
    const double duration = path.empty() ? 0.0 : path.back().stamp - path.front().stamp;
    rows += "<tr><td><span class=\"swatch\" style=\"background:" + hexColour(paletteColour(i)) +
            "\"></span>" + escapeHtml(r.name) + "</td><td class=\"num\">" +
            format("%.1f", duration) + "</td><td class=\"num\">" + format("%.2f", length) +
            "</td><td class=\"num\">" + endError(r.odometry, r.groundtruth) + "</td>";
    if (corrected) rows += "<td class=\"num\">" + endError(r.corrected, r.groundtruth) + "</td>";
    rows += "</tr>\n";
  }
  return rows;
}

// A file name as a URL path relative to the page: bytes outside [A-Za-z0-9-._~/] escaped.
std::string urlPath(const std::string& file) {
  std::string out;
  for (const unsigned char c : file) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/')
      out += static_cast<char>(c);
    else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

constexpr const char* kCss = R"(
body { font: 15px/1.5 "Helvetica Neue", Helvetica, Arial, sans-serif; color: #222;
       max-width: 1000px; margin: 2em auto; padding: 0 1.2em; background: #fff; }
h1 { font-size: 1.6em; font-weight: 600; margin: 0; }
p.sub { color: #666; margin: .1em 0 1.5em; }
h2 { font-size: 1.15em; font-weight: 600; border-bottom: 1px solid #ccc; padding-bottom: .2em;
     margin: 2em 0 .6em; }
table { border-collapse: collapse; border-top: 2px solid #222; border-bottom: 2px solid #222;
        margin: .6em 0 1.2em; }
th, td { padding: .25em 1em .25em 0; text-align: left; vertical-align: top; }
thead th { border-bottom: 1px solid #222; font-weight: 600; }
tbody th { font-weight: normal; color: #444; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td { font-variant-numeric: tabular-nums; }
figure { margin: 1em 0 1.6em; }
figure img { display: block; max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: .9em; color: #444; margin-top: .5em; max-width: 760px; }
figcaption b { color: #222; }
figcaption .file, figcaption .file a { color: #777; }
.maps { display: grid; grid-template-columns: repeat(auto-fill, minmax(300px, 1fr)); gap: 0 1.4em; }
.swatch { display: inline-block; width: .9em; height: .9em; vertical-align: -.1em;
          margin-right: .35em; border-radius: 2px; }
svg.plot { display: block; width: 100%; max-width: 720px; height: auto; }
footer { color: #999; font-size: .85em; margin-top: 3em; border-top: 1px solid #eee;
         padding-top: .5em; }
)";

std::string renderHtml(const ReportData& d, bool trajectories) {
  int figure = 0;
  auto caption = [&](const std::string& body) {
    return "<figcaption><b>Figure " + std::to_string(++figure) + ".</b> " + body +
           "</figcaption>\n";
  };
  const bool corrected = anyCorrected(d);
  const std::string title = d.title.empty() ? "coopmap run" : d.title;
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>" +
      escapeHtml(title) + " &ndash; coopmap report</title>\n<style>" + kCss +
      "</style>\n</head>\n<body>\n";
  h += "<header><h1>" + escapeHtml(title) +
       "</h1><p class=\"sub\">coopmap run report</p></header>\n";

  if (!d.summary.empty() || !d.robots.empty()) h += "<section>\n<h2>Summary</h2>\n";
  if (!d.summary.empty()) {
    h += "<table class=\"summary\"><tbody>\n";
    for (const auto& [key, value] : d.summary)
      h += "<tr><th scope=\"row\">" + escapeHtml(key) + "</th><td>" + escapeHtml(value) +
           "</td></tr>\n";
    h += "</tbody></table>\n";
  }
  if (!d.robots.empty()) {
    h += "<table class=\"robots\"><thead><tr><th>robot</th><th>duration (s)</th>"
         "<th>path length (m)</th><th>odometry error at the end</th>";
    if (corrected) h += "<th>corrected error at the end</th>";
    h += "</tr></thead><tbody>\n" + robotRows(d, corrected) + "</tbody></table>\n";
  }
  if (!d.summary.empty() || !d.robots.empty()) h += "</section>\n";

  if (trajectories) {
    std::string robots;
    for (size_t i = 0; i < d.robots.size(); ++i)
      robots += std::string(i ? ", " : "") +
                "<span class=\"swatch\" style=\"background:" + hexColour(paletteColour(i)) +
                "\"></span>" + escapeHtml(d.robots[i].name);
    h += "<section>\n<h2>Trajectories</h2>\n<figure><a href=\"trajectories.png\"><img "
         "src=\"trajectories.png\" alt=\"trajectories over the true map\"></a>\n" +
         caption(
             std::string(d.truth ? "Trajectories over the true map (walls grey)" : "Trajectories") +
             ": ground truth solid, odometry dashed" + (corrected ? ", corrected dotted" : "") +
             "; a circle marks the start, a dot each end. " + robots + ".") +
         "</figure>\n</section>\n";
  }

  auto plot = [&](const char* heading, const std::vector<ReportSeries>& series,
                  const PlotAxes& axes, const std::string& note) {
    if (series.empty()) return;
    h += "<section>\n<h2>" + std::string(heading) + "</h2>\n<figure>\n" +
         renderSvgPlot(series, axes) + "\n" + caption(escapeHtml(note)) + "</figure>\n</section>\n";
  };
  PlotAxes coverage_axes;
  coverage_axes.y_label = "coverage";
  coverage_axes.y_percent = true;
  coverage_axes.y_max = 1.0;
  coverage_axes.reference = {{0.9, "90 %"}};
  plot("Coverage", d.coverage, coverage_axes, d.coverage_note);
  PlotAxes error_axes;
  error_axes.y_label = "position error (m)";
  plot("Position error", d.error, error_axes, d.error_note);

  if (!d.images.empty()) {
    h += "<section>\n<h2>Maps</h2>\n<div class=\"maps\">\n";
    for (const ReportImage& im : d.images) {
      const std::string url = escapeHtml(urlPath(im.file));
      h += "<figure><a href=\"" + url + "\"><img src=\"" + url + "\" alt=\"" +
           escapeHtml(im.caption) + "\" loading=\"lazy\"></a>\n" +
           caption(escapeHtml(im.caption) + " <span class=\"file\">(<a href=\"" + url + "\">" +
                   escapeHtml(im.file) + "</a>)</span>") +
           "</figure>\n";
    }
    h += "</div>\n</section>\n";
  }
  h += "<footer>Written by coopmap. Images are files in this folder.</footer>\n</body>\n</html>\n";
  return h;
}

}  // namespace

void writeReport(const std::string& out_dir, const ReportData& data) {
  const bool draw_map = data.truth || data.limits.width > 0 || hasPoses(data);
  if (draw_map) {
    const std::string path = out_dir + "/trajectories.png";
    std::string png;
    try {
      png = encodeTrajectoriesPng(data);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::exception& e) {  // OpenCV's, e.g. an image too large to encode
      throw std::runtime_error("cannot write '" + path + "': " + e.what());
    }
    writeFileAtomic(path, png);
  }
  writeFileAtomic(out_dir + "/report.html", renderHtml(data, draw_map));
}

}  // namespace coopmap

// The report's colours and number formatting, shared by trajectories.png (report_html.cpp)
// and the SVG plots (svg_plot.cpp). Internal to the runner.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

namespace coopmap::report_style {

// Okabe-Ito colours (safe for colour-blind readers), shared by the PNG and the plots.
struct Rgb {
  unsigned char r, g, b;
};
constexpr Rgb kPalette[] = {{0, 114, 178},   {213, 94, 0},  {0, 158, 115},
                            {204, 121, 167}, {230, 159, 0}, {86, 180, 233}};
constexpr size_t kPaletteSize = sizeof kPalette / sizeof kPalette[0];

inline Rgb paletteColour(size_t i) { return kPalette[i % kPaletteSize]; }
inline std::string hexColour(const Rgb& c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

inline std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace coopmap::report_style

#include "core/io/tum.h"

#include <cmath>
#include <cstdio>

#include "core/io/atomic_file.h"

namespace coopmap {

std::string formatTum(const std::vector<StampedPose2>& trajectory, const std::string& comment) {
  std::string out = "# " + comment + "\n# timestamp tx ty tz qx qy qz qw\n";
  char line[160];
  for (const StampedPose2& p : trajectory) {
    const double h = 0.5 * p.pose.theta;
    std::snprintf(line, sizeof line, "%.6f %.6f %.6f 0 0 0 %.9f %.9f\n", p.stamp, p.pose.x,
                  p.pose.y, std::sin(h), std::cos(h));
    out += line;
  }
  return out;
}

void writeTum(const std::string& path, const std::vector<StampedPose2>& trajectory,
              const std::string& comment) {
  writeFileAtomic(path, formatTum(trajectory, comment));
}

}  // namespace coopmap

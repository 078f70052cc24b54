// A radial-map return for tests that build radial maps by hand.
#pragma once

#include "core/perception/radial_map.h"

namespace coopmap {

// An obstacle at `range` (m) along `bearing` (rad, robot frame), with its 1-sigma.
inline RadialReading hit(double bearing, double range, double sigma) {
  RadialReading r;
  r.bearing = bearing;
  r.range = range;
  r.sigma = sigma;
  r.kind = RadialKind::kHit;
  return r;
}

}  // namespace coopmap

// Shared by the cooperative scenario tests: one line on a run's shared map, for the log.
#pragma once

#include <cstdint>
#include <cstdio>

#include "sim/runner/world_run.h"

namespace coopmap::scenario_test {

inline void printSharedMap(uint64_t seed, const RunResult& r) {
  const SharedMapResult& s = r.shared_map;
  std::printf(
      "seed %llu: shared wall_recall %.3f FOR %.4f coverage %.3f (%d posts); naive "
      "%.3f %.4f; 90 %% coverage after %.0f s\n",
      static_cast<unsigned long long>(seed), s.protocol.wall_recall, s.protocol.false_occupied_rate,
      s.protocol.coverage, s.posts_accepted, s.naive.wall_recall, s.naive.false_occupied_rate,
      r.time_to_90_s);
}

}  // namespace coopmap::scenario_test

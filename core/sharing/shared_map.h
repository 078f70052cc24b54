// The shared map (section 4 of the paper): robots post radial maps with poses corrected at
// the home base, and import the common grid. A post is applied whole or not at all, the map
// is versioned, and with a folder it is persisted atomically before a post is acknowledged,
// so a crash loses nothing that was acknowledged. `SharedMapService` is the interface a
// networked service would implement too; `LocalSharedMap` is the in-process one.
//
// Two grids take the same posts. The robots import the shared grid: their aligner's distance
// field and their planner's obstacles, which want each return drawn over a wide band (the
// home-base fixes are worse with a narrower one). The published grid is the map people get
// (outputs, metrics): each return drawn over the band its range error has. Stereo's is
// narrower than the band the shared grid draws, as `coopmap remap --range-errors` measures it
// on the building's runs (measured: docs/experiments/2026-12-building-sessions-25-34.md).
//
// Snapshot file format, version 2 (little-endian): 8 bytes magic "CMSHAREM", u32 version,
// f64 resolution, f64 origin x, y, i32 width, height, u64 map version, u32 robot count, per
// robot (u32 name length, name, u64 last post id), then the shared grid's width*height i16
// log-odds and width*height u8 seen flags, then the published grid's (the same two layers),
// then u32 CRC-32 of everything before it. Version 1 (no published layers) is still read: its
// published grid starts as a copy of the shared one.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/correction/traverse_log.h"
#include "core/geometry/pose2.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

// One radial map at its pose in the shared (map) frame.
struct PostedScan {
  RadialMap scan;
  Pose2 pose;  // X_MR
};

struct MapPost {
  std::string robot;
  uint64_t post_id = 0;  // increasing per robot; a repeated id is a retry, not new data
  std::vector<PostedScan> scans;
};

enum class PostStatus { kAccepted, kDuplicate, kRejected };
const char* toString(PostStatus s);

struct PostResult {
  PostStatus status = PostStatus::kRejected;
  uint64_t version = 0;  // the map version after the post
  std::string reason;    // why a post was rejected
};

struct SharedMapSnapshot {
  uint64_t version = 0;
  std::vector<int16_t> log_odds;  // the grid's layers, row-major over the service's limits
  std::vector<uint8_t> seen;
};

class SharedMapService {
 public:
  virtual ~SharedMapService() = default;
  SharedMapService() = default;
  SharedMapService(const SharedMapService&) = delete;
  SharedMapService& operator=(const SharedMapService&) = delete;

  // Applies a post whole or not at all; acknowledged (kAccepted) only once it is durable.
  virtual PostResult post(const MapPost& post) = 0;
  // The current map.
  virtual SharedMapSnapshot snapshot() const = 0;
  // The id of `robot`'s last post applied (0: none). A robot numbers its posts after it, so
  // that a robot joining a map kept from earlier runs (or restarted) is not taken for a
  // duplicate of itself.
  virtual uint64_t lastPost(const std::string& robot) const = 0;
  // The grid geometry and update rule every robot must use to import the map.
  virtual const MapLimits& limits() const = 0;
  virtual const OccupancyConfig& config() const = 0;
};

// The published grid's band (OccupancyConfig::sigma_scale) the runs use by default: half the
// modelled sigma, about the robust spread stereo's range errors have in the building's runs.
// Drawn at it, the published map loses a little wall recall and has far fewer false
// obstacles than at the shared grid's band (measured:
// docs/experiments/2026-12-building-sessions-25-34.md).
inline constexpr double kPublishedSigmaScale = 0.5;

// The in-process service; thread-safe. With a non-empty `folder` the map is restored from
// `folder/shared_map.bin` if present and saved there (temp file + rename) on every post,
// before the post is acknowledged; one service per folder.
// `published`: the published grid's update rule (unset: `config`, the one grid twice).
class LocalSharedMap final : public SharedMapService {
 public:
  // Throws std::runtime_error naming the file for an unreadable or corrupt snapshot, or one
  // made for other limits.
  LocalSharedMap(const MapLimits& limits, const OccupancyConfig& config,
                 const std::string& folder = "",
                 const std::optional<OccupancyConfig>& published = std::nullopt);

  PostResult post(const MapPost& post) override;
  SharedMapSnapshot snapshot() const override;
  uint64_t lastPost(const std::string& robot) const override;
  const MapLimits& limits() const override { return grid_.limits(); }
  const OccupancyConfig& config() const override { return grid_.config(); }
  // The current shared grid (a copy): what the robots import.
  OccupancyGrid grid() const;
  // The current published grid (a copy): the map for metrics and outputs.
  OccupancyGrid publishedGrid() const;
  const OccupancyConfig& publishedConfig() const { return published_.config(); }
  uint64_t version() const;

  static std::string encodeSnapshot(const OccupancyGrid& grid, const OccupancyGrid& published,
                                    uint64_t version,
                                    const std::map<std::string, uint64_t>& last_posts);

 private:
  void load(const std::string& path);
  mutable std::mutex mutex_;
  OccupancyGrid grid_;
  OccupancyGrid published_;  // kept only when separate_ (else the shared grid is published)
  bool separate_ = false;    // the published grid has its own update rule
  uint64_t version_ = 0;
  std::map<std::string, uint64_t> last_post_;  // per robot
  std::string file_;
};

// A motion filter on what is posted (GMapping's linearUpdate/angularUpdate, Cartographer's
// motion filter): a robot standing still takes the same view again and again, with the same
// stereo errors, and posting all of them lets one viewpoint's phantoms outvote the free space
// seen from everywhere else. A radial map is posted when the robot has moved min_move_m or
// turned min_turn_rad since the last one posted (the first always is). Zeros post all.
struct PostThinning {
  double min_move_m = 0.1;
  double min_turn_rad = 0.1;
  void validate() const;  // throws std::invalid_argument naming the field
};

// A robot's corrected traverse as a post: its entries' radial maps at their corrected poses,
// thinned. Throws std::invalid_argument when the pose count differs from the log's.
MapPost correctedPost(const TraverseLog& log, const std::vector<Pose2>& corrected, uint64_t post_id,
                      const PostThinning& thinning = {});
// The paper's "simplest form of cooperation": the radial maps at their uncorrected odometry
// poses, as they are taken (thinned the same way, so that only the poses differ).
MapPost naivePost(const TraverseLog& log, uint64_t post_id, const PostThinning& thinning = {});

}  // namespace coopmap

#include "core/sharing/shared_map.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/io/binary_io.h"

namespace coopmap {

namespace {

constexpr char kMagic[8] = {'C', 'M', 'S', 'H', 'A', 'R', 'E', 'M'};
constexpr uint32_t kFormatVersion = 2;

// Why a scan cannot be applied, or empty.
std::string checkScan(const PostedScan& s, const MapLimits& limits, size_t index) {
  const std::string where = "scan " + std::to_string(index) + ": ";
  const Pose2& p = s.pose;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta))
    return where + "pose is not finite";
  const Eigen::Vector2d lo = limits.origin;
  const Eigen::Vector2d hi = lo + Eigen::Vector2d(limits.width, limits.height) * limits.resolution;
  if (p.x < lo.x() || p.y < lo.y() || p.x > hi.x() || p.y > hi.y())
    return where + "pose (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
           ") is outside the shared map";
  for (const RadialReading& r : s.scan.readings)
    if (!std::isfinite(r.bearing) || !std::isfinite(r.range) || !std::isfinite(r.sigma) ||
        r.range < 0.0 || r.sigma < 0.0)
      return where + "a reading is not finite or negative";
  return "";
}

}  // namespace

const char* toString(PostStatus s) {
  switch (s) {
    case PostStatus::kAccepted:
      return "accepted";
    case PostStatus::kDuplicate:
      return "duplicate";
    case PostStatus::kRejected:
      return "rejected";
  }
  return "?";
}

LocalSharedMap::LocalSharedMap(const MapLimits& limits, const OccupancyConfig& config,
                               const std::string& folder,
                               const std::optional<OccupancyConfig>& published)
    : grid_(limits, config),
      published_(limits, published.value_or(config)),
      separate_(published && !(*published == config)) {
  if (folder.empty()) return;
  std::filesystem::create_directories(folder);
  file_ = folder + "/shared_map.bin";
  // A service killed while saving left its temporary file: the snapshot it was replacing is
  // the last acknowledged state (one service per folder).
  const std::string partial = "shared_map.bin.tmp.";
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().filename().string().rfind(partial, 0) == 0)
      std::filesystem::remove(entry.path());
  if (std::filesystem::exists(file_)) load(file_);
}

std::string LocalSharedMap::encodeSnapshot(const OccupancyGrid& grid,
                                           const OccupancyGrid& published, uint64_t version,
                                           const std::map<std::string, uint64_t>& last_posts) {
  ByteWriter w;
  w.out.append(kMagic, sizeof(kMagic));
  w.put<uint32_t>(kFormatVersion);
  const MapLimits& l = grid.limits();
  w.put(l.resolution);
  w.put(l.origin.x());
  w.put(l.origin.y());
  w.put<int32_t>(l.width);
  w.put<int32_t>(l.height);
  w.put<uint64_t>(version);
  w.put<uint32_t>(static_cast<uint32_t>(last_posts.size()));
  for (const auto& [robot, id] : last_posts) {
    w.put<uint32_t>(static_cast<uint32_t>(robot.size()));
    w.putBytes(robot);
    w.put<uint64_t>(id);
  }
  for (const OccupancyGrid* g : {&grid, &published}) {
    const auto& lo = g->logOddsGrid().cells;
    const auto& seen = g->seenGrid().cells;
    w.out.append(reinterpret_cast<const char*>(lo.data()), lo.size() * sizeof(int16_t));
    w.out.append(reinterpret_cast<const char*>(seen.data()), seen.size());
  }
  w.put<uint32_t>(crc32Of(w.out.data(), w.out.size()));
  return w.out;
}

void LocalSharedMap::load(const std::string& path) {
  const std::string bytes = readFile(path);
  auto fail = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
  const size_t header = sizeof(kMagic) + 4 + 3 * 8 + 2 * 4 + 8 + 4;
  if (bytes.size() < header + 4 || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    fail("not a coopmap shared map (expected magic 'CMSHAREM' at byte 0)");
  {
    ByteReader c(bytes, bytes.size() - 4, bytes.size());
    if (c.get<uint32_t>() != crc32Of(bytes.data(), bytes.size() - 4))
      fail("checksum mismatch (the file is corrupt or truncated)");
  }
  ByteReader r(bytes, sizeof(kMagic), bytes.size() - 4);
  const uint32_t format = r.get<uint32_t>();
  if (format != 1 && format != kFormatVersion)
    fail("shared map format version " + std::to_string(format) + " (this build reads 1 and " +
         std::to_string(kFormatVersion) + ")");
  const double resolution = r.get<double>();
  const double ox = r.get<double>(), oy = r.get<double>();
  const int32_t width = r.get<int32_t>(), height = r.get<int32_t>();
  const MapLimits& l = grid_.limits();
  if (resolution != l.resolution || ox != l.origin.x() || oy != l.origin.y() || width != l.width ||
      height != l.height)
    fail("made for other map limits (" + std::to_string(width) + " x " + std::to_string(height) +
         " cells of " + std::to_string(resolution) + " m)");
  const uint64_t version = r.get<uint64_t>();
  const uint32_t robots = r.get<uint32_t>();
  std::map<std::string, uint64_t> last;
  for (uint32_t i = 0; i < robots; ++i) {
    if (r.left() < 4) fail("truncated robot list");
    const uint32_t n = r.get<uint32_t>();
    if (r.left() < static_cast<size_t>(n) + 8) fail("truncated robot list");
    std::string name(n, '\0');
    r.getBytes(name.data(), n);
    last[name] = r.get<uint64_t>();
  }
  const size_t cells = l.size();
  const size_t grids = format == 1 ? 1 : 2;
  if (r.left() != grids * cells * 3)
    fail("expected " + std::to_string(grids * cells * 3) + " bytes of map layers, found " +
         std::to_string(r.left()));
  for (OccupancyGrid* g : {&grid_, &published_}) {
    std::vector<int16_t> lo(cells);
    std::vector<uint8_t> seen(cells);
    if (g == &grid_ || grids == 2) {
      r.getBytes(lo.data(), cells * sizeof(int16_t));
      r.getBytes(seen.data(), cells);
    } else {
      lo = grid_.logOddsGrid().cells;
      seen = grid_.seenGrid().cells;
    }
    g->assign(lo, seen);
  }
  version_ = version;
  last_post_ = std::move(last);
}

PostResult LocalSharedMap::post(const MapPost& post) {
  std::lock_guard<std::mutex> lock(mutex_);
  PostResult result;
  result.version = version_;
  if (post.robot.empty()) {
    result.reason = "the post names no robot";
    return result;
  }
  const auto last = last_post_.find(post.robot);
  if (last != last_post_.end() && post.post_id <= last->second) {
    result.status = PostStatus::kDuplicate;
    result.reason = "post " + std::to_string(post.post_id) + " of " + post.robot +
                    " was already applied (last " + std::to_string(last->second) + ")";
    return result;
  }
  // Whole or not at all: every scan is checked before any is applied.
  for (size_t i = 0; i < post.scans.size(); ++i) {
    const std::string why = checkScan(post.scans[i], grid_.limits(), i);
    if (!why.empty()) {
      result.reason = why;
      return result;
    }
  }
  OccupancyGrid next = grid_;
  for (const PostedScan& s : post.scans) next.insert(s.scan, s.pose);
  // Without a rule of its own the published grid is the shared one (publishedGrid()).
  std::optional<OccupancyGrid> next_published;
  if (separate_) {
    next_published = published_;
    for (const PostedScan& s : post.scans) next_published->insert(s.scan, s.pose);
  }
  std::map<std::string, uint64_t> next_last = last_post_;
  next_last[post.robot] = post.post_id;
  // Durable before acknowledged.
  if (!file_.empty())
    writeFileAtomic(file_, encodeSnapshot(next, next_published ? *next_published : next,
                                          version_ + 1, next_last));
  grid_ = std::move(next);
  if (next_published) published_ = std::move(*next_published);
  last_post_ = std::move(next_last);
  ++version_;
  result.status = PostStatus::kAccepted;
  result.version = version_;
  return result;
}

uint64_t LocalSharedMap::lastPost(const std::string& robot) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto last = last_post_.find(robot);
  return last == last_post_.end() ? 0 : last->second;
}

SharedMapSnapshot LocalSharedMap::snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {version_, grid_.logOddsGrid().cells, grid_.seenGrid().cells};
}

OccupancyGrid LocalSharedMap::grid() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return grid_;
}

OccupancyGrid LocalSharedMap::publishedGrid() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return separate_ ? published_ : grid_;
}

uint64_t LocalSharedMap::version() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return version_;
}

void PostThinning::validate() const {
  if (!(min_move_m >= 0.0))
    throw std::invalid_argument("post thinning: field 'min_move_m': expected a number >= 0, got " +
                                std::to_string(min_move_m));
  if (!(min_turn_rad >= 0.0))
    throw std::invalid_argument(
        "post thinning: field 'min_turn_rad': expected a number >= 0, got " +
        std::to_string(min_turn_rad));
}

namespace {

// Appends the scans at their poses, skipping those taken less than the thinning's motion
// from the last one kept.
template <typename PoseOf>
void appendThinned(MapPost& post, const TraverseLog& log, const PostThinning& thinning,
                   PoseOf&& poseOf) {
  thinning.validate();
  const Pose2* last = nullptr;
  for (size_t i = 0; i < log.entries.size(); ++i) {
    const Pose2& pose = poseOf(i);
    if (last && std::hypot(pose.x - last->x, pose.y - last->y) < thinning.min_move_m &&
        std::abs(wrapAngle(pose.theta - last->theta)) < thinning.min_turn_rad)
      continue;
    post.scans.push_back({log.entries[i].scan, pose});
    last = &pose;
  }
}

}  // namespace

MapPost correctedPost(const TraverseLog& log, const std::vector<Pose2>& corrected, uint64_t post_id,
                      const PostThinning& thinning) {
  if (corrected.size() != log.entries.size())
    throw std::invalid_argument("correctedPost: " + std::to_string(corrected.size()) +
                                " poses for a log of " + std::to_string(log.entries.size()));
  MapPost p;
  p.robot = log.robot;
  p.post_id = post_id;
  appendThinned(p, log, thinning, [&](size_t i) -> const Pose2& { return corrected[i]; });
  return p;
}

MapPost naivePost(const TraverseLog& log, uint64_t post_id, const PostThinning& thinning) {
  MapPost p;
  p.robot = log.robot;
  p.post_id = post_id;
  appendThinned(p, log, thinning,
                [&](size_t i) -> const Pose2& { return log.entries[i].scan.odometry; });
  return p;
}

}  // namespace coopmap

#include "sim/runner/stereo_evaluation.h"

#include <filesystem>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "core/io/atomic_file.h"
#include "core/io/image_file.h"
#include "core/mapping/grid.h"
#include "robots/robot_model.h"
#include "sim/runner/world_run.h"
#include "sim/world/world.h"

namespace coopmap {

namespace {

cv::Mat readGrey(const std::string& path, const std::string& what) {
  if (path.empty()) throw std::invalid_argument("--" + what + ": expected an image file");
  return readImage(path, cv::IMREAD_GRAYSCALE, kMaxMapCells);
}

void writePng(const std::string& path, const cv::Mat& img) {
  std::vector<unsigned char> buf;
  if (!cv::imencode(".png", img, buf)) throw std::runtime_error(path + ": PNG encoding failed");
  writeFileAtomic(path, std::string(buf.begin(), buf.end()));
}

// Accumulates scores over frames (counts add up; rates are recomputed).
struct Accumulator {
  DisparityScore total;
  double abs_sum = 0.0, signed_sum = 0.0, relative_sum = 0.0;
  int frames = 0;
  void add(const DisparityScore& s) {
    total.evaluated += s.evaluated;
    total.valid += s.valid;
    total.bad += s.bad;
    abs_sum += s.mae * s.valid;
    total.good += s.good;
    signed_sum += s.bias * s.good;
    relative_sum += s.depth_scale_error * s.good;
    ++frames;
  }
  DisparityScore result() const {
    DisparityScore r = total;
    r.density = r.evaluated ? double(r.valid) / r.evaluated : 0.0;
    r.bad_pixel_rate = r.valid ? double(r.bad) / r.valid : 0.0;
    r.mae = r.valid ? abs_sum / r.valid : 0.0;
    r.bias = r.good ? signed_sum / r.good : 0.0;
    r.depth_scale_error = r.good ? relative_sum / r.good : 0.0;
    return r;
  }
};

void writePictures(const StereoEvalOptions& o, const cv::Mat& reference, const cv::Mat& disparity,
                   const cv::Mat& truth, double max_d) {
  if (o.png_dir.empty()) return;
  std::filesystem::create_directories(o.png_dir);
  writePng(o.png_dir + "/reference.png", reference);
  writePng(o.png_dir + "/disparity.png", colourDisparity(disparity, max_d));
  writePng(o.png_dir + "/truth.png", colourDisparity(truth, max_d));
  writePng(o.png_dir + "/errors.png", errorPicture(disparity, truth));
}

}  // namespace

StereoEvalResult runStereoEval(const StereoEvalOptions& o) {
  StereoEvalResult result;
  Accumulator acc;
  if (!o.world.empty()) {
    // Frames rendered along the first robot's route, ground truth from the depth buffer.
    struct Frame {
      TrinocularFrame frame;
      cv::Mat depth;
    };
    std::vector<Frame> frames;
    RunOptions run;
    run.world_file = o.world;
    run.seed = o.seed;
    run.robots = 1;
    run.odometry = "perfect";
    run.frame_observer = [&](const std::string&, const TrinocularFrame& f, const cv::Mat& depth) {
      frames.push_back({f, depth.clone()});
    };
    runWorld(run);
    if (frames.empty()) throw std::runtime_error(o.world + ": the run produced no frames");
    const RobotModel model = loadRobotModel(sim::loadWorld(o.world).robots[0].model_file);
    TrinocularMatcher matcher(model.description.rig, o.stereo);
    const int n = std::max(1, std::min<int>(o.frames, static_cast<int>(frames.size())));
    cv::Mat disparity;
    for (int i = 0; i < n; ++i) {
      const Frame& f = frames[static_cast<size_t>(i) * frames.size() / n];
      matcher.compute(f.frame.reference, f.frame.horizontal, f.frame.vertical, disparity);
      const cv::Mat truth = disparityFromDepth(f.depth, matcher.focalBaseline());
      acc.add(scoreDisparity(disparity, truth, 1.0, o.border));
      if (i == 0) writePictures(o, f.frame.reference, disparity, truth, o.stereo.num_disparities);
    }
    result.max_disparity = o.stereo.num_disparities;
  } else {
    const cv::Mat ref = readGrey(o.reference, "reference");
    const cv::Mat hor = readGrey(o.horizontal, "horizontal");
    const cv::Mat ver = readGrey(o.vertical, "vertical");
    if (ref.size() != hor.size() || ref.size() != ver.size())
      throw std::invalid_argument("the reference, horizontal and vertical images differ in size");
    if (o.truth.empty()) throw std::invalid_argument("--truth: expected an image file");
    cv::Mat truth_raw = readImage(o.truth, cv::IMREAD_UNCHANGED, kMaxMapCells);
    if (truth_raw.size() != ref.size() || truth_raw.channels() != 1)
      throw std::invalid_argument(o.truth +
                                  ": expected a one-channel image the size of the reference");
    cv::Mat truth;
    truth_raw.convertTo(truth, CV_32F, 1.0 / o.truth_scale);
    TrinocularRig rig;
    if (!o.rig.empty()) {
      rig = loadRobotModel(o.rig).description.rig;
    } else {
      rig.horizontal_offset = {o.horizontal_offset, 0.0, 0.0};
      rig.vertical_offset = {0.0, o.vertical_offset, 0.0};
    }
    rig.intrinsics.width = ref.cols;
    rig.intrinsics.height = ref.rows;
    TrinocularMatcher matcher(rig, o.stereo);
    cv::Mat disparity;
    matcher.compute(ref, hor, ver, disparity);
    acc.add(scoreDisparity(disparity, truth, 1.0, o.border));
    double max_t = 1.0;
    cv::minMaxLoc(truth, nullptr, &max_t);
    result.max_disparity = max_t * 1.2;
    writePictures(o, ref, disparity, truth, result.max_disparity);
  }
  result.score = acc.result();
  result.frames = acc.frames;
  return result;
}

}  // namespace coopmap

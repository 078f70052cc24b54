// coopmap stereo-eval: trinocular stereo scored against ground-truth disparities.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "apps/commands/commands.h"
#include "core/io/json_writer.h"
#include "sim/runner/stereo_evaluation.h"

namespace coopmap::apps {
namespace {

class StereoEvalCommand : public Command {
 public:
  explicit StereoEvalCommand(CLI::App& app);
  int run() override;

 private:
  StereoEvalOptions options_;
  std::string tsukuba_;
  std::string photometric_ = toString(options_.stereo.photometric);
  bool single_pair_ = false;
  bool json_ = false;
};

StereoEvalCommand::StereoEvalCommand(CLI::App& app)
    : Command(app.add_subcommand(
          "stereo-eval",
          "Score trinocular stereo against ground truth: bad-pixel rate (error > 1 px), mean "
          "absolute error and density. Sources: an image triple with a truth image, the Tsukuba "
          "multi-view set (--tsukuba), or frames rendered along a world's route (--world).")) {
  CLI::App* cmd = cli();
  cmd->add_option("--tsukuba", tsukuba_,
                  "Tsukuba folder: reference row3.col3, horizontal row3.col4, vertical "
                  "row2.col3, truth truedisp.row3.col3.pgm / 16")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--reference", options_.reference, "Reference image")->check(CLI::ExistingFile);
  cmd->add_option("--horizontal", options_.horizontal, "Horizontal partner image")
      ->check(CLI::ExistingFile);
  cmd->add_option("--vertical", options_.vertical, "Vertical partner image")
      ->check(CLI::ExistingFile);
  cmd->add_option("--truth", options_.truth, "Ground-truth disparity image")
      ->check(CLI::ExistingFile);
  cmd->add_option("--truth-scale", options_.truth_scale,
                  "Truth pixel value per pixel of disparity (Tsukuba: 16)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--horizontal-offset", options_.horizontal_offset,
                  "Horizontal partner's offset along the reference camera's x (right), in "
                  "baselines; any sign and length")
      ->capture_default_str();
  cmd->add_option("--vertical-offset", options_.vertical_offset,
                  "Vertical partner's offset along the reference camera's y (down), in "
                  "baselines of the horizontal pair; any sign and length")
      ->capture_default_str();
  cmd->add_option("--rig", options_.rig, "Take the partner offsets (metres) from a robot file")
      ->check(CLI::ExistingFile);
  cmd->add_option("--world", options_.world, "Render frames along the first robot's route")
      ->check(CLI::ExistingFile);
  cmd->add_option("--frames", options_.frames, "Frames to evaluate from the world run")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", options_.seed, "Seed of the world run")
      ->check(kSeed)
      ->capture_default_str();
  cmd->add_option("--disparities", options_.stereo.num_disparities, "Disparities searched")
      ->capture_default_str();
  cmd->add_option("--window", options_.stereo.window, "SAD window side (odd, 3..11)")
      ->capture_default_str();
  cmd->add_option("--uniqueness", options_.stereo.uniqueness,
                  "Best must beat the runner-up by this fraction")
      ->capture_default_str();
  cmd->add_option("--min-texture", options_.stereo.min_texture,
                  "Minimum mean |gradient| in the window (grey levels)")
      ->capture_default_str();
  cmd->add_option("--pair-consistency", options_.stereo.pair_consistency,
                  "Fraction each pair's cost at the winner may exceed its own best "
                  "(negative: off)")
      ->capture_default_str();
  cmd->add_option("--window-shift", options_.stereo.window_shift,
                  "Shiftable windows: px each pixel's window may move left or right against "
                  "foreground fattening (0: centred windows, at most window / 2)")
      ->capture_default_str();
  cmd->add_option("--photometric", photometric_,
                  "Photometric normalisation: global (partners' mean and spread matched to "
                  "the reference), local (mean removed over --prefilter-window), none")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "global", "local"}));
  cmd->add_option("--prefilter-window", options_.stereo.prefilter_window,
                  "Window of the local prefilter (odd px)")
      ->capture_default_str();
  cmd->add_option("--border", options_.border, "Pixels skipped on every side")
      ->capture_default_str();
  cmd->add_flag("--single-pair", single_pair_, "Use the horizontal pair only");
  cmd->add_option("--png", options_.png_dir,
                  "Folder for pictures: reference, disparity and truth in colour, errors");
  cmd->add_flag("--json", json_,
                "Print bad_pixel_rate, mae, bias, depth_scale_error, density as JSON");
}

int StereoEvalCommand::run() {
  if (!tsukuba_.empty()) {
    options_.reference = tsukuba_ + "/scene1.row3.col3.ppm";
    options_.horizontal = tsukuba_ + "/scene1.row3.col4.ppm";
    options_.vertical = tsukuba_ + "/scene1.row2.col3.ppm";
    options_.truth = tsukuba_ + "/truedisp.row3.col3.pgm";
    options_.truth_scale = 16.0;
    if (cli()->count("--disparities") == 0) options_.stereo.num_disparities = 16;
  }
  options_.stereo.use_vertical = !single_pair_;
  options_.stereo.photometric = parsePhotometric(photometric_);
  if (options_.world.empty() && (options_.reference.empty() || options_.truth.empty()))
    throw std::invalid_argument(
        "stereo-eval: expected --tsukuba DIR, --world FILE, or --reference/--horizontal/"
        "--vertical/--truth");
  const StereoEvalResult r = runStereoEval(options_);
  if (json_) {
    JsonWriter j;
    j.beginObject();
    j.value("bad_pixel_rate", r.score.bad_pixel_rate).value("mae", r.score.mae);
    j.value("bias", r.score.bias).value("depth_scale_error", r.score.depth_scale_error);
    j.value("density", r.score.density).value("frames", r.frames);
    j.value("evaluated_pixels", r.score.evaluated).value("valid_pixels", r.score.valid);
    j.endObject();
    std::printf("%s", j.str().c_str());
  } else {
    std::printf(
        "frames %d: bad_pixel_rate %.4f (> 1 px), mae %.3f px, bias %+.3f px, depth "
        "scale error %+.4f (good pixels), density %.3f (%d of %d pixels with ground truth)\n",
        r.frames, r.score.bad_pixel_rate, r.score.mae, r.score.bias, r.score.depth_scale_error,
        r.score.density, r.score.valid, r.score.evaluated);
  }
  return 0;
}

}  // namespace

std::unique_ptr<Command> addStereoEvalCommand(CLI::App& app) {
  return std::make_unique<StereoEvalCommand>(app);
}

}  // namespace coopmap::apps

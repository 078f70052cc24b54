// coopmap calibrate: the trinocular rig's calibration from checkerboard views.
#include <cstdio>

#include "apps/commands/commands.h"
#include "robots/camera/calibrate_rig.h"

namespace coopmap::apps {
namespace {

class CalibrateCommand : public Command {
 public:
  explicit CalibrateCommand(CLI::App& app)
      : Command(app.add_subcommand(
            "calibrate",
            "Calibrate the trinocular rig from checkerboard views: each camera (focal lengths, "
            "principal point, distortion k1 k2 p1 p2 k3), each partner against the reference "
            "(rotation, baseline); prints them with the reprojection RMS and writes the "
            "calibration (OpenCV FileStorage YAML) that the camera driver rectifies with.")) {
    CLI::App* cmd = cli();
    cmd->add_option("--reference", options_.sources[0],
                    "Reference camera's views: an image sequence (printf pattern, e.g. "
                    "ref_%04d.png) or a video file")
        ->required();
    cmd->add_option("--horizontal", options_.sources[1], "Horizontal partner's views")->required();
    cmd->add_option("--vertical", options_.sources[2], "Vertical partner's views")->required();
    cmd->add_option("--board", options_.board, "Inner corners COLSxROWS, e.g. 9x6")->required();
    cmd->add_option("--square", options_.square, "Side of a square (m)")
        ->required()
        ->check(CLI::PositiveNumber);
    cmd->add_option("--out", options_.out_file, "Calibration file to write (YAML)")->required();
  }

  int run() override {
    std::printf("%s", runCalibrate(options_).report.c_str());
    return 0;
  }

 private:
  CalibrateOptions options_;
};

}  // namespace

std::unique_ptr<Command> addCalibrateCommand(CLI::App& app) {
  return std::make_unique<CalibrateCommand>(app);
}

}  // namespace coopmap::apps

// coopmap corners: corner landmarks of a map_server map.
#include <cstdio>

#include "apps/commands/commands.h"
#include "core/landmarks/corner_report.h"

namespace coopmap::apps {
namespace {

class CornersCommand : public Command {
 public:
  explicit CornersCommand(CLI::App& app)
      : Command(app.add_subcommand(
            "corners",
            "Find corner landmarks in a ROS map_server map (MAP.yaml + image): writes "
            "corners.png (edges blue, fitted corners red) and corners.json (position in metres, "
            "heading, RMS in cells, iterations) to --out.")) {
    cli()
        ->add_option("map", options_.map_yaml, "Map YAML (map_server format)")
        ->required()
        ->check(CLI::ExistingFile);
    cli()->add_option("--out", options_.out_dir, "Output folder")->required()->check(kOutputFolder);
    cli()
        ->add_option("--arm-length", options_.arm_length, "Arm length of the corner model (m)")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
  }

  int run() override {
    StagedFolder out(options_.out_dir, "coopmap corners");
    const CornersResult r = runCorners(options_);
    out.commit();
    std::printf(
        "%zu corners (%d candidates, %d rejected by RMS, %d not converged, %d edge "
        "cells); %s/corners.png and corners.json written\n",
        r.search.corners.size(), r.search.candidates, r.search.rejected_rms, r.search.not_converged,
        r.edge_cells, out.given().c_str());
    return 0;
  }

 private:
  CornersOptions options_;
};

}  // namespace

std::unique_ptr<Command> addCornersCommand(CLI::App& app) {
  return std::make_unique<CornersCommand>(app);
}

}  // namespace coopmap::apps

// coopmap carmen: an occupancy grid, its corners and the trajectory from a CARMEN laser log.
#include <cstdio>

#include "apps/commands/commands.h"
#include "robots/carmen/carmen_mapping.h"

namespace coopmap::apps {
namespace {

class CarmenCommand : public Command {
 public:
  explicit CarmenCommand(CLI::App& app)
      : Command(app.add_subcommand(
            "carmen",
            "Map a laser log in CARMEN format (ODOM, FLASER/RLASER, RAWLASER1-4, ROBOTLASER1-2 "
            "lines; the classic public robot data sets) through the robot interface: writes the "
            "occupancy grid (map.pgm/.yaml/.png), its corners (corners.json/.png) and the "
            "trajectory (trajectory_odometry.tum; trajectory_groundtruth.tum with TRUEPOS) to "
            "--out.")) {
    CLI::App* cmd = cli();
    cmd->add_option("log", options_.log, "CARMEN log file (uncompressed)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--out", options_.out_dir, "Output folder")->required()->check(kOutputFolder);
    cmd->add_option("--resolution", options_.resolution, "Map resolution (m per cell)")
        ->capture_default_str();
    cmd->add_option("--max-range", options_.max_range,
                    "Usable laser range (m): farther returns only clear free space up to it; 0: "
                    "the laser's maximum (FLASER: 80 m)")
        ->capture_default_str();
    cmd->add_option("--laser", options_.laser,
                    "Laser to map with: 1 front (FLASER, RAWLASER1, ROBOTLASER1), 2 rear, 3, 4; "
                    "0: the lowest in the log")
        ->capture_default_str();
    cmd->add_option("--arm-length", options_.arm_length, "Arm length of the corner model (m)")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
  }

  int run() override {
    StagedFolder out(options_.out_dir, "coopmap carmen");
    const CarmenResult r = runCarmen(options_);
    out.commit();
    const MapLimits& lim = r.grid->limits();
    std::printf(
        "%d scans of laser %d over %.1f s, odometry path %.1f m; map %d x %d cells at %.3f "
        "m: %d occupied, %d free; %zu corners; outputs in %s\n",
        r.scans, r.laser, r.duration_s, r.path_length_m, lim.width, lim.height, lim.resolution,
        r.occupied_cells, r.free_cells, r.corners.search.corners.size(), out.given().c_str());
    return 0;
  }

 private:
  CarmenOptions options_;
};

}  // namespace

std::unique_ptr<Command> addCarmenCommand(CLI::App& app) {
  return std::make_unique<CarmenCommand>(app);
}

}  // namespace coopmap::apps

// The coopmap subcommands. Each function adds its subcommand and that subcommand's options to
// `app` and returns the command holding the option values; `coopmap --help` lists them in
// the order they are added.
#pragma once

#include <memory>

#include "apps/command.h"

namespace coopmap::apps {

std::unique_ptr<Command> addRunCommand(CLI::App& app);          // run
std::unique_ptr<Command> addSettingsCommand(CLI::App& app);     // settings
std::unique_ptr<Command> addReplayCommand(CLI::App& app);       // replay
std::unique_ptr<Command> addStereoEvalCommand(CLI::App& app);   // stereo-eval
std::unique_ptr<Command> addCornersCommand(CLI::App& app);      // corners
std::unique_ptr<Command> addCarmenCommand(CLI::App& app);       // carmen
std::unique_ptr<Command> addOdometryFitCommand(CLI::App& app);  // odometry-fit
std::unique_ptr<Command> addBenchCommand(CLI::App& app);        // bench drift, bench explore
std::unique_ptr<Command> addTraverseCommand(CLI::App& app);     // traverse
std::unique_ptr<Command> addRemapCommand(CLI::App& app);        // remap
std::unique_ptr<Command> addStereoScaleCommand(CLI::App& app);  // stereo-scale
std::unique_ptr<Command> addRobotCommand(CLI::App& app);        // robot
std::unique_ptr<Command> addCalibrateCommand(CLI::App& app);    // calibrate
std::unique_ptr<Command> addWorldCommand(CLI::App& app);        // world generate

}  // namespace coopmap::apps

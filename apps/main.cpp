// coopmap: the command-line program. Each subcommand adds its options and runs in its own
// file (apps/commands/); here the program parses the command line, runs the command given and
// turns failures into messages and exit codes.
#include <cstdio>
#include <exception>

#include <opencv2/core/utils/logger.hpp>

#include "apps/command.h"
#include "apps/commands/commands.h"
#include "core/io/yaml_reader.h"

int main(int argc, char** argv) {
  namespace apps = coopmap::apps;
  // coopmap reports what went wrong itself, naming the file: no library log lines before it.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  CLI::App app{
      "coopmap: a simulation-first testbed for cooperative stereo-vision mapping with B-14 "
      "robots (Little, Jennings, Murray)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", COOPMAP_VERSION);

  // In the order `coopmap --help` lists them.
  apps::CommandGroup commands(&app);
  commands.add(apps::addRunCommand(app));
  commands.add(apps::addSettingsCommand(app));
  commands.add(apps::addReplayCommand(app));
  commands.add(apps::addStereoEvalCommand(app));
  commands.add(apps::addCornersCommand(app));
  commands.add(apps::addCarmenCommand(app));
  commands.add(apps::addOdometryFitCommand(app));
  commands.add(apps::addBenchCommand(app));
  commands.add(apps::addTraverseCommand(app));
  commands.add(apps::addRemapCommand(app));
  commands.add(apps::addStereoScaleCommand(app));
  commands.add(apps::addRobotCommand(app));
  commands.add(apps::addCalibrateCommand(app));
  commands.add(apps::addWorldCommand(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Help and version exit 0; every bad option or value exits 2, as all bad input does.
    return app.exit(e) == 0 ? 0 : 2;
  }

  try {
    return commands.run();
  } catch (const coopmap::ConfigError& e) {
    std::fprintf(stderr, "coopmap: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "coopmap: error: %s\n", e.what());
    return 1;
  }
}

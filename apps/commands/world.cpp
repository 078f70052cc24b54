// coopmap world: world files; `world generate` writes a generated office-like building.
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "apps/commands/commands.h"
#include "core/io/atomic_file.h"
#include "core/io/yaml_reader.h"
#include "sim/world/world_generator.h"

namespace coopmap::apps {
namespace {

// `text`, the value of `option`, as a finite number; ConfigError naming the option and what
// it expects otherwise.
double parseNumber(const std::string& option, const std::string& text, const char* expected) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !std::isfinite(value))
    throw ConfigError(option + ": expected " + expected + ", got '" + text + "'");
  return value;
}

class GenerateCommand : public Command {
 public:
  explicit GenerateCommand(CLI::App& world);
  int run() override;

 private:
  // Options are taken as text and checked here, so that every bad value exits with code 2
  // and a message naming the option.
  std::string seed_, area_, family_, out_;
};

GenerateCommand::GenerateCommand(CLI::App& world)
    : Command(world.add_subcommand(
          "generate",
          "Generate a world file: an office-like building (100-600 m^2) the robots have never "
          "seen, with rooms, doorways, furniture, low-texture walls, people walking the "
          "corridors, slippery patches, and a start room with the home base and the robots jose "
          "and eric. Each world is checked (it loads; all floor reachable; starts clear; home "
          "base in view) before it is written; the same options write the same bytes.")) {
  CLI::App* cmd = cli();
  cmd->add_option("--seed", seed_, "Seed of every choice (a non-negative integer)");
  cmd->add_option("--out", out_, "World file to write (YAML)");
  cmd->add_option("--family", family_, "corridor, lt, loop or open (default: drawn from the seed)");
  cmd->add_option("--area", area_, "Floor area in m^2, 100-600 (default: drawn from the seed)");
}

int GenerateCommand::run() {
  sim::WorldGeneratorOptions options;
  if (seed_.empty()) throw ConfigError("--seed: expected a seed, none given");
  if (seed_.find_first_not_of("0123456789") != std::string::npos || seed_.size() > 19)
    throw ConfigError("--seed: expected a non-negative integer, got '" + seed_ + "'");
  options.seed = std::stoull(seed_);
  options.family = family_;
  if (cli()->count("--family") && family_.empty())
    throw ConfigError("--family: expected corridor, lt, loop or open, got ''");
  if (!area_.empty()) options.area = parseNumber("--area", area_, "a floor area in m^2");
  options.out_file = out_;
  options.validate();
  const sim::GeneratedWorld w = sim::generateWorld(options);
  try {
    writeFileAtomic(out_, w.yaml);
  } catch (const std::exception& e) {
    throw ConfigError("--out: expected a writable file path: " + std::string(e.what()));
  }
  std::printf("%s: %s building, %.1f m^2 of floor, %d rooms, %d doorways\n", out_.c_str(),
              w.family.c_str(), w.floor_area, w.rooms, w.doors);
  return 0;
}

}  // namespace

std::unique_ptr<Command> addWorldCommand(CLI::App& app) {
  auto world = std::make_unique<CommandGroup>(app.add_subcommand("world", "World files"));
  world->cli()->require_subcommand(1);
  world->add(std::make_unique<GenerateCommand>(*world->cli()));
  return world;
}

}  // namespace coopmap::apps

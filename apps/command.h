// A coopmap command: the object that holds one subcommand's option values, adds the
// subcommand and its options to the command line, and runs it when it was given. What the
// commands share: the seed and output-folder validators and all-or-nothing output folders.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

// CLI11 is header-only here: every file that adds subcommands needs the definitions of the
// formatter and config objects a new CLI::App makes.
#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>

#include "core/io/output_folder.h"

namespace coopmap::apps {

class Command {
 public:
  // `cli`: the command's subcommand, owned by its parent CLI::App.
  explicit Command(CLI::App* cli) : cli_(cli) {}
  virtual ~Command() = default;
  // The options are bound to the members by address.
  Command(const Command&) = delete;
  Command& operator=(const Command&) = delete;

  // Runs the command with the parsed options and returns the exit code. Throws ConfigError
  // for bad input (exit 2), another std::exception when the work fails (exit 1).
  virtual int run() = 0;

  CLI::App* cli() const { return cli_; }

 private:
  CLI::App* cli_;
};

// Commands under one CLI::App (the program, `bench`, `world`), of which the command line
// gives exactly one.
class CommandGroup : public Command {
 public:
  using Command::Command;
  // Adds a command whose subcommand is one of this group's.
  void add(std::unique_ptr<Command> command) { commands_.push_back(std::move(command)); }
  // Runs the command whose subcommand was given.
  int run() override;

 private:
  std::vector<std::unique_ptr<Command>> commands_;
};

// A seed as typed: a decimal integer that fits 64 unsigned bits. (CLI11 alone would take
// "-1" and wrap it, or cap a longer number, and two different seeds would give one run.)
extern const CLI::Validator kSeed;

// A folder a command writes its outputs to, checked before any work: absent (and can be
// created), empty, or one coopmap wrote; outputs replace it all or nothing (OutputFolder).
extern const CLI::Validator kOutputFolder;

// An output folder option while its command runs: the option names a staging folder, and
// commit() puts that in place of the folder given (all or nothing); messages name the folder
// as given. When the command fails, the staging folder is removed with this object.
class StagedFolder {
 public:
  // `dir`: the option's value, pointed at the staging folder; "" (no folder): nothing is
  // staged. `command`: what writes the folder, for its marker.
  StagedFolder(std::string& dir, const char* command);
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  // The folder as given ("" when none).
  const std::string& given() const { return given_; }
  // Puts the outputs in place; nothing when nothing is staged.
  void commit();

 private:
  std::string given_;
  std::optional<OutputFolder> folder_;
};

}  // namespace coopmap::apps

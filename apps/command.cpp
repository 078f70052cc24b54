#include "apps/command.h"

#include <charconv>
#include <cstdint>
#include <stdexcept>
#include <system_error>

namespace coopmap::apps {

int CommandGroup::run() {
  for (const std::unique_ptr<Command>& command : commands_)
    if (command->cli()->parsed()) return command->run();
  throw std::logic_error("CommandGroup::run: no subcommand given");
}

const CLI::Validator kSeed(
    [](std::string& text) -> std::string {
      uint64_t value = 0;
      const char* end = text.data() + text.size();
      const auto [at, error] = std::from_chars(text.data(), end, value);
      if (text.empty() || error != std::errc() || at != end)
        return "expected an integer from 0 to 18446744073709551615, got '" + text + "'";
      return "";
    },
    "SEED");

const CLI::Validator kOutputFolder(
    [](std::string& path) -> std::string { return outputFolderProblem(path); }, "FOLDER");

StagedFolder::StagedFolder(std::string& dir, const char* command) {
  if (dir.empty()) return;
  given_ = dir;
  folder_.emplace(dir, command);
  dir = folder_->path().string();
}

void StagedFolder::commit() {
  if (folder_) folder_->commit();
}

}  // namespace coopmap::apps

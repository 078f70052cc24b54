#include "core/io/output_folder.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "core/io/atomic_file.h"
#include "core/io/yaml_reader.h"

namespace coopmap {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStagingInfix = ".partial-";

// The folder's absolute, normalized path (no trailing separator), so that its parent and
// its name are what the user meant by "out/" or "out/.".
fs::path normalized(const fs::path& folder) {
  std::error_code ec;
  fs::path p = fs::absolute(folder, ec).lexically_normal();
  if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p;
}

bool processAlive(long pid) {
  return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

// Staging folders beside `folder` whose process is gone (a run killed while writing).
void removeOrphans(const fs::path& folder) {
  std::error_code ec;
  const std::string prefix = folder.filename().string() + kStagingInfix;
  for (const fs::directory_entry& e : fs::directory_iterator(folder.parent_path(), ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string pid = name.substr(prefix.size());
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    if (processAlive(std::stol(pid))) continue;
    std::error_code ignored;
    fs::remove_all(e.path(), ignored);
  }
}

}  // namespace

std::string outputFolderProblem(const std::string& path) {
  if (path.empty()) return "expected a folder to write to, got ''";
  const fs::path folder = normalized(path);
  std::error_code ec;
  if (fs::exists(folder, ec)) {
    if (!fs::is_directory(folder, ec))
      return "expected a folder to write to, '" + path + "' is a file";
    const bool marked = fs::exists(folder / kOutputMarker, ec);
    if (!marked && !fs::is_empty(folder, ec))
      return "expected an empty folder or one coopmap wrote, '" + path +
             "' holds other files (no " + kOutputMarker +
             " marker): nothing in it is replaced; give another folder or empty it";
  }
  // The staging folder goes beside it, and the folder is renamed there: its parent (the
  // nearest existing ancestor, when missing folders are to be created) must be writable.
  fs::path ancestor = folder.parent_path();
  while (!ancestor.empty() && ancestor != ancestor.root_path() && !fs::exists(ancestor, ec))
    ancestor = ancestor.parent_path();
  if (!fs::is_directory(ancestor, ec))
    return "expected a folder to write to, '" + path + "' cannot be created ('" +
           ancestor.string() + "' is a file)";
  if (::access(ancestor.c_str(), W_OK) != 0)
    return "expected a folder to write to, '" + path + "' cannot be written ('" +
           ancestor.string() + "' is not writable)";
  return "";
}

OutputFolder::OutputFolder(fs::path folder, std::string command)
    : folder_(normalized(folder)), command_(std::move(command)) {
  if (const std::string problem = outputFolderProblem(folder.string()); !problem.empty())
    throw ConfigError("--out: " + problem);
  std::error_code ec;
  fs::create_directories(folder_.parent_path(), ec);
  if (ec)
    throw std::runtime_error("cannot create '" + folder_.parent_path().string() +
                             "': " + ec.message());
  removeOrphans(folder_);
  staging_ = folder_.parent_path() /
             (folder_.filename().string() + kStagingInfix + std::to_string(::getpid()));
  fs::remove_all(staging_, ec);
  fs::create_directory(staging_, ec);
  if (ec) throw std::runtime_error("cannot create '" + staging_.string() + "': " + ec.message());
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

void OutputFolder::commit() {
  if (committed_) throw std::logic_error("OutputFolder::commit: committed already");
  writeFileAtomic((staging_ / kOutputMarker).string(), command_ + "\n");
  std::error_code ec;
  const bool replacing = fs::exists(folder_, ec);
  if (replacing) {
    // One step: the staging folder and the old one change places, so that the folder is
    // always either the old outputs or the new ones; the old ones are then removed.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, folder_.c_str(), RENAME_EXCHANGE) != 0)
      throw std::runtime_error("cannot put the outputs in '" + folder_.string() +
                               "': " + std::strerror(errno));
    committed_ = true;
    fs::remove_all(staging_, ec);
    return;
  }
  if (::rename(staging_.c_str(), folder_.c_str()) != 0)
    throw std::runtime_error("cannot put the outputs in '" + folder_.string() +
                             "': " + std::strerror(errno));
  committed_ = true;
}

}  // namespace coopmap

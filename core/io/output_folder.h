// Output folders written all or nothing.
//
// A command writes its files into a staging folder beside the one asked for
// (`<name>.partial-<pid>`); commit() puts the staging folder in its place in one rename
// (an atomic exchange when the folder exists) and marks it as coopmap's with a marker file.
// A run that fails or is killed leaves the folder as it was; its staging folder is removed
// on failure, and by the next command writing beside it after a kill.
#pragma once

#include <filesystem>
#include <string>

namespace coopmap {

// The marker file in every folder coopmap wrote: an existing folder is replaced only when it
// holds this file (or is empty).
inline constexpr const char* kOutputMarker = ".coopmap-output";

// Why `path` cannot take a command's outputs, or "" when it can: it is absent and can be
// created, an empty folder, or a folder coopmap wrote (marker), and its parent is writable.
std::string outputFolderProblem(const std::string& path);

class OutputFolder {
 public:
  // Checks `folder` (outputFolderProblem; ConfigError naming it when it cannot be used),
  // removes the staging folders of dead processes beside it, and creates a fresh staging
  // folder. `command`: what wrote it, for the marker.
  OutputFolder(std::filesystem::path folder, std::string command);
  ~OutputFolder();  // not committed: the staging folder and what is in it are removed
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where the command writes now (the staging folder).
  const std::filesystem::path& path() const { return staging_; }
  // The folder asked for.
  const std::filesystem::path& folder() const { return folder_; }
  // Writes the marker and puts the staging folder in the folder's place; the earlier
  // contents are removed. Throws std::runtime_error naming the folder when it cannot.
  void commit();

 private:
  std::filesystem::path folder_, staging_;
  std::string command_;
  bool committed_ = false;
};

}  // namespace coopmap

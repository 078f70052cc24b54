// What every fuzz target shares: the errors a reader may throw for bad input, and a fuzz
// input of several files (for readers of a folder).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace coopmap::fuzz {

// Runs `read` on one input: an error the reader reports for bad input (std::runtime_error,
// which ConfigError is, or std::invalid_argument) is the expected outcome; anything else
// (another exception, a crash, a sanitizer report, an allocation beyond libFuzzer's limit)
// is a finding.
void expectCleanError(const std::function<void()>& read);

// A fuzz input holding several files: "=== NAME ===\n" lines start each file, NAME a path
// relative to the folder. Bytes before the first such line are ignored.
std::map<std::string, std::string> splitFiles(std::string_view input);

// A fresh folder for this process under /dev/shm (or the temporary folder), emptied, with
// `files` written into it; returns its path.
std::filesystem::path writeFiles(const std::map<std::string, std::string>& files);

}  // namespace coopmap::fuzz

// The mission settings of `coopmap run` as options: each overrides the world's setting of
// the same name (World::Exploration), which overrides coopmap's default; unset, it is left
// to them (RunOptions' optional fields).
#pragma once

#include <CLI/App.hpp>

#include "apps/run_world.h"

namespace coopmap {

// Adds the options to `run_command`; parsing sets the fields of `run` they name.
void addMissionSettingOptions(CLI::App& run_command, RunOptions& run);

}  // namespace coopmap

#include "core/agent/agent_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "core/io/yaml_reader.h"

namespace coopmap {

namespace {

std::vector<std::string> splitChoices(const char* choices) {
  std::vector<std::string> out;
  std::string cur;
  for (const char* c = choices; *c; ++c) {
    if (*c == '|') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += *c;
    }
  }
  out.push_back(cur);
  return out;
}

std::string joinedChoices(const char* choices) {
  std::string out;
  const std::vector<std::string> all = splitChoices(choices);
  for (size_t i = 0; i < all.size(); ++i)
    out += (i == 0 ? "" : i + 1 == all.size() ? " or " : ", ") + all[i];
  return out;
}

// For messages: as short as it reads back.
std::string number(double v) {
  char b[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(b, sizeof b, "%.*g", digits, v);
    if (std::strtod(b, nullptr) == v) break;
  }
  return b;
}

// What a setting expects, for messages.
template <typename T>
std::string expected(const SettingInfo& info) {
  if constexpr (std::is_same_v<T, bool>) {
    return "true or false";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return info.choices ? "one of " + joinedChoices(info.choices) : "text";
  } else if constexpr (std::is_same_v<T, int>) {
    return "an integer in [" + number(info.min) + ", " + number(info.max) + "]";
  } else {
    return std::string("a number in [") + number(info.min) + ", " + number(info.max) + "]" +
           (*info.unit ? std::string(" ") + info.unit : "");
  }
}

template <typename T>
bool inRange(const SettingInfo& info, const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    return true;
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!info.choices) return true;
    for (const std::string& c : splitChoices(info.choices))
      if (c == v) return true;
    return false;
  } else {
    return std::isfinite(static_cast<double>(v)) && v >= info.min && v <= info.max;
  }
}

// Parses `text` as a T; false when it is not one.
template <typename T>
bool parse(const std::string& text, T& out) {
  if constexpr (std::is_same_v<T, bool>) {
    if (text == "true" || text == "on" || text == "yes") return out = true, true;
    if (text == "false" || text == "off" || text == "no") return out = false, true;
    return false;
  } else if constexpr (std::is_same_v<T, std::string>) {
    out = text;
    return true;
  } else {
    std::istringstream in(text);
    T v{};
    in >> v;
    if (in.fail() || !in.eof()) return false;
    out = v;
    return true;
  }
}

// Settings earlier versions had, and the value that left each off. A file naming one (a
// recording's agent.yaml, an old settings file) reads as before when it holds that value;
// any other value asked for something this version no longer does.
struct RemovedSetting {
  const char* name;
  bool boolean;  // true: off is false; else off is 0
};
constexpr RemovedSetting kRemovedSettings[] = {
    {"closure_decided_points", true}, {"post_gate_m", false},     {"track_shared_map", true},
    {"goal_clearance", false},        {"look_again_gain", false},
};

// Whether `key` is a removed setting; fails on `field` when it is one set to anything but off.
bool removedSetting(const std::string& key, const YamlField& field) {
  for (const RemovedSetting& r : kRemovedSettings) {
    if (key != r.name) continue;
    bool flag = true;
    double number = 1.0;
    const bool off =
        field.isScalar() && (r.boolean ? parse(field.asString(), flag) && !flag
                                       : parse(field.asString(), number) && number == 0.0);
    if (!off)
      field.failMessage(std::string("a setting this version no longer has: only its old "
                                    "default, ") +
                        (r.boolean ? "false" : "0") + " (off), reads");
    return true;
  }
  return false;
}

}  // namespace

std::vector<SettingInfo> agentSettingInfos() {
  std::vector<SettingInfo> out;
  AgentSettings().visit([&](const SettingInfo& info, const auto&) { out.push_back(info); });
  return out;
}

void AgentSettings::validate() const {
  visit([](const SettingInfo& info, const auto& v) {
    using T = std::decay_t<decltype(v)>;
    if (!inRange(info, v))
      throw std::invalid_argument(std::string("agent settings: '") + info.name + "': expected " +
                                  expected<T>(info));
  });
}

std::string settingFlag(const std::string& name) {
  std::string out = "--" + name;
  for (char& c : out)
    if (c == '_') c = '-';
  return out;
}

void readAgentSettings(const YamlField& mapping, AgentSettings& settings,
                       const std::vector<std::string>& other_keys) {
  if (!mapping.isMap()) mapping.fail("a mapping of agent settings");
  for (const std::string& key : mapping.keys()) {
    if (std::find(other_keys.begin(), other_keys.end(), key) != other_keys.end()) continue;
    const YamlField field = mapping[key];
    if (removedSetting(key, field)) continue;
    bool known = false;
    settings.visit([&](const SettingInfo& info, auto& value) {
      using T = std::decay_t<decltype(value)>;
      if (key != info.name) return;
      known = true;
      T parsed{};
      if (!field.isScalar() || !parse(field.asString(), parsed) || !inRange(info, parsed))
        field.fail(expected<T>(info));
      value = parsed;
    });
    if (!known) {
      std::string names;
      for (const SettingInfo& info : agentSettingInfos())
        names += (names.empty() ? "" : ", ") + std::string(info.name);
      field.failMessage("unknown setting (known: " + names + ")");
    }
  }
}

void setAgentSetting(AgentSettings& settings, const std::string& name, const std::string& text) {
  bool known = false;
  settings.visit([&](const SettingInfo& info, auto& value) {
    using T = std::decay_t<decltype(value)>;
    if (name != info.name) return;
    known = true;
    T parsed{};
    if (!parse(text, parsed) || !inRange(info, parsed))
      throw std::invalid_argument(settingFlag(name) + ": expected " + expected<T>(info) +
                                  ", got '" + text + "'");
    value = parsed;
  });
  if (!known) throw std::invalid_argument("unknown agent setting '" + name + "'");
}

std::string agentSettingsYaml(const AgentSettings& settings, int indent) {
  std::string out;
  const std::string pad(static_cast<size_t>(indent), ' ');
  settings.visit([&](const SettingInfo& info, const auto& value) {
    using T = std::decay_t<decltype(value)>;
    out += pad + info.name + ": ";
    if constexpr (std::is_same_v<T, bool>)
      out += value ? "true" : "false";
    else if constexpr (std::is_same_v<T, std::string>)
      out += value;
    else if constexpr (std::is_same_v<T, int>)
      out += std::to_string(value);
    else
      out += number(value);
    out += "\n";
  });
  return out;
}

std::string agentSettingsMarkdown() {
  std::string out =
      "# Agent settings\n\n"
      "Generated from the table in `core/agent/agent_settings.h` by `coopmap settings "
      "--markdown`; a test fails when this file is stale. In YAML (`coopmap run --settings "
      "FILE`, a robot config's `mission:` -> `settings:`) a setting is `name: value`; on "
      "`coopmap run`'s command line `--name-in-kebab-case VALUE`.\n\n"
      "| setting | flag | default | allowed | what it does |\n"
      "|---|---|---|---|---|\n";
  AgentSettings().visit([&](const SettingInfo& info, const auto& value) {
    using T = std::decay_t<decltype(value)>;
    std::string shown;
    if constexpr (std::is_same_v<T, bool>)
      shown = value ? "true" : "false";
    else if constexpr (std::is_same_v<T, std::string>)
      shown = value;
    else if constexpr (std::is_same_v<T, int>)
      shown = std::to_string(value);
    else
      shown = number(value) + (*info.unit ? std::string(" ") + info.unit : "");
    out += "| `" + std::string(info.name) + "` | `" + settingFlag(info.name) + "` | " + shown +
           " | " + expected<T>(info) + " | " + info.help + " |\n";
  });
  return out;
}

}  // namespace coopmap

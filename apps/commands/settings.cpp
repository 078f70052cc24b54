// coopmap settings: the agents' settings with their defaults, as YAML or a Markdown table.
#include <cstdio>

#include "apps/commands/commands.h"
#include "core/agent/agent_settings.h"

namespace coopmap::apps {
namespace {

class SettingsCommand : public Command {
 public:
  explicit SettingsCommand(CLI::App& app)
      : Command(app.add_subcommand(
            "settings",
            "The agents' settings with their defaults, as a settings file for `run --settings` "
            "(or, with --markdown, the reference docs/settings.md)")) {
    cli()->add_flag("--markdown", markdown_,
                    "A Markdown table of every setting: flag, default, range and help");
  }

  int run() override {
    std::fputs(
        markdown_ ? agentSettingsMarkdown().c_str() : agentSettingsYaml(AgentSettings{}).c_str(),
        stdout);
    return 0;
  }

 private:
  bool markdown_ = false;
};

}  // namespace

std::unique_ptr<Command> addSettingsCommand(CLI::App& app) {
  return std::make_unique<SettingsCommand>(app);
}

}  // namespace coopmap::apps

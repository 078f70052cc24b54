// What teammates tell each other while they work (beyond the shared map): where each
// stands and where it is going, in the map frame, so that they keep clear of each other,
// leave each other out of their maps and split the frontiers. `TeamChannel` is the interface
// a radio link would implement too; `LocalTeamChannel` is the in-process one.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace coopmap {

struct TeammateReport {
  std::string robot;
  // Knows where it stands in the map frame (its first look at the home base fixed it).
  bool localized = false;
  // Stopped for good without knowing where it stands: its position is not to be trusted.
  bool lost = false;
  Eigen::Vector2d position{0.0, 0.0};   // m, map frame (when localized)
  std::optional<Eigen::Vector2d> goal;  // the frontier it explores towards, map frame
  bool at_start = false;                // still at its start, waiting to go
};

class TeamChannel {
 public:
  virtual ~TeamChannel() = default;
  TeamChannel() = default;
  TeamChannel(const TeamChannel&) = delete;
  TeamChannel& operator=(const TeamChannel&) = delete;

  // Replaces the robot's report (the first report of a robot joins it to the team).
  virtual void publish(const TeammateReport& report) = 0;
  // The latest report of every other robot of the team, in the order they joined.
  virtual std::vector<TeammateReport> others(const std::string& robot) const = 0;
};

class LocalTeamChannel final : public TeamChannel {
 public:
  void publish(const TeammateReport& report) override;
  std::vector<TeammateReport> others(const std::string& robot) const override;

 private:
  std::vector<TeammateReport> reports_;  // one per robot, in join order
};

}  // namespace coopmap

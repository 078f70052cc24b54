#include "core/sharing/team.h"

namespace coopmap {

void LocalTeamChannel::publish(const TeammateReport& report) {
  for (TeammateReport& r : reports_)
    if (r.robot == report.robot) {
      r = report;
      return;
    }
  reports_.push_back(report);
}

std::vector<TeammateReport> LocalTeamChannel::others(const std::string& robot) const {
  std::vector<TeammateReport> out;
  for (const TeammateReport& r : reports_)
    if (r.robot != robot) out.push_back(r);
  return out;
}

}  // namespace coopmap

#include "core/localization/home_base.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace coopmap {

std::vector<HomeBaseDesign::Arm> HomeBaseDesign::arms() const {
  std::vector<Arm> out;
  for (const Corner* c : {&corners.first, &corners.second})
    for (double side : {1.0, -1.0}) {
      const double a = c->heading + side * M_PI / 4.0;
      Arm arm;
      arm.center = c->position + 0.5 * arm_length * Eigen::Vector2d(std::cos(a), std::sin(a));
      arm.half_length = 0.5 * (arm_length + thickness);
      arm.half_width = 0.5 * thickness;
      arm.yaw = a;
      out.push_back(arm);
    }
  return out;
}

HomeBase HomeBaseDesign::visibleCorners() const {
  HomeBase out = corners;
  for (Corner* c : {&out.first, &out.second})
    c->position +=
        thickness / std::sqrt(2.0) * Eigen::Vector2d(std::cos(c->heading), std::sin(c->heading));
  return out;
}

void HomeBaseDesign::validate() const {
  if (!(arm_length > 0.0 && std::isfinite(arm_length)))
    throw std::invalid_argument("home base: field 'arm_length': expected a positive length, got " +
                                std::to_string(arm_length));
  if (!(thickness > 0.0 && thickness < arm_length))
    throw std::invalid_argument(
        "home base: field 'thickness': expected a positive thickness below arm_length, got " +
        std::to_string(thickness));
  const double spacing = (corners.second.position - corners.first.position).norm();
  if (!(spacing > thickness && std::isfinite(spacing)))
    throw std::invalid_argument(
        "home base: field 'corners': expected two distinct corners, got them " +
        std::to_string(spacing) + " m apart");
}

HomeBaseRegistration registerHomeBase(const CornerDetector& detector, const Eigen::Vector2d& first,
                                      const Eigen::Vector2d& second, double search_radius) {
  HomeBaseRegistration r;
  const CornerSearch a = detector.findNear(first, search_radius);
  if (a.status != CornerStatus::kOk) {
    r.status = a.status;
    return r;
  }
  const CornerSearch b = detector.findNear(second, search_radius);
  if (b.status != CornerStatus::kOk) {
    r.status = b.status;
    return r;
  }
  r.home = HomeBase{a.corners.front(), b.corners.front()};
  return r;
}

namespace {

// The fix from a pair of observed corners matched to the registered ones.
HomeBaseFix fixFromCorners(const HomeBase& home, const Corner& first, const Corner& second,
                           const Pose2& odometry, double resolution, double max_separation_error) {
  HomeBaseFix fix;
  fix.first = first;
  fix.second = second;
  const Eigen::Vector2d reg = home.second.position - home.first.position;
  const Eigen::Vector2d obs = fix.second.position - fix.first.position;
  fix.separation_error = std::abs(obs.norm() - reg.norm());
  if (fix.separation_error > max_separation_error) {
    fix.status = HomeBaseStatus::kGeometryMismatch;
    return fix;
  }
  // Heading from the line joining the corners; translation that puts their midpoint back.
  const double dtheta = std::atan2(reg.y(), reg.x()) - std::atan2(obs.y(), obs.x());
  const double c = std::cos(dtheta), s = std::sin(dtheta);
  const Eigen::Vector2d mid_obs = 0.5 * (fix.first.position + fix.second.position);
  const Eigen::Vector2d mid_reg = 0.5 * (home.first.position + home.second.position);
  const Eigen::Vector2d rotated(c * mid_obs.x() - s * mid_obs.y(),
                                s * mid_obs.x() + c * mid_obs.y());
  const Eigen::Vector2d t = mid_reg - rotated;
  fix.correction = Pose2(t.x(), t.y(), wrapAngle(dtheta));
  fix.pose = fix.correction * odometry;
  // Uncertainty: each corner's position to about its RMS / sqrt(points) cells; both ends of
  // the joining line add to the heading error.
  fix.rms = std::max(fix.first.rms, fix.second.rms);
  const double per_corner = std::max(0.1, fix.rms / 4.0) * resolution;  // m
  fix.sigma_xy = per_corner / std::sqrt(2.0);
  fix.sigma_theta = std::sqrt(2.0) * per_corner / std::max(obs.norm(), 1e-6);
  fix.status = HomeBaseStatus::kOk;
  return fix;
}

}  // namespace

HomeBaseFix localizeAtHomeBase(const CornerDetector& detector, const HomeBase& home,
                               const Pose2& odometry, double search_radius,
                               double max_separation_error, const Pose2& guess) {
  const Pose2 to_odometry = guess.inverse();
  const CornerSearch a = detector.findNear(to_odometry * home.first.position, search_radius,
                                           wrapAngle(home.first.heading + to_odometry.theta));
  const CornerSearch b = detector.findNear(to_odometry * home.second.position, search_radius,
                                           wrapAngle(home.second.heading + to_odometry.theta));
  if (a.status != CornerStatus::kOk || b.status != CornerStatus::kOk) return {};
  return fixFromCorners(home, a.corners.front(), b.corners.front(), odometry,
                        detector.limits().resolution, max_separation_error);
}

HomeBaseFix findHomeBase(const std::vector<Corner>& corners, double resolution,
                         const HomeBase& home, const Pose2& odometry, const Eigen::Vector2d& center,
                         double radius, double max_separation_error) {
  std::vector<Corner> near;
  for (const Corner& c : corners)
    if ((c.position - center).norm() <= radius) near.push_back(c);
  const Eigen::Vector2d reg = home.second.position - home.first.position;
  const double reg_angle = std::atan2(reg.y(), reg.x());
  const double rel1 = wrapAngle(home.first.heading - reg_angle);
  const double rel2 = wrapAngle(home.second.heading - reg_angle);
  // Score: separation error in units of 2 cm plus heading mismatches in units of 5 degrees.
  const double deg5 = 5.0 * M_PI / 180.0;
  double best_score = 1e300;
  const Corner *best_a = nullptr, *best_b = nullptr;
  for (const Corner& a : near)
    for (const Corner& b : near) {
      if (&a == &b) continue;
      const Eigen::Vector2d obs = b.position - a.position;
      const double sep = std::abs(obs.norm() - reg.norm());
      if (sep > max_separation_error) continue;
      const double angle = std::atan2(obs.y(), obs.x());
      const double h1 = std::abs(wrapAngle(a.heading - angle - rel1));
      const double h2 = std::abs(wrapAngle(b.heading - angle - rel2));
      if (h1 > 4 * deg5 || h2 > 4 * deg5) continue;
      const double score = sep / 0.02 + (h1 + h2) / deg5;
      if (score < best_score) {
        best_score = score;
        best_a = &a;
        best_b = &b;
      }
    }
  if (!best_a) {
    HomeBaseFix none;
    none.status =
        near.size() < 2 ? HomeBaseStatus::kCornerNotFound : HomeBaseStatus::kGeometryMismatch;
    return none;
  }
  return fixFromCorners(home, *best_a, *best_b, odometry, resolution, max_separation_error);
}

Pose2 placementOnCorner(const Corner& seen, const Corner& designed) {
  const double turn = wrapAngle(designed.heading - seen.heading);
  const Eigen::Vector2d t = designed.position - Pose2(0.0, 0.0, turn) * seen.position;
  return Pose2(t.x(), t.y(), turn);
}

}  // namespace coopmap

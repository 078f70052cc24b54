// Ground truth watching a run (sim/runner/world_run.h): the robots' true trajectories,
// paths and contacts, coverage and error over time, and each robot's result scored against
// the world, all in the map frame. It reads the agents; nothing it knows reaches them.
#pragma once

#include <string>
#include <vector>

#include "core/agent/robot_agent.h"
#include "sim/physics/physics_world.h"
#include "sim/runner/world_run.h"
#include "sim/world/world.h"

namespace coopmap {

class RunScoring {
 public:
  // `X_WM`: each robot's map frame in the world; `limits`: the map (map frame of robot 0, the
  // frame every robot shares when the world has a home base).
  RunScoring(const sim::World& world, const MapLimits& limits, std::vector<Pose2> X_WM,
             const std::vector<RobotDescription>& descriptions, double timeline_period_s);

  // After robot k's step at time t: its true pose (world) and odometry, and its agent.
  void observeStep(size_t k, double t, const Pose2& true_pose, const Pose2& odometry,
                   const RobotAgent& agent);
  // After a physics step of dt s: robot k's true pose (world), the simulator's contact log,
  // and what its agent was doing.
  void observeMotion(size_t k, double dt, const Pose2& true_pose,
                     const std::vector<sim::ContactEvent>& log, const std::string& phase);
  // A timeline sample when one is due (or `last`: at the end, unless there is one for t).
  void sample(double t, const std::vector<const RobotAgent*>& agents, const LocalSharedMap* live,
              bool last = false);

  // Robot k's result but for what the simulator counts (collisions, odometry error).
  RobotRunResult robotResult(size_t k, const RobotAgent& agent) const;
  const GridU8& floor() const { return floor_; }
  // The true occupancy up to the tallest robot's swept height (what a shared map shows).
  const GridU8& sharedTruth() const { return truths_[tallest_]; }
  const std::vector<TimelineSample>& timeline() const { return timeline_; }

 private:
  struct Robot {
    std::vector<StampedPose2> groundtruth, odometry, estimate;
    std::vector<ContactRecord> contacts;
    std::vector<PhaseTime> phases;
    Pose2 last_true;
    bool moved = false;
  };
  // Robot k's true pose at `stamp` (the sample at or just before it), map frame.
  Pose2 truthAt(size_t k, double stamp) const;
  std::vector<Pose2> X_WM_;
  bool shared_frame_ = true;  // every robot maps in the same frame (the home base's)
  GridU8 floor_;
  std::vector<GridU8> truths_;
  size_t tallest_ = 0;
  std::vector<Eigen::Vector2d> starts_;  // each robot's true start, map frame
  std::vector<Robot> robots_;
  double period_ = 10.0;
  double next_sample_ = 0.0;
  std::vector<TimelineSample> timeline_;
};

}  // namespace coopmap

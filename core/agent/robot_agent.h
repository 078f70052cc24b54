// One robot's agent: everything a robot decides, on any robot. Made from the robot
// interface (whose clock it runs on), the shared map service, the team channel and its
// settings, it is the same object on a simulated B-14, a real one and a recording.
//
// Each step it reads the robot's odometry, takes a trinocular frame when one is due and
// maps it (stereo, radial map, occupancy grid, traverse log), decides (a route, or the
// exploring mission) and commands the robot. At its start it looks at the home base and
// places its odometry frame in the map frame, which is the home base's (start_fix.h); back
// home at the end of each sortie it runs the paper's protocol: localize at the home base,
// correct the sortie's traverse, post it to the shared map and import the shared map
// (cooperation.h). It never sees the simulator or ground truth.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/agent/agent_settings.h"
#include "core/agent/cooperation.h"
#include "core/agent/map_tracker.h"
#include "core/agent/mapper.h"
#include "core/agent/mission.h"
#include "core/agent/route_follower.h"
#include "core/correction/odometry_calibration.h"
#include "core/correction/start_fix.h"
#include "core/correction/stereo_scale.h"
#include "core/localization/home_base.h"
#include "core/robot/robot_interface.h"
#include "core/sharing/shared_map.h"
#include "core/sharing/team.h"

namespace coopmap {

// What a robot is set to do: who it is, the map it builds and what defines its frame.
struct AgentSetup {
  enum class Mode {
    kRoute,    // look at the home base, then follow `route`
    kExplore,  // the exploring mission, in sorties when there is a shared map
    // Driven by someone else (a person, a script: stepDriven): it maps and logs what the
    // robot does and decides nothing; it places itself when the first look at the start ends
    // (the first command that drives after one that turned).
    kDriven,
  };
  std::string name;
  Mode mode = Mode::kExplore;
  std::vector<Waypoint> route;  // kRoute: map frame
  MapLimits map;                // the map's extent and resolution, map frame
  // The home base as designed: it defines the map frame, and the robot finds its start in it
  // from its first look. Unset: the map frame is the robot's start (a robot alone).
  std::optional<HomeBaseDesign> home_base;
  uint32_t seed = 1;      // the path planner's
  bool priority = false;  // right of way over teammates (one robot of a team)
  void validate() const;  // throws std::invalid_argument naming the field
};
const char* toString(AgentSetup::Mode mode);

class RobotAgent {
 public:
  // `robot` is borrowed for the agent's lifetime; so are `shared` (null: nothing shared, one
  // sortie) and `team` (null: alone). Throws std::invalid_argument for bad settings or setup.
  RobotAgent(RobotInterface& robot, const AgentSetup& setup, const AgentSettings& settings,
             SharedMapService* shared = nullptr, TeamChannel* team = nullptr);
  RobotAgent(const RobotAgent&) = delete;
  RobotAgent& operator=(const RobotAgent&) = delete;

  // One control step at the robot's now(): read it, take a frame when one is due, map,
  // decide, command (a robot that cannot be steered ignores the command). kRoute, kExplore.
  void step();
  // The same for kDriven: `driven` is the driver's command, passed to the robot.
  void stepDriven(const MotionCommand& driven);
  // The mission or the route is over (the robot has stopped for good).
  bool done() const;

  const std::string& name() const { return setup_.name; }
  const AgentSetup& setup() const { return setup_; }
  const AgentSettings& settings() const { return settings_; }
  const Mapper& mapper() const { return *mapper_; }
  // The mission (kExplore), or null.
  const MissionAgent* mission() const { return mission_.get(); }
  // The home-base protocol of the sorties (kExplore with a shared map; kRoute with one: the
  // route is one sortie), or null.
  const HomeBaseCooperation* cooperation() const { return coop_.get(); }
  // The first look's fix that found the home base (its correction: X_MO), if any: where the
  // robot believed it started. (A robot that started far from the home base drives nearer and
  // looks again; that look places it, see log().)
  const std::optional<StartFix>& startFix() const { return start_fix_; }
  // Placed in the map frame by its looks at the start, and when (s; -1: not yet).
  bool localized() const { return localized_; }
  double localizedAt() const { return localized_at_; }
  // The first traverse entry of the look that placed it (what came before, a first look from
  // afar and the drive nearer, is no part of its first sortie).
  size_t placedFrom() const { return placed_from_; }
  // The pose estimate now (map frame once localized, the odometry frame before).
  Pose2 estimate() const { return mapper_->estimate(odo_); }
  // The odometry as the agent uses it now (calibrated when calibrate_odometry).
  const Pose2& odometry() const { return odo_; }
  // The encoders' odometry at each traverse entry (before calibration).
  const std::vector<Pose2>& rawFrameOdometry() const { return raw_; }
  // The odometry calibration it drives on (calibrate_odometry).
  const OdometryBias& calibration() const { return calibration_.bias(); }
  // Lines for people: the start, each sortie's end, each look again.
  const std::vector<std::string>& log() const { return log_; }
  // Whether the last step took a frame, and the motion segment it was labelled with.
  bool sensedLastStep() const { return sensed_; }
  MotionSegment lastFrameSegment() const { return frame_segment_; }
  const MotionCommand& lastCommand() const { return command_; }
  int frames() const { return frames_; }
  // Where the robot is in its work, for people ("look at home", "explore", "route", ...).
  std::string phase() const;

 private:
  // Reads the robot and takes a frame when one is due (the first half of a step).
  void observe(double now);
  void sense();
  // Passes the step's command to the robot and tells the teammates (the second half).
  void act(const MotionCommand& command);
  MotionCommand decide(double now, const RobotStatus& status);
  void publish();
  // The first look is over: place the odometry frame in the map frame, or look again.
  void localizeStart(double now);
  // Waiting at the start for the teammates to be placed too; true when it may go.
  bool teamReady(double now) const;
  void leaveStart(double now);
  void trackWhileDriving();
  void calibrateStereoScale(TraverseLog& sortie);
  void endSortie(double now);
  // kRoute: the waypoint is a look at the home base, a turn where the robot started.
  bool isLookAtHome(const Waypoint& w) const;
  // The frame now belongs to a look at the home base: matched on centred windows, as the
  // landmarks' fits expect (see Mapper::process).
  bool lookingAtHomeBase() const;
  // The sortie's protocol asks for another look: drive to `home` (the estimate's frame) and
  // look at the home base there.
  void lookAgainAt(const Pose2& home, double now);
  // The sortie is over (fixed or not): the mission goes again or stops; a route is done.
  void sortieEnded(bool fixed, int sortie, double now);
  // Where the placed teammates stand (map frame), as they report it.
  std::vector<Eigen::Vector2d> teammatePositions() const;

  RobotInterface& robot_;
  AgentSetup setup_;
  AgentSettings settings_;
  SharedMapService* shared_;
  TeamChannel* team_;
  std::unique_ptr<Mapper> mapper_;
  std::unique_ptr<MissionAgent> mission_;
  std::unique_ptr<HomeBaseCooperation> coop_;
  std::unique_ptr<RouteFollower> look_;   // kRoute: the first look
  std::unique_ptr<RouteFollower> route_;  // kRoute: the route, once placed
  CooperationConfig cooperation_config_;
  double sense_period_ = 1.0 / 3.0;
  double next_sense_ = 0.0;
  bool sensed_ = false;
  MotionSegment frame_segment_ = MotionSegment::kStop;
  int turn_steps_ = 0, straight_steps_ = 0;  // control steps of each motion since the last frame
  int frames_ = 0;
  Pose2 raw_now_;  // the encoders' odometry this step
  Pose2 odo_;
  const RadialMap* latest_ = nullptr;
  MotionCommand command_;
  std::vector<Pose2> raw_;
  std::vector<std::string> log_;
  bool done_ = false;           // kRoute: the route is over (or cannot start)
  bool driven_turned_ = false;  // kDriven: the driver has turned the robot
  bool looked_home_ = false;    // kRoute: the look at home after the route was begun

  // The start.
  std::optional<StartFix> start_fix_;
  bool localized_ = false;
  bool started_ = false;        // left the start
  double localized_at_ = -1.0;  // s
  int start_looks_ = 0;         // looks at the start that found no home base
  size_t look_begin_ = 0;       // the first entry of the look being taken
  size_t placed_from_ = 0;      // see placedFrom()
  bool approached_ = false;     // drove nearer to look again
  Pose2 home_;                  // the start, map frame

  // The sorties (see endSortie).
  size_t sortie_begin_ = 0;  // the current sortie's first traverse entry
  bool reapproaching_ = false;
  Pose2 reapproach_fix_;  // the first look's correction (chain frame), while reapproaching_
  int looks_again_ = 0;
  size_t look_from_ = 0;
  Pose2 sortie_frame_;  // the estimate's frame when the sortie began
  WallHeadingTracker headings_;
  OdometryCalibration calibration_;
  bool calibrate_ = false;
  bool stereo_scale_ = false;
  StereoScale stereo_;
  size_t stereo_measured_ = SIZE_MAX;
  double sortie_scale_ = 0.0;
};

}  // namespace coopmap

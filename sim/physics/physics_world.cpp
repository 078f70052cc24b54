#include "sim/physics/physics_world.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace coopmap::sim {

struct Robot {
  RobotDescription description;
  DriveConfig drive;
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btDefaultMotionState> motion;
  std::unique_ptr<btRigidBody> body;
  MotionCommand target;                            // commanded
  MotionCommand setpoint;                          // after the base's acceleration profile
  bool slip_linear = false, slip_angular = false;  // traction saturated this step
  bool contact = false;
  Eigen::Vector2d contact_point{0.0, 0.0};  // world, while in contact
  int contact_events = 0;
  // What the robot touched in the last step (static world, people, robots) and the counts.
  std::array<bool, 3> touching_kind{};
  ContactCounts counts;
  std::vector<ContactEvent> log;
};

namespace {
// User indices tagging bodies, so contacts can be told apart (the default is -1: static).
constexpr int kPersonTag = 1;
constexpr int kRobotTag = 2;
enum ContactKind { kStaticWorld = 0, kPerson = 1, kOtherRobot = 2 };

ContactKind kindOf(const btCollisionObject* body) {
  switch (body->getUserIndex()) {
    case kPersonTag:
      return kPerson;
    case kRobotTag:
      return kOtherRobot;
    default:
      return kStaticWorld;
  }
}
}  // namespace

struct PhysicsWorld::Impl {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> statics;
  btRigidBody* floor = nullptr;
  std::vector<std::unique_ptr<Robot>> robots;
  std::vector<SurfaceSpec> surfaces;
  std::vector<btRigidBody*> kinematic;  // owned by statics
  std::vector<double> kinematic_z;      // their centres' heights when present

  ~Impl() {
    for (auto& r : robots) world.removeRigidBody(r->body.get());
    for (auto& s : statics) world.removeRigidBody(s.get());
  }

  btRigidBody* addStatic(std::unique_ptr<btCollisionShape> shape, const btTransform& pose,
                         double friction) {
    btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, shape.get());
    info.m_startWorldTransform = pose;
    info.m_friction = static_cast<btScalar>(friction);
    auto body = std::make_unique<btRigidBody>(info);
    world.addRigidBody(body.get());
    shapes.push_back(std::move(shape));
    statics.push_back(std::move(body));
    return statics.back().get();
  }
};

PhysicsWorld::PhysicsWorld(const World& world, double step)
    : impl_(std::make_unique<Impl>()), step_(step) {
  if (!(step > 0.0 && step < 0.1))
    throw std::invalid_argument("physics step must be in (0, 0.1) s");
  Impl& im = *impl_;
  im.surfaces = world.surfaces;
  im.world.setGravity(btVector3(0, 0, -9.81));
  btTransform floor_pose;
  floor_pose.setIdentity();
  im.floor =
      im.addStatic(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), floor_pose, 0.0);
  for (const SolidBox& box : world.solids()) {
    btTransform pose;
    pose.setIdentity();
    pose.setOrigin(btVector3(box.center.x(), box.center.y(), box.z0 + 0.5 * box.size.z()));
    pose.setRotation(btQuaternion(btVector3(0, 0, 1), static_cast<btScalar>(box.yaw)));
    im.addStatic(std::make_unique<btBoxShape>(
                     btVector3(0.5 * box.size.x(), 0.5 * box.size.y(), 0.5 * box.size.z())),
                 pose, 0.3);
  }
}

PhysicsWorld::~PhysicsWorld() = default;

int PhysicsWorld::addKinematicCylinder(double radius, double height,
                                       const Eigen::Vector2d& position) {
  Impl& im = *impl_;
  btTransform pose;
  pose.setIdentity();
  pose.setOrigin(btVector3(position.x(), position.y(), 0.5 * height + 0.001));
  btRigidBody* body = im.addStatic(
      std::make_unique<btCylinderShapeZ>(btVector3(radius, radius, 0.5 * height)), pose, 0.3);
  body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  body->setActivationState(DISABLE_DEACTIVATION);
  body->setUserIndex(kPersonTag);
  im.kinematic.push_back(body);
  im.kinematic_z.push_back(0.5 * height + 0.001);
  return static_cast<int>(im.kinematic.size()) - 1;
}

int PhysicsWorld::addKinematicBox(const SolidBox& box) {
  Impl& im = *impl_;
  btTransform pose;
  pose.setIdentity();
  pose.setOrigin(btVector3(box.center.x(), box.center.y(), box.z0 + 0.5 * box.size.z()));
  pose.setRotation(btQuaternion(btVector3(0, 0, 1), static_cast<btScalar>(box.yaw)));
  btRigidBody* body = im.addStatic(std::make_unique<btBoxShape>(btVector3(
                                       0.5 * box.size.x(), 0.5 * box.size.y(), 0.5 * box.size.z())),
                                   pose, 0.3);
  body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  body->setActivationState(DISABLE_DEACTIVATION);
  im.kinematic.push_back(body);
  im.kinematic_z.push_back(box.z0 + 0.5 * box.size.z());
  return static_cast<int>(im.kinematic.size()) - 1;
}

void PhysicsWorld::moveKinematic(int index, const Eigen::Vector2d& position, bool present) {
  btRigidBody* body = impl_->kinematic.at(index);
  btTransform pose = body->getWorldTransform();
  // Out of the way: far below the floor, where nothing else is.
  const double z = present ? impl_->kinematic_z.at(index) : -100.0;
  pose.setOrigin(btVector3(position.x(), position.y(), z));
  body->setWorldTransform(pose);
  body->setInterpolationWorldTransform(pose);
}

int PhysicsWorld::robotCount() const { return static_cast<int>(impl_->robots.size()); }

int PhysicsWorld::addRobot(const RobotDescription& d, const Pose2& start,
                           const DriveConfig& drive) {
  Impl& im = *impl_;
  auto r = std::make_unique<Robot>();
  r->description = d;
  r->drive = drive;
  const double h = d.body_height;
  r->shape = std::make_unique<btCylinderShapeZ>(btVector3(d.body_radius, d.body_radius, 0.5 * h));
  btTransform pose;
  pose.setIdentity();
  pose.setOrigin(btVector3(start.x, start.y, 0.5 * h + 0.001));
  pose.setRotation(btQuaternion(btVector3(0, 0, 1), static_cast<btScalar>(start.theta)));
  r->motion = std::make_unique<btDefaultMotionState>(pose);
  btVector3 inertia(0, 0, 0);
  r->shape->calculateLocalInertia(drive.mass, inertia);
  btRigidBody::btRigidBodyConstructionInfo info(drive.mass, r->motion.get(), r->shape.get(),
                                                inertia);
  // The body slides on its wheels; traction is applied by the drive model in step().
  info.m_friction = 0.0;
  info.m_restitution = 0.0;
  r->body = std::make_unique<btRigidBody>(info);
  r->body->setAngularFactor(btVector3(0, 0, 1));  // a synchro-drive base does not tip
  r->body->setActivationState(DISABLE_DEACTIVATION);
  r->body->setUserIndex(kRobotTag);
  im.world.addRigidBody(r->body.get());
  im.robots.push_back(std::move(r));
  return static_cast<int>(im.robots.size()) - 1;
}

void PhysicsWorld::command(int robot, const MotionCommand& cmd) {
  Robot& r = *impl_->robots.at(robot);
  const RobotDescription& d = r.description;
  r.target.linear = std::clamp(cmd.linear, -d.max_linear_speed, d.max_linear_speed);
  r.target.angular = std::clamp(cmd.angular, -d.max_angular_speed, d.max_angular_speed);
}

void PhysicsWorld::step() {
  Impl& im = *impl_;
  const double g = 9.81;
  for (auto& rp : im.robots) {
    Robot& r = *rp;
    const RobotDescription& d = r.description;
    // The base's motion profile: the setpoint ramps towards the command.
    const double dv = d.max_linear_accel * step_, dw = d.max_angular_accel * step_;
    r.setpoint.linear += std::clamp(r.target.linear - r.setpoint.linear, -dv, dv);
    r.setpoint.angular += std::clamp(r.target.angular - r.setpoint.angular, -dw, dw);

    // Wheel-floor traction: a servo force towards the setpoint, limited by mu * m * g;
    // what it cannot deliver, the wheels slip.
    const int index = static_cast<int>(&rp - &im.robots[0]);
    const BodyVelocity v = bodyVelocity(index);
    const Pose2 at = truePose(index);
    double mu = r.drive.traction_mu;  // the floor patch under the robot, if any
    for (const SurfaceSpec& s : im.surfaces)
      if (s.contains(at.translation())) mu = s.traction_mu;
    const double m = r.drive.mass, tau = r.drive.velocity_time_constant;
    const double f_max = mu * m * g;
    double fx = m * (r.setpoint.linear - v.forward) / tau;
    double fy = m * (0.0 - v.lateral) / tau;  // wheels resist sideways sliding
    const double f = std::hypot(fx, fy);
    r.slip_linear = f > f_max;
    if (r.slip_linear) {
      fx *= f_max / f;
      fy *= f_max / f;
    }
    const double izz = 0.5 * m * d.body_radius * d.body_radius;
    const double t_max = f_max * d.body_radius;
    const double t_want = izz * (r.setpoint.angular - v.yaw_rate) / tau;
    r.slip_angular = std::abs(t_want) > t_max;
    const double tz = std::clamp(t_want, -t_max, t_max);
    const btTransform& tf = r.body->getWorldTransform();
    const btVector3 force = tf.getBasis() * btVector3(fx, fy, 0);
    r.body->applyCentralForce(force);
    r.body->applyTorque(btVector3(0, 0, tz));
  }
  im.world.stepSimulation(static_cast<btScalar>(step_), 0);
  time_ += step_;

  // Contacts with anything but the floor, by the kind of what was touched.
  std::vector<std::array<bool, 3>> touching(im.robots.size(), std::array<bool, 3>{});
  std::vector<std::array<btVector3, 3>> where(im.robots.size());
  const int manifolds = im.dispatcher.getNumManifolds();
  for (int i = 0; i < manifolds; ++i) {
    const btPersistentManifold* mf = im.dispatcher.getManifoldByIndexInternal(i);
    const btCollisionObject* a = mf->getBody0();
    const btCollisionObject* b = mf->getBody1();
    if (a == im.floor || b == im.floor) continue;
    int real = -1;
    for (int c = 0; c < mf->getNumContacts(); ++c)
      if (mf->getContactPoint(c).getDistance() < 0.002f) real = c;
    if (real < 0) continue;
    const btVector3 point = mf->getContactPoint(real).getPositionWorldOnA();
    for (size_t k = 0; k < im.robots.size(); ++k) {
      const btCollisionObject* self = im.robots[k]->body.get();
      const btCollisionObject* other = a == self ? b : b == self ? a : nullptr;
      if (!other) continue;
      touching[k][kindOf(other)] = true;
      where[k][kindOf(other)] = point;
    }
  }
  for (size_t k = 0; k < im.robots.size(); ++k) {
    Robot& r = *im.robots[k];
    const bool any = touching[k][kStaticWorld] || touching[k][kPerson] || touching[k][kOtherRobot];
    if (any && !r.contact) ++r.contact_events;
    r.contact = any;
    for (int kind = 0; kind < 3; ++kind)
      if (touching[k][kind]) r.contact_point = {where[k][kind].x(), where[k][kind].y()};
    int* counts[3] = {&r.counts.static_world, &r.counts.people, &r.counts.robots};
    for (int kind = 0; kind < 3; ++kind) {
      if (touching[k][kind] && !r.touching_kind[kind]) {
        ++*counts[kind];
        r.log.push_back({time_, static_cast<ContactEvent::Kind>(kind),
                         Eigen::Vector2d(where[k][kind].x(), where[k][kind].y())});
      }
      r.touching_kind[kind] = touching[k][kind];
    }
  }
}

Pose2 PhysicsWorld::truePose(int robot) const {
  const btTransform& tf = impl_->robots.at(robot)->body->getWorldTransform();
  btScalar yaw, pitch, roll;
  tf.getBasis().getEulerZYX(yaw, pitch, roll);
  return {tf.getOrigin().x(), tf.getOrigin().y(), wrapAngle(yaw)};
}

BodyVelocity PhysicsWorld::bodyVelocity(int robot) const {
  const btRigidBody& body = *impl_->robots.at(robot)->body;
  const Pose2 p = truePose(robot);
  const btVector3 v = body.getLinearVelocity();
  const double c = std::cos(p.theta), s = std::sin(p.theta);
  return {c * v.x() + s * v.y(), -s * v.x() + c * v.y(), body.getAngularVelocity().z()};
}

BodyVelocity PhysicsWorld::wheelVelocity(int robot) const {
  const Robot& r = *impl_->robots.at(robot);
  BodyVelocity w = bodyVelocity(robot);
  if (r.slip_linear) w.forward = r.setpoint.linear;
  if (r.slip_angular) w.yaw_rate = r.setpoint.angular;
  return w;
}

bool PhysicsWorld::inContact(int robot) const { return impl_->robots.at(robot)->contact; }
std::optional<Eigen::Vector2d> PhysicsWorld::contactPoint(int robot) const {
  const Robot& r = *impl_->robots.at(robot);
  if (!r.contact) return std::nullopt;
  return r.contact_point;
}
const std::vector<ContactEvent>& PhysicsWorld::contactLog(int robot) const {
  return impl_->robots.at(robot)->log;
}

const char* toString(ContactEvent::Kind k) {
  switch (k) {
    case ContactEvent::Kind::kPerson:
      return "person";
    case ContactEvent::Kind::kRobot:
      return "robot";
    default:
      return "static_world";
  }
}

int PhysicsWorld::contactEvents(int robot) const { return impl_->robots.at(robot)->contact_events; }
ContactCounts PhysicsWorld::contactCounts(int robot) const {
  return impl_->robots.at(robot)->counts;
}

}  // namespace coopmap::sim

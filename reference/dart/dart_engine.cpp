#include "boxpile/reference/dart/dart_engine.hpp"

#include <cmath>
#include <unordered_map>

#include <dart/collision/CollisionObject.hpp>
#include <dart/collision/CollisionResult.hpp>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/constraint/ContactConstraint.hpp>
#include <dart/constraint/DantzigBoxedLcpSolver.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>
#include <dart/dynamics/BallJoint.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/PlaneShape.hpp>
#include <dart/dynamics/PrismaticJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/WeldJoint.hpp>
#include <dart/simulation/World.hpp>

#include "boxpile/reference/body_states.hpp"
#include "boxpile/reference/dart/dart_convention.hpp"
#include "boxpile/reference/dart/dart_support.hpp"
#include "boxpile/sim/world.hpp"

namespace boxpile {

using namespace reference_detail;
using dart::dynamics::BodyNode;
using dart::dynamics::ShapeFrame;
using dart::dynamics::Skeleton;

namespace {

// Which scene body and which of its boxes a shape node stands for.
struct ShapeTag {
  int body = kGround;
  int shape = 0;
};

// DART combines the two shapes' coefficients of a contact as min(mu_a, mu_b) and e_a e_b
// (ContactConstraint). Each shape gets its body's mu and sqrt(e): a pair of equal materials then
// gets exactly our rule's mu and e (sqrt(mu mu), max(e, e)); unequal ones get min(mu_a, mu_b)
// <= sqrt(mu_a mu_b) and sqrt(e_a e_b) <= max(e_a, e_b) (docs/reference-engines.md).
struct ShapeMaterial {
  double friction = 0.0;
  double restitution = 0.0;
};

ShapeMaterial shape_material(const Material& m, const Effects& fx) {
  return {fx.friction ? m.friction : 0.0, fx.restitution ? std::sqrt(m.restitution) : 0.0};
}

}  // namespace

struct DartEngine::World {
  World(const Scene& scene, const DartSettings& settings);

  void configure_solver();
  Skeleton* add_skeleton(const std::string& name);
  void add_shape(BodyNode* node, const dart::dynamics::ShapePtr& shape, const Eigen::Isometry3d& relative,
                 const Material& material, ShapeTag tag);
  void add_boxes(BodyNode* node, int index);
  void add_free_body(int index);
  void add_fixed_body(int index);
  void add_wire_body(int index);
  void add_ground(const HalfSpace& ground);
  void apply_effects();
  void apply_contact_parameters() const;
  void record_boxes();
  void read_contacts();
  OrientedBox box_of(const ShapeTag& tag) const;

  Scene scene;
  DartSettings settings;
  std::vector<RigidBody> bodies;
  dart::simulation::WorldPtr world;
  std::vector<BodyNode*> nodes;  // scene order: the body node of each body (fixed ones too)
  std::vector<bool> mobile;      // scene order
  std::unordered_map<const ShapeFrame*, ShapeTag> tags;
  std::vector<std::vector<OrientedBox>> boxes;  // per body: its boxes where the last step found contacts
  OrientedBox ground_box;                       // when the ground is a box
  bool ground_is_plane = false;
  std::vector<BodyContact> contacts;
  std::uint64_t steps = 0;
};

DartEngine::World::World(const Scene& s, const DartSettings& st)
    : scene(s), settings(st), bodies(make_bodies(s)), world(dart::simulation::World::create("boxpile")) {
  const Vec3 g = scene.effects.gravity ? scene.gravity : Vec3::Zero();
  world->setGravity(g);
  world->setTimeStep(scene.time.dt);
  configure_solver();
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    const BodyDesc& desc = scene.bodies[static_cast<std::size_t>(i)];
    if (bodies[static_cast<std::size_t>(i)].fixed) {
      add_fixed_body(i);
    } else if (desc.wire) {
      add_wire_body(i);
    } else {
      add_free_body(i);
    }
  }
  if (scene.ground) add_ground(*scene.ground);
  boxes.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) boxes[i].resize(bodies[i].shapes.size());
  contacts.reserve(static_cast<std::size_t>(settings.max_contacts));
}

void DartEngine::World::configure_solver() {
  using namespace dart::constraint;
  auto* solver = dynamic_cast<BoxedLcpConstraintSolver*>(world->getConstraintSolver());
  if (!solver) {
    world->setConstraintSolver(std::make_unique<BoxedLcpConstraintSolver>());
    solver = static_cast<BoxedLcpConstraintSolver*>(world->getConstraintSolver());
  }
  auto pgs = std::make_shared<PgsBoxedLcpSolver>();
  PgsBoxedLcpSolver::Option option = pgs->getOption();
  option.mMaxIteration = settings.pgs_iterations;
  pgs->setOption(option);
  if (settings.lcp_solver == DartLcpSolver::Pgs) {
    solver->setBoxedLcpSolver(pgs);
    solver->setSecondaryBoxedLcpSolver(nullptr);
  } else {
    solver->setBoxedLcpSolver(std::make_shared<DantzigBoxedLcpSolver>());
    solver->setSecondaryBoxedLcpSolver(settings.pgs_fallback ? pgs : nullptr);
  }
  solver->setCollisionDetector(make_dart_detector(settings.detector));
  solver->getCollisionOption().maxNumContacts = static_cast<std::size_t>(settings.max_contacts);
}

Skeleton* DartEngine::World::add_skeleton(const std::string& name) {
  auto skeleton = Skeleton::create(name);
  world->addSkeleton(skeleton);  // keeps it alive
  return skeleton.get();
}

void DartEngine::World::add_shape(BodyNode* node, const dart::dynamics::ShapePtr& shape,
                                  const Eigen::Isometry3d& relative, const Material& material, ShapeTag tag) {
  using namespace dart::dynamics;
  ShapeNode* sn = node->createShapeNodeWith<CollisionAspect, DynamicsAspect>(shape);
  sn->setRelativeTransform(relative);
  const ShapeMaterial m = shape_material(material, scene.effects);
  sn->getDynamicsAspect()->setFrictionCoeff(m.friction);
  sn->getDynamicsAspect()->setRestitutionCoeff(m.restitution);
  tags[sn] = tag;
}

// The body node sits at the centre of mass in the body axes: its boxes at their offsets.
void DartEngine::World::add_boxes(BodyNode* node, int index) {
  const RigidBody& rb = bodies[static_cast<std::size_t>(index)];
  for (int k = 0; k < static_cast<int>(rb.shapes.size()); ++k) {
    const BoxShape& box = rb.shapes[static_cast<std::size_t>(k)];
    add_shape(node, std::make_shared<dart::dynamics::BoxShape>(2.0 * box.half_extents),
              dart_transform(box.offset, box.orientation.toRotationMatrix()), rb.material, {index, k});
  }
}

void DartEngine::World::add_free_body(int index) {
  const RigidBody& rb = bodies[static_cast<std::size_t>(index)];
  Skeleton* skeleton = add_skeleton(rb.name);
  auto [joint, node] = skeleton->createJointAndBodyNodePair<dart::dynamics::FreeJoint>();
  node->setInertia(dart::dynamics::Inertia(rb.mass, Vec3::Zero(), rb.inertia_body));
  add_boxes(node, index);
  joint->setTransform(dart_transform(rb.x, rb.R));
  joint->setLinearVelocity(rb.v);
  joint->setAngularVelocity(rb.omega);
  nodes.push_back(node);
  mobile.push_back(true);
}

// An immobile skeleton welded to the world at the body's centre of mass and axes.
void DartEngine::World::add_fixed_body(int index) {
  const RigidBody& rb = bodies[static_cast<std::size_t>(index)];
  Skeleton* skeleton = add_skeleton(rb.name);
  auto [joint, node] = skeleton->createJointAndBodyNodePair<dart::dynamics::WeldJoint>();
  joint->setTransformFromParentBodyNode(dart_transform(rb.x, rb.R));
  add_boxes(node, index);
  skeleton->setMobile(false);
  nodes.push_back(node);
  mobile.push_back(false);
}

// The wire as a chain in reduced coordinates: a carriage on a prismatic joint along the wire
// (position limits 0 and the wire's length: the ends), the body on a ball joint at the anchor.
// The chain keeps the anchor on the wire exactly; the carriage has no shape and a small fraction
// of the body's mass and inertia (DART's articulated-body algorithm needs some on every body).
// The body's initial velocity keeps the anchor's component along the wire and the angular
// velocity; a component across the wire is dropped (as the wire forbids it).
void DartEngine::World::add_wire_body(int index) {
  const BodyDesc& desc = scene.bodies[static_cast<std::size_t>(index)];
  const Wire& wire = *desc.wire;
  const RigidBody& rb = bodies[static_cast<std::size_t>(index)];
  const Vec3 along = wire.to - wire.from;
  const double length = along.norm();
  const Vec3 axis = along / length;
  const Vec3 anchor = desc.frame.apply(wire.anchor);
  const Vec3 anchor_local = rb.frame_offset + wire.anchor;  // about the centre of mass, body axes

  Skeleton* skeleton = add_skeleton(rb.name);
  dart::dynamics::PrismaticJoint::Properties slide;
  slide.mName = rb.name + " slide";
  slide.mAxis = axis;
  slide.mT_ParentBodyToJoint = dart_transform(wire.from, Mat3::Identity());
  auto [prismatic, carriage] = skeleton->createJointAndBodyNodePair<dart::dynamics::PrismaticJoint>(
      nullptr, slide, BodyNode::AspectProperties(rb.name + " carriage"));
  const double f = settings.wire_carriage_mass_fraction;
  carriage->setInertia(dart::dynamics::Inertia(f * rb.mass, Vec3::Zero(), f * rb.inertia_body));
  prismatic->setPositionLowerLimit(0, 0.0);
  prismatic->setPositionUpperLimit(0, length);
  prismatic->setLimitEnforcement(true);
  prismatic->setPosition(0, (anchor - wire.from).dot(axis));
  prismatic->setVelocity(0, axis.dot(rb.velocity_at(anchor)));

  dart::dynamics::BallJoint::Properties ball;
  ball.mName = rb.name + " ball";
  ball.mT_ChildBodyToJoint = dart_transform(anchor_local, Mat3::Identity());
  auto [joint, node] = skeleton->createJointAndBodyNodePair<dart::dynamics::BallJoint>(
      carriage, ball, BodyNode::AspectProperties(rb.name));
  node->setInertia(dart::dynamics::Inertia(rb.mass, Vec3::Zero(), rb.inertia_body));
  add_boxes(node, index);
  joint->setPositions(dart::dynamics::BallJoint::convertToPositions(rb.R));
  joint->setVelocities(rb.R.transpose() * rb.omega);  // the child's angular velocity, child axes
  nodes.push_back(node);
  mobile.push_back(true);
}

void DartEngine::World::add_ground(const HalfSpace& ground) {
  Skeleton* skeleton = add_skeleton("ground");
  auto [joint, node] = skeleton->createJointAndBodyNodePair<dart::dynamics::WeldJoint>();
  ground_is_plane = dart_detector_takes_planes(settings.detector);
  if (ground_is_plane) {
    add_shape(node, std::make_shared<dart::dynamics::PlaneShape>(ground.normal, ground.offset),
              Eigen::Isometry3d::Identity(), scene.material, {kGround, 0});
  } else {
    // Centred under the bodies' mean starting position.
    Vec3 near = Vec3::Zero();
    for (const RigidBody& rb : bodies) near += rb.x / static_cast<double>(bodies.size());
    ground_box = dart_ground_box(ground, near);
    joint->setTransformFromParentBodyNode(dart_transform(ground_box));
    add_shape(node, std::make_shared<dart::dynamics::BoxShape>(2.0 * ground_box.half), Eigen::Isometry3d::Identity(),
              scene.material, {kGround, 0});
  }
  skeleton->setMobile(false);
}

// Damping and the gyroscopic term, as forces or velocity changes before DART's step.
//  - damping: DART's joint damping is a force per velocity (N s/m), applied implicitly, so
//    v <- v / (1 + c dt / m); the scene's law dv/dt = -c v is matched exactly instead by scaling
//    each mobile joint's velocities by exp(-c dt) (linear and angular rates apart).
//  - gyroscopic: DART's equations of motion always hold the term omega x I omega (its Coriolis
//    force, evaluated at the step's start velocities). With the effect off, each body gets the
//    opposite torque omega x (I_world omega) at the same velocities, which cancels it exactly:
//    a torque-free body then keeps its angular velocity, as in the other engines.
void DartEngine::World::apply_effects() {
  const Effects& fx = scene.effects;
  const double dt = scene.time.dt;
  const double linear = fx.damping ? std::exp(-scene.damping.linear * dt) : 1.0;
  const double angular = fx.damping ? std::exp(-scene.damping.angular * dt) : 1.0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!mobile[i]) continue;
    BodyNode* node = nodes[i];
    if (fx.damping) {
      if (auto* free = dynamic_cast<dart::dynamics::FreeJoint*>(node->getParentJoint())) {
        Eigen::Vector6d v = free->getVelocities();  // angular then linear, body axes
        v.head<3>() *= angular;
        v.tail<3>() *= linear;
        free->setVelocities(v);
      } else {
        node->getParentJoint()->setVelocities(node->getParentJoint()->getVelocities() * angular);  // the ball
        BodyNode* carriage = node->getParentBodyNode();
        carriage->getParentJoint()->setVelocities(carriage->getParentJoint()->getVelocities() * linear);
      }
    }
    if (!fx.gyroscopic) {
      const Mat3 R = node->getWorldTransform().linear();
      const Vec3 w = node->getAngularVelocity();
      const Mat3 I = R * bodies[i].inertia_body * R.transpose();
      node->addExtTorque(w.cross(I * w), /*isLocal=*/false);
    }
  }
}

// DART keeps the contact constraint's parameters in static members, shared by every DART world
// of the process: each engine sets its own before each of its steps.
void DartEngine::World::apply_contact_parameters() const {
  using dart::constraint::ContactConstraint;
  ContactConstraint::setErrorAllowance(settings.error_allowance);
  ContactConstraint::setErrorReductionParameter(settings.erp);
  ContactConstraint::setMaxErrorReductionVelocity(settings.max_erv);
  ContactConstraint::setConstraintForceMixing(settings.cfm);
}

OrientedBox DartEngine::World::box_of(const ShapeTag& tag) const {
  if (tag.body == kGround) return ground_box;
  return boxes[static_cast<std::size_t>(tag.body)][static_cast<std::size_t>(tag.shape)];
}

// DART finds contacts at the positions the step starts from: the boxes are recorded there.
void DartEngine::World::record_boxes() {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Isometry3d t = nodes[i]->getWorldTransform();
    const RigidBody& rb = bodies[i];
    for (std::size_t k = 0; k < rb.shapes.size(); ++k) {
      const BoxShape& s = rb.shapes[k];
      boxes[i][k] = {t * s.offset, t.linear() * s.orientation.toRotationMatrix(), s.half_extents};
    }
  }
}

// DART's normal points toward the contact's first object: that object is our A, unless it is the
// ground (always B) or fixed while the other is not. Pairs of fixed bodies and the ground are
// left out (nothing moves them).
void DartEngine::World::read_contacts() {
  contacts.clear();
  for (const dart::collision::Contact& c : world->getLastCollisionResult().getContacts()) {
    ShapeTag first = tags.at(c.collisionObject1->getShapeFrame());
    ShapeTag second = tags.at(c.collisionObject2->getShapeFrame());
    const auto moves = [&](const ShapeTag& t) { return t.body != kGround && mobile[static_cast<std::size_t>(t.body)]; };
    if (!moves(first) && !moves(second)) continue;
    Vec3 n = c.normal;
    if (first.body == kGround || !moves(first)) {
      std::swap(first, second);
      n = -n;
    }
    const Vec3 p = c.point;
    Contact contact;
    if (second.body == kGround && ground_is_plane) {
      contact = dart_box_plane_contact(p, n, c.penetrationDepth);
    } else {
      contact = dart_box_box_contact(settings.detector, box_of(first), box_of(second), p, n, c.penetrationDepth);
      if (second.body == kGround) contact.feature = kind_only(FeatureKind::Plane);
    }
    contacts.push_back({contact, first.body, second.body, first.shape, second.shape});
  }
}

DartEngine::DartEngine(const Scene& scene, const DartSettings& settings)
    : world_(std::make_unique<World>(scene, settings)) {}

DartEngine::~DartEngine() = default;

void DartEngine::step() {
  World& w = *world_;
  w.apply_effects();
  w.apply_contact_parameters();
  w.record_boxes();
  w.world->step();
  w.read_contacts();
  ++w.steps;
}

double DartEngine::time() const { return static_cast<double>(world_->steps) * world_->scene.time.dt; }

void DartEngine::body_states(std::vector<BodyState>& out) const {
  const World& w = *world_;
  reference_detail::collect_body_states(w.bodies, out, [&](std::size_t i, BodyState& s) {
    const BodyNode* node = w.nodes[i];
    const Eigen::Isometry3d t = node->getWorldTransform();
    s.orientation = Quat(t.linear()).normalized();
    s.position = t.translation() + s.orientation * w.bodies[i].frame_offset;
    // The node's origin is the centre of mass.
    s.velocity = w.mobile[i] ? Vec3(node->getLinearVelocity()) : Vec3::Zero();
    s.angular_velocity = w.mobile[i] ? Vec3(node->getAngularVelocity()) : Vec3::Zero();
  });
}

void DartEngine::contacts(std::vector<BodyContact>& out) const { out = world_->contacts; }

}  // namespace boxpile

// World: the public face of the engine. Box2D lives behind box2d_bridge.h, the tensions in
// cable_solver.h; this file keeps the state a user edits and the order of a step.
#include "engine/dynamics/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>

#include "engine/cable/crossing.h"
#include "engine/core/error.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/box2d_limits.h"
#include "engine/dynamics/cable_islands.h"
#include "engine/dynamics/cable_solver.h"
#include "engine/dynamics/contact_catch.h"
#include "engine/dynamics/end_states.h"
#include "engine/dynamics/floors.h"
#include "engine/dynamics/joint_energy.h"
#include "engine/dynamics/knock_motion.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/midpoint_solver.h"
#include "engine/dynamics/servo_drive.h"
#include "engine/dynamics/wheel_rope_energy.h"
#include "engine/dynamics/world_state.h"

namespace cablelab {

namespace {

// Wrap events (docs/cables.md, "Events"), as shares of the sub-step.
constexpr double kSelectAhead = 1e-6;   // the look-ahead of the wrap selection
constexpr double kMinEventStep = 1e-4;  // events closer than this are taken at this time
// After a step cut at an event, the bodies land a little short of it: the cut step's own solve
// moves them a little differently from the motion the event was located on. The same change
// found again this close ahead is the one the cut was for, and is taken now (otherwise each
// event cost two or three more cuts, each nearer: 1.5 cuts a step where 0.13 were due).
constexpr double kCutReach = 0.05;
// Pieces of a sub-step that locate wrap events (and shorten for fast catches); the rest of it is
// one step. 16 ran out where a light polygon's fast catch cut a sub-step into pieces of 0.6 ms, and
// a wrap change in the rest moved the length 1.4 cm; 32 at 30 Hz, 1.6 cm (docs/knocks.md).
constexpr int kMaxEventsPerSubstep = 64;
constexpr double kSubstepRest = 1e-9;     // of the sub-step: a rest this short ends it
constexpr int kMaxUnsettledHalvings = 4;  // of a step whose main-solve Newton found no answer
// A wrap event's cut is located again this often: once. Not more: on a stiff elastic band (omega h
// ~ 7, World.StiffMembraneCatchesADroppedLightBody) each shorter cut moves the point differently
// again, three relocations did not settle, and the energy of its settle rose 1.1e-6 J a step.
constexpr int kEventRelocations = 1;
constexpr int kFloorRelocations = 3;  // a floor arrival's cut is located again at most this often
constexpr double kMaxOmegaDt = 0.3;   // longest midpoint step over the fastest transverse mode
// Box2D's step limits (box2d_limits.h), less a margin for its float arithmetic, and how often a
// step is shortened to keep within them.
constexpr double kBox2DMaxTurn = 0.9 * kBox2DMaxStepTurn;  // rad
constexpr double kBox2DMaxMove = 0.9 * kBox2DMaxStepMove;  // m
constexpr int kMaxLimitShortenings = 4;
// A wrap event on a knocked step's actual motion this near its end is taken there (the length
// moves by (v dt)^2 / l: 1e-8 m at 5 m/s).
constexpr double kKnockReach = 1e-3;

// The first wrap event of any cable over `motion` within `limit` (s); `cable` -1 if none.
struct FirstWrapEvent {
  std::optional<double> time;
  int cable = -1;
  WrapEvent event;
};
FirstWrapEvent firstWrapEvent(std::span<const Cable> cables, std::span<const BodyState> motion,
                              double limit) {
  FirstWrapEvent first;
  for (size_t i = 0; i < cables.size(); ++i)
    if (auto e = cables[i].nextEvent(motion, first.time ? *first.time : limit)) {
      first = {e->time, static_cast<int>(i), *e};
    }
  return first;
}

SceneDef validated(SceneDef scene, const std::string& source) {
  validateScene(scene, source);
  return scene;
}

// Per body, the largest restitution of its shapes: what a body bounces off its pulley with
// (docs/floors.md, "Bouncing off a pulley"). Empty where none bounces: the solve skips the check.
std::vector<double> floorRestitution(const SceneDef& scene) {
  std::vector<double> restitution(scene.bodies.size(), 0.0);
  for (size_t b = 0; b < scene.bodies.size(); ++b)
    restitution[b] = largestRestitution(scene, static_cast<int>(b));
  if (std::all_of(restitution.begin(), restitution.end(), [](double e) { return e == 0; }))
    restitution.clear();
  return restitution;
}

}  // namespace

World::World(SceneDef scene, const std::string& source)
    : scene_(validated(scene.history ? scene.history->origin : scene, source)),
      b2_(std::make_unique<Box2DBridge>(scene_)),
      solver_(std::make_unique<CableSolver>(floorRestitution(scene_))),
      midpoint_(std::make_unique<MidpointSolver>()),
      islands_(std::make_unique<CableIslands>()),
      jointEnergy_(std::make_unique<JointEnergy>()),
      gravity_(scene_.gravity) {
  jointNeighbours_.assign(scene_.bodies.size(), {});
  for (const JointDef& jd : scene_.joints) {
    const int a = findBody(jd.bodyA), b = findBody(jd.bodyB);
    jointBodies_.push_back({a, b});
    if (a >= 0 && b >= 0) jointNeighbours_[a].push_back(b), jointNeighbours_[b].push_back(a);
  }
  servos_ = std::make_unique<ServoDrive>(scene_, jointBodies_);
  // A fresh scene's targets are reached over the first step from where the joints start; one
  // written mid-run holds them (servo_targets.h).
  std::vector<double> jointStarts;
  if (scene_.time == 0 && scene_.stepCount == 0)
    for (size_t j = 0; j < scene_.joints.size(); ++j)
      jointStarts.push_back(b2_->jointCoordinate(static_cast<int>(j)).value);
  servoTargets_.reset(scene_.joints, jointStarts);
  jointForces_.assign(scene_.joints.size(), 0.0);
  servoImpulses_.assign(scene_.joints.size(), 0.0);
  stalls_.assign(scene_.joints.size(), StallWatch{});
  cables_.reserve(scene_.cables.size());
  for (int i = 0; i < static_cast<int>(scene_.cables.size()); ++i)
    cables_.emplace_back(scene_, i, source);
  b2_->readBodies(bodies_);
  for (size_t i = 0; i < cables_.size(); ++i) {
    cables_[i].update(bodies_, &warnings_);
    if (cables_[i].length() < 1e-9)
      throw InputError(source, "cables[" + std::to_string(i) + "]",
                       "must not have zero length: its ends coincide at the initial pose (got " +
                           formatNumber(cables_[i].length()) + " m)");
    // A rigid cable longer than its rest length at the start snaps to it (kBaumgarte of the
    // excess a sub-step): say so, as it is rarely meant.
    if (const Cable& c = cables_[i]; !c.elastic() && c.stretch() > 1e-3)
      warnings_.push_back("cable '" + c.name() + "': rigid and " + formatNumber(c.stretch()) +
                          " m longer than its rest length " + formatNumber(c.restLength()) +
                          " m at the start: it snaps taut to it (give it stiffness to stretch)");
  }
  time_ = scene_.time, steps_ = scene_.stepCount;
  // A scene written mid-run: rebuilt bit for bit from where it started (world_state.h).
  if (scene.history) resumeHistory(*this, scene, source);
}

World::~World() = default;

int World::findBody(std::string_view name) const {
  for (size_t i = 0; i < scene_.bodies.size(); ++i)
    if (scene_.bodies[i].name == name) return static_cast<int>(i);
  return -1;
}

int World::findCable(std::string_view name) const {
  for (size_t i = 0; i < cables_.size(); ++i)
    if (cables_[i].name() == name) return static_cast<int>(i);
  return -1;
}

int World::findJoint(std::string_view name) const {
  for (size_t i = 0; i < scene_.joints.size(); ++i)
    if (scene_.joints[i].name == name) return static_cast<int>(i);
  return -1;
}

void World::setBodyTransform(int i, const Vec2& position, double angle) {
  history_.add({WorldInput::Kind::BodyTransform, i, 1, {position.x(), position.y(), angle}});
  b2_->setTransform(i, position, angle);
  b2_->readBodies(bodies_);
  rateSteps_.clear();  // the rates a user sets are the motion's
  tautSteps_.clear();
  servos_->forgetMotion();
  servoTargets_.jump();
}

void World::refreshCables() {
  history_.add({WorldInput::Kind::RefreshCables});
  b2_->readBodies(bodies_);
  for (Cable& c : cables_) {
    c.update(bodies_, &warnings_);
    c.refresh(bodies_);
  }
}

void World::setBodyVelocity(int i, const Vec2& velocity, double angularVelocity) {
  history_.add(
      {WorldInput::Kind::BodyVelocity, i, 1, {velocity.x(), velocity.y(), angularVelocity}});
  b2_->setVelocity(i, velocity, angularVelocity);
  b2_->readBodies(bodies_);
  rateSteps_.clear();
  tautSteps_.clear();
  servos_->forgetMotion();
  servoTargets_.jump();
}

void World::applyForce(int i, const Vec2& force, const Vec2& worldPoint) {
  history_.add(
      {WorldInput::Kind::Force, i, 1, {force.x(), force.y(), worldPoint.x(), worldPoint.y()}});
  if (pendingForces_.size() != bodies_.size()) pendingForces_.assign(bodies_.size(), Vec3::Zero());
  const Vec2 r = worldPoint - bodies_[i].position;
  pendingForces_[i] += Vec3(force.x(), force.y(), cross(r, force));
}

void World::beginDrag(int body, const Vec2& worldPoint, double stiffnessHz) {
  endDrag();
  history_.add(
      {WorldInput::Kind::BeginDrag, body, 1, {worldPoint.x(), worldPoint.y(), stiffnessHz}});
  if (!b2_->beginDrag(body, worldPoint, stiffnessHz, gravity_.norm())) return;
  dragBody_ = body;
  dragTarget_ = worldPoint;
}

void World::dragTo(const Vec2& target) {
  if (dragBody_ < 0) return;
  history_.add({WorldInput::Kind::DragTo, 0, 1, {target.x(), target.y()}});
  b2_->dragTo(target);
  dragTarget_ = target;
}

void World::endDrag() {
  if (dragBody_ >= 0) history_.add({WorldInput::Kind::EndDrag});
  b2_->endDrag();
  dragBody_ = -1;
}

void World::setCableParameters(int i, double restLength, double stiffness, double preload,
                               double damping) {
  const std::string field = "cables[" + std::to_string(i) + "]";
  auto check = [&](double v, const char* name, bool positiveOnly) {
    if (!std::isfinite(v) || v < 0 || (positiveOnly && v == 0))
      throw InputError(
          "live edit", field + "." + name,
          std::string(positiveOnly ? "must be positive" : "must be >= 0") + gotValue(v));
  };
  check(restLength, "rest_length", true);
  check(stiffness, "stiffness", false);
  check(preload, "preload", false);
  check(damping, "damping", false);
  cables_[i].setParameters({restLength, stiffness, preload, damping});
  history_.add(
      {WorldInput::Kind::CableParameters, i, 1, {restLength, stiffness, preload, damping}});
}

JointState World::joint(int i) const {
  const JointDef& def = scene_.joints[i];
  JointState s{def.name, def.kind, b2_->anchorA(i), b2_->anchorB(i)};
  const JointCoordinate q = b2_->jointCoordinate(i);
  s.value = q.value;
  s.speed = q.speed;
  s.servoTarget = servoTargets_[i];
  s.force = jointForces_[i];
  return s;
}

void World::setWrapSkipping(bool on) {
  for (Cable& c : cables_) c.setSkipping(on);
  history_.add({WorldInput::Kind::WrapSkipping, on});
}

void World::setGravity(const Vec2& g) {
  gravity_ = g;
  b2_->setGravity(g);
  history_.add({WorldInput::Kind::Gravity, 0, 1, {g.x(), g.y()}});
}

std::vector<ContactForce> World::contactForces() const {
  return b2_->contactForces();
}

double World::energy() const {
  double e = 0;
  for (const BodyState& b : bodies_)
    if (b.invMass > 0) e += kineticEnergy(b) + gravityEnergy(b, gravity_);
  for (const Cable& c : cables_)
    e += c.elasticEnergy();  // span by span where friction holds it apart
  return e;
}

void World::checkFinite() const {
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const BodyState& b = bodies_[i];
    if (!isFinite(b.position) || !isFinite(b.velocity) || !std::isfinite(b.angle) ||
        !std::isfinite(b.angularVelocity))
      throw SimulationError("body '" + scene_.bodies[i].name + "' has a non-finite state at t = " +
                            std::to_string(time_) + " s (reduce --dt or raise --substeps)");
  }
  for (const Cable& c : cables_)
    if (!std::isfinite(c.tension()) || !std::isfinite(c.length()))
      throw SimulationError("cable '" + c.name() + "' has a non-finite tension or length at t = " +
                            std::to_string(time_) + " s");
}

// The wrap set at the start of a step is the one of the moment after (kSelectAhead of the
// sub-step later at the current velocities): a point exactly on a segment and moving onto its
// wrap side is in, one leaving is out (docs/cables.md, "Events").
void World::selectWraps(double h) {
  motion_ = bodies_;
  double ahead = kSelectAhead * h;
  if (cutCable_ >= 0) {
    const auto e = cables_[cutCable_].nextEvent(motion_, kCutReach * h);
    if (e && e->pulley == cutEvent_.pulley && e->kind == cutEvent_.kind &&
        e->vertex == cutEvent_.vertex)
      ahead += e->time;
    cutCable_ = -1;
  }
  for (BodyState& b : motion_) {
    b.position += ahead * b.velocity;
    b.angle += ahead * b.angularVelocity;
  }
  for (Cable& c : cables_) c.update(motion_, bodies_, &warnings_);
}

// Every body over the next dt as Box2D will move it with the loads in forces_ (symplectic
// Euler: the end-of-step velocity carries the pose), to locate wrap events on.
void World::predictMotion(double dt) {
  motion_ = bodies_;
  for (size_t b = 0; b < bodies_.size(); ++b) {
    BodyState& m = motion_[b];
    if (m.invMass > 0) m.velocity += dt * (gravity_ + m.invMass * forces_[b].head<2>());
    m.angularVelocity += dt * m.invInertia * forces_[b].z();
  }
}

// The user's loads, the servos, then the cable tensions for a Box2D step of dt (of a sub-step h):
// per cable island the midpoint solve where it applies, the main solve on the rest.
void World::solveForces(double dt, double h) {
  const double share = std::min(1.0, dt / h);
  forces_ = pendingForces_;
  applyServos(dt);
  kicks_.assign(bodies_.size(), Vec3::Zero());
  ends_.clear();
  placements_.assign(bodies_.size(), Placement{});
  excluded_.assign(bodies_.size(), 0);
  for (const auto& [a, b] : jointBodies_)
    for (int body : {a, b})
      if (body >= 0) excluded_[body] = 1;
  touching_.assign(bodies_.size(), 0);
  b2_->markTouching(touching_, true);
  for (size_t b = 0; b < bodies_.size(); ++b) excluded_[b] |= touching_[b];
  midpointCables_.clear();
  midpointUnsettled_ = false;
  mainUnsettled_ = false;
  bool mainLeft = true;
  if (CableIslands::anyFree(bodies_, cables_, excluded_)) {
    islands_->build(bodies_, cables_, !midpointPerIsland_);
    mainLeft = false;
    for (int i = 0; i < islands_->count(); ++i) {
      const std::span<const int> island = islands_->cables(i);
      if (takesMidpointRule(island, dt, h)) {
        const int iterations =
            midpoint_->solve(bodies_, cables_, island, gravity_, dt, share, forces_, kicks_);
        if (iterations >= 0) {
          stats_.solverIterations += iterations;
          ++stats_.midpointSolves;
          midpointCables_.insert(midpointCables_.end(), island.begin(), island.end());
          midpoint_->appendEnds(ends_);
          continue;
        }
        stats_.solverIterations += midpoint_->iterationsRun();
        ++stats_.midpointFallbacks;  // Newton did not settle (nothing changed): the main solve
        stats_.midpointRedundant += midpoint_->redundant();
        stats_.midpointFloorHits += midpoint_->floorHit();
        midpointUnsettled_ |= !midpoint_->redundant() && !midpoint_->floorHit();
      }
      mainLeft = true;
    }
  }
  midpointUsed_ = !midpointCables_.empty();
  if (!mainLeft) {  // every island was the midpoint solve's
    for (const int c : islands_->idle()) cables_[c].setTension(0);
    flyFreeBodies(dt);
    return;
  }
  if (midpointUsed_) {
    midpointCable_.assign(cables_.size(), 0);
    for (const int c : midpointCables_) midpointCable_[c] = 1;
  }
  // applyServos read the joints' frames at this same pose.
  if (!servos_->any()) b2_->jointFrames(scene_.joints, jointBodies_, jointFrames_);
  const int unsettled = stats_.unsettledIslands;
  solver_->solve({dt, share, gravity_, bodies_, jointFrames_, jointNeighbours_,
                  midpointUsed_ ? std::span<const char>(midpointCable_) : std::span<const char>(),
                  touching_, kicks_, placements_, contactExpected_},
                 cables_, forces_, stats_);
  mainUnsettled_ = stats_.unsettledIslands > unsettled;
  flyFreeBodies(dt);
}

// A body that no cable, joint or contact acts on flies under constant forces (gravity, the
// user's), which Box2D's symplectic Euler integrates with a loss of m (a h)^2 / 2 a step: a ball
// bouncing on an elastic trampoline lost all its energy in 20 s of flights between catches. Such
// a body takes the trapezoid rule instead, exact for constant forces: Box2D moves it with
// v0 + h a / 2 and it gets the other half after the step (kicks), as under the midpoint rules.
// Linear damping keeps Box2D's integration.
void World::flyFreeBodies(double dt) {
  onCable_.assign(bodies_.size(), 0);
  for (const Cable& c : cables_)
    for (const WrapPoint& w : c.path())
      if (w.body >= 0) onCable_[w.body] = 1;
  for (size_t b = 0; b < bodies_.size(); ++b) {
    const BodyState& s = bodies_[b];
    if (!(s.invMass > 0) || onCable_[b] || excluded_[b] || scene_.bodies[b].linearDamping != 0)
      continue;
    const Vec2 half = 0.5 * dt * (gravity_ + s.invMass * forces_[b].head<2>());
    forces_[b].head<2>() -= half / (dt * s.invMass);
    kicks_[b].head<2>() += half;
  }
}

// One Box2D step of `left` seconds or less: cut at the first wrap event if `locate`, so the
// change happens where the new point lies on the old path (theorem 1). Returns the time taken.
double World::advance(double left, double h, bool locate) {
  using Clock = std::chrono::steady_clock;
  const auto c0 = Clock::now();
  b2_->readBodies(bodies_);
  // Knocks first: an elastic rope's point off a free polygon (hull_bounce.h), two polygon pulleys
  // with restitution with their taut rigid ropes (pulley_knock.h). Then the step's start is
  // remembered: else a pivoted polygon a knock slowed got back its energy (keepJointEnergy) while
  // the point kept what it took (docs/cables.md, "Points inside a hull").
  b2_->bounceHullPoints(bodies_, cables_, left);
  if (keepsJointEnergy_ && !scene_.joints.empty()) jointEnergy_->remember(bodies_);
  // Ropes over wheels end the step on the trapezoid rule (wheel_rope_energy.h): from this state.
  static thread_local std::vector<BodyState> ropeStart;  // scratch: no allocation a step
  bool wheelRopes = false;
  for (const Cable& c : cables_)
    for (const WrapPoint& w : c.path()) wheelRopes |= w.radius != 0;
  if (wheelRopes) ropeStart = bodies_;
  selectWraps(h);
  solveForces(left, h);
  double dt = left;
  // A midpoint island whose Newton did not settle: halve the step and solve again, down to
  // kMinEventStep of the sub-step (shorter steps are nearer linear: a 0.01 kg puck catching at
  // 50 m/s a cable that a 100 kg ballast holds). Past that the main solve keeps the island.
  while (locate && midpointUnsettled_ && dt > 2 * kMinEventStep * h) {
    dt *= 0.5;
    solveForces(dt, h);
    ++stats_.refinements;
  }
  // The main solve's Newton found no end-of-step lengths it could keep, and the start-of-step
  // linearisation it answered with misses them (cable_solver.cpp, stage 6): the motion is far
  // from linear (a box turning at 10 rad/s as it reached its pulley: its rope 22 cm long). A
  // shorter step is nearer linear: halved up to kMaxUnsettledHalvings times while that holds.
  for (int halving = 0;
       locate && mainUnsettled_ && halving < kMaxUnsettledHalvings && dt > 2 * kMinEventStep * h;
       ++halving) {
    dt *= 0.5;
    solveForces(dt, h);
    ++stats_.refinements;
  }
  // Resolve a fast catch (MidpointSolver::fastCatchStep; docs/swings.md, "The fast catch near a
  // peg").
  if (locate && midpointUsed_) {
    const double resolved =
        std::max(MidpointSolver::fastCatchStep(bodies_, cables_, midpointCables_, dt, kMaxOmegaDt),
                 kMinEventStep * h);
    if (resolved < dt) {
      dt = resolved;
      solveForces(dt, h);
      ++stats_.refinements;
    }
  }
  // Box2D turns a body at most pi / 2 a step and slows it to fit: a midpoint island's body then
  // ends short of the pose its solve assumed, with the end velocities set after the step, and the
  // step no longer keeps the energy (a square whirled at 138 rad/s at 60 Hz on a rope gained 7% of
  // its energy on steps with no wrap change). Shortened until Box2D moves it as solved; and halved
  // as above where the fast catch's shorter step left a midpoint Newton unsettled (the main
  // solve's start-of-step answer took half the energy of a square spun at 5 rad a step).
  for (int again = 0; again < kMaxLimitShortenings && dt > 2 * kMinEventStep * h; ++again) {
    const double share =
        midpointUsed_ ? shareOfBox2DLimits(bodies_, ends_, dt, kBox2DMaxTurn, kBox2DMaxMove) : 0.0;
    if (locate && midpointUnsettled_)
      dt *= 0.5;
    else if (share > 1)
      dt = std::max(dt / share, kMinEventStep * h);
    else
      break;
    solveForces(dt, h);
    ++stats_.refinements;
  }
  if (locate) {
    predictMotion(dt);
    auto [first, cable, event] = firstWrapEvent(cables_, motion_, dt);
    // A body arriving at its pulley (floors.h, floorArrival): no wrap change, cableless cut.
    auto floorArrivals = [&](std::optional<double>& soonest) {
      bool any = false;
      for (const Cable& c : cables_) {
        if (!hasFloors(c) || staysSlack(c, bodies_, dt, gravity_)) continue;
        const auto& path = c.path();
        for (size_t i = 0; i + 1 < path.size(); ++i) {
          if (c.mayEnterHull(i) || slackAtPinnedFloor(c, i, bodies_, dt, gravity_)) continue;
          if (auto t = floorArrival(path[i], path[i + 1], motion_, soonest ? *soonest : dt)) {
            soonest = t;
            any = true;
          }
        }
      }
      return any;
    };
    if (floorArrivals(first)) cable = -1;
    const double whole = dt;  // the step before any cut at a wrap event
    if (first && *first < dt) {
      const double cut = std::max(*first, kMinEventStep * h);
      if (cut < dt) {
        dt = cut;
        solveForces(dt, h);
        ++stats_.events;
        cutCable_ = cable;
        cutEvent_ = event;
      }
    }
    // Where the step's rule or length changes, each taut rigid cable starts on the rate the step
    // ends on (start_rates.h): solved again from there.
    if (matchRates(dt, h)) solveForces(dt, h);
    // The event was located on the motion of the whole step, but the cut's own solve moves the
    // bodies differently (a rope taut over the step is slack over the cut: a spool turned at
    // 8.8 rad/s where 6.4 were predicted, its corner straightened early and left late, moving the
    // length 1.5 mm). Located again on the cut's motion, and cut there if sooner
    // (kEventRelocations).
    for (int again = 0; again < kEventRelocations && cable >= 0 && cutCable_ >= 0; ++again) {
      predictMotion(dt);
      const FirstWrapEvent sooner = firstWrapEvent(cables_, motion_, dt);
      if (!sooner.time) break;
      // Found again within the time it was located to: the same instant, nothing to do.
      const double cut = std::max(*sooner.time, kMinEventStep * h);
      if (!(cut < dt - crossingTolerance(h))) break;
      dt = cut;
      solveForces(dt, h);
      cutCable_ = sooner.cable;
      cutEvent_ = sooner.event;
    }
    // Nor may it reach it yet: an elastic cable's cut then ends where it does, once (taken ahead,
    // corners joined off the old path: docs/cables.md, "Events"; a rigid rope stores no energy).
    if (cable >= 0 && cutCable_ >= 0 && cables_[cutCable_].elastic()) {
      predictMotion(dt);
      const FirstWrapEvent later =
          firstWrapEvent(cables_, motion_, std::min(whole, dt + kCutReach * h));
      if (later.time && *later.time > dt + crossingTolerance(h) && later.cable == cutCable_ &&
          later.event.pulley == cutEvent_.pulley && later.event.kind == cutEvent_.kind &&
          later.event.vertex == cutEvent_.vertex) {
        dt = *later.time;
        solveForces(dt, h);
      }
    }
    // The arrival was located at the velocities of the whole step, but Box2D moves the bodies
    // over the cut one at v0 + dt a: a weight swung at a winch drum at 15 m/s^2 landed 0.65 mm
    // further in than located, past its floor, which lies 0.1 mm outside the rim. Located again
    // with the cut's own motion (and cut there if sooner), it lands at the floor.
    for (int again = 0; again < kFloorRelocations && cable < 0 && first; ++again) {
      predictMotion(dt);
      std::optional<double> sooner;
      if (!floorArrivals(sooner)) break;
      const double cut = std::max(*sooner, kMinEventStep * h);
      if (!(cut < dt)) break;
      dt = cut;
      solveForces(dt, h);
    }
    rulesKept_ = false;
  }
  // What the wrap events were located on, to tell a knock inside Box2D's step (knock_motion.h).
  static thread_local std::vector<BodyState> start, predicted;  // scratch: no allocation a step
  if (locate) {
    predictMotion(dt);
    start = bodies_;
    predicted = motion_;
  }
  stats_.cableMicros += std::chrono::duration<double, std::micro>(Clock::now() - c0).count();
  // Box2D: integrates with those forces, then contacts, friction and joints; then the second
  // half of a midpoint step's velocity change (midpoint_solver.h).
  b2_->applyLoads(forces_);
  b2_->step(dt, h);
  b2_->addVelocities(kicks_);
  setEndStates(*b2_, {bodies_, scene_.bodies, excluded_, dragBody_, ends_, forces_, kicks_},
               gravity_, dt);
  for (size_t b = 0; b < placements_.size(); ++b)
    if (placements_[b].place)
      b2_->placeBody(static_cast<int>(b), placements_[b].position, placements_[b].angle);
  b2_->readBodies(bodies_);
  catchContactStretch(*b2_, cables_, bodies_, jointBodies_, touching_);
  keepJointEnergy(dt);
  // A knock inside Box2D's step (its time-of-impact solve, a contact's push, the catch above) took
  // the bodies off the motion the wrap events were located on: a wrap change on the actual motion
  // was never located, and taken at the next selection it moved the length (1.2 to 7 mm for
  // polygons knocking in rope loops). Bodies on joints are left out (knock_motion.h). The actual
  // motion is taken as the predicted one up to the knock (which had no event) and a straight one
  // from there to the end; where a wrap event falls after the knock, the bodies go back along it to
  // the event, so that the change happens on the old path, and the rest of the sub-step is
  // stepped again (knock_motion.h).
  double taken = dt;
  static thread_local std::vector<char> jointed;
  jointed.assign(bodies_.size(), 0);
  for (const auto& [a, b] : jointBodies_)
    for (const int body : {a, b})
      if (body >= 0) jointed[body] = 1;
  if (locate && deviationFromPrediction(start, predicted, bodies_, jointed, dt) > kKnockDeviation) {
    const double knock = knockTime(start, predicted, bodies_, dt);
    motionAfterKnock(start, predicted, bodies_, dt, knock, motion_);
    const FirstWrapEvent after = firstWrapEvent(cables_, motion_, dt - knock);
    const double at = after.time ? std::max(knock + *after.time, kMinEventStep * h) : dt;
    if (at < dt - kKnockReach * h) {
      taken = at;
      backAfterKnock(motion_, bodies_, forces_, gravity_, jointed, dt - at, at - knock);
      for (size_t b = 0; b < bodies_.size(); ++b) {
        if (!moves(bodies_[b]) && !driven(bodies_[b])) continue;
        b2_->placeBody(static_cast<int>(b), bodies_[b].position, bodies_[b].angle);
        b2_->setVelocity(static_cast<int>(b), bodies_[b].velocity, bodies_[b].angularVelocity);
      }
      b2_->readBodies(bodies_);
      cutCable_ = after.cable;
      cutEvent_ = after.event;
      ++stats_.events;
    }
  }
  // Ropes over wheels: the step's bodies end on the trapezoid rule (wheel_rope_energy.h), unless
  // a knock took part of the step back.
  if (wheelRopes && taken == dt) {
    static thread_local std::vector<char> worked;
    static thread_local std::vector<int> changed;
    worked.assign(bodies_.size(), 0);
    b2_->markTouching(worked);
    for (size_t b = 0; b < bodies_.size(); ++b)
      worked[b] |= touching_[b] || !pendingForces_[b].isZero() || static_cast<int>(b) == dragBody_;
    changed.clear();
    keepWheelRopeEnergy({ropeStart, cables_, &scene_, jointBodies_, worked, gravity_, dt}, bodies_,
                        changed);
    for (int b : changed) b2_->placeBody(b, bodies_[b].position, bodies_[b].angle);
    if (!changed.empty()) b2_->readBodies(bodies_);  // the pose Box2D holds (floats)
  }
  recordRates(dt, taken == dt);
  if (left - taken <= kSubstepRest * h) expectContacts(b2_->contactSumTime());  // sub-step's end
  time_ += taken;
  servoTargets_.moveOn(taken);  // a servo with a speed drives its joint at that rate
  for (size_t j = 0; j < scene_.joints.size(); ++j) servoImpulses_[j] += servos_->forces()[j] * dt;
  return taken;
}

// Box2D's contacts act after the cable solve, which predicts each body's motion without them: a
// block pulled across a table by a hanging weight slid slower than the solve predicted, and the
// rope stretched 4 mm (7 mm where static friction held the block). The solve takes the contact
// force of the steps before as a load it expects (not one applied: Box2D applies its own), the
// lesser of the last two sub-steps' in each component and 0 where they disagree in sign, so that
// persistent contacts (resting, sliding, held by friction) count and a one-step impact does not.
// A sub-step's force is its pieces' impulses over the time they cover (`dt`): a knock read over
// its own 1 ms piece (wrap events cut the sub-step) was 120 N on a 0.2 kg pentagon, the next
// rope pulled 90 N against it, Box2D gave 47 N, and the pentagon gained 17 J (docs/cables.md,
// "Contacts and the rope").
void World::expectContacts(double dt) {
  const std::span<const Vec3> impulses = b2_->contactImpulseSum();
  contactLast_.resize(impulses.size(), Vec3::Zero());
  contactExpected_.resize(impulses.size(), Vec3::Zero());
  for (size_t b = 0; b < impulses.size(); ++b) {
    const Vec3 now = impulses[b] / dt;
    for (int c = 0; c < 3; ++c) {
      const double a = contactLast_[b][c], n = now[c];
      contactExpected_[b][c] = a * n > 0 ? (std::abs(a) < std::abs(n) ? a : n) : 0.0;
    }
    contactLast_[b] = now;
  }
  b2_->restartContactSum();
}

// A sub-step cut at wrap events: each cable's tension over it is its impulses over its length. The
// last piece's own (impulse over a piece that may last 1e-6 s) is mostly what took out the rest
// of the cable's length rate at the event (1951 N with ten ropes round a pivoted hexagon,
// which pull 15 N).
void World::addImpulses(double dt, bool first) {
  if (first) impulses_.resize(cables_.size());
  for (size_t c = 0; c < cables_.size(); ++c) {
    std::vector<double>& sum = impulses_[c];
    const int spans = cables_[c].spanCount();
    if (first) sum.assign(spans, 0.0);
    if (static_cast<int>(sum.size()) != spans) {
      sum.clear();  // a wheel split or joined the cable: its last tensions stand
      continue;
    }
    for (int k = 0; k < spans; ++k) sum[k] += cables_[c].spanTension(k) * dt;
  }
}

void World::averageTensions(double h) {
  for (size_t c = 0; c < cables_.size(); ++c)
    for (size_t k = 0; k < impulses_[c].size(); ++k)
      cables_[c].setSpanTension(static_cast<int>(k), impulses_[c][k] / h);
}

// The tensions a step reports are its impulses over its length (N), each span's (over the part
// since a wheel last split or joined its spans): what acted
// over the step, not the last sub-step's solve, which with sub-steps may be a quarter of it and
// off by a tenth. The solves read back what they set (their warm start and geometric stiffness),
// so the last sub-step's tensions are kept and given back at the next step (end false).
void World::reportStepTensions(bool end) {
  if (!end) {
    for (size_t c = 0; c < solved_.size() && c < cables_.size(); ++c)
      if (static_cast<int>(solved_[c].size()) == cables_[c].spanCount())
        for (size_t k = 0; k < solved_[c].size(); ++k)
          cables_[c].setSpanTension(static_cast<int>(k), solved_[c][k]);
    stepImpulses_.assign(cables_.size(), {});
    stepTimes_.assign(cables_.size(), 0.0);
    return;
  }
  solved_.resize(cables_.size());
  for (size_t c = 0; c < cables_.size(); ++c) {
    const int spans = cables_[c].spanCount();
    solved_[c].resize(spans);
    for (int k = 0; k < spans; ++k) solved_[c][k] = cables_[c].spanTension(k);
    for (int k = 0; k < spans; ++k)
      cables_[c].setSpanTension(k, stepImpulses_[c][k] / stepTimes_[c]);
  }
}

void World::step(double dt, int substeps) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  stats_ = {};
  history_.add({WorldInput::Kind::Step, substeps, 1, {dt}});
  for (const Cable& c : cables_) {
    stats_.selectionSkips -= static_cast<int>(c.skippedSelections());
    stats_.searchSkips -= static_cast<int>(c.skippedSearches());
  }
  const double h = dt / std::max(1, substeps);
  if (pendingForces_.size() != bodies_.size()) pendingForces_.assign(bodies_.size(), Vec3::Zero());
  std::fill(servoImpulses_.begin(), servoImpulses_.end(), 0.0);
  reportStepTensions(false);
  for (int s = 0; s < std::max(1, substeps); ++s) {
    servoTargets_.beginSubstep(s, std::max(1, substeps));  // a target set is reached at the end
    // Wrap events cut the sub-step; a bounded number per sub-step bounds the cost.
    double left = h, first = 0;
    int steps = 0;
    for (; left > kSubstepRest * h; ++steps) {
      if (steps == 1) addImpulses(first, true);  // a cut: the first piece's, before they change
      const double taken = advance(left, h, steps < kMaxEventsPerSubstep);
      left -= taken;
      if (steps == 0)
        first = taken;
      else
        addImpulses(taken, false);
    }
    if (steps > 1) averageTensions(h);
    for (size_t c = 0; substeps > 1 && c < cables_.size(); ++c) {
      std::vector<double>& sum = stepImpulses_[c];
      const int spans = cables_[c].spanCount();
      if (s == 0 || static_cast<int>(sum.size()) != spans) {  // from here: spans split or joined
        sum.assign(spans, 0.0);
        stepTimes_[c] = 0;
      }
      for (int k = 0; k < spans; ++k) sum[k] += cables_[c].spanTension(k) * h;
      stepTimes_[c] += h;
    }
  }
  if (substeps > 1)
    reportStepTensions(true);
  else
    solved_.clear();  // one sub-step: its solve's tensions are the step's
  pendingForces_.assign(bodies_.size(), Vec3::Zero());
  // Lengths reported (and energy) belong to the end-of-step state; the wrap points are
  // re-selected at the start of the next step.
  for (Cable& c : cables_) c.refresh(bodies_);
  ++steps_;
  servoTargets_.endStep();
  for (const Cable& c : cables_) {
    stats_.wrapPoints += c.wraps();
    stats_.selectionSkips += static_cast<int>(c.skippedSelections());
    stats_.searchSkips += static_cast<int>(c.skippedSearches());
  }
  for (size_t j = 0; j < jointForces_.size(); ++j) jointForces_[j] = servoImpulses_[j] / dt;
  payOutUnheld();
  reportPayOuts();
  reportDrumArrivals();
  reportStalls(dt);
  reportOverstretch();
  stats_.stepMicros = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  checkFinite();
}

// A rigid cable on no body the solve moves, hauled by a kinematic one (a hook pulling a rope tied
// to the world), has no row in the solve: nothing can hold it, and it pays out what it is too
// long, as stage 6d of the solve lets a hauled cable do (cable_solver.cpp).
void World::payOutUnheld() {
  for (Cable& c : cables_) {
    if (c.elastic()) continue;
    bool held = false, hauled = false;
    for (const auto& e : c.kinematics().jacobian) {
      const BodyState& b = bodies_[e.body];
      held |= moves(b);
      hauled |= driven(b);
    }
    if (held || !hauled) continue;
    for (int k = 0; k < c.spanCount(); ++k)
      if (c.spanStretch(k) > kLengthSlop) c.payOut(k, c.spanStretch(k));
  }
}

}  // namespace cablelab

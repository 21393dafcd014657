// The Box2D bridge: the one place Box2D's bodies and joints are made, read and stepped.
//
// Box2D is float; everything cablelab computes is double, converted here. The header shows no
// Box2D type, so the World and the cable solver read like the rest of the engine. Private to
// engine/dynamics.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/contact_force.h"
#include "engine/model/scene.h"

class b2Contact;  // Box2D's, only named here

namespace cablelab {

/// A joint's coordinate (angle in rad or translation in m) and its rate; 0 for welds.
struct JointCoordinate {
  double value = 0, speed = 0;
};

/// A Box2D joint as the cable solver sees it this sub-step.
struct JointFrame {
  JointDef::Kind kind = JointDef::Kind::Revolute;
  int bodyA = -1, bodyB = -1;   ///< indices into the scene's bodies, -1: the world
  Vec2 anchor = Vec2::Zero();   ///< Box2D's anchor on body B, world (m)
  Vec2 anchorA = Vec2::Zero();  ///< ... and on body A (the same point while the joint holds)
  Vec2 axis = Vec2(1, 0);       ///< prismatic: sliding axis, world, unit (turns with body A)
  bool limited = false;         ///< its coordinate has limits (Box2D's joint correction holds them)
  double value = 0;             ///< limited joints: the coordinate now (rad or m)
  double lower = 0, upper = 0;  ///< ... and its limits
};

class Box2DBridge {
 public:
  /// Creates the bodies and joints of a validated scene (mass and inertia as World documents).
  explicit Box2DBridge(const SceneDef& scene);
  ~Box2DBridge();
  Box2DBridge(const Box2DBridge&) = delete;
  Box2DBridge& operator=(const Box2DBridge&) = delete;

  /// Pose, velocity and inverse mass of every body, in double precision.
  void readBodies(std::vector<BodyState>& bodies) const;
  void setTransform(int body, const Vec2& position, double angle);
  /// Moves a body to a pose within a run (setTransform restarts its turn count). With
  /// `keepDropped`, the part of the pose Box2D's float drops is kept and read back (readBodies)
  /// until Box2D next steps: a body creeping by less than a float's spacing a step still moves.
  void placeBody(int body, const Vec2& position, double angle, bool keepDropped = false);
  void setVelocity(int body, const Vec2& velocity, double angularVelocity);
  void setGravity(const Vec2& g);

  /// Applies (fx, fy, torque) per body at its origin for the next step(); zero loads are skipped.
  void applyLoads(std::span<const Vec3> loads);
  /// One Box2D step of h seconds (fixed velocity and position iterations), a piece of a
  /// sub-step of `substep` seconds: after a piece under a tenth of its sub-step, no contact is
  /// warm-started with more than the impulse it took over it (docs/knocks.md, "Warm-started
  /// from a short piece").
  void step(double h, double substep);
  /// Reverses the approach of an elastic rope's point towards a polygon pulley on another body
  /// that would reach Box2D's contact with it within `horizon` s (hull_bounce.h), and knocks two
  /// polygon pulleys that would, together with the taut rigid ropes of `cables` on them
  /// (pulley_knock.h): in `bodies` and in Box2D.
  void bounceHullPoints(std::vector<BodyState>& bodies, std::span<const Cable> cables,
                        double horizon);
  /// Adds (dvx, dvy, domega) per body to the velocities Box2D holds; zeros are skipped.
  void addVelocities(std::span<const Vec3> dv);
  /// Per body, the impulse (px, py, angular about its origin) Box2D's contacts gave it over the
  /// last step().
  std::span<const Vec3> contactImpulses() const;
  /// Per body, those impulses summed over every step() since restartContactSum(), and the time
  /// those steps covered (s).
  std::span<const Vec3> contactImpulseSum() const;
  double contactSumTime() const;
  void restartContactSum();
  /// Per pair of bodies in touch, the force of their contact points over the last step().
  std::vector<ContactForce> contactForces() const;
  /// Sets touching[b] = 1 for every body in a touching, non-sensor contact. With
  /// `leaveSeparatingKnocks`, two polygon pulleys that pulley_knock.h knocks and that are moving
  /// apart are not in touch: their contact will not act unless the step brings them back.
  void markTouching(std::vector<char>& touching, bool leaveSeparatingKnocks = false) const;
  /// Whether any two bodies (or a body and the ground) are in a touching, non-sensor contact.
  bool anyTouching() const;

  JointCoordinate jointCoordinate(int joint) const;
  Vec2 anchorA(int joint) const;
  Vec2 anchorB(int joint) const;
  /// Prismatic joints: the sliding axis in the world, turning with body A.
  Vec2 prismaticAxis(int joint) const;
  /// Every joint's frame (bodies as given, anchors and axes from Box2D now).
  void jointFrames(std::span<const JointDef> defs, std::span<const std::array<int, 2>> bodies,
                   std::vector<JointFrame>& frames) const;

  /// Mouse drag (Box2D's mouse joint): false, and nothing made, if the body is not dynamic.
  bool beginDrag(int body, const Vec2& worldPoint, double stiffnessHz, double gravity);
  void dragTo(const Vec2& target);
  void endDrag();

 private:
  struct Impl;
  /// Whether contact `c` is of two polygon pulleys that pulley_knock.h knocks, moving apart at
  /// every point.
  bool separatingKnock(b2Contact* c) const;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cablelab

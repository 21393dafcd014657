// Elastic knocks between a polygon pulley and a point of an elastic rope on another moving body or
// fixed in the world (docs/cables.md, "Points inside a hull"). The rope keeps its energy, so the
// knock must too: Box2D's contact is inelastic (it takes the whole approach), and with restitution
// it reverses the velocity after the step's loads are integrated and corrects positions, so neither
// keeps it. Before each piece of a sub-step, a point that would reach the pair's contact skin
// within it has its approach speed along the hull's normal reversed by one impulse at the bodies'
// present pose: the relative normal speed leaves as fast as it came and no faster, the poses do not
// move, and the kinetic energy is exactly what it was. Box2D's contact (hull_contacts.h) stays
// as the backstop for a point that creeps in slowly (pressed on by the rope).
#pragma once

#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/hull_contacts.h"
#include "engine/model/scene.h"

namespace cablelab {

class HullBounce {
 public:
  /// The pairs of `contacts` that bounce (HullContact::bounces) whose bodies move freely or on
  /// one unlimited revolute joint to the world (a pivot): their response to an impulse is known
  /// in closed form. Pairs with other jointed bodies keep Box2D's contact alone.
  HullBounce(const SceneDef& scene, const std::vector<HullContact>& contacts);

  /// Reverses the approach of every armed pair whose point, outside the polygon, would come
  /// within `skin` (m) of its hull within `horizon` (s) at its present speed. A pair is armed
  /// once its point lies further than `skin` from the hull (pairs placed touching wait until
  /// apart). Returns the bodies whose velocities changed (in `bodies`).
  std::vector<int> bounce(std::vector<BodyState>& bodies, double horizon, double skin);

  /// How many pairs bounce (for tests).
  int pairCount() const { return static_cast<int>(pairs_.size()); }

 private:
  struct Pair {
    int polygonBody = -1, pointBody = -1;  ///< pointBody -1: a point fixed in the world
    std::vector<Vec2> polygon;             ///< polygonBody's frame, counter-clockwise
    Vec2 point = Vec2::Zero();             ///< pointBody's frame (the world's)
    bool armed = false;
  };
  std::vector<KnockResponse> responses_;  ///< per body
  std::vector<Pair> pairs_;
  std::vector<Vec2> hull_;  ///< scratch: the polygon of the pair in hand, in the world frame

  /// The inverse effective mass of `body` for an impulse along `normal` at world point `at`, and
  /// the velocity of that point.
  double inverseMass(const BodyState& b, int body, const Vec2& at, const Vec2& normal) const;
  /// A pivoted body's pivot in the world, and its inverse moment about it.
  static Vec2 pivotOf(const BodyState& b, const KnockResponse& r);
  static double inversePivotInertia(const BodyState& b, const KnockResponse& r);
  void applyImpulse(BodyState& b, int body, const Vec2& at, const Vec2& impulse) const;
};

}  // namespace cablelab

// Knocks between two polygon pulleys of one rope (docs/knocks.md, "Two pulleys in one loop"). Box2D
// knocks the pair (hull_contacts.h) knowing nothing of the rope that holds them: with restitution 1
// it sent the bodies off along a taut rigid rope, which the contact catch then stopped (an
// inelastic catch, contact_catch.h), and two sensor triangles let go in one loop lost 40% of their
// energy in 6 s whatever their restitution. Before each piece of a sub-step, a pair whose hulls
// would come within Box2D's contact skin within it is knocked here instead, by one impulse at the
// bodies' present pose solved together with the taut rigid ropes on them: the hulls' approach
// leaves at the shapes' restitution, each rope's rate along it is reversed (about zero), and a rope
// that would have to push goes slack. Every row's rate is reversed or the knock's restitution
// applied, so the impulse's work is (1 - e) of the plastic loss and no more. Pairs of restitution 0
// keep Box2D's knock.
#pragma once

#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/hull_contacts.h"
#include "engine/model/scene.h"

namespace cablelab {

class PulleyKnock {
 public:
  /// The pairs of `contacts` that are two polygons on dynamic bodies with a restitution above 0
  /// (the larger of the two bodies' largestRestitution, as Box2D mixes it).
  PulleyKnock(const SceneDef& scene, const std::vector<HullContact>& contacts);

  /// Knocks every armed pair whose hulls, apart, would come within `skin` (m) of each other within
  /// `horizon` (s) at their present speeds, with the taut rigid ropes of `cables` on its bodies.
  /// A pair is armed once its hulls lie further apart than `skin` (pairs placed touching wait).
  /// Pairs with a body, theirs or a rope's, that is neither free nor on one unlimited pivot to the
  /// world keep Box2D's knock. Returns the bodies whose velocities changed (in `bodies`).
  std::vector<int> knock(std::vector<BodyState>& bodies, std::span<const Cable> cables,
                         double horizon, double skin);

  int pairCount() const { return static_cast<int>(pairs_.size()); }
  /// Whether the pulleys of bodies `a` and `b` (either way round) are knocked here.
  bool knocks(int a, int b) const;

 private:
  struct Pair {
    int bodyA = -1, bodyB = -1;
    std::vector<Vec2> polygonA, polygonB;  ///< each in its body's frame, counter-clockwise
    double restitution = 0;
    bool armed = false;
  };
  /// One row of the knock: a rate (m/s) per body as a wrench direction (x, y, turn).
  struct Row {
    std::vector<std::pair<int, Vec3>> entries;
    double rate = 0;    ///< before the knock
    double target = 0;  ///< after it
  };
  std::vector<KnockResponse> responses_;  ///< per body
  std::vector<Pair> pairs_;

  /// The velocity change (x, y, turn) of body `body` for the wrench `w` at its origin.
  Vec3 response(const BodyState& b, int body, const Vec3& w) const;
  /// Solves the rows' impulses (ropes that would push dropped) and applies them; false if the
  /// contact row takes no impulse.
  bool solveAndApply(std::vector<Row>& rows, std::vector<BodyState>& bodies,
                     std::vector<int>& changed) const;
};

}  // namespace cablelab

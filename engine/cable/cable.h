// Cable: a chain anchor -> pulleys -> anchor, its wrap points, length, Jacobian and J-dot-v.
//
// Where to find things:
//   wrap-point selection and the guards ......... Cable::updatePath()   (cable.cpp)
//   length, J = d length / dq, J-dot-v ........... cableKinematics()    (cable_kinematics.cpp)
//   skipping while the wrap set cannot change .... keepWrapSet()        (wrap_skip.cpp)
//
// Generalized coordinates are every body's (x, y, theta) in the world frame (docs/model.md); the
// world itself is body -1 and never moves. A wrap point is a point fixed on a body; its world
// position is x_b + R(theta_b) r.
//
// Guard rules for pulleys that are not Threaded (the thesis leaves these undefined):
//  * A disengaged pulley JOINS the path when the segment it would sit on (between its engaged
//    neighbours) cuts it, and at the previous update it lay entirely on the non-wrap side of that
//    segment's line: it must cross the segment from outside. A pulley coming from the wrap side,
//    or sitting on the wrap side beyond the segment's ends, is left out (the cable passes it).
//    A free polygon (one-sided, on a moving body, not gripping, not tied) joins any other
//    segment it crosses so too, and takes its place there in the path's order of pulleys: flung
//    past its neighbour, it lands on the rope there (pulley_order.cpp, docs/knocks.md). It
//    crosses a segment from either side and wraps on the side it came from, as an auto pulley.
//  * An "auto" pulley (a polygon or a circle) JOINS from either side: when the segment cuts it
//    (a circle: comes within its radius) or its centre crossed the segment between its ends, and
//    it wraps on the side it came from.
//  * An engaged pulley LEAVES when the path no longer bends around it: a point pulley or a
//    polygon when the angle the path turns round it goes below zero (a straight turn keeps it:
//    it changes neither length nor J); a circle when its arc goes below zero. That angle is kept
//    continuous over time, like a circle's arc: a pulley swung round past an end anchor, which
//    the cable bends round by more than half a turn or winds round for whole turns, STAYS, and a
//    polygon's chain grows and shrinks one vertex at a time (wrapChainTurning, wrap.h).
//  * A cable end fixed on a polygon pulley's own body, on or inside its hull, next to it in the
//    path, ties the cable to that polygon (a spool, tied_end.h): it is engaged from the start,
//    never leaves, and winds whole turns. The rules below do not apply to that end.
//  * Neighbouring polygons meet on their common tangent (commonTangent, wrap_hold.h). A point fixed
//    in the world or a neighbouring polygon's corner pressed into an engaged polygon's hull (no
//    taut path exists) HOLDS the chain end it was on, which then moves one vertex at a time as a
//    wrap point does, so the length stays continuous (wrapChainHeld, wrap_hold.h).
//  * Any other terminal inside a polygon pulley's hull (a point on a body that the polygon passes
//    through, as the hand's box through a finger) has no taut path:
//    the polygon is DROPPED (it leaves the path) and a warning says so. A dropped polygon that
//    still cuts its segment REJOINS as soon as a taut path round it exists again and that path is
//    no longer than the straight segment by more than the drop took out (+ kLengthJump), with a
//    warning: drop and rejoin together add no length. One that moved through the cable while
//    dropped (its taut path would go round its far side, much longer) stays out; one that clears
//    the segment is an ordinary disengaged pulley again.
//  * Consecutive coincident wrap points (a zero-length segment, < 1e-12 m) are merged: the
//    segment is left out of J and J-dot-v, never divided by, and a warning says so. A point
//    inside a circle pulley's disc (no tangent exists) makes such a segment too.
//  * Any wrap change that moves the length by more than kLengthJump (1 mm) names the jump in a
//    warning: it did not happen on the old path (a guard acted, or a crossing was found late).
//    A polygon whose chain empties with such a jump is RELEASED, and the warning says so: it
//    moved off the cable within one update further than the turn kept over time can follow
//    (moved by hand, a crossing missed by the events), so its wrap is lost.
//  At creation every pulley that the straight segment cuts joins (as if it had just crossed).
//  The World locates every join and leave inside the step (nextEvent(), docs/cables.md) and
//  selects the wrap set a moment after it, so the new point lies on the old path and length and
//  J stay continuous (theorem 1); these rules then only decide what that moment's set is.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "engine/cable/wrap_hold.h"
#include "engine/model/scene.h"

namespace cablelab {

/// World-frame state of a rigid body. The world is not a BodyState (index -1).
struct BodyState {
  Vec2 position = Vec2::Zero();  ///< m
  double angle = 0;              ///< rad
  Vec2 velocity = Vec2::Zero();  ///< m/s
  double angularVelocity = 0;    ///< rad/s
  double invMass = 0;            ///< 1/kg, 0 for static and kinematic bodies
  double invInertia = 0;         ///< 1/(kg m^2) about the body origin... see World
};

/// Whether a solve can move the body (static and kinematic bodies have no inverse mass).
inline bool moves(const BodyState& b) {
  return b.invMass > 0 || b.invInertia > 0;
}

/// Whether a body the solve cannot move moves anyway: a kinematic body with a velocity.
inline bool driven(const BodyState& b) {
  return !moves(b) && (b.velocity.squaredNorm() > 0 || b.angularVelocity != 0);
}

/// Kinetic energy of the body's motion (J); a body the solve cannot move carries none.
inline double kineticEnergy(const BodyState& b) {
  return 0.5 * ((b.invMass > 0 ? b.velocity.squaredNorm() / b.invMass : 0.0) +
                (b.invInertia > 0 ? b.angularVelocity * b.angularVelocity / b.invInertia : 0.0));
}

/// Gravity's energy of the body (J) in field `gravity` (m/s^2), zero at the origin.
inline double gravityEnergy(const BodyState& b, const Vec2& gravity) {
  return b.invMass > 0 ? -gravity.dot(b.position) / b.invMass : 0.0;
}

/// Velocity of the body's material point now at `at` (world frame).
inline Vec2 pointVelocity(const BodyState& b, const Vec2& at) {
  return b.velocity + b.angularVelocity * perp(Vec2(at - b.position));
}

/// One point of a cable's current path.
struct WrapPoint {
  enum class Kind { Anchor, Point, Vertex, Circle };
  Kind kind = Kind::Anchor;
  int body = -1;              ///< -1: world
  Vec2 local = Vec2::Zero();  ///< body frame (world frame for the world)
  Vec2 world = Vec2::Zero();  ///< current world position
  int pulley = -1;            ///< index into CableDef::pulleys, -1 for anchors
  int vertex = -1;            ///< polygon vertex index, -1 otherwise
  /// Circle: signed radius (m), + when the cable passes on the circle's left (it turns clockwise
  /// round it), - on its right; 0 for every other kind. `local` and `world` are the centre.
  double radius = 0;
  /// Circle: the angle the cable turns on it (rad, >= 0 while wrapped, continuous over turns).
  /// At a path's end (a drum, a wheel the cable does not slip on): the angle between the
  /// tangent point and the mark, in the winding sense.
  double arc = 0;
  double mark = 0;  ///< Circle at a path's end: body-frame angle of the cable's fixed point (rad)
  Vec2 tangentIn = Vec2::Zero();   ///< Circle: where the cable arrives (world), set by kinematics
  Vec2 tangentOut = Vec2::Zero();  ///< Circle: where it leaves (world)

  /// Where the cable leaves this point for the next one: a circle's tangent point, else the point.
  Vec2 leaving() const { return radius == 0 ? world : tangentOut; }
  /// Where the cable reaches this point from the one before.
  Vec2 arriving() const { return radius == 0 ? world : tangentIn; }
};

/// d(length)/d(x, y, theta) of one body.
struct BodyJacobian {
  int body;
  Vec3 d;
};

/// length, J and J-dot-v of a path (pure functions of the path and the bodies' state).
struct CableKinematics {
  double length = 0;                   ///< m
  double lengthRate = 0;               ///< J v (m/s)
  double jdotV = 0;                    ///< J-dot v (m/s^2)
  std::vector<BodyJacobian> jacobian;  ///< one entry per moving body touched, sorted by body
  int zeroLengthSegments = 0;          ///< segments left out of J (coincident points)
  std::vector<Vec2> directions;        ///< unit direction of each segment (path size - 1)
};

/// One 2x2 block of d^2 length / (d x_a d x_b), x = a body's translation.
struct StiffnessBlock {
  int a, b;
  Eigen::Matrix2d k;
};

/// The translational Hessian of the length of a path (world points already set), appended to
/// `blocks` (no allocation once it has the capacity): tension times this is the cable's
/// geometric stiffness, which a stiff membrane on a light body needs implicitly. Rotations are
/// left out. Blocks of world-fixed points are skipped. Circles: between the tangent points.
void appendLengthHessianTranslation(std::span<const WrapPoint> path,
                                    std::vector<StiffnessBlock>& blocks);

/// World position of a point fixed on a body.
Vec2 worldPoint(std::span<const BodyState> bodies, int body, const Vec2& local);

/// Fills p.world for every point, then length, J, J-dot-v (docs/model.md#cable-geometry).
CableKinematics cableKinematics(std::span<WrapPoint> path, std::span<const BodyState> bodies);
/// The same into `k`, reusing its Jacobian's storage.
void cableKinematics(std::span<WrapPoint> path, std::span<const BodyState> bodies,
                     CableKinematics& k);
/// Length and J only, without the velocity terms (k.lengthRate and k.jdotV mean nothing): what a
/// Newton step of the solver needs at each predicted pose.
void cableLengthJacobian(std::span<WrapPoint> path, std::span<const BodyState> bodies,
                         CableKinematics& k);

/// A bound on |length(q1) - length(q0) - J(q0) (q1 - q0)| for a path of points fixed on bodies
/// (no circles; world points set at q0 = `bodies`), the bodies moved to `moved`: how far the
/// start-of-step linearisation can be off. Infinite when an end could move half its segment.
double lengthRemainderBound(std::span<const WrapPoint> path, std::span<const BodyState> bodies,
                            std::span<const BodyState> moved);

/// The discrete gradient of a path's length between two states (docs/cables.md, "Energy"):
/// a row G with G (q1 - q0) = length(q1) - length(q0) exactly, which tends to J as q1 -> q0.
/// Each segment contributes along (d0 + d1) / (|d0| + |d1|); a turn dtheta of a body moves its
/// point by sinc(dtheta / 2) dtheta perp(r_mid). A path with circles (arcs) takes the
/// gradient at the midpoint pose plus Gonzalez's correction along (q1 - q0). `path`'s world
/// points are left at q1. Returns length(q1) (m).
double lengthDiscreteGradient(std::span<WrapPoint> path, std::span<const BodyState> q0,
                              std::span<const BodyState> q1, std::vector<BodyJacobian>& gradient);

/// A wrap change inside a sub-step (docs/cables.md, "Events"); Hull: a point fixed in the world
/// at an end of a segment goes into or out of a polygon's hull across edge `vertex`.
struct WrapEvent {
  enum class Kind { Join, Leave, Vertex, Hull };
  double time = 0;  ///< s into the sub-step
  int pulley = -1;  ///< index into CableDef::pulleys
  Kind kind = Kind::Join;
  int vertex = -1;  ///< the polygon vertex that crosses or straightens (Hull: the edge from it)
};

/// A cable's parameters as they are now: the scene's values until World::setCableParameters
/// edits them (the scene itself is never edited).
struct CableParameters {
  double restLength = -1.0;  ///< m; < 0 until the first update measures the initial length
  double stiffness = 0.0;    ///< N/m; 0 = rigid
  double preload = 0.0;      ///< m
  double damping = 0.0;      ///< N s/m
};

/// A wheel that grips the cable (no slip or capstan friction), or a polygon with friction,
/// between span k and span k + 1.
struct SpanLink {
  int pulley = -1;           ///< index into CableDef::pulleys
  Grip grip = Grip::NoSlip;  ///< NoSlip or Capstan
  double mu = 0;             ///< capstan friction coefficient
  double wrapAngle = 0;      ///< rad, the angle the cable turns on the wheel (both spans' arcs);
                             ///< a polygon: at all its engaged corners together
  bool slipped = false;      ///< the last solve let the cable slide (tension ratio e^(mu theta))
};

/// One engaged corner of a polygon with friction (docs/polygon_friction.md).
struct CornerTension {
  int vertex = -1;        ///< polygon vertex index
  double turn = 0;        ///< rad, the angle the cable turns at the corner (>= 0)
  double tensionIn = 0;   ///< N, on the segment that arrives at the corner
  double tensionOut = 0;  ///< N, on the segment that leaves it
};

class Cable {
 public:
  /// `scene` resolves body names and polygon shapes; throws InputError on bad references.
  /// The cable refers to scene.cables[index], which must outlive it (the World owns both).
  Cable(const SceneDef& scene, int index, const std::string& source);

  /// Re-selects the wrap points (guards above), then recomputes length and J.
  /// Appends a line to `warnings` when a guard had to repair the geometry.
  void update(std::span<const BodyState> bodies, std::vector<std::string>* warnings = nullptr) {
    update(bodies, bodies, warnings);
  }
  /// The same with the wrap points selected on `select` (the bodies a moment later, so that a
  /// point exactly on a segment and moving onto its wrap side counts as crossed) and length and J
  /// worked out on `bodies`.
  void update(std::span<const BodyState> select, std::span<const BodyState> bodies,
              std::vector<std::string>* warnings);
  /// The first wrap change in (0, h] if every body moves as `motion` says over the sub-step
  /// (start pose, and the velocity it moves with); nullopt if none.
  std::optional<WrapEvent> nextEvent(std::span<const BodyState> motion, double h) const;

  /// The authored definition (geometry and initial parameters); parameters() has the live ones.
  const CableDef& def() const { return *def_; }
  const std::string& name() const { return def_->name; }
  /// Recomputes length and J for the current wrap points (no re-selection).
  void refresh(std::span<const BodyState> bodies);

  const std::vector<WrapPoint>& path() const { return path_; }
  /// A point pulley's turn at the last update (rad; continuedPointTurn), 0 for other kinds.
  double pointTurn(int pulley) const {
    const PulleyState& p = pulleys_[pulley];
    return p.polygon || p.circle ? 0.0 : p.arc;
  }
  /// The turns a circle or polygon pulley is wound with now: its wrap (circle) or the angle the
  /// path turns round it (polygon) over 2 pi, 0 off the path. What a scene written now gives as
  /// its `turns`, so that a World built from it starts with the same length (sceneNow).
  double woundTurns(int pulley) const {
    const PulleyState& p = pulleys_[pulley];
    return (p.polygon || p.circle) && p.engaged ? std::max(p.arc, 0.0) / (2 * M_PI) : 0.0;
  }
  /// A drum end's turns wound now (its arc over 2 pi; 0 once it has paid all out), 0 for a point.
  /// Read off the path, which refresh() keeps at the step's end: the terminal's copy is the last
  /// update's, a step's turn behind (a drum at 6 rad/s, 60 Hz, r = 5 cm: 5 mm of rope).
  double drumTurns(bool atStart) const {
    const WrapPoint& w = path_.empty() ? (atStart ? start_ : end_)
                         : atStart     ? path_.front()
                                       : path_.back();
    return w.radius != 0 ? std::max(w.arc, 0.0) / (2 * M_PI) : 0.0;
  }
  /// Length and J of the path (cableLengthJacobian: the solvers need no J v or J-dot v, and
  /// cableKinematics gives them for any path).
  const CableKinematics& kinematics() const { return kin_; }
  double length() const { return kin_.length; }
  const CableParameters& parameters() const { return params_; }
  double restLength() const { return params_.restLength; }
  double stiffness() const { return params_.stiffness; }
  double preload() const { return params_.preload; }
  double damping() const { return params_.damping; }
  bool elastic() const { return params_.stiffness > 0; }
  /// Pulley wrap points in use (path points that are not anchors).
  int wraps() const { return static_cast<int>(path_.size()) - 2; }
  /// The scene's pulleys (def().pulleys): a free polygon's second place is not one of them.
  int pulleyCount() const { return namedPulleys_; }
  /// The body a pulley is fixed on (-1: the world), engaged or not.
  int pulleyBody(int pulley) const { return pulleys_[pulley].body; }
  bool engaged(int pulley) const { return pulleys_[pulley].engaged; }
  /// The scene's pulley (def().pulleys) a place in the path belongs to: a free polygon's second
  /// place (docs/knocks.md, "Wedged in its neighbour's loop") is its sibling's pulley.
  /// Any other index (a drum end's, -1) is returned as it is.
  int scenePulley(int pulley) const {
    const bool second =
        pulley >= 0 && pulley < static_cast<int>(pulleys_.size()) && pulleys_[pulley].secondPlace;
    return second ? pulleys_[pulley].twin : pulley;
  }
  /// Whether the scene's pulley k is on the path at either of its places.
  bool sceneEngaged(int k) const {
    return engaged(k) || (pulleys_[k].twin >= 0 && engaged(pulleys_[k].twin));
  }
  /// The side an engaged pulley is wrapped on (an "auto" pulley's resolved side).
  WrapSide wrapSide(int pulley) const { return pulleys_[pulley].side; }

  /// Constraint value: length - rest length (+ preload for elastic cables) (m).
  double stretch() const;
  /// Tension of the last step (N) and whether it was slack. With spans: the largest.
  double tension() const { return tension_; }
  bool slack() const { return tension_ <= 0; }
  void setTension(double t);
  /// Live parameter edits (validated by the World).
  void setParameters(const CableParameters& parameters);

  // Spans: wheels that grip the cable (no slip, capstan) split it into spans, each its own
  // constraint with its own rest length and tension (docs/wheels.md). Without such wheels the
  // cable is one span: the whole path.
  int spanCount() const { return spans_.empty() ? 1 : static_cast<int>(spans_.size()); }
  std::span<const WrapPoint> spanPath(int k) const;
  const CableKinematics& spanKinematics(int k) const;
  /// Span length - span rest length (m); the whole stretch() for a one-span cable. On an elastic
  /// cable split by a polygon with friction the rest is the span's unstretched material.
  double spanStretch(int k) const;
  /// The energy stored in the cable's spring (J; 0 for a rigid cable). Split by a polygon with
  /// friction, each span and each piece of rope stuck between the polygon's corners is a spring of
  /// its own material r: T^2 r / (2 k L) each (docs/polygon_friction.md, "Elastic cables").
  double elasticEnergy() const;
  /// The rope between the engaged corners of polygons with friction (m): on an elastic cable its
  /// material, so that the spans' rests and it sum to rest length - preload; on a rigid one its
  /// length.
  double cornerRest() const { return cornerRest_; }
  /// Span k's stiffness (N/m) and damping (N s/m): the cable's, or on an elastic cable split by a
  /// polygon with friction the cable's times (rest length - preload) / span material, so that
  /// equal strains give the unsplit cable's tension (docs/polygon_friction.md).
  double spanStiffness(int k) const { return params_.stiffness * spanScale(k); }
  double spanDamping(int k) const { return params_.damping * spanScale(k); }
  double spanTension(int k) const { return spans_.empty() ? tension_ : spans_[k].tension; }
  void setSpanTension(int k, double t);
  /// The wheel between spans k and k + 1 (spanCount() - 1 of them).
  const SpanLink& link(int k) const { return links_[k]; }
  /// The solver let the cable slide on link k's wheel this sub-step: the next update moves rest
  /// length between the two spans so that the slide is not undone.
  void setSlipped(int k, bool slipped) { links_[k].slipped = slipped; }
  /// On an elastic cable that slid over link k - 1 or k: span k's stretch at the end of the
  /// solved step (m, on its material before the slide). The next refresh or update shares the
  /// slid spans' material so that their strains keep these proportions, and so their tensions
  /// the solved ratio (docs/polygon_friction.md, "Elastic cables").
  void setSlidStretch(int k, double stretch) {
    spans_[k].slidStrain = stretch / std::max(spans_[k].rest, 1e-12);
  }
  /// Whether path segment i runs from a polygon's corner to a point fixed in the world, which
  /// may be pressed into its hull and hold its chain there (wrap_hold.h): the point goes into the
  /// hull rather than stopping it, so the segment has no floor (floors.h; docs/cables.md, "Points
  /// inside a hull").
  bool mayEnterHull(size_t i) const;
  /// Tension on path segment i (path()[i] -> path()[i + 1]): its span's, or between two corners
  /// of a polygon with friction, what cornerTensions() gives it.
  double segmentTension(size_t i) const;
  /// Link k's corners in path order, if it is a polygon with friction (else none), into `out`.
  /// While the cable slides, each corner's tensions are in the ratio e^(mu theta_i); while it
  /// holds (the split between the corners of a rigid polygon is not determined), every corner
  /// takes the same share of its friction: T_out / T_in = (T_k+1 / T_k)^(theta_i / theta).
  void cornerTensions(int k, std::vector<CornerTension>& out) const;
  /// Lets span k pay out `length` (m): its rest length grows by it. The solver does this where a
  /// kinematic body hauls a rigid cable that nothing can hold (docs/model.md, "Driven bodies").
  void payOut(int k, double length);
  /// Rest length paid out since construction (m).
  double paidOut() const { return paidOut_; }

  /// Skipping (wrap_skip.cpp, docs/cables.md "Skipping"): while no wrap point or candidate vertex
  /// can reach the line it is tested against, update() keeps the wrap set without re-selecting
  /// and nextEvent() reports none without searching. On by default; off re-selects every time.
  void setSkipping(bool on);
  /// Updates that kept the wrap set and event searches skipped, since construction.
  long skippedSelections() const { return skippedSelections_; }
  long skippedSearches() const { return skippedSearches_; }

 private:
  struct PulleyState {
    int body = -1;
    std::vector<Vec2> local;         ///< point or polygon vertices (a circle's centre), body frame
    std::vector<Vec2> world;         ///< the same in the world frame, this update
    WrapSide side = WrapSide::Left;  ///< resolved side (an auto pulley's while engaged)
    bool autoSide = false;           ///< "side": "auto": the side is chosen at each join
    bool polygon = false;
    bool circle = false;
    double radius = 0;   ///< circle, m (unsigned)
    bool grips = false;  ///< circle that the cable does not slide freely on
    double turns = 0;    ///< turns wound at the start (0: from the geometry, < 1 turn)
    double arc = 0;      ///< circle: wrap angle at the last update (branch reference);
                         ///< point, polygon: the angle the path turns round it (rad,
                         ///< continuous over time, wrapChainTurning)
    bool engaged = false;
    double previousDepth = 0;  ///< wrap-side depth at the last update (guard memory)
    double previousLeft = 0;   ///< auto: signed distance left of the host segment (guard memory)
    bool dropped = false;      ///< left by a guard (terminal inside the hull): may rejoin
    double dropCut = 0;        ///< length the drop took out of the path (m): the most a rejoin
                               ///< may put back
    /// Polygon the cable is tied to (a terminal fixed on its body, on or inside its hull: a
    /// spool, tied_end.h): which end (-1 start, +1 end, 0 none), the corner the cable leaves the
    /// hull at towards it, and whether the end lies inside the hull off every edge
    int tiedEnd = 0;
    int tiedCorner = -1;
    bool tiedInside = false;
    ChainHold hold;  ///< polygon: its chain's ends, held through a point in its hull
    /// A free polygon off the path: how deep it reached past each path segment (named by its
    /// ends' pulleys) at the last update (pulley_order.cpp).
    struct SegmentDepth {
      int from, to;
      /// The deepest vertex's wrapSideDistance for each side (m): at most 0 for one side, the
      /// polygon lay wholly on that side's non-wrap side.
      double left, right;
      bool cut;  ///< the segment cut the polygon
    };
    std::vector<SegmentDepth> segmentDepths;
    /// A free polygon's other place in the order (its twin's index; -1: none): wedged between
    /// two strands of the rope, the path bends round it at both (pulley_order.cpp).
    int twin = -1;
    bool secondPlace = false;  ///< the twin itself: on the path only through its sibling
    double signedRadius() const { return side == WrapSide::Right ? -radius : radius; }
    /// The wrap branch at the start: the turns it was wound with, else within (0, 2 pi).
    double initialArc() const { return turns > 0 ? 2 * M_PI * turns : M_PI; }
  };
  struct Span {
    size_t first = 0, last = 0;  ///< path_ indices of its end points (shared with neighbours)
    std::vector<WrapPoint> path;
    CableKinematics kin;
    double rest = 0;        ///< m
    double tension = 0;     ///< N
    double slidStrain = 0;  ///< the solver's end-of-step strain when it slid (elastic)
  };
  void placePulleys(std::span<const BodyState> bodies);
  /// At the first update: a warning for each one-sided point pulley fixed where it is that the
  /// rope does not reach (pulley_left_out.cpp).
  void reportPulleysLeftOut(std::span<const BodyState> bodies,
                            std::vector<std::string>* warnings) const;
  bool buildPath(std::vector<std::string>* warnings);
  bool seedCommonTangents(std::vector<std::vector<int>>& chains) const;
  bool holdsAgainst(int node) const;
  Vec2 entryPoint(int node, const std::vector<std::vector<int>>& chains) const;
  Vec2 exitPoint(int node, const std::vector<std::vector<int>>& chains) const;
  bool touchesPath(int node, const std::vector<std::vector<int>>& chains) const;
  bool leaveRound();
  bool joinRound(std::vector<std::string>* warnings);
  void storeArcs();
  void placeDrumMarks(std::span<const BodyState> bodies);
  /// Where a gripping pulley splits the path: path_[in] ends one span, path_[out] starts the
  /// next (the same point for a wheel; a polygon's first and last engaged corners).
  struct Split {
    size_t in = 0, out = 0;
  };
  void updateSpans(std::span<const BodyState> bodies);
  void splitIntoSpans(std::span<const BodyState> bodies, const std::vector<Split>& splits);
  void rebaseMarks();
  /// Elastic spans beside a polygon with friction that break its capstan ratio slide to it.
  void slideElasticSpans();
  /// After the solver let elastic spans slide: their material shared by the solved strains.
  void shareSlidMaterial();
  /// Elastic: the corner rope after the chains changed (spans' paths updated, their rests and
  /// spanBefore_ still the old ones): pieces that left go back to their span whole, pieces that
  /// joined take the rope their span gave up at its strain (a slack span's at its length).
  void moveCornerRope(const std::vector<Split>& splits);
  /// Elastic: rope slides over each corner of a polygon with friction that its two sides' tensions
  /// break the capstan ratio at, piece or span, until every corner holds.
  void slideCornerRope();
  static constexpr int kCornerSweeps = 32;  ///< slideCornerRope's passes over a chain at most
  /// Elastic: the corner rope of a fresh split, each piece at `stretchRatio` (length / material).
  void shareCornerRope(const std::vector<Split>& splits, double stretchRatio);
  /// The distance between two corners of polygon `pulley` (m; fixed, the polygon is rigid).
  double cornerGap(int pulley, int a, int b) const;
  /// Unstretched length of an elastic cable's material (m): rest length - preload.
  double materialLength() const;
  double spanScale(int k) const;
  /// The angle the path turns at path_[i], a polygon corner, on its wrap side (>= 0, rad).
  double cornerTurn(size_t i) const;
  /// The length of the path between the spans, over the corners of polygons with friction (m).
  double cornerLength(const std::vector<Split>& splits) const;
  bool updateDrumEnd(WrapPoint& end, bool atStart, std::span<const BodyState> bodies);
  // A cable end tied to the polygon it winds round (tied_end.cpp).
  void findTiedEnds();
  /// The chain (and turn) of a tied polygon between path points a and b; nullopt: no taut path.
  std::optional<double> tiedChain(const PulleyState& p, const Vec2& a, const Vec2& b,
                                  std::vector<int>& chain) const;
  /// The corner of a tied polygon that may join path segment `segment` (it runs straight into
  /// the tied end, no corner in the path), with its pulley; -1 when none.
  int tiedCornerWaiting(size_t segment, int& pulley) const;

  const CableDef* def_;     ///< the scene's, never edited
  CableParameters params_;  ///< live values
  int startBody_, endBody_;
  WrapPoint start_, end_;  ///< the terminals (drums keep their mark and arc here)
  /// A drum end unwound to its mark is a point on the rim until the cable wraps it again, on
  /// whichever side (a yo-yo): its centre and radius while it is a point.
  struct Drum {
    Vec2 centre = Vec2::Zero();
    double radius = 0;
  };
  Drum startDrum_, endDrum_;
  std::vector<PulleyState> pulleys_;
  /// The pulleys in the order the path meets them: the scene's, except that a free polygon
  /// joins whichever segment it crosses and takes its place there (pulley_order.cpp); rank_ is
  /// each pulley's place in order_.
  std::vector<int> order_, rank_;
  /// The scene's pulleys (the first of pulleys_); the free polygons' second places follow.
  int namedPulleys_ = 0;
  /// Free polygons' second places (pulley_order.cpp).
  void addSecondPlaces();
  /// A second place off the path: it takes part in nothing until its sibling puts it on.
  bool idleSecondPlace(int j) const { return pulleys_[j].secondPlace && !pulleys_[j].engaged; }
  /// Pulley j off the path, its other place (a free polygon's: pulley_order.cpp) on it at an end
  /// of the segment from path point a to path point b: the polygon is there already, and a corner
  /// of it crossing the segment is that place's chain growing, not a join (docs/knocks.md, "Next
  /// to its own other place").
  bool besideItsOtherPlace(int j, const WrapPoint& a, const WrapPoint& b) const {
    const int twin = pulleys_[j].twin;
    return !pulleys_[j].engaged && twin >= 0 && pulleys_[twin].engaged &&
           (a.pulley == twin || b.pulley == twin);
  }
  /// Moves pulley j's place in the order to right after the pulley segment `i` starts at.
  void placeAfterSegment(int j, size_t i);
  /// Whether pulley j may join any segment of the path, not only its own (pulley_order.cpp).
  bool joinsAnySegment(int j) const;
  /// Free polygon j off the path: joins a segment other than its own that cuts it now and that it
  /// lay wholly on one side of at the last update, taking its place there and wrapping on the
  /// side it came from; records its depths for the next update. True if it joined.
  bool joinCrossedSegment(int j);
  /// Whether path segment i is an edge of one polygon's chain (nothing joins it from outside).
  bool chainEdge(size_t i) const;
  std::vector<WrapPoint> path_;
  std::vector<int> nodes_;                ///< buildPath scratch: engaged chain nodes
  std::vector<std::vector<int>> chains_;  ///< buildPath scratch: polygon vertex chains
  double previousLength(std::span<const BodyState> bodies);
  void reportLengthJump(std::span<const BodyState> bodies, std::vector<std::string>* warnings);
  /// Wrap changes that move the length by more than this say so in a warning (m).
  static constexpr double kLengthJump = 1e-3;
  std::vector<WrapPoint> previousPath_;  ///< the path before update (length-jump check)
  CableKinematics previousKin_;          ///< scratch of the length-jump check
  std::vector<int> rejoinChain_;         ///< scratch of the rejoin test
  std::vector<char> droppedBefore_;      ///< scratch: pulleys dropped before this update
  std::vector<char> engagedBefore_;      ///< scratch: pulleys engaged before this update
  CableKinematics kin_;
  std::vector<Span> spans_;        ///< empty: one span, the whole path
  std::vector<SpanLink> links_;    ///< spans_.size() - 1
  std::vector<int> splitPulleys_;  ///< pulleys at the links, in path order (scratch + memory)
  std::vector<Split> splits_;      ///< updateSpans scratch
  double cornerRest_ = 0;          ///< cornerLength() at the last update: rigid, outside the spans
                                   ///< (elastic: the material between the corners, in sum)
  /// Elastic: the rope stuck between a polygon's engaged corners, piece by piece (one per link;
  /// none at a wheel). rests[i] is the material between vertices[i] and vertices[i + 1]: each
  /// piece keeps what it took when its corner joined and gives it back when it leaves
  /// (corner_rope.cpp; docs/polygon_friction.md, "Elastic cables").
  struct CornerRope {
    int pulley = -1;
    std::vector<int> vertices;  ///< the engaged corners in path order
    std::vector<double> rests;  ///< m, vertices.size() - 1 pieces
  };
  std::vector<CornerRope> cornerRopes_;
  /// A span whose end corner changed: its length on its old path (m); -1: unchanged.
  std::vector<double> spanBefore_;
  std::vector<double> spanGained_, spanLeft_;  ///< moveCornerRope scratch, per span
  CableKinematics spanScratch_;                ///< a span's previous path, measured again
  // Skipping: a certificate built at a full update's selection pose. Each test is one signed
  // distance the event search watches (a point p from the line a-b), with its value then; the
  // wrap set cannot change while every point's displacement since is too small to zero one.
  struct SkipBody {
    int body;
    Vec2 position;
    double angle;
    double reach = 0;  ///< certificate: the largest |local| of its tested points (m)
  };
  struct SkipTest {
    int a, b, p;         ///< indices into skipBodies_
    double ra, rb, rp;   ///< |local| of the points (m)
    double margin;       ///< |distance of p from line a-b| (m)
    double arm, length;  ///< |p - a|, |b - a| (m)
  };
  struct SkipTurn {
    int pulley;
    int in, out;  ///< path segments into and out of the pulley
    double sign;  ///< -1 for WrapSide::Right, else +1
    double arc;   ///< scratch: the new turn angle (rad)
  };
  bool skipEligible() const;
  void buildSkipCertificate(std::span<const BodyState> pose);
  bool wrapSetCertain(std::span<const BodyState> pose, double h) const;
  bool keepWrapSet(std::span<const BodyState> select, std::span<const BodyState> bodies);
  /// The vertex a polygon's chain would grow by at `end`, a chain end on segment (a, b): the one
  /// before its first (end is b, the segment enters the chain) or after its last (end is a).
  int chainEndNeighbour(const WrapPoint& end, bool entering) const;
  /// nextEvent() without the skip: every watched distance sampled over the sub-step.
  [[gnu::noinline]] std::optional<WrapEvent> searchEvents(std::span<const BodyState> motion,
                                                          double h) const;
  void finishUpdate(std::span<const BodyState> bodies, std::vector<std::string>* warnings);
  std::vector<SkipBody> skipBodies_;
  std::vector<SkipTest> skipTests_;
  /// Every test holds while each of its points has moved by at most this (m; -1: none).
  double skipAllowance_ = -1;
  mutable std::vector<Vec2> skipMotion_;  ///< scratch: per skip body, (linear, angular) bound
  std::vector<SkipTurn> skipTurns_;       ///< the pulley turns a kept wrap set updates
  /// The poses of the path's bodies that kin_ was last worked out on while a certificate held
  /// (refresh, keepWrapSet): a refresh or a kept wrap set on the same poses (the first sub-step
  /// after a step's refresh, a hand at rest) has its length and J already.
  std::vector<SkipBody> kinPoses_;
  bool kinPosesValid_ = false;
  bool turnsCurrent_ = false;  ///< keepWrapSet kept the pulley turns of kin_ (its poses')
  bool kinematicsCurrent(std::span<const BodyState> bodies) const;
  void noteKinematicsPoses(std::span<const BodyState> bodies);
  bool skipping_ = true;
  bool skipValid_ = false;
  long skippedSelections_ = 0;
  mutable long skippedSearches_ = 0;
  double tension_ = 0;
  double paidOut_ = 0;
  bool firstUpdate_ = true;
  bool reportedZeroLength_ = false;
};

}  // namespace cablelab

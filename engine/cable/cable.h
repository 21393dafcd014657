// Cable: a chain anchor -> pulleys -> anchor, its wrap points, length, Jacobian and J-dot-v.
//
// Where to find things:
//   wrap-point selection and the guards ......... Cable::updatePath()   (cable.cpp)
//   length, J = d length / dq, J-dot-v ........... cableKinematics()    (cable_kinematics.cpp)
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
//  * An engaged pulley LEAVES when the path no longer bends around it: a point pulley when the
//    turn at it is straight or the wrong way; a polygon when its hull chain is empty.
//  * A terminal inside a polygon pulley's hull (a neighbouring pulley inside it) has no taut path:
//    the polygon leaves the path and a warning says so.
//  * Consecutive coincident wrap points (a zero-length segment, < 1e-12 m) are merged: the
//    segment is left out of J and J-dot-v, never divided by, and a warning says so.
//  At creation every pulley that the straight segment cuts joins (as if it had just crossed).
//  Joins and leaves only happen where the new point lies on the current path, up to one step of
//  motion, so length and J stay continuous (theorem 1) up to that: a pulley detected d metres
//  past the segment adds a length jump of order d^2 / segment length, and a taut cable then
//  does work T times that jump. It is second order in the step (tests bound it).
#pragma once

#include <span>
#include <string>
#include <vector>

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

/// One point of a cable's current path.
struct WrapPoint {
  enum class Kind { Anchor, Point, Vertex };
  Kind kind = Kind::Anchor;
  int body = -1;              ///< -1: world
  Vec2 local = Vec2::Zero();  ///< body frame (world frame for the world)
  Vec2 world = Vec2::Zero();  ///< current world position
  int pulley = -1;            ///< index into CableDef::pulleys, -1 for anchors
  int vertex = -1;            ///< polygon vertex index, -1 otherwise
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
};

/// One 2x2 block of d^2 length / (d x_a d x_b), x = a body's translation.
struct StiffnessBlock {
  int a, b;
  Eigen::Matrix2d k;
};

/// The translational Hessian of the length of a path (world points already set), appended to
/// `blocks` (no allocation once it has the capacity): tension times this is the cable's
/// geometric stiffness, which a stiff membrane on a light body needs implicitly. Rotations are
/// left out. Blocks of world-fixed points are skipped.
void appendLengthHessianTranslation(std::span<const WrapPoint> path,
                                    std::vector<StiffnessBlock>& blocks);

/// World position of a point fixed on a body.
Vec2 worldPoint(std::span<const BodyState> bodies, int body, const Vec2& local);

/// Fills p.world for every point, then length, J, J-dot-v (docs/model.md#cable-geometry).
CableKinematics cableKinematics(std::span<WrapPoint> path, std::span<const BodyState> bodies);
/// The same into `k`, reusing its Jacobian's storage (the solver calls this every Newton step).
void cableKinematics(std::span<WrapPoint> path, std::span<const BodyState> bodies,
                     CableKinematics& k);

/// A cable's parameters as they are now: the scene's values until World::setCableParameters
/// edits them (the scene itself is never edited).
struct CableParameters {
  double restLength = -1.0;  ///< m; < 0 until the first update measures the initial length
  double stiffness = 0.0;    ///< N/m; 0 = rigid
  double preload = 0.0;      ///< m
  double damping = 0.0;      ///< N s/m
};

class Cable {
 public:
  /// `scene` resolves body names and polygon shapes; throws InputError on bad references.
  /// The cable refers to scene.cables[index], which must outlive it (the World owns both).
  Cable(const SceneDef& scene, int index, const std::string& source);

  /// Re-selects the wrap points (guards above), then recomputes length, J and J-dot-v.
  /// Appends a line to `warnings` when a guard had to repair the geometry.
  void update(std::span<const BodyState> bodies, std::vector<std::string>* warnings = nullptr);

  /// The authored definition (geometry and initial parameters); parameters() has the live ones.
  const CableDef& def() const { return *def_; }
  const std::string& name() const { return def_->name; }
  /// Recomputes length, J and J-dot-v for the current wrap points (no re-selection).
  void refresh(std::span<const BodyState> bodies) { cableKinematics(path_, bodies, kin_); }

  const std::vector<WrapPoint>& path() const { return path_; }
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
  bool engaged(int pulley) const { return pulleys_[pulley].engaged; }

  /// Constraint value: length - rest length (+ preload for elastic cables) (m).
  double stretch() const;
  /// Tension of the last step (N) and whether it was slack.
  double tension() const { return tension_; }
  bool slack() const { return tension_ <= 0; }
  void setTension(double t) { tension_ = t; }
  /// Live parameter edits (validated by the World).
  void setParameters(const CableParameters& parameters) { params_ = parameters; }

 private:
  struct PulleyState {
    int body = -1;
    std::vector<Vec2> local;  ///< point or polygon vertices, body frame
    std::vector<Vec2> world;  ///< the same in the world frame, this update
    WrapSide side = WrapSide::Left;
    bool polygon = false;
    bool engaged = false;
    double previousDepth = 0;  ///< wrap-side depth at the last update (guard memory)
  };
  void placePulleys(std::span<const BodyState> bodies);
  bool buildPath(std::vector<std::string>* warnings);
  Vec2 entryPoint(int node, const std::vector<std::vector<int>>& chains) const;
  Vec2 exitPoint(int node, const std::vector<std::vector<int>>& chains) const;

  const CableDef* def_;     ///< the scene's, never edited
  CableParameters params_;  ///< live values
  int startBody_, endBody_;
  std::vector<PulleyState> pulleys_;
  std::vector<WrapPoint> path_;
  std::vector<int> nodes_;                ///< buildPath scratch: engaged chain nodes
  std::vector<std::vector<int>> chains_;  ///< buildPath scratch: polygon vertex chains
  CableKinematics kin_;
  double tension_ = 0;
  bool firstUpdate_ = true;
  bool reportedZeroLength_ = false;
};

}  // namespace cablelab

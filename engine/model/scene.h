// Scene definitions: what a user authors (in JSON or in code) before a World is built.
//
// Authoring (SceneDef) -> World (Box2D bodies + cablelab cables, per-step state).
// Every def has documented defaults and units; validateScene() checks a whole scene once
// and throws InputError naming the field ("bodies[2].mass: must be positive").
// Lengths in metres, masses in kilograms, angles in radians, time in seconds.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/math.h"

namespace cablelab {

enum class BodyType { Static, Kinematic, Dynamic };

/// A collision shape fixed to a body, in the body's local frame.
struct ShapeDef {
  enum class Kind { Circle, Polygon };
  Kind kind = Kind::Circle;
  double radius = 0.1;         ///< circle radius (m)
  Vec2 center = Vec2::Zero();  ///< circle centre, local (m)
  std::vector<Vec2> vertices;  ///< convex polygon, counter-clockwise, local (m); 3..8 vertices
  double friction = 0.6;       ///< Coulomb friction coefficient
  double restitution = 0.0;    ///< bounciness in [0, 1]
  bool sensor = false;         ///< true: takes part in no contact (a pure pulley)
};

struct BodyDef {
  std::string name;  ///< unique, non-empty; "world" is reserved
  BodyType type = BodyType::Dynamic;
  Vec2 position = Vec2::Zero();  ///< origin of the body frame, world (m)
  double angle = 0.0;            ///< rad
  Vec2 velocity = Vec2::Zero();  ///< of the body origin (m/s)
  double angularVelocity = 0.0;  ///< rad/s
  double mass = 1.0;             ///< kg, > 0 for dynamic bodies; the shapes share it
  double inertia = 0.0;          ///< kg m^2 about the origin; 0 = from the shapes
  bool fixedRotation = false;    ///< true: the body translates only
  double linearDamping = 0.0;    ///< 1/s
  double angularDamping = 0.0;   ///< 1/s
  std::vector<ShapeDef> shapes;  ///< at least one for dynamic bodies
};

/// A servo on a joint: PD force on the joint coordinate, tracking `target`.
struct ServoDef {
  bool enabled = false;
  double kp = 500.0;      ///< N/m or N m/rad
  double kd = 44.72;      ///< N s/m or N m s/rad (default 2 sqrt(500))
  double target = 0.0;    ///< m or rad, in the joint's coordinate
  double maxForce = 1e4;  ///< N or N m, clamp
  /// m/s or rad/s: the target moves at this rate (a drive at constant speed; 0 = holds still),
  /// and the damping term tracks it: force = kp (target - q) + kd (speed - q').
  double speed = 0.0;
};

struct JointDef {
  enum class Kind { Revolute, Prismatic, Weld };
  Kind kind = Kind::Revolute;
  std::string name;             ///< unique among joints
  std::string bodyA = "world";  ///< "world" or a body name
  std::string bodyB;            ///< a body name
  Vec2 anchor = Vec2::Zero();   ///< world point at the scene's initial pose (m)
  Vec2 axis = Vec2(1, 0);       ///< prismatic: sliding axis, world, unit
  bool enableLimit = false;
  double lower = 0.0, upper = 0.0;  ///< limits on the joint coordinate (rad or m)
  bool collideConnected = false;
  /// The joint coordinate at the scene's pose (rad or m): 0 for a scene as authored; a scene
  /// written mid-run (World.to_dict(current=True)) keeps the coordinate the servo targets and
  /// limits refer to.
  double value = 0.0;
  ServoDef servo;
};

/// Which way the cable goes round a pulley.
///  Left:  walking along the cable, the cable passes on the left of the pulley
///         (the pulley lies on the cable's right).
///  Right: the mirror image.
///  Threaded: always in the path, whatever the bend (an eyelet the cable runs through).
///  Auto:  Left or Right, whichever side the pulley meets the cable from (polygons, circles).
enum class WrapSide { Left, Right, Threaded, Auto };

/// How a cable grips a circle or polygon pulley (docs/wheels.md, docs/polygon_friction.md).
///  Frictionless: slides freely; one tension on both sides, the wheel is not driven.
///  NoSlip: never slides; the wheel's angle enters the constraint and the two sides carry
///          their own tensions (a toothed belt, a rope on a winch barrel).
///  Capstan: sticks while T_high <= T_low e^(mu theta) (theta the wrap angle), slides at that
///           ratio beyond (Euler-Eytelwein). On a polygon each engaged corner holds while
///           T_high <= T_low e^(mu theta_i), theta_i the angle the cable turns there.
enum class Grip { Frictionless, NoSlip, Capstan };

/// A pulley fixed to a body or the world: a point, the vertices of a convex polygon, or a circle.
struct PulleyDef {
  enum class Kind { Point, Polygon, Circle };
  Kind kind = Kind::Point;
  std::string body = "world";      ///< "world" or a body name
  Vec2 point = Vec2::Zero();       ///< Point: position; Circle: centre (body frame; world frame
                                   ///< for "world")
  std::vector<Vec2> vertices;      ///< Polygon: CCW convex polygon, body frame; empty = the
                                   ///< body's first polygon shape
  WrapSide side = WrapSide::Left;  ///< Polygon pulleys cannot be Threaded
  double radius = 0.0;             ///< Circle: m, > 0
  Grip grip = Grip::Frictionless;  ///< Circle: any; Polygon: Frictionless or Capstan
  double mu = 0.0;                 ///< Capstan: friction coefficient, > 0
  double turns = 0.0;              ///< Circle: the wrap at the start in turns, for a cable wound
                                   ///< round more than once (2.25 = 810 degrees); 0 = the wrap
                                   ///< the geometry gives, under one turn
};

/// One end of a cable, fixed to a body (or the world). With a radius it is a drum: the cable is
/// wound `turns` turns onto a circle round `point` (the end fixed on the drum's rim), and winds
/// or unwinds as the drum turns: the length stored is r times the angle turned.
struct AnchorDef {
  std::string body = "world";
  Vec2 point = Vec2::Zero();       ///< body frame (world frame for "world"); a drum's centre
  double radius = 0.0;             ///< m; 0 = a point, > 0 = a drum
  WrapSide side = WrapSide::Left;  ///< drum: the side the cable passes it (Left or Right)
  double turns = 1.0;              ///< drum: turns wound at the start (> 0)
};

/// A cable from `start` over `pulleys` (in order) to `end`.
/// stiffness == 0: an inextensible cable, tension from the constraint.
/// stiffness > 0: an elastic cable (membrane), tension k (length - restLength + preload)
///                + damping * d(length)/dt, never negative.
struct CableDef {
  std::string name;
  AnchorDef start, end;
  std::vector<PulleyDef> pulleys;
  double restLength = -1.0;  ///< m; < 0 = the length at the initial pose
  double stiffness = 0.0;    ///< N/m; 0 = rigid
  double preload = 0.0;      ///< m of pre-stretch, >= 0 (elastic cables only)
  double damping = 0.0;      ///< N s/m, >= 0 (elastic cables only)
};

/// True for a circle or polygon pulley the cable does not slide freely on (it splits the cable
/// in spans).
inline bool gripsCable(const PulleyDef& p) {
  return p.kind != PulleyDef::Kind::Point && p.grip != Grip::Frictionless;
}

/// Where the camera looks by default (for the sandbox and snapshots).
struct ViewDef {
  Vec2 center = Vec2::Zero();  ///< m
  double height = 4.0;         ///< visible world height (m)
};

struct SceneHistory;

struct SceneDef {
  std::string name;
  std::string description;
  Vec2 gravity = Vec2(0, -9.81);  ///< m/s^2
  double dt = 1.0 / 60.0;         ///< default time step (s)
  int substeps = 1;               ///< default substeps per step
  ViewDef view;
  std::vector<BodyDef> bodies;
  std::vector<JointDef> joints;
  std::vector<CableDef> cables;
  double time = 0.0;   ///< the World's clock at the scene's pose (s)
  long stepCount = 0;  ///< steps taken before the scene's pose
  /// Set in a scene written mid-run: the scene it started from and its inputs since, from which
  /// the World is rebuilt bit for bit (docs/scene-format.md, "history"); null otherwise.
  std::shared_ptr<const SceneHistory> history;
};

/// Where a scene written mid-run came from: the scene as built and every input the World took
/// since, one row each as WorldInput holds it (engine/dynamics/world_history.h): kind, index,
/// count, four values.
struct SceneHistory {
  SceneDef origin;
  std::vector<std::array<double, 7>> inputs;
};

/// Checks every field; throws InputError(source, field, what) on the first bad one.
void validateScene(const SceneDef& scene, const std::string& source);

/// Index of the body called `name` in scene.bodies, -1 for "world", -2 if unknown.
int findBodyIndex(const SceneDef& scene, const std::string& name);

/// The largest restitution of body `body`'s shapes, sensors too (0 for the world, -1): what it
/// bounces with off its pulleys and its pulley neighbours (docs/scene-format.md, Shapes).
double largestRestitution(const SceneDef& scene, int body);

/// A polygon pulley's vertices in its body's frame (the world's for "world"): its own, or else its
/// body's first polygon shape (empty if it has neither).
std::vector<Vec2> pulleyPolygon(const SceneDef& scene, const PulleyDef& pulley);

}  // namespace cablelab

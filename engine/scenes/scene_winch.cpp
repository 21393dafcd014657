// A drum on a driven axle winds the cable and lifts `weight` for many turns: the rise is r times
// the angle turned (docs/wheels.md). The servo drives the drum at omega (rad/s).
#include "engine/scenes/scene_parts.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {

SceneDef makeWinchScene(const SceneParams& p) {
  const double r = p.at("r"), y = 3.0;
  SceneDef s;
  s.name = "winch";
  s.description =
      "a servo-driven drum winds the cable and lifts the weight: try --set omega=-2 (lowers), "
      "omega=0 (holds), or r=0.2 (twice as fast)";
  s.view = {Vec2(0, 1.0), 6.0};

  BodyDef drum = wheelBody("drum", Vec2(0, y), r);
  drum.mass = 2.0;
  drum.inertia = 0.5;  // a flywheel on the drum's axle keeps the servo stable at 60 Hz
  s.bodies = {drum, boxBody("weight", Vec2(r, y - 3.5), p.at("mass"), 0.1)};

  JointDef axle;
  axle.name = "axle";
  axle.bodyB = "drum";
  axle.anchor = Vec2(0, y);
  axle.servo.enabled = true;
  // Explicit PD at 60 Hz: kd h / I and kp h^2 / I well below 1.
  axle.servo.kp = 100;
  axle.servo.kd = 20;
  axle.servo.maxForce = 1e4;
  axle.servo.speed = p.at("omega");
  s.joints = {axle};

  CableDef cable;
  cable.name = "cable";
  cable.start = {"weight", Vec2(0, 0.1)};
  // Up the drum's right side and counter-clockwise over the top: turning the drum
  // counter-clockwise (omega > 0) winds.
  cable.end.body = "drum";
  cable.end.radius = r;
  cable.end.side = WrapSide::Right;
  cable.end.turns = 1.0;
  s.cables = {cable};
  return s;
}

}  // namespace cablelab

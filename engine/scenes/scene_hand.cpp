// Thesis chapter 4: the two-finger soft hand pinching a square manipuland between two membranes.
//
// Seen from above, so gravity is off: the statics model of section 4.2 (and the controller built
// on it) has no gravity term, and a real hand positioning an object on a table works in that
// plane. The scene is built at the pinch pose (all joint coordinates zero); `cablelab track`
// swings the fingers open before it starts. Every shape is a sensor: fingers and box meet only
// through the membranes, as in the thesis (no rigid contact; friction only with `mu`).
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"
#include "engine/core/parse.h"
#include "engine/hand/hand_kinematics.h"
#include "engine/hand/hand_model.h"
#include "engine/scenes/scene_hand.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {

namespace {

ShapeDef bar(double x0, double x1, double y0, double y1) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::Polygon;
  s.vertices = {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
  s.sensor = true;
  return s;
}

constexpr double kSliderLength = 1.0;  // drawn length of the slider bar (m)

}  // namespace

std::array<double, 6> HandModel::effectiveInertia() const {
  const double iLink = linkMass * linkLength * linkLength / 3;  // rod about its end
  const double iSlider = sliderMass * kSliderLength * kSliderLength / 12;
  const double iPaddle = paddleMass * 4 * paddleHalfWidth * paddleHalfWidth / 12;
  // The grasped box is carried too (half by each finger): at the pinch it sits a link length from
  // the base and a paddle half width from the corners that tilt it.
  const double carried = 0.5 * boxMass;
  const double proximal =
      iLink + (sliderMass + paddleMass + carried) * linkLength * linkLength + iSlider + iPaddle;
  const double slide = sliderMass + paddleMass + carried;
  const double distal = iPaddle + carried * paddleHalfWidth * paddleHalfWidth;
  return {proximal, slide, distal, proximal, slide, distal};
}

SceneDef buildHandScene(const HandModel& m) {
  SceneDef s;
  s.name = "hand";
  char text[640];
  std::snprintf(
      text, sizeof text,
      "thesis ch. 4 two-finger soft hand seen from above (gravity off), metres: proximal joints at "
      "(%g, +/-%g), link %g, slide [%g, %g], paddle %g wide, membrane corners %g from the "
      "distal joint, square box %g x %g (%g kg) centred at the pinch (0, 0); membranes k %g N/m, "
      "b %g N s/m, preload %g m; joint limits proximal/distal +/-%g rad; servos k_p = 500 I, "
      "k_d = 2 sqrt(500) I per joint effective inertia I",
      m.baseX, m.baseY, m.linkLength, m.lower[kSlide], m.upper[kSlide], 2 * m.paddleHalfWidth,
      m.paddleOffset, 2 * m.boxHalfSize, 2 * m.boxHalfSize, m.boxMass, m.stiffness, m.damping,
      m.preload, m.upper[kProximal]);
  s.description = text;
  s.gravity = Vec2::Zero();
  s.substeps = 4;
  s.view = {Vec2(-0.6, 0), 4.5};

  const std::array<double, 6> inertia = m.effectiveInertia();
  const HandJoints zero = HandJoints::Zero();
  const char* fingerNames[2] = {"top", "bottom"};
  for (int f = 0; f < 2; ++f) {
    const FingerPose pose = fingerPose(m, zero, f);
    const std::string name = fingerNames[f];
    const double sgn = HandModel::side(f);

    BodyDef link;
    link.name = name + "_link";
    link.position = pose.link;
    link.mass = m.linkMass;
    link.inertia = m.linkMass * m.linkLength * m.linkLength / 3;
    link.shapes = {bar(0, m.linkLength - kSliderLength, -0.04, 0.04)};

    BodyDef slider;
    slider.name = name + "_slider";
    slider.position = pose.slider;
    slider.mass = m.sliderMass;
    slider.inertia = m.sliderMass * kSliderLength * kSliderLength / 12;
    slider.shapes = {bar(-kSliderLength, 0, -0.025, 0.025)};

    BodyDef paddle;
    paddle.name = name + "_paddle";
    paddle.position = pose.paddle;
    paddle.mass = m.paddleMass;
    paddle.inertia = m.paddleMass * 4 * m.paddleHalfWidth * m.paddleHalfWidth / 12;
    paddle.shapes = {
        bar(-m.paddleHalfWidth, m.paddleHalfWidth, sgn > 0 ? 0.0 : -0.06, sgn > 0 ? 0.06 : 0.0)};
    s.bodies.insert(s.bodies.end(), {link, slider, paddle});

    for (int j = 0; j < 3; ++j) {
      JointDef joint;
      joint.name = kHandJointNames[3 * f + j];
      joint.kind = j == kSlide ? JointDef::Kind::Prismatic : JointDef::Kind::Revolute;
      joint.bodyA = j == kProximal ? "world" : (j == kSlide ? link.name : slider.name);
      joint.bodyB = j == kProximal ? link.name : (j == kSlide ? slider.name : paddle.name);
      joint.anchor = j == kProximal ? pose.link : pose.paddle;
      joint.axis = Vec2(1, 0);
      joint.enableLimit = true;
      joint.lower = m.lower[3 * f + j];
      joint.upper = m.upper[3 * f + j];
      // Thesis gains are per unit inertia (an acceleration-level PD, 22 rad/s, critically damped):
      // scale both by the inertia each joint drives.
      joint.servo.enabled = true;
      joint.servo.kp = m.servoKp * inertia[3 * f + j];
      joint.servo.kd = 2 * std::sqrt(m.servoKp) * inertia[3 * f + j];
      joint.servo.target = 0;
      s.joints.push_back(joint);
    }
  }

  BodyDef box;
  box.name = kHandBoxName;
  box.mass = m.boxMass;
  box.fixedRotation = !m.turn;
  box.linearDamping = m.boxDamping;
  // The table's drag on the box's turning, at the same rate as on its sliding.
  if (m.turn) box.angularDamping = m.boxDamping;
  const double h = m.boxHalfSize;
  box.shapes = {bar(-h, h, -h, h)};
  s.bodies.push_back(box);

  for (int f = 0; f < 2; ++f) {
    CableDef band;
    band.name = kHandCableNames[f];
    const std::string paddle = std::string(fingerNames[f]) + "_paddle";
    band.start = {paddle, paddleCorner(m, f, 0)};
    band.end = {paddle, paddleCorner(m, f, 1)};
    PulleyDef wrap;
    wrap.kind = PulleyDef::Kind::Polygon;
    wrap.body = kHandBoxName;
    // Walking left to right, the top band has the box on its right (Left), the bottom one on its
    // left.
    wrap.side = f == 0 ? WrapSide::Left : WrapSide::Right;
    if (m.friction > 0) {  // the membrane grips the box's corners (docs/polygon_friction.md)
      wrap.grip = Grip::Capstan;
      wrap.mu = m.friction;
    }
    band.pulleys = {wrap};
    band.restLength = m.restLength();
    band.stiffness = m.stiffness;
    band.preload = m.preload;
    band.damping = m.damping;
    s.cables.push_back(band);
  }
  return s;
}

namespace {
HandModel handModel(const SceneParams& p) {
  HandModel m;
  m.stiffness = p.at("k");
  m.damping = p.at("damping");
  m.preload = p.at("preload");
  m.boxMass = p.at("box_mass");
  const double turn = p.at("turn");
  if (turn != 0 && turn != 1)
    throw InputError(kCommandLine, "--set turn", "must be 0 or 1" + gotValue(turn));
  m.turn = turn == 1;
  m.friction = p.at("mu");
  return m;
}
}  // namespace

SceneDef makeHandScene(const SceneParams& p) {
  return buildHandScene(handModel(p));
}

HandModel handModelWithSettings(const std::vector<std::pair<std::string, double>>& overrides) {
  return handModel(sceneParams(*findBuiltinScene("hand"), overrides));
}

}  // namespace cablelab

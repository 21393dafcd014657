// The two-finger soft hand of thesis chapter 4: its dimensions, joint limits and servo gains.
//
// One struct feeds the `hand` scene builder, the fingertip kinematics, the Jacobian controller
// and the reach sweep, so the scene and the controller's model can never disagree.
//
// Layout (seen from above, gravity off, metres): finger 0 ("top") and finger 1 ("bottom") have
// their proximal joints at (baseX, +/-baseY). Each finger is a link turning about its base
// (theta_p), a slider moving along the link (theta_l, the prismatic joint), and a paddle turning
// about the slider's tip (theta_d). The membrane runs between the paddle's two corners on the
// face towards the box. At q = 0 (the pinch pose) both fingers are horizontal, the paddles'
// centres sit at (0, +/-baseY) and the box (centre (0, 0)) presses into both membranes.
#pragma once

#include <Eigen/Core>
#include <array>

#include "engine/core/math.h"
#include "engine/model/scene.h"

namespace cablelab {

/// Actuated joints in controller order: top proximal, top slide, top distal, then the same for
/// the bottom finger. Radians for the revolute joints, metres for the slides.
using HandJoints = Eigen::Matrix<double, 6, 1>;

/// Joint i of finger f is HandJoints index 3 f + i.
enum HandJoint { kProximal = 0, kSlide = 1, kDistal = 2 };

struct HandModel {
  double baseX = -2.0;           ///< x of both proximal joints (m)
  double baseY = 0.2;            ///< |y| of the proximal joints and paddle centres at q = 0 (m)
  double linkLength = 2.0;       ///< base to distal joint at theta_l = 0 (m)
  double paddleHalfWidth = 0.6;  ///< membrane corners at +/- this along the paddle (m)
  double paddleOffset = 0.05;    ///< corners sit this far from the distal joint towards the box (m)
  double boxHalfSize = 0.25;     ///< the square manipuland's half side (m)
  double boxMass = 1.0;          ///< kg
  /// Box linear damping (1/s), the table's viscous drag on the box (seen from above). The
  /// membranes hold the box sideways only through their bend (about 40 N/m at the pinch, a
  /// 1 Hz mode for the 1 kg box) and do not damp that motion at all; with 1/s the mode has
  /// damping ratio 0.08 and the outer loop (k_p / T = 1.9 1/s, k_d = 0.58) excites it into a
  /// growing oscillation. 6/s gives damping ratio 0.5.
  double boxDamping = 6.0;
  double linkMass = 1.0;     ///< kg
  double sliderMass = 0.5;   ///< kg
  double paddleMass = 1.0;   ///< kg (the membranes get their full tension on jointed bodies)
  double stiffness = 150.0;  ///< membrane k_s (N/m)
  double damping = 550.0;    ///< membrane b_s (N s/m)
  double preload = 0.3;      ///< membrane pre-stretch (m): tension k (stretch + preload)
  double servoKp = 500.0;    ///< inner PD stiffness per unit effective inertia (1/s^2)
  /// The box may turn (scene parameter `turn`): the statics and the controller work in
  /// (x, y, theta) (docs/hand.md). Off, the box keeps its angle, the thesis's model.
  bool turn = false;
  /// Friction between membrane and box (scene parameter `mu`): each corner a membrane wraps holds
  /// while T_high <= T_low e^(mu theta_i) (docs/control.md, "Membrane friction"). 0: none, the
  /// thesis's model.
  double friction = 0.0;
  std::array<double, 6> lower = {-0.7, -0.6, -0.7, -0.7, -0.6, -0.7};  ///< joint limits (rad, m)
  std::array<double, 6> upper = {0.7, 0.9, 0.7, 0.7, 0.9, 0.7};        ///< joint limits (rad, m)

  /// +1 for the top finger (membrane below its paddle), -1 for the bottom one.
  static double side(int finger) { return finger == 0 ? 1.0 : -1.0; }
  Vec2 base(int finger) const { return {baseX, side(finger) * baseY}; }
  /// Membrane rest length (m): the corner-to-corner distance.
  double restLength() const { return 2 * paddleHalfWidth; }
  /// Clamps every joint value into its limits.
  HandJoints clamp(const HandJoints& q) const;
  /// The non-grasping start pose: both fingers swung open, paddles kept parallel to the box.
  HandJoints openPose() const;
  /// Effective inertia each servo drives at q = 0 (kg m^2 or kg): everything distal of the joint.
  std::array<double, 6> effectiveInertia() const;
};

/// Body and joint names of the scene, joint j of the scene = HandJoints index j.
inline constexpr const char* kHandJointNames[6] = {
    "top_proximal", "top_slide", "top_distal", "bottom_proximal", "bottom_slide", "bottom_distal"};
inline constexpr const char* kHandBoxName = "box";
inline constexpr const char* kHandCableNames[2] = {"top_membrane", "bottom_membrane"};

/// The `hand` scene at the pinch pose q = 0 (joint coordinates are zero there). Gravity off.
SceneDef buildHandScene(const HandModel& m);

}  // namespace cablelab

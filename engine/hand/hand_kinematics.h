// Forward kinematics of the hand's fingertips (the membrane corners) and its analytic Jacobian.
//
// Fingertip vector layout (8 x 1, metres), the order the statics sensitivity uses:
//   (a0.x, a0.y, b0.x, b0.y, a1.x, a1.y, b1.x, b1.y)
// with cable 0 the top membrane, cable 1 the bottom one, a the left corner (the cable's start)
// and b the right corner (its end).
#pragma once

#include <Eigen/Core>

#include "engine/hand/hand_model.h"

namespace cablelab {

using FingertipPoints = Eigen::Matrix<double, 8, 1>;
/// d(fingertip points)/d(actuated joints): 8 x 6 (m/rad or m/m).
using FingertipJacobian = Eigen::Matrix<double, 8, 6>;

/// World pose of one finger's three bodies (link, slider, paddle); origins in metres, angles rad.
struct FingerPose {
  Vec2 link, slider, paddle;
  double linkAngle = 0, sliderAngle = 0, paddleAngle = 0;
};

/// Body poses of finger `finger` (0 top, 1 bottom) at joints q. Bodies' origins: the link at the
/// base, the slider and the paddle at the distal joint.
FingerPose fingerPose(const HandModel& m, const HandJoints& q, int finger);

/// The rigid pinch centred at box position g: both paddles face-on (horizontal) with their centres
/// at g +/- (0, baseY), as at q = 0 about the origin. Not clamped to the joint limits.
HandJoints pinchJoints(const HandModel& m, const Vec2& g);

/// Whether pinchJoints(m, g) is within every joint limit (the fingertips' own reach).
bool pinchWithinLimits(const HandModel& m, const Vec2& g);

/// Membrane corner in the paddle frame: corner 0 (left, cable start) or 1 (right, cable end).
Vec2 paddleCorner(const HandModel& m, int finger, int corner);

/// The four membrane corners in world coordinates.
FingertipPoints fingertipPoints(const HandModel& m, const HandJoints& q);

/// Analytic d(fingertipPoints)/dq.
FingertipJacobian fingertipJacobian(const HandModel& m, const HandJoints& q);

/// Whether both membranes wrap the box at centre p face-on (each fingertip beside its face's
/// corner, below/above it), the configuration the reduction assumes.
bool wrapsFaceOn(const HandModel& m, const FingertipPoints& tips, const Vec2& p);

/// How far (m) the box at p is from no longer wrapping face-on: the smallest slack of the
/// conditions wrapsFaceOn() checks (negative when one fails).
double faceOnMargin(const HandModel& m, const FingertipPoints& tips, const Vec2& p);

/// The face-on conditions one by one, each linear in the fingertips and the box centre. Per
/// finger f, rows 6 f + 0..5: the left corner beside the box's left face, the right corner beside
/// its right face, then for the left and the right corner its height above the centre below +h
/// and above -h (on the wrapped face's side). faceOnMargin() is the smallest value.
struct FaceOnTerms {
  Eigen::Matrix<double, 12, 1> value;  ///< slack of each condition (m)
  Eigen::Matrix<double, 12, 8> dTips;  ///< d value / d fingertip points
  Eigen::Matrix<double, 12, 2> dBox;   ///< d value / d box centre
  Eigen::Matrix<double, 12, 1> dAngle = Eigen::Matrix<double, 12, 1>::Zero();  ///< d / d angle
};
FaceOnTerms faceOnTerms(const HandModel& m, const FingertipPoints& tips, const Vec2& p);
/// The same conditions for a box turned by `angle` (rad): checked in the box's frame, where the
/// fingertips are R(-angle) (tip - p); dAngle is their derivative in the angle.
FaceOnTerms faceOnTerms(const HandModel& m, const FingertipPoints& tips, const Vec2& p,
                        double angle);

}  // namespace cablelab

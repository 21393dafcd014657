#include "engine/hand/hand_kinematics.h"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace cablelab {

HandJoints HandModel::clamp(const HandJoints& q) const {
  HandJoints c;
  for (int i = 0; i < 6; ++i) c[i] = std::min(upper[i], std::max(lower[i], q[i]));
  return c;
}

HandJoints HandModel::openPose() const {
  HandJoints q = HandJoints::Zero();
  // Swung apart by 0.35 rad; the distal joints keep the paddles horizontal, face-on to the box.
  q[kProximal] = 0.35, q[kDistal] = -0.35;
  q[3 + kProximal] = -0.35, q[3 + kDistal] = 0.35;
  return q;
}

FingerPose fingerPose(const HandModel& m, const HandJoints& q, int finger) {
  const double tp = q[3 * finger + kProximal];
  const double reach = m.linkLength + q[3 * finger + kSlide];
  FingerPose pose;
  pose.link = m.base(finger);
  pose.linkAngle = tp;
  pose.slider = pose.link + reach * Vec2(std::cos(tp), std::sin(tp));
  pose.sliderAngle = tp;
  pose.paddle = pose.slider;
  pose.paddleAngle = tp + q[3 * finger + kDistal];
  return pose;
}

HandJoints pinchJoints(const HandModel& m, const Vec2& g) {
  HandJoints q;
  for (int f = 0; f < 2; ++f) {
    const Vec2 d = g + Vec2(0, HandModel::side(f) * m.baseY) - m.base(f);
    const double tp = std::atan2(d.y(), d.x());
    q[3 * f + kProximal] = tp;
    q[3 * f + kSlide] = d.norm() - m.linkLength;
    q[3 * f + kDistal] = -tp;
  }
  return q;
}

bool pinchWithinLimits(const HandModel& m, const Vec2& g) {
  const HandJoints q = pinchJoints(m, g);
  for (int j = 0; j < 6; ++j)
    if (q[j] < m.lower[j] || q[j] > m.upper[j]) return false;
  return true;
}

Vec2 paddleCorner(const HandModel& m, int finger, int corner) {
  return {corner == 0 ? -m.paddleHalfWidth : m.paddleHalfWidth,
          -HandModel::side(finger) * m.paddleOffset};
}

FingertipPoints fingertipPoints(const HandModel& m, const HandJoints& q) {
  FingertipPoints tips;
  for (int f = 0; f < 2; ++f) {
    const FingerPose pose = fingerPose(m, q, f);
    for (int c = 0; c < 2; ++c)
      tips.segment<2>(4 * f + 2 * c) =
          pose.paddle + rotate(paddleCorner(m, f, c), pose.paddleAngle);
  }
  return tips;
}

FingertipJacobian fingertipJacobian(const HandModel& m, const HandJoints& q) {
  FingertipJacobian J = FingertipJacobian::Zero();
  for (int f = 0; f < 2; ++f) {
    const FingerPose pose = fingerPose(m, q, f);
    const Vec2 axis(std::cos(pose.linkAngle), std::sin(pose.linkAngle));
    for (int c = 0; c < 2; ++c) {
      const Vec2 arm = rotate(paddleCorner(m, f, c), pose.paddleAngle);  // distal joint -> corner
      const Vec2 corner = pose.paddle + arm;
      // Proximal turns everything about the base; the slide moves along the link; the distal
      // joint turns the paddle about the slider tip.
      J.block<2, 1>(4 * f + 2 * c, 3 * f + kProximal) = perp(corner - pose.link);
      J.block<2, 1>(4 * f + 2 * c, 3 * f + kSlide) = axis;
      J.block<2, 1>(4 * f + 2 * c, 3 * f + kDistal) = perp(arm);
    }
  }
  return J;
}

FaceOnTerms faceOnTerms(const HandModel& m, const FingertipPoints& tips, const Vec2& p) {
  const double h = m.boxHalfSize;
  FaceOnTerms t;
  t.dTips.setZero(), t.dBox.setZero();
  for (int f = 0; f < 2; ++f) {
    const double s = HandModel::side(f);
    const int row = 6 * f, a = 4 * f, b = 4 * f + 2;  // rows, and the corners' x in the tips
    // Each corner must sit beside the box and between its faces, on the wrapped face's side.
    t.value[row] = (p.x() - h) - tips[a];
    t.dBox(row, 0) = 1, t.dTips(row, a) = -1;
    t.value[row + 1] = tips[b] - (p.x() + h);
    t.dBox(row + 1, 0) = -1, t.dTips(row + 1, b) = 1;
    for (int c = 0; c < 2; ++c) {
      const int y = 4 * f + 2 * c + 1, r = row + 2 + 2 * c;
      const double depth = s * (tips[y] - p.y());  // the corner's height above the centre
      t.value[r] = h - depth;
      t.dTips(r, y) = -s, t.dBox(r, 1) = s;
      t.value[r + 1] = depth + h;
      t.dTips(r + 1, y) = s, t.dBox(r + 1, 1) = -s;
    }
  }
  return t;
}

FaceOnTerms faceOnTerms(const HandModel& m, const FingertipPoints& tips, const Vec2& p,
                        double angle) {
  FingertipPoints local;  // the fingertips in the box's frame, the box at its origin
  for (int i = 0; i < 4; ++i) local.segment<2>(2 * i) = rotate(tips.segment<2>(2 * i) - p, -angle);
  const FaceOnTerms boxFrame = faceOnTerms(m, local, Vec2::Zero());
  const Eigen::Matrix2d back = Eigen::Rotation2Dd(-angle).toRotationMatrix();  // d local / d tip
  FaceOnTerms t;
  t.value = boxFrame.value;
  t.dBox.setZero(), t.dAngle.setZero();
  for (int i = 0; i < 4; ++i) {
    const auto dLocal = boxFrame.dTips.middleCols<2>(2 * i);
    t.dTips.middleCols<2>(2 * i) = dLocal * back;
    t.dBox -= dLocal * back;
    // d/d angle of R(-angle) v is -perp(R(-angle) v).
    t.dAngle -= dLocal * perp(local.segment<2>(2 * i));
  }
  return t;
}

double faceOnMargin(const HandModel& m, const FingertipPoints& tips, const Vec2& p) {
  return faceOnTerms(m, tips, p).value.minCoeff();
}

bool wrapsFaceOn(const HandModel& m, const FingertipPoints& tips, const Vec2& p) {
  return faceOnMargin(m, tips, p) > 0;
}
}  // namespace cablelab

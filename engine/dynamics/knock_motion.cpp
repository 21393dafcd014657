#include "engine/dynamics/knock_motion.h"

#include <algorithm>
#include <cmath>

namespace cablelab {

namespace {

Vec3 poseOf(const BodyState& b) {
  return Vec3(b.position.x(), b.position.y(), b.angle);
}

Vec3 rateOf(const BodyState& b) {
  return Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity);
}

}  // namespace

double deviationFromPrediction(std::span<const BodyState> start,
                               std::span<const BodyState> predicted, std::span<const BodyState> end,
                               std::span<const char> jointed, double dt) {
  double worst = 0;
  for (size_t b = 0; b < start.size(); ++b) {
    if (jointed[b]) continue;
    const Vec3 off = poseOf(end[b]) - poseOf(start[b]) - dt * rateOf(predicted[b]);
    worst = std::max(worst, off.head<2>().norm() + std::abs(off.z()));
  }
  return worst;
}

double knockTime(std::span<const BodyState> start, std::span<const BodyState> predicted,
                 std::span<const BodyState> end, double dt) {
  double worst = 0;
  size_t knocked = 0;
  for (size_t b = 0; b < start.size(); ++b) {
    const Vec3 off = poseOf(end[b]) - poseOf(start[b]) - dt * rateOf(predicted[b]);
    if (off.head<2>().norm() + std::abs(off.z()) > worst) {
      worst = off.head<2>().norm() + std::abs(off.z());
      knocked = b;
    }
  }
  // x1 - x0 - dt v1 = t (v0 - v1): least squares for t, kept only where it explains the end pose.
  const Vec3 off = poseOf(end[knocked]) - poseOf(start[knocked]) - dt * rateOf(end[knocked]);
  const Vec3 change = rateOf(predicted[knocked]) - rateOf(end[knocked]);
  if (!(change.squaredNorm() > 0)) return 0;
  const double t = off.dot(change) / change.squaredNorm();
  if (!(t > 0 && t < dt)) return 0;
  return (off - t * change).norm() < 0.1 * worst ? t : 0.0;
}

void motionAfterKnock(std::span<const BodyState> start, std::span<const BodyState> predicted,
                      std::span<const BodyState> end, double dt, double knock,
                      std::vector<BodyState>& motion) {
  motion.assign(start.begin(), start.end());
  for (size_t b = 0; b < start.size(); ++b) {
    BodyState& m = motion[b];
    m.position += knock * predicted[b].velocity;
    m.angle += knock * predicted[b].angularVelocity;
    m.velocity = (end[b].position - m.position) / (dt - knock);
    m.angularVelocity = (end[b].angle - m.angle) / (dt - knock);
  }
}

void backAfterKnock(std::span<const BodyState> after, std::span<BodyState> end,
                    std::span<const Vec3> loads, const Vec2& gravity, std::span<const char> jointed,
                    double again, double t) {
  for (size_t b = 0; b < after.size(); ++b) {
    BodyState& s = end[b];
    s.position = after[b].position + t * after[b].velocity;
    s.angle = after[b].angle + t * after[b].angularVelocity;
    s.angularVelocity -= again * s.invInertia * loads[b].z();
    if (s.invMass > 0 && !jointed[b])
      s.velocity -= again * (gravity + s.invMass * loads[b].head<2>());
  }
}

}  // namespace cablelab

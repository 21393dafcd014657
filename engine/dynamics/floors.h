// Floors (docs/floors.md): a cable segment cannot go below zero length. A segment
// between two different bodies, one of which the solve moves, that is short (kFloorWatch, or
// what its ends can close within the step; its length between its contact points: a circle's
// tangent point, floorGap) gets a unilateral row keeping it at least kFloorLength long, so a body
// that reaches its pulley stops there (an inelastic stop, as a real block at a real pulley).
// Both cable solves (the midpoint one and the main one with joints) add these rows; a floor that
// pushes in the midpoint solve hands the step to the main one. Private to engine/dynamics.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>

#include "engine/cable/cable.h"
#include "engine/dynamics/length_targets.h"

namespace cablelab {

inline constexpr double kFloorWatch = 0.5;    ///< m: segments shorter than this get a floor row
inline constexpr double kFloorLength = 0.01;  ///< m: the closest two points of a segment come
/// m: a body this far inside an elastic cable's floor came in while the cable was slack
/// (staysSlack); one less deep sank in by the step's linearisation (a hand's tendons, 0.5 mm).
inline constexpr double kCameInsideFloor = 0.1 * kFloorLength;
/// m: a cable no longer than this has no floors. One of kFloorLength fought a rope that short for
/// its own length: a 5 mm pendulum was held at 7.5 mm, a 1 cm one lost all its swing in 15 s.
inline constexpr double kShortestFlooredCable = 4 * kFloorLength;

// m/s: a body arriving at its floor (or a hull contact, hull_contacts.h) slower than this stops
// there whatever its restitution, as at a Box2D contact (b2_velocityThreshold), so that with e < 1
// its bounces die out and it rests. The speed is the one the step starts with, which the floor held
// at 0 for a body resting there: not Box2D's 1 m/s (for the g h its velocity solve sees), which
// stopped an Atwood's light side reaching its wheel at 0.9 m/s dead in a conservative scene.
inline constexpr double kSlowestBounce = 0.25;

/// Whether `cable` gets floors (kShortestFlooredCable).
inline bool hasFloors(const Cable& cable) {
  return cable.restLength() > kShortestFlooredCable;
}

/// Which end of segment (p, q) is a circle when the other is a point (0: p, 1: q), else -1.
inline int rimEnd(const WrapPoint& p, const WrapPoint& q) {
  if ((p.radius == 0) == (q.radius == 0)) return -1;
  return p.radius != 0 ? 0 : 1;
}

/// How far point x is outside its floor at the circle (centre c, radius r): |x - c| - sqrt(r^2 +
/// kFloorLength^2), zero where the point's tangent length to the circle, sqrt(|x - c|^2 - r^2)
/// (the length of a segment from x that leaves the circle on its tangent), is kFloorLength, and
/// negative closer in or inside. A floor along the segment's direction (floorNormal) stops a point
/// that runs into the tangent point; one that comes at the rim from the side (a weight that swung
/// onto a winch drum) it let slide past the tangent point into the drum, where the cable, left
/// with a segment of no length, let it fall. So a segment between a point and a circle gets a
/// second floor row, on this clearance. It holds the tangent length at kFloorLength as a row on
/// that length would, but near linearly: the length's gradient grows as 1 / L at the rim (53 at
/// the floor of a 0.53 m drum), and Newton on it diverged where a weight rested at a drum; its
/// start-of-step fallback left the weight 1 mm inside and the rope 2 cm long. `gradient` gets
/// d/dx: the unit vector from c to x.
inline double rimClearance(const Vec2& x, const Vec2& c, double r, Vec2& gradient) {
  const Vec2 out = x - c;
  const double d = out.norm();
  gradient = d > 0 ? Vec2(out / d) : Vec2(1, 0);
  return d - std::sqrt(r * r + kFloorLength * kFloorLength);
}

/// The tangent length sqrt(|x - c|^2 - r^2) itself (inside: |x - c| - r), `gradient` its d/dx
/// taken at a length of at least kFloorLength / 4.
inline double tangentLength(const Vec2& x, const Vec2& c, double r, Vec2& gradient) {
  const Vec2 out = x - c;
  const double d2 = out.squaredNorm(), r2 = r * r;
  if (d2 > r2) {
    const double length = std::sqrt(d2 - r2);
    gradient = out / std::max(length, 0.25 * kFloorLength);
    return length;
  }
  const double d = std::sqrt(d2);
  gradient = d > 0 ? Vec2(out / d) : Vec2(1, 0);
  return d - std::abs(r);
}

/// The rim row's gap for point x (on `pointBody`, -1 the world) at the circle (c, r), kFloorLength
/// at its floor, and its d/dx. A point on a body takes kFloorLength plus its clearance: a weight
/// swung onto a winch drum. A point fixed in the world takes the tangent length: a trolley that
/// runs into the end of its zipline, along the clearance, sank 3 mm onto the anchor and its rope
/// ran 6 cm long (2 mm along the tangent length, whose steep gradient holds the trolley).
inline double rimGap(int pointBody, const Vec2& x, const Vec2& c, double r, Vec2& gradient) {
  return pointBody < 0 ? tangentLength(x, c, r, gradient)
                       : kFloorLength + rimClearance(x, c, r, gradient);
}

/// Whether segment (p, q) runs from a circle to a point on a body that is at its rim floor (the
/// rim row's gap within kLengthSlop of kFloorLength, or inside it).
inline bool atRimFloor(const WrapPoint& p, const WrapPoint& q) {
  const int rim = rimEnd(p, q);
  if (rim < 0) return false;
  const WrapPoint &circle = rim == 0 ? p : q, &point = rim == 0 ? q : p;
  if (point.body < 0) return false;
  Vec2 gradient;
  return rimGap(point.body, point.world, circle.world, circle.radius, gradient) <
         kFloorLength + kLengthSlop;
}

/// The gap a floor keeps open: the segment's length as the path has it, between its contact
/// points (a circle's tangent point). Next to a wheel that is the tangent segment, which goes to
/// zero where a box hauled up along it reaches the rim. With `rim` (a point-circle segment's
/// second row), rimGap: kFloorLength - gap is then that row's error, as for the others.
inline double floorGap(const WrapPoint& p, const WrapPoint& q, bool rim = false) {
  if (rim) {
    const bool circleFirst = rimEnd(p, q) == 0;
    const WrapPoint &circle = circleFirst ? p : q, &point = circleFirst ? q : p;
    Vec2 gradient;
    return rimGap(point.body, point.world, circle.world, circle.radius, gradient);
  }
  return (q.arriving() - p.leaving()).norm();
}

/// Where segment (p, q)'s far contact point moves relative to its near one over a sub-step h, at
/// the velocities they have now plus a step of gravity on a dynamic body (the world and kinematic
/// bodies keep their velocity).
inline Vec2 floorDrift(const WrapPoint& p, const WrapPoint& q, std::span<const BodyState> bodies,
                       double h, const Vec2& gravity) {
  auto velocity = [&](const WrapPoint& w, const Vec2& at) -> Vec2 {
    if (w.body < 0) return Vec2::Zero();
    const BodyState& b = bodies[w.body];
    const Vec2 v = pointVelocity(b, at);
    return b.invMass > 0 ? Vec2(v + h * gravity) : v;
  };
  return h * (velocity(q, q.arriving()) - velocity(p, p.leaving()));
}

/// Whether segment i (points i and i + 1) of `path` is near its floor this sub-step: its ends are
/// on different bodies, one of which the solve moves (`moved(body)`; the world, -1, never moves),
/// and it is shorter than kFloorWatch or than the way its ends can close within the sub-step
/// (twice floorDrift: a body at 50 m/s covers 0.8 m in a 60 Hz step).
template <class Moved>
bool nearFloor(std::span<const WrapPoint> path, size_t i, std::span<const BodyState> bodies,
               double h, const Vec2& gravity, Moved moved) {
  const int a = path[i].body, b = path[i + 1].body;
  if (a == b || !((a >= 0 && moved(a)) || (b >= 0 && moved(b)))) return false;
  const double gap = floorGap(path[i], path[i + 1]);
  return gap < kFloorWatch || gap < 2 * floorDrift(path[i], path[i + 1], bodies, h, gravity).norm();
}

/// Whether `cable` is elastic and stays slack over the sub-step: its stretch, with every segment
/// opening by twice the way its ends can move apart (floorDrift), stays below zero. Nothing pulls
/// along it, so its direction may turn over: a body passing over the anchor of a slack tether
/// passes on, where a floor would stop it and take its energy.
inline bool staysSlack(const Cable& cable, std::span<const BodyState> bodies, double h,
                       const Vec2& gravity) {
  if (!cable.elastic()) return false;
  const auto& path = cable.path();
  double stretch = cable.stretch();
  for (size_t i = 0; i + 1 < path.size() && stretch < 0; ++i)
    stretch += 2 * floorDrift(path[i], path[i + 1], bodies, h, gravity).norm();
  return stretch < 0;
}

/// Whether segment i of elastic `cable` runs from an end pinned in the world (its anchor) and the
/// cable is slack whenever that segment is at its floor: its stretch with the segment at
/// kFloorLength and every other segment as long as it gets while its far end moves straight by
/// twice its drift (floorDrift; along a straight motion a length is largest at one end). A body
/// passes over the pin while nothing pulls, and the segment only turns over about it, as a
/// tether about its anchor. (staysSlack reads the whole step: a bob heading through its slack
/// tether's anchor at 10 m/s and 30 Hz would come taut on the far side, and the floor stopped it
/// at the anchor, 81% of the energy in one step; docs/floors.md.)
inline bool slackAtPinnedFloor(const Cable& cable, size_t i, std::span<const BodyState> bodies,
                               double h, const Vec2& gravity) {
  const auto& path = cable.path();
  const bool pinned =
      (i == 0 && path.front().body < 0) || (i + 2 == path.size() && path.back().body < 0);
  if (!cable.elastic() || !pinned) return false;
  double stretch = cable.stretch() - floorGap(path[i], path[i + 1]) + kFloorLength;
  for (size_t j = 0; j + 1 < path.size() && stretch < 0; ++j) {
    if (j == i) continue;
    const Vec2 d0 = path[j + 1].arriving() - path[j].leaving();
    const Vec2 d1 = d0 + 2 * floorDrift(path[j], path[j + 1], bodies, h, gravity);
    stretch += std::max(0.0, d1.norm() - d0.norm());
  }
  return stretch < 0;
}

/// Whether segment i of `cable`'s path needs a floor row this sub-step: the cable has floors, the
/// segment is near its floor and does not run to a point that may enter a polygon's hull
/// (Cable::mayEnterHull), and the cable does not stay slack, over the step or wherever the
/// segment is at its floor next to a pin (slackAtPinnedFloor).
template <class Moved>
bool needsFloor(const Cable& cable, size_t i, std::span<const BodyState> bodies, double h,
                const Vec2& gravity, Moved moved) {
  return hasFloors(cable) && !cable.mayEnterHull(i) &&
         nearFloor(cable.path(), i, bodies, h, gravity, moved) &&
         !staysSlack(cable, bodies, h, gravity) &&
         !slackAtPinnedFloor(cable, i, bodies, h, gravity);
}

/// Whether segment i of elastic `cable`, between a point on a moving body and a circle, gets the
/// circle's rim row (rimGap) alone where needsFloor gives it none because the cable is slack: the
/// disc stops the body as it would were the rope taut. A bob on a slack bungee flew into a world
/// drum's disc, where its path has no tangent (the segment out of J); the rope, taut again with the
/// bob inside, gained up to 28% of a busy scene's energy in a step (docs/floors.md, "The disc of a
/// round pulley"). A point already inside the disc gets none: held at its depth, it slid round
/// the inside of the rim.
template <class Moved>
bool needsDiscFloor(const Cable& cable, size_t i, std::span<const BodyState> bodies, double h,
                    const Vec2& gravity, Moved moved) {
  const auto& path = cable.path();
  const int rim = rimEnd(path[i], path[i + 1]);
  if (rim < 0 || !cable.elastic() || !hasFloors(cable) || cable.mayEnterHull(i)) return false;
  const WrapPoint& point = rim == 0 ? path[i + 1] : path[i];
  if (point.body < 0 || !moved(point.body)) return false;
  const double gap = floorGap(path[i], path[i + 1], true);
  if (gap < kFloorLength - 0.1 * kFloorLength) return false;
  const bool near =
      gap < kFloorWatch || gap < 2 * floorDrift(path[i], path[i + 1], bodies, h, gravity).norm();
  return near && !needsFloor(cable, i, bodies, h, gravity, moved);
}

/// The direction n a floor row measures segment (p, q) along: its constraint is
/// n . (q - p) >= kFloorLength at the end of the sub-step (contacts carried with their bodies).
/// If the contacts' straight relative motion over the sub-step (floorDrift) comes within
/// 1.5 kFloorLength of each other, a body is heading into its pulley: n is the segment's direction
/// now, and measured along it a body that would pass through its pulley within the step goes
/// negative instead of coming out the other side at a length that looks allowed. Else the body
/// passes beside the pulley: n is the direction at the end of that motion, so the row is the
/// segment's length, which stays long (measured along the old direction, a body flying past an
/// anchor would read as passing through it and be thrown back).
inline Vec2 floorNormal(const WrapPoint& p, const WrapPoint& q, std::span<const BodyState> bodies,
                        double h, const Vec2& gravity) {
  const Vec2 d0 = q.arriving() - p.leaving(), drift = floorDrift(p, q, bodies, h, gravity);
  const double moved2 = drift.squaredNorm();
  const double t = moved2 > 0 ? std::clamp(-d0.dot(drift) / moved2, 0.0, 1.0) : 0.0;
  const Vec2 d1 = d0 + drift;
  if ((d0 + t * drift).norm() < 1.5 * kFloorLength || !(d1.norm() > 0)) return d0.normalized();
  return d1.normalized();
}

/// When, within (0, dt], segment (p, q) first closes to its floor if every body moves straight
/// with its velocity in `motion` from its pose there: its two points come within kFloorLength,
/// or a point's tangent length to a circle end comes down to kFloorLength. World cuts the step
/// there (an event, like a wrap change), so that the floor rows meet the arrival from a pose
/// where they are near linear: a box thrown at 4 m/s at a small wheel passed through its rim in
/// one sub-step, the tangent length's gradient growing as 1 / L on the way. nullopt if it does
/// not close within dt, or is within 2 kFloorLength already (resting at its floor).
inline std::optional<double> floorArrival(const WrapPoint& p, const WrapPoint& q,
                                          std::span<const BodyState> motion, double dt) {
  if (p.body == q.body || (p.radius != 0 && q.radius != 0)) return std::nullopt;
  auto velocity = [&](const WrapPoint& w) -> Vec2 {
    if (w.body < 0) return Vec2::Zero();
    return pointVelocity(motion[w.body], w.world);
  };
  // |d + t v|^2 = reach^2, d from p to q (a circle's centre: its world point).
  const Vec2 d = q.world - p.world, v = velocity(q) - velocity(p);
  const double r2 = std::max(p.radius * p.radius, q.radius * q.radius);
  const double reach2 = r2 + kFloorLength * kFloorLength;
  const double a = v.squaredNorm(), b = d.dot(v), c = d.squaredNorm() - reach2;
  if (!(b < 0) || d.squaredNorm() <= r2 + 4 * kFloorLength * kFloorLength) return std::nullopt;
  const double disc = b * b - a * c;
  if (!(disc >= 0)) return std::nullopt;
  const double t = (-b - std::sqrt(disc)) / a;
  if (t > 0 && t <= dt) return t;
  return std::nullopt;
}

}  // namespace cablelab

// When, inside a sub-step, a moving point crosses a moving segment (docs/cables.md, "Events").
//
// Over a sub-step of length h Box2D moves every body on a straight line at its end-of-step
// velocity: x(t) = x0 + t v, theta(t) = theta0 + t omega (symplectic Euler). A point fixed on a
// body therefore moves on a line plus a turn, and a wrap change (a pulley joining or leaving a
// cable, a polygon vertex entering or leaving its chain) happens where a signed distance along
// that motion changes sign. These functions find the first such instant; they know nothing of
// cables, so every pulley kind (point, polygon vertex, circle) can state its own event as a
// signed-distance function and reuse firstRise().
#pragma once

#include <cmath>
#include <optional>
#include <span>

#include "engine/cable/cable.h"

namespace cablelab {

/// A point fixed on a body (or the world, body -1), moving as Box2D integrates the body over a
/// sub-step: `motion` holds the start pose and the velocity it moves with.
struct MovingPoint {
  Vec2 origin = Vec2::Zero();    ///< body position at t = 0 (m)
  Vec2 velocity = Vec2::Zero();  ///< m/s
  double angle = 0;              ///< rad at t = 0
  double angularVelocity = 0;    ///< rad/s
  Vec2 local = Vec2::Zero();     ///< body frame (world frame for the world)
  /// at(0) and the speed bound |v| + |omega| |local|, set by on(): the early-outs read every
  /// point's several times.
  std::optional<Vec2> start;
  std::optional<double> speed;

  static MovingPoint on(std::span<const BodyState> motion, int body, const Vec2& local);
  /// The same with the body's cos and sin of its angle already known (many points on one body).
  static MovingPoint on(std::span<const BodyState> motion, int body, const Vec2& local, double c,
                        double s);
  /// World position at time t (s) into the sub-step.
  Vec2 at(double t) const {
    return origin + t * velocity + rotate(local, angle + t * angularVelocity);
  }
  Vec2 atStart() const { return start ? *start : at(0); }
};

/// Sample count that resolves the turns of the given points over h (a point on a body turning
/// by a quarter of a radian between samples cannot cross a line twice unseen at these sizes).
int crossingSamples(std::span<const MovingPoint> points, double h);

/// First t in (0, h] at which g goes from <= 0 to > 0 and `accept(t)` holds, located to
/// `tolerance` (s) by regula falsi. g is sampled at `samples` equal intervals first, so two
/// crossings closer than h / samples may be missed. nullopt: no such rise.
template <class G, class Accept>
std::optional<double> firstRise(G&& g, Accept&& accept, double h, int samples, double tolerance) {
  double t0 = 0, g0 = g(0.0);
  for (int i = 1; i <= samples; ++i) {
    const double t1 = h * i / samples, g1 = g(t1);
    if (g0 <= 0 && g1 > 0) {
      // Illinois regula falsi on [a, b] with g(a) <= 0 < g(b).
      double a = t0, b = t1, ga = g0, gb = g1;
      int side = 0;
      for (int it = 0; it < 100 && b - a > tolerance; ++it) {
        double t = (ga * b - gb * a) / (ga - gb);
        if (!(t > a && t < b)) t = 0.5 * (a + b);
        const double gt = g(t);
        if (gt > 0) {
          b = t, gb = gt;
          if (side == 1) ga *= 0.5;
          side = 1;
        } else {
          a = t, ga = gt;
          if (side == -1) gb *= 0.5;
          side = -1;
        }
      }
      if (accept(b)) return b;
    }
    t0 = t1, g0 = g1;
  }
  return std::nullopt;
}

/// True when p's signed distance from the line a-b cannot change sign in [0, h]: it starts
/// farther from zero than the points' speeds can carry it. Most points of a resting cable are
/// far from any event, and this spares them the sampling (each sample turns three points);
/// false says nothing. With `reach` (m): p cannot come within reach of the line either (circles).
bool sideCannotChange(const MovingPoint& a, const MovingPoint& b, const MovingPoint& p, double h,
                      double reach = 0);

/// A crossing of a segment: when, and where along it (0 at a, 1 at b).
struct Crossing {
  double time = 0;   ///< s into the sub-step
  double along = 0;  ///< segment parameter of the crossing point
};

/// First time in (0, h] at which p comes within `reach` (m) of the segment a-b's wrap side (the
/// wrapSideDistance of p goes from <= -reach to > -reach) between the segment's ends. Reach 0:
/// a point crosses; a circle's radius: the circle round p starts to cut the segment.
std::optional<Crossing> pointCrossesSegment(const MovingPoint& a, const MovingPoint& b,
                                            const MovingPoint& p, WrapSide side, double h,
                                            double reach = 0);

/// First time in (0, h] at which the path a -> p -> b stops bending round p the `side` way
/// (p's wrapSideDistance from the line a-b goes from > -reach to <= -reach): p, or the circle of
/// radius `reach` round it, leaves the path.
std::optional<double> turnStraightens(const MovingPoint& a, const MovingPoint& p,
                                      const MovingPoint& b, WrapSide side, double h,
                                      double reach = 0);

/// Locating tolerance of the events (s), relative to the sub-step.
inline double crossingTolerance(double h) {
  return 1e-10 * h;
}

}  // namespace cablelab

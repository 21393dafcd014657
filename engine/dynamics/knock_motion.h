// A knock inside Box2D's step (docs/knocks.md): Box2D resolves a knock between two polygons (its
// time-of-impact solve) or a push by a contact inside its step, and the contact catch moves bodies
// after it, so the bodies can end the step far from the motion the cable solve predicted and the
// wrap events were located on: a wrap change on the actual motion was never located, and at the
// next selection it moved the length by 1 to 14 mm. The step's actual motion is taken as the
// predicted one up to the knock and a straight one from there to the end pose; where a wrap event
// falls after the knock, the bodies go back along it to the event and the rest of the sub-step is
// stepped again from there. Private to engine/dynamics.
#pragma once

#include <span>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab {

/// m (a turn counts in rad): a body that ends its step further than this from its predicted pose
/// was moved by something the prediction did not know (Box2D's float rounding is 1e-6 m).
inline constexpr double kKnockDeviation = 1e-4;

/// The largest |x1 - x0 - dt v| + |theta1 - theta0 - dt omega| over the bodies not `jointed`: how
/// far the step ended (`end`) from the motion predicted from `start` at `predicted`'s velocities.
/// Jointed bodies are left out: Box2D's knock between polygons on pivots ignores the pivots, and
/// going back along it moved the hexagons' rope at other times, not less often (docs/knocks.md).
double deviationFromPrediction(std::span<const BodyState> start,
                               std::span<const BodyState> predicted, std::span<const BodyState> end,
                               std::span<const char> jointed, double dt);

/// When in [0, dt) the body furthest off its prediction was knocked: the time at which, moving at
/// its predicted velocity until then and at its end velocity after, it ends where it did (Box2D's
/// time-of-impact solve moves a bullet so). 0 where that does not fit the end pose (a push at the
/// step's start, the contact catch's move after it).
double knockTime(std::span<const BodyState> start, std::span<const BodyState> predicted,
                 std::span<const BodyState> end, double dt);

/// The motion after a knock at `knock`: the bodies where the prediction had them then, with the
/// velocities that carry them straight to `end`'s poses by dt (what the wrap events are located
/// on; a knock at 0 is the straight motion from the start pose to the end pose).
void motionAfterKnock(std::span<const BodyState> start, std::span<const BodyState> predicted,
                      std::span<const BodyState> end, double dt, double knock,
                      std::vector<BodyState>& motion);

/// The bodies (`end`, in place) moved back to time t of `after`, the motion after a knock at
/// `knock` (motionAfterKnock). Their velocities are the end's, less what the step's loads (`loads`,
/// per body: force and torque; gravity added to bodies with mass) gave them over the
/// dt - knock - t that will be stepped again, so that the loads do not work twice. A jointed body
/// (`jointed`) keeps its linear velocity (its joint holds it) and loses only the torque's part.
void backAfterKnock(std::span<const BodyState> after, std::span<BodyState> end,
                    std::span<const Vec3> loads, const Vec2& gravity, std::span<const char> jointed,
                    double again, double t);

}  // namespace cablelab

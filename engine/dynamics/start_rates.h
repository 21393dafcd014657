// The length rate a taut rigid cable starts a step with, matched to the step's integrator
// (docs/model.md, "Coupling to Box2D").
//
// A taut rigid cable's length does not change, so the rate J v it carries from one step to the
// next is the integrator's, not the motion's. The main solve (Box2D's symplectic Euler with the
// length held at the end of the step) ends a step of dt on the chord's rate, (dt / 2) L'' (L'' the
// length's second derivative along the motion, |v_across|^2 / l for a bob on a rope of length l);
// the midpoint rule ends a step on none. A step that starts on another rule's rate takes the
// difference out with an impulse along the cable: its tension reads m (rate) / dt too high and
// the energy of the rate is lost. That happens where the step changes: a step cut short at a wrap
// event (the main solve's chord rate of a whole step at the start of a cut of 1e-4 of one), the
// rest of the sub-step after it, and a hand-over between the main solve and the midpoint rule (a
// bob whose rope wraps a peg: its tension 17% high over the wrap step, 1.4e-3 of its energy lost).
// Such a rate is turned across the cable instead, the kinetic energy kept: the velocity is the
// one the step's rule would have carried, and the pose is untouched.
//
// The midpoint rule's own end rate is of second order, about h^2 L3 / 6 (L3 the length's third
// derivative along the motion: 3 |v_across| a_across / l for a bob), and a midpoint step that
// starts on a rate left by one of another length reads about 2 m (the rates' difference) / h
// off: the whole sub-step after a fast-catch refinement's parts, 3.8-9.5% at 30 Hz near a peg
// (docs/swings.md, "The fast catch near a peg"). That rate is scaled by the square of the
// steps' ratio.
#pragma once

#include <span>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab {

/// The step a cable's last solve ended on: its length (s) under the main solve, 0 under the
/// midpoint rule, kNoStartRate where its rate says nothing of a rule (slack, elastic, over wheels).
constexpr double kNoStartRate = -1;

/// What matchStartRates reads of the step about to be taken.
struct StartRateInput {
  std::span<const Cable> cables;      // with the step's wrap set and tensions solved
  std::span<const double> lastSteps;  // per cable: the step its rate was left by
  std::span<const double> nextSteps;  // per cable: the step about to be taken (same units)
  std::span<const char> excluded;     // per body: jointed or touching (left alone)
  int dragBody;                       // -1: none
  double h;                           // the sub-step (s)
  std::span<const double> lastMidpointSteps = {};  // per cable: its last midpoint step (0: none)
  double step = 0;                                 // the step about to be taken (s)
};

/// Turns the start rate of each taut rigid cable whose step changes to the rate its next step
/// ends on, keeping the kinetic energy of the bodies it changes. Only cables whose points between
/// the ends are fixed in the world and whose segments are far from their floors: pulleys on
/// moving bodies, wheels, and bodies that are jointed, touching, dragged or driven are left
/// alone, as is a rate further from the last step's than the step's own could leave (a knock).
/// Returns the bodies whose velocities changed (`bodies` updated).
std::vector<int> matchStartRates(const StartRateInput& in, std::vector<BodyState>& bodies);

/// The step each cable's solve just ended on (lastSteps for the next call): `dt` under the main
/// solve, 0 where `midpoint` (per cable) says the midpoint rule took it, kNoStartRate where its
/// rate says nothing (slack, elastic, over wheels).
/// `midpointSteps` (lastMidpointSteps for the next call): `dt` where the midpoint rule took it.
void recordStartRateSteps(std::span<const Cable> cables, std::span<const char> midpoint, double dt,
                          std::vector<double>& steps, std::vector<double>& midpointSteps);

}  // namespace cablelab

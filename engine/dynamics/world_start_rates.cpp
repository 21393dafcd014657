// World: the length rates taut rigid cables start a step with, matched to the step's rule and
// length where it changes (start_rates.h, docs/model.md, "Coupling to Box2D").
#include <algorithm>
#include <span>
#include <vector>

#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/midpoint_solver.h"
#include "engine/dynamics/start_rates.h"
#include "engine/dynamics/world.h"

namespace cablelab {

namespace {

// Per cable: 1 where the midpoint solve took it this step.
void markMidpointCables(size_t cables, std::span<const int> midpoint, std::vector<char>& took) {
  took.assign(cables, 0);
  for (const int c : midpoint) took[c] = 1;
}

}  // namespace

// After solveForces(dt, h): true if some velocity changed (solve again).
bool World::matchRates(double dt, double h) {
  if (!matchesStartRates_) return false;
  if (rateSteps_.size() != cables_.size()) rateSteps_.assign(cables_.size(), kNoStartRate);
  markMidpointCables(cables_.size(), midpointCables_, tookMidpoint_);
  rulesKept_ = true;  // until the step is taken (takesMidpointRule)
  nextSteps_.resize(cables_.size());
  for (size_t c = 0; c < cables_.size(); ++c) nextSteps_[c] = tookMidpoint_[c] ? 0.0 : dt;
  const std::vector<int> changed = matchStartRates(
      {cables_, rateSteps_, nextSteps_, excluded_, dragBody_, h, midpointSteps_, dt}, bodies_);
  for (const int b : changed) b2_->setVelocity(b, bodies_[b].velocity, bodies_[b].angularVelocity);
  if (!changed.empty()) b2_->readBodies(bodies_);
  return !changed.empty();
}

// Whether the midpoint solve takes an island's step of dt (in a sub-step of h). Once its start
// rates are matched to the rule it took, the step's solves keep that rule: changed with the
// tension the choice reads, it started the step on the other rule's rate and took it out with an
// impulse (a rope wrapping a peg read 22% high, then 21% low: docs/model.md, "Coupling to Box2D").
bool World::takesMidpointRule(std::span<const int> island, double dt, double h) {
  if (rulesKept_) return tookMidpoint_[island.front()] != 0;
  // A rope taut when the run starts (or the user sets the bodies' motion) was caught by nothing:
  // it counts as settled, so its swing starts on the rule it keeps (docs/swings.md).
  if (tautSteps_.size() != cables_.size()) {
    tautSteps_.assign(cables_.size(), 0);
    for (size_t c = 0; c < cables_.size(); ++c)
      if (cables_[c].stretch() >= -10 * kLengthSlop)
        tautSteps_[c] = MidpointSolver::kSettledTautSteps;
  }
  midpoint_->setTautSteps(tautSteps_);
  return midpoint_->applies(bodies_, cables_, island, excluded_, dt, h, gravity_);
}

// After Box2D's step of dt; `whole`: no knock took part of it back (the rates then say nothing).
void World::recordRates(double dt, bool whole) {
  markMidpointCables(cables_.size(), midpointCables_, tookMidpoint_);
  recordStartRateSteps(cables_, tookMidpoint_, dt, rateSteps_, midpointSteps_);
  if (!whole) std::fill(rateSteps_.begin(), rateSteps_.end(), kNoStartRate);
  // Steps each rigid cable has been taut in a row, pulling or within kSettledSlack of its length
  // (the tension a wrap event leaves can read 0): a rope just caught from slack keeps the main
  // solve until its catch has settled (MidpointSolver::setTautSteps, docs/swings.md).
  constexpr double kSettledSlack = 10 * kLengthSlop;
  tautSteps_.resize(cables_.size(), 0);
  for (size_t c = 0; c < cables_.size(); ++c) {
    const Cable& cable = cables_[c];
    const bool taut = cable.tension() > 0 || cable.stretch() >= -kSettledSlack;
    tautSteps_[c] = !cable.elastic() && taut ? std::min(tautSteps_[c] + 1, 1 << 20) : 0;
  }
}

}  // namespace cablelab

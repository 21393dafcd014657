// The kinetic energy a rigid rope's end-rate settle moves, put back (docs/swings.md, "The settle's
// energy").
//
// MidpointSolver::settleRates holds a taut rigid rope's end rate to the mean of its start and end
// rates with an impulse along the rope at the end of the step. The midpoint step before it keeps
// the energy exactly; the impulse does not: it takes a little energy on some steps and gives it on
// others, and the sum is a steady leak of a swing round a polygon peg. The change is put back by
// scaling the velocities the impulse moved, the rate it left scaled with them (by very nearly 1:
// the alternation the settle stops stays stopped).

#pragma once

#include <cmath>

#include <Eigen/Core>

namespace cablelab {

/// Largest share of the shifted bodies' kinetic energy the settle may move and have put back: a
/// larger change is a catch's (a rope going taut in the step), whose loss is the rope's.
constexpr double kMaxSettledEnergyShare = 1e-3;

/// The kinetic energy of the dofs `shift` moves (nonzero entries), at the velocities `v`, with the
/// dofs' inverse masses `invM` (0: not moved).
inline double kineticEnergyOfShifted(const Eigen::VectorXd& v, const Eigen::VectorXd& shift,
                                     const Eigen::VectorXd& invM) {
  double e = 0;
  for (Eigen::Index d = 0; d < v.size(); ++d)
    if (shift[d] != 0 && invM[d] > 0) e += 0.5 * v[d] * v[d] / invM[d];
  return e;
}

/// Scales the shifted dofs of `v` (the end velocities after the settle's `shift`, v = unshifted -
/// shift) back to the kinetic energy `before` they had without it, and `shift` with them. Left as
/// they are where the change is over kMaxSettledEnergyShare of `before`.
inline void keepSettledEnergy(Eigen::VectorXd& v, Eigen::VectorXd& shift,
                              const Eigen::VectorXd& invM, double before) {
  const double after = kineticEnergyOfShifted(v, shift, invM);
  if (!(after > 0) || !(std::abs(before - after) <= kMaxSettledEnergyShare * before)) return;
  const double scale = std::sqrt(before / after);
  for (Eigen::Index d = 0; d < v.size(); ++d)
    if (shift[d] != 0 && invM[d] > 0) {
      const double unshifted = v[d] + shift[d];
      v[d] *= scale;
      shift[d] = unshifted - v[d];
    }
}

}  // namespace cablelab

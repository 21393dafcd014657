// Damped Newton in p for the statics problem (statics.h): the fast path.
//
// Newton steps on E(p) with the analytic gradient and Hessian, a tiny Levenberg shift for the
// singular directions (non-unique minimisers) and a backtracking (Armijo) line search on E.
// E has a kink at every fingertip point of a taut cable; a minimiser there makes plain Newton
// crawl (each step overshoots the kink and is halved). With `detectFingertips` the solver tests
// the nearest fingertip point with the subgradient condition whenever the line search had to
// backtrack, and steps off a fingertip point an iterate lands on exactly (along the
// minimum-norm subgradient). Without it this is plain damped Newton.
#pragma once

#include <Eigen/Core>

#include "engine/statics/statics.h"

namespace cablelab {

struct NewtonOptions {
  int maxIterations = 60;        ///< Newton steps before giving up (result.converged = false)
  double forceTol = 1e-13;       ///< stop when |dE/dp| <= forceTol * max tension
  bool detectFingertips = true;  ///< test / step off fingertip points (false: plain Newton)
};

/// The Levenberg shift added to the Hessian's diagonal (N/m): 1e-12 trace + 0.1 |g| / scale.
/// Proportional to the gradient so that it vanishes at the solution (quadratic convergence)
/// yet bounds the step along a flat direction of a non-unique minimiser, where the Hessian is
/// singular and a pure Newton step would shoot along the valley.
double levenbergShift(const Eigen::Matrix2d& hessian, double gradientNorm, double scale);

/// Damped Newton from staticsInitialGuess(). Sets result.converged; result storage is reused
/// and nothing is allocated once it has the size. Never throws on a valid problem.
void solveStaticsNewton(const StaticsProblem& problem, StaticsResult& result,
                        const NewtonOptions& options = {});

/// Convenience form.
StaticsResult solveStaticsNewton(const StaticsProblem& problem, const NewtonOptions& options = {});

}  // namespace cablelab

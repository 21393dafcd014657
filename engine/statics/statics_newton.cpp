#include "engine/statics/statics_newton.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace cablelab {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kArmijo = 1e-4;
constexpr double kMinStep = 1e-12;      // line search gives up below this fraction of the step
constexpr int kAnchorCheckAfter = 12;   // also check fingertips after this many steps
constexpr double kSnapDistance = 1e-2;  // fraction of the length scale: "close to a fingertip"
constexpr int kMaxJumps = 4;            // jumps onto non-minimising fingertips before giving up

/// Backtracks from p + step until E decreases enough; returns the fraction taken (0: failed).
double lineSearch(const StaticsProblem& problem, const Vec2& p, double energy, const Vec2& step,
                  double slope, Vec2& next) {
  // Round-off allowance: near convergence E changes by less than its last bits.
  const double noise = 8 * kEps * std::max(energy, 0.0);
  for (double alpha = 1; alpha >= kMinStep; alpha *= 0.5) {
    next = p + alpha * step;
    if (staticsEnergy(problem, next) <= energy + kArmijo * alpha * slope + noise) return alpha;
  }
  return 0;
}

}  // namespace

double levenbergShift(const Eigen::Matrix2d& hessian, double gradientNorm, double scale) {
  return 1e-12 * hessian.trace() + 0.1 * gradientNorm / scale + 1e-300;
}

void solveStaticsNewton(const StaticsProblem& problem, StaticsResult& result,
                        const NewtonOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const double scale = staticsLengthScale(problem);
  Vec2 p = staticsInitialGuess(problem);
  result.converged = false;
  result.method = StaticsMethod::Newton;
  result.fellBack = false;
  double lastAlpha = 1;
  int iter = 0, jumps = 0;
  for (; iter <= options.maxIterations; ++iter) {
    const StaticsDerivatives d = staticsDerivatives(problem, p);
    if (options.detectFingertips && d.nearest >= 0 && d.nearestDistance == 0) {
      // Exactly on a fingertip: either it is the minimiser or we step off it downhill.
      const StaticsKink kink = staticsKink(problem, p);
      const double slack = 1e-12 * (kink.absorbable + kink.smoothGradient.norm() + kink.maxTension);
      if (kink.excess() <= slack) {
        result.converged = true;
        break;
      }
      if (iter == options.maxIterations) break;
      const Vec2 dir = -kink.smoothGradient.normalized();
      // Step to the 1D minimum of the smooth part's quadratic model, past the kink's share.
      const double curvature = dir.dot(d.hessian * dir);
      const double length = curvature > 0 ? kink.excess() / curvature : scale;
      Vec2 next;
      lastAlpha = lineSearch(problem, p, d.energy, std::min(length, scale) * dir,
                             -kink.excess() * std::min(length, scale), next);
      if (lastAlpha == 0) break;
      p = next;
      continue;
    }
    if (d.maxTension == 0) {  // every cable slack: E = 0 here, a minimiser
      result.converged = true;
      break;
    }
    const double gnorm = d.gradient.norm();
    if (gnorm <= options.forceTol * d.maxTension) {
      result.converged = true;
      break;
    }
    if (options.detectFingertips && (lastAlpha < 1 || iter >= kAnchorCheckAfter)) {
      if (fingertipIsMinimiser(problem, d.nearest)) {
        // Newton overshot a kink: the nearest fingertip absorbs the net force, it is the answer.
        p = fingertip(problem, d.nearest);
        result.converged = true;
        break;
      }
      if (d.nearestDistance < kSnapDistance * scale && jumps < kMaxJumps) {
        // Drawn into a kink that is not the minimiser (its tangential curvature T / r traps
        // Newton): go onto the fingertip and step off it along the minimum-norm subgradient.
        ++jumps;
        p = fingertip(problem, d.nearest);
        continue;
      }
    }
    if (iter == options.maxIterations) break;
    Eigen::Matrix2d h = d.hessian;
    const double shift = levenbergShift(h, gnorm, scale);
    h(0, 0) += shift;
    h(1, 1) += shift;
    const double det = h(0, 0) * h(1, 1) - h(0, 1) * h(1, 0);
    Vec2 step(-(h(1, 1) * d.gradient.x() - h(0, 1) * d.gradient.y()) / det,
              -(h(0, 0) * d.gradient.y() - h(1, 0) * d.gradient.x()) / det);
    if (!(step.allFinite())) step = -d.gradient * (scale / gnorm);
    const double stepNorm = step.norm();
    if (stepNorm > 10 * scale) step *= 10 * scale / stepNorm;  // trust the model only so far
    Vec2 next;
    lastAlpha = lineSearch(problem, p, d.energy, step, d.gradient.dot(step), next);
    if (lastAlpha == 0) {
      // No decrease is possible in double precision: accept p if the force is round-off small.
      result.converged = gnorm <= 1e-10 * d.maxTension;
      break;
    }
    const bool tiny = (next - p).norm() <= 4 * kEps * (scale + p.norm());
    p = next;
    if (tiny && gnorm <= 1e-10 * d.maxTension) {
      result.converged = true;
      break;
    }
  }
  result.p = p;
  result.iterations = iter;
  finishStaticsResult(problem, result);
  result.solveMicros =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

StaticsResult solveStaticsNewton(const StaticsProblem& problem, const NewtonOptions& options) {
  StaticsResult result;
  solveStaticsNewton(problem, result, options);
  return result;
}

}  // namespace cablelab

// Statics of a point held by cables (thesis section 4.2, docs/model.md#statics).
//
// A point p in the plane is held by N cables; cable i runs a_i -> p -> b_i with stiffness k_i and
// rest length L_i. Its length is l_i(p) = |p - a_i| + |p - b_i| and its tension
// T_i = k_i max(0, l_i - L_i) (a cable cannot push). The equilibrium minimises the elastic energy
//   E(p) = sum_i k_i / 2 max(0, l_i(p) - L_i)^2,
// which is convex. E has a kink at every fingertip point (a_i or b_i) of a taut cable: the
// minimiser may sit exactly there, the fingertip absorbing the net force (docs/model.md#statics),
// and it need not be unique (one taut cable with p on its own a-b segment, or every cable slack).
//
// Where to find things:
//   problem, validation, energy, gradient, Hessian ....... this file (statics.cpp)
//   the default solver (Newton, SOCP fallback) ........... solveStatics() below (statics.cpp)
//   damped Newton in p .................................. statics_newton.h
//   interior-point SOCP ................................. socp.h
//   d p* / d fingertips ................................. statics_sensitivity.h
//   box -> point reduction (figure 4-2) ................. box_reduction.h
//   a box that may turn (x, y, theta) .................... box_pose.h
//   JSON in and out ..................................... statics_io.h
// Units: lengths in metres, stiffness in N/m, tension in N, energy in J, time in microseconds.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/math.h"

namespace cablelab {

/// One cable a -> p -> b.
struct StaticsCable {
  Vec2 a = Vec2::Zero();  ///< first fingertip point (m)
  Vec2 b = Vec2::Zero();  ///< second fingertip point (m)
  double k = 1.0;         ///< stiffness (N/m), > 0
  double L = 0.0;         ///< rest length (m); user input must be >= 0, the solvers accept any
                          ///< finite value (a box reduction may give L < 0, box_reduction.h)
};

/// The statics problem: fixed fingertip points, the point p free.
struct StaticsProblem {
  std::vector<StaticsCable> cables;  ///< (N), N >= 1
  std::optional<Vec2> p0;            ///< initial guess for p (m); default: the stiffness-weighted
                                     ///< centroid of the fingertip points
};

/// Which algorithm produced a result.
enum class StaticsMethod {
  Newton,  ///< damped Newton in p (statics_newton.h), possibly ending on a fingertip point
  Socp,    ///< the interior-point SOCP (socp.h)
};

/// "newton" or "socp".
const char* toString(StaticsMethod method);

/// The equilibrium and what the solver did to get it.
struct StaticsResult {
  Vec2 p = Vec2::Zero();         ///< the minimiser (m)
  std::vector<double> lengths;   ///< (N) cable lengths |p - a_i| + |p - b_i| (m)
  std::vector<double> tensions;  ///< (N) k_i max(0, length_i - L_i) (N)
  double energy = 0;             ///< E(p) (J)
  int iterations = 0;            ///< solver iterations (Newton steps or interior-point steps)
  double residual = 0;           ///< |net force on p| / max tension, 0 if all slack; on a
                                 ///< fingertip point the smallest net force the fingertip cannot
                                 ///< absorb (the minimum-norm subgradient), see staticsResidual()
  double solveMicros = 0;        ///< wall time of the solve (us)
  StaticsMethod method = StaticsMethod::Newton;  ///< the solver that produced p
  bool fellBack = false;   ///< true: Newton was not safe and the SOCP produced p
  bool converged = false;  ///< the solver met its tolerance
  int anchor = -1;         ///< fingertip index p sits exactly on (2 i: a_i, 2 i + 1: b_i), or -1
};

/// Throws InputError(source, "cables[i].k", ...) on the first bad value: no cables, k <= 0,
/// L < 0, or any non-finite number (also in p0).
void validateStatics(const StaticsProblem& problem, const std::string& source);

/// Fingertip point number j: a_{j/2} for even j, b_{j/2} for odd j.
inline const Vec2& fingertip(const StaticsProblem& problem, int j) {
  const StaticsCable& c = problem.cables[j / 2];
  return (j % 2 == 0) ? c.a : c.b;
}

/// Stretch max(0, ra + rb - L) of a cable whose segments are ra and rb long (m); a stretch
/// within round-off of zero (4 eps (ra + rb + |L|)) counts as slack. Every function here uses it.
double cableStretch(double ra, double rb, double restLength);

/// E(p) (J). Continuous everywhere.
double staticsEnergy(const StaticsProblem& problem, const Vec2& p);

/// Energy, gradient and Hessian of E at p. A fingertip point that coincides with p exactly
/// (the kink) contributes nothing to the gradient or Hessian; see staticsKink() for its share.
struct StaticsDerivatives {
  double energy = 0;                                  ///< J
  Vec2 gradient = Vec2::Zero();                       ///< dE/dp = minus the net force on p (N)
  Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();  ///< d2E/dp2 (N/m), positive semidefinite
  double maxTension = 0;                              ///< N
  double nearestDistance = 0;  ///< distance from p to the nearest fingertip point (m)
  int nearest = -1;            ///< that fingertip's index (2 i or 2 i + 1)
};

/// Energy, gradient and (if `withHessian`) Hessian at p.
StaticsDerivatives staticsDerivatives(const StaticsProblem& problem, const Vec2& p,
                                      bool withHessian = true);

/// The subdifferential of E at a point c: the set smoothGradient + absorbable * (unit disc).
/// `absorbable` is the sum of the tensions of the cables with a fingertip exactly at c (N);
/// c minimises E exactly when |smoothGradient| <= absorbable (E is convex).
struct StaticsKink {
  Vec2 smoothGradient = Vec2::Zero();  ///< gradient of the terms smooth at c (N)
  double absorbable = 0;               ///< N
  double maxTension = 0;               ///< N
  /// |smoothGradient| - absorbable (N): <= 0 when c is a minimiser.
  double excess() const { return smoothGradient.norm() - absorbable; }
};

/// The subdifferential at c (any point; a fingertip point is what makes it interesting).
StaticsKink staticsKink(const StaticsProblem& problem, const Vec2& c);

/// True when fingertip point j minimises E: the subgradient condition with a relative slack of
/// `relTol` times the sum of tensions at it (round-off).
bool fingertipIsMinimiser(const StaticsProblem& problem, int j, double relTol = 1e-12);

/// |net force on p| / max tension (0 if every cable is slack). Where p coincides exactly with a
/// fingertip point, the net force is the minimum-norm subgradient (what the fingertip cannot
/// absorb), so a minimiser on a fingertip has residual 0.
double staticsResidual(const StaticsProblem& problem, const Vec2& p);

/// Fills lengths, tensions, energy, residual and anchor of `result` for the point result.p.
/// Reuses the vectors' storage (no allocation once they have the size).
void finishStaticsResult(const StaticsProblem& problem, StaticsResult& result);

/// A characteristic length of the problem (m): the largest distance of a fingertip point from
/// their centroid, or of a rest length's half, at least 1e-300. Used for tolerances.
double staticsLengthScale(const StaticsProblem& problem);

/// The default initial guess: p0 if given, else the stiffness-weighted centroid of the
/// fingertip points (m).
Vec2 staticsInitialGuess(const StaticsProblem& problem);

class SocpWorkspace;

/// The default path: damped Newton (statics_newton.h), which detects a minimiser on a
/// fingertip point; falls back to the interior-point SOCP (socp.h) when Newton does not
/// converge. `result` storage is reused. `socp`: scratch memory for the fallback (nullptr: a
/// per-thread one).
void solveStatics(const StaticsProblem& problem, StaticsResult& result,
                  SocpWorkspace* socp = nullptr);

/// Convenience form of solveStatics().
StaticsResult solveStatics(const StaticsProblem& problem);

}  // namespace cablelab

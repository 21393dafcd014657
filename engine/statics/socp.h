// Interior-point SOCP for the statics problem (thesis section 4.2 in the slack form of
// docs/model.md#statics).
//
// The conic program, in the variables x = (p, then per cable i: l_ia, l_ib, t_i):
//   minimise   sum_i k_i / 2 t_i^2
//   subject to t_i >= 0,  t_i >= l_ia + l_ib - L_i           (2 N nonnegative-orthant cones)
//              (l_ij, p - p_ij) in the Lorentz cone Q^3       (2 N second-order cones)
// i.e. l_ij >= |p - p_ij|. The quadratic objective is kept as it is (a conic QP) rather than as a
// rotated-cone epigraph: the same solution, and the Newton system stays positive definite. At
// the optimum E(p) = sum k_i / 2 t_i^2, slack cables included (t_i = 0 for them).
//
// Algorithm: primal-dual path following with Nesterov-Todd scaling and Mehrotra's
// predictor-corrector (as in CVXOPT's coneqp and ECOS), infeasible start. The Newton system
//   (P + G^T W^-2 G) dx = rhs
// is block-arrow: every cable couples its own (l_ia, l_ib, t_i) only with p. The solver
// eliminates each cable's 3x3 block and solves a 2x2 Schur complement in p: O(N) work per
// iteration, no dense KKT and no allocation inside the loop (the workspace keeps the arrays).
// The problem is translated and scaled to unit length and unit stiffness first.
// Accuracy: the interior point's p is only accurate to about the square root of the duality
// gap (the angle between a cone's primal and dual rays closes like sqrt(gap)), and the gap
// cannot go much below 1e-12 in double precision. So the solver stops at a moderate gap and
// finishes in one of two ways: a nearby fingertip point that passes the subgradient test is
// optimal (E is convex) and p snaps onto it; otherwise a few Newton steps on E polish p (kept
// only while they lower |dE/dp|), which squares the error each step.
#pragma once

#include <vector>

#include "engine/statics/statics.h"

namespace cablelab {

struct SocpOptions {
  int maxIterations = 30;      ///< interior-point iterations before giving up
  double gapTol = 1e-10;       ///< stop when s^T z <= gapTol (scaled problem: unit length, unit k)
  double feasTol = 1e-12;      ///< and the primal and dual residuals are below this (scaled)
  int polishSteps = 3;         ///< Newton steps on E after the interior point (0: none)
  double stepFraction = 0.99;  ///< fraction of the step to the cone boundary
  int refinements = 1;         ///< iterative-refinement steps per Newton solve
  bool warmStart = false;      ///< start from the workspace's previous solution (same cable count)
};

/// What the last solve did (scaled problem units: unit length, unit largest stiffness).
struct SocpStats {
  int iterations = 0;
  double gap = 0;             ///< s^T z, the duality gap
  double primalResidual = 0;  ///< max |G x + s - h|
  double dualResidual = 0;    ///< max |P x + G^T z|
  bool converged = false;
  int polishSteps = 0;  ///< Newton polishing steps taken
};

/// Scratch memory of the solver: reuse one across solves (allocation only when N grows).
/// Not thread-safe: one per thread.
class SocpWorkspace {
 public:
  SocpWorkspace();
  ~SocpWorkspace();
  SocpWorkspace(const SocpWorkspace&) = delete;
  SocpWorkspace& operator=(const SocpWorkspace&) = delete;

  /// Statistics of the last solve.
  const SocpStats& stats() const { return stats_; }

  struct Cable;  // per-cable state (socp.cpp)

 private:
  friend void solveStaticsSocp(const StaticsProblem&, StaticsResult&, SocpWorkspace&,
                               const SocpOptions&);
  std::vector<Cable> cables_;
  SocpStats stats_;
  Vec2 lastP_ = Vec2::Zero();  ///< the previous solution (m), for warm starts
  bool hasLast_ = false;
};

/// Solves the statics problem with the interior-point method; fills `result` (method = Socp,
/// iterations, converged) and the workspace's stats. Never throws on a valid problem.
void solveStaticsSocp(const StaticsProblem& problem, StaticsResult& result,
                      SocpWorkspace& workspace, const SocpOptions& options = {});

/// Convenience form with a fresh workspace.
StaticsResult solveStaticsSocp(const StaticsProblem& problem, const SocpOptions& options = {});

}  // namespace cablelab

#include "engine/statics/statics_sensitivity.h"

#include <Eigen/Eigenvalues>

namespace cablelab {

namespace {

/// d g / d x for the fingertip x of a taut cable with tension `tension`, segment unit vector
/// `u` (from x to p) of length r, and direction sum `dir` = u_a + u_b.
Eigen::Matrix2d gradientByFingertip(double k, double tension, const Vec2& u, double r,
                                    const Vec2& dir) {
  return -k * dir * u.transpose() -
         (tension / r) * (Eigen::Matrix2d::Identity() - u * u.transpose());
}

}  // namespace

StaticsSensitivity staticsSensitivity(const StaticsProblem& problem, const Vec2& p) {
  const int n = int(problem.cables.size());
  StaticsSensitivity out;
  out.dp.setZero(2, 4 * n);
  const StaticsDerivatives d = staticsDerivatives(problem, p);
  if (d.nearest >= 0 && d.nearestDistance == 0) {
    // On a fingertip: with a strict subgradient condition p* moves with that one fingertip.
    const StaticsKink kink = staticsKink(problem, p);
    int coincident = 0;
    for (int j = 0; j < 2 * n; ++j) coincident += fingertip(problem, j) == p;
    if (kink.excess() < 0 && coincident == 1) {
      out.kind = StaticsSensitivity::Kind::OnFingertip;
      out.dp.block<2, 2>(0, 2 * d.nearest).setIdentity();
    } else {
      out.kind = StaticsSensitivity::Kind::Singular;
    }
    return out;
  }
  // Inverse Hessian, or its pseudo-inverse along flat directions (non-unique minimiser).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(d.hessian);
  const Eigen::Vector2d lambda = eig.eigenvalues();
  const double cutoff = 1e-9 * std::max(lambda.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::Matrix2d inverse = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 2; ++i) {
    if (lambda(i) > cutoff)
      inverse += eig.eigenvectors().col(i) * eig.eigenvectors().col(i).transpose() / lambda(i);
    else
      out.kind = StaticsSensitivity::Kind::Singular;
  }
  for (int i = 0; i < n; ++i) {
    const StaticsCable& c = problem.cables[i];
    const Vec2 da = p - c.a, db = p - c.b;
    const double ra = da.norm(), rb = db.norm();
    const double stretch = cableStretch(ra, rb, c.L);
    if (stretch <= 0) continue;
    const double tension = c.k * stretch;
    const Vec2 ua = da / ra, ub = db / rb;
    const Vec2 dir = ua + ub;
    out.dp.block<2, 2>(0, 4 * i) = -inverse * gradientByFingertip(c.k, tension, ua, ra, dir);
    out.dp.block<2, 2>(0, 4 * i + 2) = -inverse * gradientByFingertip(c.k, tension, ub, rb, dir);
  }
  return out;
}

}  // namespace cablelab

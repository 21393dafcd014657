#include "engine/point_equilibrium.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace cablelab {

namespace {

constexpr double kGradientTolerance = 1e-12;  // relative to the force scale
constexpr double kMinDistance = 1e-9;         // m: closer to a cable end counts as on it
constexpr int kMaxIterations = 60;

struct Derivatives {
  double energy = 0;
  Vec2 gradient = Vec2::Zero();
  Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();
  bool onEnd = false;  // p sits on a cable end: E has a kink there
};

Derivatives derivatives(const std::vector<SpringCable>& cables, const Vec2& p) {
  Derivatives d;
  for (const SpringCable& c : cables) {
    const Vec2 da = p - c.a, db = p - c.b;
    const double ra = da.norm(), rb = db.norm();
    const double stretch = ra + rb - c.L;
    if (stretch <= 0) continue;  // slack: no energy, no force
    d.energy += 0.5 * c.k * stretch * stretch;
    if (ra < kMinDistance || rb < kMinDistance) {
      d.onEnd = true;
      continue;
    }
    const Vec2 ua = da / ra, ub = db / rb, u = ua + ub;
    const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
    d.gradient += c.k * stretch * u;
    d.hessian += c.k * (u * u.transpose()) +
                 c.k * stretch * ((I - ua * ua.transpose()) / ra + (I - ub * ub.transpose()) / rb);
  }
  return d;
}

}  // namespace

double springEnergy(const std::vector<SpringCable>& cables, const Vec2& p) { return derivatives(cables, p).energy; }

PointEquilibrium solvePointEquilibrium(const std::vector<SpringCable>& cables, const Vec2& guess) {
  PointEquilibrium out;
  Vec2 p = guess;
  Derivatives d = derivatives(cables, p);
  double forceScale = 1;  // N: tolerances are relative to the largest cable force
  for (const SpringCable& c : cables) forceScale = std::max(forceScale, c.k * std::max(0.0, (c.b - c.a).norm() - c.L));
  for (int it = 0; it < kMaxIterations; ++it) {
    out.iterations = it + 1;
    if (d.onEnd) {  // step off the kink towards lower energy along a probe direction
      p += Vec2(1e-6, 1e-6);
      d = derivatives(cables, p);
      continue;
    }
    if (d.gradient.norm() < kGradientTolerance * forceScale) break;
    // Newton direction, falling back to steepest descent when the Hessian is not positive definite.
    Eigen::LLT<Eigen::Matrix2d> llt(d.hessian);
    Vec2 step = llt.info() == Eigen::Success ? Vec2(-llt.solve(d.gradient)) : Vec2(-d.gradient);
    if (step.dot(d.gradient) >= 0) step = -d.gradient;
    double t = 1;
    Derivatives next;
    // Near the minimum the predicted decrease drops below the energy's rounding: take the full
    // Newton step there (the line search could only reject it on noise).
    const bool tiny = -step.dot(d.gradient) < 1e-13 * (1 + d.energy);
    for (int ls = 0; ls < 40; ++ls, t *= 0.5) {
      next = derivatives(cables, p + t * step);
      if (tiny || next.energy <= d.energy + 1e-4 * t * step.dot(d.gradient)) break;
    }
    p += t * step;
    d = next;
  }
  out.p = p;
  out.energy = d.energy;
  const int n = static_cast<int>(cables.size());
  out.sensitivity = Eigen::Matrix<double, 2, Eigen::Dynamic>::Zero(2, 4 * n);
  Eigen::LLT<Eigen::Matrix2d> llt(d.hessian);
  out.converged = !d.onEnd && d.gradient.norm() < 1e-8 * forceScale && llt.info() == Eigen::Success;
  if (!out.converged) return out;
  // Implicit function theorem: H dp = -(d gradient / d ends) d ends.
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  for (int i = 0; i < n; ++i) {
    const SpringCable& c = cables[i];
    const Vec2 da = p - c.a, db = p - c.b;
    const double ra = da.norm(), rb = db.norm();
    const double stretch = ra + rb - c.L;
    if (stretch <= 0) continue;
    const Vec2 ua = da / ra, ub = db / rb, u = ua + ub;
    const Eigen::Matrix2d dGda = -c.k * (u * ua.transpose()) - c.k * stretch * (I - ua * ua.transpose()) / ra;
    const Eigen::Matrix2d dGdb = -c.k * (u * ub.transpose()) - c.k * stretch * (I - ub * ub.transpose()) / rb;
    out.sensitivity.block<2, 2>(0, 4 * i) = -llt.solve(dGda);
    out.sensitivity.block<2, 2>(0, 4 * i + 2) = -llt.solve(dGdb);
  }
  return out;
}

}  // namespace cablelab

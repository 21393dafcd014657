#include "engine/statics/statics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "engine/core/error.h"
#include "engine/statics/socp.h"
#include "engine/statics/statics_newton.h"

namespace cablelab {

const char* toString(StaticsMethod method) {
  return method == StaticsMethod::Socp ? "socp" : "newton";
}

namespace {

std::string describe(double v) {
  return formatNumber(v);
}

void requireFinite(const Vec2& v, const std::string& source, const std::string& field) {
  if (!isFinite(v))
    throw InputError(source, field,
                     "must be finite (got [" + describe(v.x()) + ", " + describe(v.y()) + "])");
}

}  // namespace

double cableStretch(double ra, double rb, double restLength) {
  const double stretch = ra + rb - restLength;
  // Within round-off of the rest length the cable counts as slack: its "tension" would be noise.
  return stretch > 4 * std::numeric_limits<double>::epsilon() * (ra + rb + std::abs(restLength))
             ? stretch
             : 0.0;
}

void validateStatics(const StaticsProblem& problem, const std::string& source) {
  // Magnitude bounds (a fuzzer finding): beyond them lengths (|p - a|^2) and energies
  // (k stretch^2) overflow to infinity. Far outside anything a cable could be.
  constexpr double kMaxCoordinate = 1e9;  // m
  constexpr double kMaxStiffness = 1e12;  // N/m
  auto bounded = [&](const Vec2& v, const std::string& field) {
    if (std::isfinite(v.x()) && std::isfinite(v.y()) && v.cwiseAbs().maxCoeff() > kMaxCoordinate)
      throw InputError(
          source, field,
          "coordinates must be within +/-1e9 m (got " + describe(v.cwiseAbs().maxCoeff()) + ")");
  };
  if (problem.cables.empty())
    throw InputError(source, "cables", "must list at least one cable (got none)");
  for (size_t i = 0; i < problem.cables.size(); ++i) {
    const StaticsCable& c = problem.cables[i];
    const std::string at = "cables[" + std::to_string(i) + "]";
    bounded(c.a, at + ".a");
    bounded(c.b, at + ".b");
    if (std::isfinite(c.k) && c.k > kMaxStiffness)
      throw InputError(source, at + ".k", "must be at most 1e12 N/m (got " + describe(c.k) + ")");
    if (std::isfinite(c.L) && c.L > 4 * kMaxCoordinate)
      throw InputError(source, at + ".L", "must be at most 4e9 m (got " + describe(c.L) + ")");
  }
  if (problem.p0) bounded(*problem.p0, "p0");
  for (size_t i = 0; i < problem.cables.size(); ++i) {
    const StaticsCable& c = problem.cables[i];
    const std::string at = "cables[" + std::to_string(i) + "]";
    requireFinite(c.a, source, at + ".a");
    requireFinite(c.b, source, at + ".b");
    if (!std::isfinite(c.k) || c.k <= 0)
      throw InputError(source, at + ".k",
                       "must be positive and finite (got " + describe(c.k) + ")");
    if (!std::isfinite(c.L) || c.L < 0)
      throw InputError(source, at + ".L",
                       "must be non-negative and finite (got " + describe(c.L) + ")");
  }
  if (problem.p0) requireFinite(*problem.p0, source, "p0");
}

double staticsEnergy(const StaticsProblem& problem, const Vec2& p) {
  double energy = 0;
  for (const StaticsCable& c : problem.cables) {
    const double stretch = cableStretch((p - c.a).norm(), (p - c.b).norm(), c.L);
    energy += 0.5 * c.k * stretch * stretch;
  }
  return energy;
}

StaticsDerivatives staticsDerivatives(const StaticsProblem& problem, const Vec2& p,
                                      bool withHessian) {
  StaticsDerivatives d;
  d.nearestDistance = INFINITY;
  for (size_t i = 0; i < problem.cables.size(); ++i) {
    const StaticsCable& c = problem.cables[i];
    const Vec2 da = p - c.a, db = p - c.b;
    const double ra = da.norm(), rb = db.norm();
    if (ra < d.nearestDistance) d.nearestDistance = ra, d.nearest = int(2 * i);
    if (rb < d.nearestDistance) d.nearestDistance = rb, d.nearest = int(2 * i + 1);
    const double stretch = cableStretch(ra, rb, c.L);
    if (stretch <= 0) continue;  // slack: no force, no stiffness
    const double tension = c.k * stretch;
    d.energy += 0.5 * tension * stretch;
    d.maxTension = std::max(d.maxTension, tension);
    // A coincident fingertip is the kink: it contributes a subgradient, handled by staticsKink.
    const Vec2 ua = ra > 0 ? Vec2(da / ra) : Vec2::Zero();
    const Vec2 ub = rb > 0 ? Vec2(db / rb) : Vec2::Zero();
    const Vec2 dir = ua + ub;
    d.gradient += tension * dir;
    if (!withHessian) continue;
    d.hessian += c.k * dir * dir.transpose();
    // Curvature of |p - x|: (I - u u^T) / r, scaled by the tension.
    if (ra > 0) d.hessian += (tension / ra) * (Eigen::Matrix2d::Identity() - ua * ua.transpose());
    if (rb > 0) d.hessian += (tension / rb) * (Eigen::Matrix2d::Identity() - ub * ub.transpose());
  }
  return d;
}

StaticsKink staticsKink(const StaticsProblem& problem, const Vec2& c) {
  StaticsKink kink;
  for (const StaticsCable& cable : problem.cables) {
    const Vec2 da = c - cable.a, db = c - cable.b;
    const double ra = da.norm(), rb = db.norm();
    const double stretch = cableStretch(ra, rb, cable.L);
    if (stretch <= 0) continue;
    const double tension = cable.k * stretch;
    kink.maxTension = std::max(kink.maxTension, tension);
    if (ra > 0)
      kink.smoothGradient += (tension / ra) * da;
    else
      kink.absorbable += tension;
    if (rb > 0)
      kink.smoothGradient += (tension / rb) * db;
    else
      kink.absorbable += tension;
  }
  return kink;
}

bool fingertipIsMinimiser(const StaticsProblem& problem, int j, double relTol) {
  const StaticsKink kink = staticsKink(problem, fingertip(problem, j));
  // The slack scales with the forces involved so that round-off never rejects a true minimiser.
  const double slack = relTol * (kink.absorbable + kink.smoothGradient.norm() + kink.maxTension);
  return kink.excess() <= slack;
}

double staticsResidual(const StaticsProblem& problem, const Vec2& p) {
  const StaticsKink kink = staticsKink(problem, p);
  if (kink.maxTension <= 0) return 0;
  return std::max(0.0, kink.excess()) / kink.maxTension;
}

void finishStaticsResult(const StaticsProblem& problem, StaticsResult& result) {
  const size_t n = problem.cables.size();
  result.lengths.resize(n);
  result.tensions.resize(n);
  result.energy = 0;
  result.anchor = -1;
  for (size_t i = 0; i < n; ++i) {
    const StaticsCable& c = problem.cables[i];
    const double ra = (result.p - c.a).norm(), rb = (result.p - c.b).norm();
    if (result.anchor < 0 && ra == 0) result.anchor = int(2 * i);
    if (result.anchor < 0 && rb == 0) result.anchor = int(2 * i + 1);
    const double length = ra + rb;
    const double stretch = cableStretch(ra, rb, c.L);
    result.lengths[i] = length;
    result.tensions[i] = c.k * stretch;
    result.energy += 0.5 * c.k * stretch * stretch;
  }
  result.residual = staticsResidual(problem, result.p);
}

double staticsLengthScale(const StaticsProblem& problem) {
  Vec2 centroid = Vec2::Zero();
  for (const StaticsCable& c : problem.cables) centroid += c.a + c.b;
  centroid /= double(2 * std::max<size_t>(1, problem.cables.size()));
  double scale = 0;
  for (const StaticsCable& c : problem.cables) {
    scale =
        std::max({scale, (c.a - centroid).norm(), (c.b - centroid).norm(), 0.5 * std::abs(c.L)});
  }
  return scale > 0 ? scale : 1.0;
}

Vec2 staticsInitialGuess(const StaticsProblem& problem) {
  if (problem.p0) return *problem.p0;
  Vec2 sum = Vec2::Zero();
  double weight = 0;
  for (const StaticsCable& c : problem.cables) {
    sum += c.k * (c.a + c.b);
    weight += 2 * c.k;
  }
  return weight > 0 ? Vec2(sum / weight) : Vec2::Zero();
}

void solveStatics(const StaticsProblem& problem, StaticsResult& result, SocpWorkspace* socp) {
  const auto start = std::chrono::steady_clock::now();
  NewtonOptions options;
  solveStaticsNewton(problem, result, options);
  if (!result.converged) {
    // Newton was not safe here (no convergence within its budget): the SOCP does not care
    // about kinks or non-uniqueness.
    thread_local SocpWorkspace local;
    const int newtonIterations = result.iterations;
    solveStaticsSocp(problem, result, socp ? *socp : local);
    result.iterations += newtonIterations;
    result.fellBack = true;
  }
  result.solveMicros =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

StaticsResult solveStatics(const StaticsProblem& problem) {
  StaticsResult result;
  solveStatics(problem, result);
  return result;
}

}  // namespace cablelab

#include "engine/membrane/membrane_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <unsupported/Eigen/NonLinearOptimization>

#include "engine/core/error.h"

namespace cablelab {
namespace {

/// Per-row quantities that do not depend on (k, preload).
struct RowGeometry {
  double stretch;     // m
  double dirY;        // (u1 + u2).y
  double angleModel;  // degrees
};

/// Weighted residuals r = [(fy_model - fy) / sigma_fy ; wrap(angle_model - angle) / sigma_angle]
/// as a functor for Eigen's Levenberg-Marquardt (x = (k, preload)).
struct Residuals {
  const std::vector<MembraneSample>& rows;
  const std::vector<RowGeometry>& geometry;
  double sigmaFy;
  double sigmaAngleDeg;

  int inputs() const { return 2; }
  int values() const { return 2 * static_cast<int>(rows.size()); }

  static double extension(const Eigen::VectorXd& x, const RowGeometry& r) {
    return r.stretch + x[1];
  }

  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
    const int n = static_cast<int>(rows.size());
    for (int i = 0; i < n; ++i) {
      const double tension = x[0] * std::max(0.0, extension(x, geometry[i]));
      f[i] = (-tension * geometry[i].dirY - rows[i].fy) / sigmaFy;
      f[n + i] = wrapAngleDeg(geometry[i].angleModel - rows[i].angleDeg) / sigmaAngleDeg;
    }
    return 0;
  }

  int df(const Eigen::VectorXd& x, Eigen::MatrixXd& J) const {
    const int n = static_cast<int>(rows.size());
    J.setZero();
    for (int i = 0; i < n; ++i) {
      const double e = extension(x, geometry[i]);
      if (e <= 0.0) continue;  // slack band: no force, no sensitivity
      J(i, 0) = -e * geometry[i].dirY / sigmaFy;
      J(i, 1) = -x[0] * geometry[i].dirY / sigmaFy;
      // Angle rows stay zero: the direction of a taut band does not depend on k or preload.
    }
    return 0;
  }
};

double sumSquares(const Eigen::VectorXd& v) {
  return v.squaredNorm();
}

/// Exact start: fy = -(a s + b) dirY is linear in (a, b) = (k, k preload).
Eigen::VectorXd linearStart(const std::vector<MembraneSample>& rows,
                            const std::vector<RowGeometry>& geometry) {
  const int n = static_cast<int>(rows.size());
  Eigen::MatrixXd A(n, 2);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    A(i, 0) = -geometry[i].stretch * geometry[i].dirY;
    A(i, 1) = -geometry[i].dirY;
    y[i] = rows[i].fy;
  }
  const Eigen::Vector2d ab = A.colPivHouseholderQr().solve(y);
  Eigen::VectorXd x(2);
  if (std::isfinite(ab[0]) && std::isfinite(ab[1]) && ab[0] > 0.0)
    x << ab[0], ab[1] / ab[0];
  else
    x << 1.0, 0.0;  // data pull the wrong way; let LM find (and the caller reject) the optimum
  return x;
}

}  // namespace

MembraneFitResult fitMembrane(const MembraneGeometry& g, const std::vector<MembraneSample>& rows,
                              const MembraneFitOptions& options) {
  const int n = static_cast<int>(rows.size());
  if (n < kMinMembraneRows)
    throw InputError(options.source, "rows",
                     "need at least " + std::to_string(kMinMembraneRows) + " measurements" +
                         gotValue(static_cast<double>(n)));

  std::vector<RowGeometry> geometry(n);
  double stretchMin = INFINITY, stretchMax = -INFINITY;
  for (int i = 0; i < n; ++i) {
    geometry[i] = {membraneStretch(g, rows[i].p), membraneDirectionSum(g, rows[i].p).y(),
                   membraneForceAngleDeg(g, rows[i].p)};
    stretchMin = std::min(stretchMin, geometry[i].stretch);
    stretchMax = std::max(stretchMax, geometry[i].stretch);
  }
  // One stretch for all points: only k (stretch + preload) is seen, not k and preload apart.
  if (stretchMax - stretchMin <= 1e-9 * std::max(1.0, stretchMax))
    throw InputError(options.source, "x",
                     "k and preload cannot be told apart: every point has the same stretch (got " +
                         formatNumber(stretchMin) + " m at all " + std::to_string(n) + " points)");

  const bool estimateFy = !(options.sigmaFy > 0.0);
  const bool estimateAngle = !(options.sigmaAngleDeg > 0.0);
  // Starting levels only set the relative weight of the two kinds in the first round.
  double sigmaFy = estimateFy ? 1.0 : options.sigmaFy;
  double sigmaAngle = estimateAngle ? 1.0 : options.sigmaAngleDeg;

  MembraneFitResult result;
  result.rows = n;
  Eigen::VectorXd x = linearStart(rows, geometry);
  Eigen::VectorXd f(2 * n);
  Eigen::MatrixXd J(2 * n, 2);
  const int maxRounds = (estimateFy || estimateAngle) ? std::max(1, options.maxRounds) : 1;
  for (int round = 0; round < maxRounds; ++round) {
    Residuals residuals{rows, geometry, sigmaFy, sigmaAngle};
    Eigen::LevenbergMarquardt<Residuals, double> lm(residuals);
    lm.parameters.maxfev = options.maxEvaluations;
    lm.parameters.ftol = 1e-15;  // tight: noise-free data should come back to ~1e-12
    lm.parameters.xtol = 1e-15;
    lm.minimize(x);
    result.iterations += static_cast<int>(lm.njev);
    result.rounds = round + 1;

    // Re-estimate each kind's level from its residuals, minus the parameters it absorbed.
    residuals(x, f);
    residuals.df(x, J);
    const Eigen::Matrix2d info = J.transpose() * J;
    const Eigen::MatrixXd hatFactor = info.ldlt().solve(J.transpose());  // (2 x 2n)
    double leverageFy = 0.0, leverageAngle = 0.0;
    for (int i = 0; i < n; ++i) {
      leverageFy += J.row(i).dot(hatFactor.col(i));
      leverageAngle += J.row(n + i).dot(hatFactor.col(n + i));
    }
    const double ssrFy = sumSquares(f.head(n)) * sigmaFy * sigmaFy;
    const double ssrAngle = sumSquares(f.tail(n)) * sigmaAngle * sigmaAngle;
    result.rmsFy = std::sqrt(ssrFy / n);
    result.rmsAngleDeg = std::sqrt(ssrAngle / n);
    if (!(estimateFy || estimateAngle)) break;

    // Floors keep exact (noise-free) data from dividing by zero.
    double fyScale = 0.0;
    for (const auto& r : rows) fyScale = std::max(fyScale, std::abs(r.fy));
    const double newFy = estimateFy ? std::max(std::sqrt(ssrFy / std::max(1.0, n - leverageFy)),
                                               1e-12 * std::max(fyScale, 1e-300))
                                    : sigmaFy;
    const double newAngle =
        estimateAngle ? std::max(std::sqrt(ssrAngle / std::max(1.0, n - leverageAngle)), 1e-12)
                      : sigmaAngle;
    const bool settled = std::abs(newFy - sigmaFy) <= 1e-6 * newFy &&
                         std::abs(newAngle - sigmaAngle) <= 1e-6 * newAngle;
    sigmaFy = newFy;
    sigmaAngle = newAngle;
    if (settled) break;
  }

  // Final Jacobian with the final levels.
  Residuals residuals{rows, geometry, sigmaFy, sigmaAngle};
  residuals(x, f);
  residuals.df(x, J);
  const Eigen::Matrix2d info = J.transpose() * J;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(info);
  if (!(eigen.eigenvalues()[0] > 1e-14 * eigen.eigenvalues()[1]))
    throw InputError(
        options.source, "fy",
        "k and preload are not determined by these data (singular fit: a slack band everywhere, "
        "or values too large?) (got " +
            std::to_string(n) + " points)");
  if (!(x[0] > 0.0) || !std::isfinite(x[1]))
    throw InputError(options.source, "fy",
                     "best fit has stiffness k <= 0: the measured forces do not pull towards the "
                     "band (sign of fy?)" +
                         gotValue(x[0]));

  result.params = {x[0], x[1]};
  result.covariance = info.inverse();
  result.kStderr = std::sqrt(result.covariance(0, 0));
  result.preloadStderr = std::sqrt(result.covariance(1, 1));
  result.sigmaFy = sigmaFy;
  result.sigmaAngleDeg = sigmaAngle;
  result.chi2PerDof = f.squaredNorm() / std::max(1, 2 * n - 2);
  // Extreme inputs (|fy| near 1e300) can overflow the sums; never hand back a NaN.
  for (double v : {result.kStderr, result.preloadStderr, result.rmsFy, result.rmsAngleDeg,
                   result.covariance(0, 1), result.chi2PerDof, sigmaFy, sigmaAngle})
    if (!std::isfinite(v))
      throw InputError(
          options.source, "fy",
          "the fit overflowed: values too large to fit (got " + std::to_string(n) + " points)");
  return result;
}

}  // namespace cablelab

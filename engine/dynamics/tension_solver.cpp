#include "engine/dynamics/tension_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>

namespace cablelab {

namespace {

// One cable: the active-set loop below always ends at once, so say what it would give. (With
// K_00 <= DBL_MIN the general loop handles the degenerate pivot.)
void solveSingle(double k, double b, LcpSolution& sol) {
  sol.x.resize(1);
  sol.iterations = 0;
  const double x = b > 0 ? b / k : 0.0;
  const double w = k * x - b;
  sol.x[0] = std::max(0.0, x);
  sol.residual = std::abs(std::min(sol.x[0] * k, w));
}

}  // namespace

LcpSolution solveLcp(const Eigen::MatrixXd& K, const Eigen::VectorXd& b) {
  LcpWorkspace work;
  LcpSolution sol;
  solveLcp(K, b, work, sol);
  return sol;
}

void solveLcp(const Eigen::MatrixXd& Kin, const Eigen::VectorXd& b, LcpWorkspace& work,
              LcpSolution& sol) {
  const int n = static_cast<int>(b.size());
  // A row that touches only immovable bodies has K_ii = 0: regularise so it stays solvable.
  Eigen::MatrixXd& K = work.K;
  K = Kin;
  for (int i = 0; i < n; ++i) K(i, i) += 1e-12 * (1 + K(i, i));
  if (n == 1 && K(0, 0) > std::numeric_limits<double>::min())
    return solveSingle(K(0, 0), b[0], sol);

  // A cable sliding on a capstan pulls with e^(mu theta) times the tension its constraint row
  // carries: K is then not symmetric (docs/wheels.md) and needs LU instead of LDLT.
  const bool symmetric = (K - K.transpose()).lpNorm<Eigen::Infinity>() <=
                         1e-12 * K.lpNorm<Eigen::Infinity>();
  sol.x.setZero(n);
  sol.iterations = 0;
  sol.residual = 0;
  std::vector<char>& active = work.active;
  active.resize(n);
  for (int i = 0; i < n; ++i) active[i] = b[i] > 0;
  Eigen::VectorXd& w = work.w;
  w.resize(n);
  std::vector<int>& idx = work.idx;
  for (const int maxIterations = 4 * n + 10; sol.iterations < maxIterations; ++sol.iterations) {
    idx.clear();
    for (int i = 0; i < n; ++i)
      if (active[i]) idx.push_back(i);
    sol.x.setZero();
    if (!idx.empty()) {
      const int m = static_cast<int>(idx.size());
      work.Ks.resize(m, m);
      work.bs.resize(m);
      for (int r = 0; r < m; ++r) {
        work.bs[r] = b[idx[r]];
        for (int c = 0; c < m; ++c) work.Ks(r, c) = K(idx[r], idx[c]);
      }
      work.xs.resize(m);
      if (symmetric) {
        work.ldlt.compute(work.Ks);
        work.xs = work.ldlt.solve(work.bs);
      } else {
        work.lu.compute(work.Ks);
        work.xs = work.lu.solve(work.bs);
      }
      for (int r = 0; r < m; ++r) sol.x[idx[r]] = work.xs[r];
    }
    w.noalias() = K * sol.x;
    w -= b;
    // Drop the most negative impulse; else add the most violated slack row; else done.
    int worst = -1;
    double worstValue = 0;
    for (int i = 0; i < n; ++i)
      if (active[i] && sol.x[i] < worstValue) worst = i, worstValue = sol.x[i];
    if (worst >= 0) {
      active[worst] = false;
      continue;
    }
    for (int i = 0; i < n; ++i)
      if (!active[i] && w[i] / K(i, i) < worstValue - 1e-15) worst = i, worstValue = w[i] / K(i, i);
    if (worst < 0) break;
    active[worst] = true;
  }
  for (int i = 0; i < n; ++i) {
    sol.x[i] = std::max(0.0, sol.x[i]);
    sol.residual = std::max(sol.residual, std::abs(std::min(sol.x[i] * K(i, i), w[i])));
  }
}

}  // namespace cablelab

#include "engine/tension_solver.h"

#include <Eigen/Dense>
#include <vector>

namespace cablelab {

LcpSolution solveLcp(const Eigen::MatrixXd& Kin, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(b.size());
  // A row that touches only immovable bodies has K_ii = 0: regularise so it stays solvable.
  Eigen::MatrixXd K = Kin;
  for (int i = 0; i < n; ++i) K(i, i) += 1e-12 * (1 + K(i, i));

  LcpSolution sol;
  sol.x = Eigen::VectorXd::Zero(n);
  std::vector<bool> active(n);
  for (int i = 0; i < n; ++i) active[i] = b[i] > 0;
  Eigen::VectorXd w(n);
  std::vector<int> idx;
  for (const int maxIterations = 4 * n + 10; sol.iterations < maxIterations; ++sol.iterations) {
    idx.clear();
    for (int i = 0; i < n; ++i)
      if (active[i]) idx.push_back(i);
    sol.x.setZero();
    if (!idx.empty()) {
      const int m = static_cast<int>(idx.size());
      Eigen::MatrixXd Ks(m, m);
      Eigen::VectorXd bs(m);
      for (int r = 0; r < m; ++r) {
        bs[r] = b[idx[r]];
        for (int c = 0; c < m; ++c) Ks(r, c) = K(idx[r], idx[c]);
      }
      const Eigen::VectorXd xs = Ks.ldlt().solve(bs);
      for (int r = 0; r < m; ++r) sol.x[idx[r]] = xs[r];
    }
    w = K * sol.x - b;
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
  return sol;
}

}  // namespace cablelab

#include "engine/tension_solver.h"

#include <Eigen/Dense>

namespace cablelab {

namespace {

Vec3 inverseMass(const BodyState& b) { return Vec3(b.invMass, b.invMass, b.invInertia); }

double rowDot(const std::vector<BodyJacobian>& a, const std::vector<BodyJacobian>& b,
              std::span<const BodyState> bodies) {
  // Both lists are sorted by body: merge.
  double sum = 0;
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i].body < b[j].body) ++i;
    else if (b[j].body < a[i].body) ++j;
    else {
      sum += a[i].d.cwiseProduct(inverseMass(bodies[a[i].body])).dot(b[j].d);
      ++i, ++j;
    }
  }
  return sum;
}

}  // namespace

TensionSolution solveTensions(std::span<const TensionRow> rows, std::span<const BodyState> bodies,
                              std::span<const Vec3> velocity) {
  const int n = static_cast<int>(rows.size());
  Eigen::MatrixXd K(n, n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    double jv = 0;
    for (const auto& e : *rows[i].jacobian) jv += e.d.dot(velocity[e.body]);
    b[i] = jv - rows[i].targetRate;
    for (int j = 0; j <= i; ++j) K(i, j) = K(j, i) = rowDot(*rows[i].jacobian, *rows[j].jacobian, bodies);
    // A row touching only immovable bodies has K_ii = 0: keep it solvable, it gets no impulse.
    K(i, i) += rows[i].compliance + 1e-12 * (1 + K(i, i));
  }

  TensionSolution sol;
  sol.impulse = Eigen::VectorXd::Zero(n);
  std::vector<bool> active(n);
  for (int i = 0; i < n; ++i) active[i] = b[i] > 0;
  const int maxIterations = 4 * n + 10;
  Eigen::VectorXd w(n);
  for (; sol.iterations < maxIterations; ++sol.iterations) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i)
      if (active[i]) idx.push_back(i);
    const int m = static_cast<int>(idx.size());
    sol.impulse.setZero();
    if (m > 0) {
      Eigen::MatrixXd Ks(m, m);
      Eigen::VectorXd bs(m);
      for (int r = 0; r < m; ++r) {
        bs[r] = b[idx[r]];
        for (int c = 0; c < m; ++c) Ks(r, c) = K(idx[r], idx[c]);
      }
      const Eigen::VectorXd ps = Ks.ldlt().solve(bs);
      for (int r = 0; r < m; ++r) sol.impulse[idx[r]] = ps[r];
    }
    w = K * sol.impulse - b;
    // Drop the most negative impulse, else add the most violated slack row, else done.
    int worst = -1;
    double worstValue = 0;
    for (int i = 0; i < n; ++i)
      if (active[i] && sol.impulse[i] < worstValue) worst = i, worstValue = sol.impulse[i];
    if (worst >= 0) {
      active[worst] = false;
      continue;
    }
    for (int i = 0; i < n; ++i)
      if (!active[i] && w[i] < worstValue * K(i, i) - 1e-14) worst = i, worstValue = w[i] / K(i, i);
    if (worst < 0) break;
    active[worst] = true;
  }
  sol.residual = 0;
  for (int i = 0; i < n; ++i) {
    sol.impulse[i] = std::max(0.0, sol.impulse[i]);
    sol.residual = std::max(sol.residual, std::abs(std::min(sol.impulse[i] * K(i, i), w[i])));
  }
  return sol;
}

void applyTensionImpulse(const TensionRow& row, double impulse, std::span<const BodyState> bodies,
                         std::span<Vec3> dv) {
  for (const auto& e : *row.jacobian)
    dv[e.body] -= impulse * e.d.cwiseProduct(inverseMass(bodies[e.body]));
}

}  // namespace cablelab

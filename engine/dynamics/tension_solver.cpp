#include "engine/dynamics/tension_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace cablelab {

namespace {

// One cable: the active-set loop below always ends at once, so say what it would give. (With
// K_00 <= DBL_MIN the general loop handles the degenerate pivot.)
void solveSingle(double k, double b, LcpSolution& sol) {
  sol.x.resize(1);
  sol.iterations = 0;
  sol.rankDeficient = false;
  const double x = b > 0 ? b / k : 0.0;
  const double w = k * x - b;
  sol.x[0] = std::max(0.0, x);
  sol.residual = std::abs(std::min(sol.x[0] * k, w));
}

// K_SS x_S = b_S on rows i and j in closed form (Eigen's factorisations cost more than the rest
// of the solve at this size); false when they are nearly dependent (then pivot).
bool solveTwoRows(const Eigen::MatrixXd& K, const Eigen::VectorXd& b, int i, int j, double& xi,
                  double& xj) {
  const double det = K(i, i) * K(j, j) - K(i, j) * K(j, i);
  if (!(std::abs(det) > 1e-6 * std::abs(K(i, i) * K(j, j)))) return false;
  xi = (K(j, j) * b[i] - K(i, j) * b[j]) / det;
  xj = (K(i, i) * b[j] - K(j, i) * b[i]) / det;
  return true;
}

// Two rows (a hand's membranes) that both ask to pull (b > 0): principal pivoting starts from
// both and stops at once when the closed form gives both impulses >= 0 (w = 0). That case without
// the loop; false (sol untouched) otherwise, or when the rows are nearly dependent. K carries the
// solve's regularisation, Kin is K as given (for the residual).
bool solveBothTaut(const Eigen::MatrixXd& K, const Eigen::MatrixXd& Kin, const Eigen::VectorXd& b,
                   LcpSolution& sol) {
  double x0, x1;
  if (!(b[0] > 0 && b[1] > 0) || !solveTwoRows(K, b, 0, 1, x0, x1)) return false;
  if (!(x0 >= 0 && x1 >= 0)) return false;
  sol.x.resize(2);
  sol.x << x0, x1;
  sol.iterations = 0;
  sol.rankDeficient = false;
  const double w0 = Kin(0, 0) * x0 + Kin(0, 1) * x1 - b[0];
  const double w1 = Kin(1, 0) * x0 + Kin(1, 1) * x1 - b[1];
  sol.residual =
      std::max(std::abs(std::min(x0 * K(0, 0), w0)), std::abs(std::min(x1 * K(1, 1), w1)));
  return true;
}

// The equal compliance that makes a singular K definite, relative to its largest diagonal: small
// enough that the impulses are the minimum-norm ones to 1e-6, large enough that the active-set
// solves stay well conditioned. The targets are consistent (projected), so it never amplifies.
constexpr double kMinimumNormRegularisation = 1e-6;

// Redundant rows (K singular): b's part outside the range of K asks for what no impulse can do,
// and would come back as an unbounded impulse. True, with K made exactly symmetric in `plain`
// and then regularised in K, if K is singular (an LDLT pivot below kRankTolerance).
bool makeMinimumNorm(Eigen::MatrixXd& K, LcpWorkspace& work) {
  work.ldlt.compute(K);
  if (!rankDeficient(work.ldlt)) return false;
  // K = J1 W is symmetric only up to the change of J over the step; the LDLT solves read its
  // lower triangle. Make it exactly symmetric so that the problem is the convex program that
  // Lawson and Hanson's method needs.
  work.Ks = K.transpose();
  work.plain = 0.5 * (K + work.Ks);
  K = work.plain;
  K.diagonal().array() += kMinimumNormRegularisation * K.diagonal().maxCoeff();
  work.symmetric = true;
  return true;
}

// The indices of the rows flagged in `set`, into idx; returns their count.
int rowsOf(const std::vector<char>& set, std::vector<int>& idx) {
  idx.clear();
  for (int i = 0; i < static_cast<int>(set.size()); ++i)
    if (set[i]) idx.push_back(i);
  return static_cast<int>(idx.size());
}

// K_SS and b_S of the rows idx.
void gatherSet(const Eigen::MatrixXd& K, const Eigen::VectorXd& b, const std::vector<int>& idx,
               Eigen::MatrixXd& Ks, Eigen::VectorXd& bs) {
  const int m = static_cast<int>(idx.size());
  Ks.resize(m, m);
  bs.resize(m);
  for (int r = 0; r < m; ++r) {
    bs[r] = b[idx[r]];
    for (int c = 0; c < m; ++c) Ks(r, c) = K(idx[r], idx[c]);
  }
}

// b with its part on the rows in `set` projected onto the range of K_SS (K_SS K_SS^+ b_S, by a
// complete orthogonal decomposition), the other rows as they are: the targets of the rows that
// pull, made consistent among themselves. The slack rows' targets (a cable slack by centimetres)
// stay out of it: projected with the rest they moved the taut cables' targets, which then held
// a ring on 5 spokes 17 mm long.
void projectTargets(const Eigen::MatrixXd& K, const Eigen::VectorXd& b,
                    const std::vector<char>& set, LcpWorkspace& work) {
  work.projected = b;
  const int m = rowsOf(set, work.idx);
  if (m == 0) return;
  gatherSet(K, b, work.idx, work.sub, work.subB);
  work.cod.setThreshold(kRankTolerance);
  work.cod.compute(work.sub);
  work.subX = work.cod.solve(work.subB);
  work.subB.noalias() = work.sub * work.subX;
  for (int r = 0; r < m; ++r) work.projected[work.idx[r]] = work.subB[r];
}

// x_S = K_SS^-1 b_S on the rows flagged in `set`, 0 elsewhere.
void solveOnSet(const Eigen::MatrixXd& K, const Eigen::VectorXd& b, const std::vector<char>& set,
                LcpWorkspace& work, Eigen::VectorXd& x) {
  std::vector<int>& idx = work.idx;
  const int m = rowsOf(set, idx);
  x.setZero(b.size());
  if (m == 0) return;
  // One or two rows (a hand's two membranes): closed form, well away from singular. Eigen's
  // factorisations cost more than the rest of the solve at these sizes.
  if (m == 1 && K(idx[0], idx[0]) > 0) {
    x[idx[0]] = b[idx[0]] / K(idx[0], idx[0]);
    return;
  }
  if (m == 2 && solveTwoRows(K, b, idx[0], idx[1], x[idx[0]], x[idx[1]])) return;
  gatherSet(K, b, idx, work.Ks, work.bs);
  if (work.symmetric) {
    work.ldlt.compute(work.Ks);
    work.xs = work.ldlt.solve(work.bs);
  } else {
    work.lu.compute(work.Ks);
    work.xs = work.lu.solve(work.bs);
  }
  for (int r = 0; r < m; ++r) x[idx[r]] = work.xs[r];
}

// Principal pivoting from the rows with b > 0: drop the most negative impulse, else add the most
// violated slack row. A few changes for these sizes when K is definite.
void principalPivoting(const Eigen::MatrixXd& K, const Eigen::VectorXd& b, LcpWorkspace& work,
                       LcpSolution& sol) {
  const int n = static_cast<int>(b.size());
  std::vector<char>& active = work.active;
  active.resize(n);
  for (int i = 0; i < n; ++i) active[i] = b[i] > 0;
  Eigen::VectorXd& w = work.w;
  for (const int maxIterations = 4 * n + 10; sol.iterations < maxIterations; ++sol.iterations) {
    solveOnSet(K, b, active, work, sol.x);
    w.noalias() = K.lazyProduct(sol.x);  // a few rows: no GEMV kernel call
    w -= b;
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
}

// Lawson and Hanson's active-set method (the NNLS algorithm, on the normal equations): adds the
// row that most wants to pull, then steps back along the segment to the new sub-solution until
// every impulse is >= 0. Finite for a definite K even when many rows are nearly dependent, where
// plain principal pivoting can cycle (40 spokes on one ring).
void lawsonHanson(const Eigen::MatrixXd& K, const Eigen::VectorXd& b, LcpWorkspace& work,
                  LcpSolution& sol) {
  const int n = static_cast<int>(b.size());
  std::vector<char>& passive = work.active;
  Eigen::VectorXd &x = sol.x, &s = work.step, &g = work.w;
  // Warm start: the rows with b > 0, less those the sub-solution gives a negative impulse, while
  // that is a feasible point (x >= 0); else from x = 0.
  passive.resize(n);
  for (int i = 0; i < n; ++i) passive[i] = b[i] > 0;
  bool feasible = false;
  for (int round = 0; round < 4 && !feasible; ++round, ++sol.iterations) {
    solveOnSet(K, b, passive, work, x);
    feasible = true;
    for (int i = 0; i < n; ++i)
      if (passive[i] && x[i] < 0) passive[i] = 0, feasible = false;
  }
  if (!feasible) {
    passive.assign(n, 0);
    x.setZero(n);
  }
  // A row whose impulse would grow by less than this (N s) is done.
  double scale = 0;
  for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(b[i]) / K(i, i));
  const double tolerance = 1e-7 * scale;      // the regularisation makes x exact to about 1e-6
  std::vector<char>& blocked = work.blocked;  // added, and dropped again at once: not now
  blocked.assign(n, 0);
  for (const int maxIterations = 10 * n + 10; sol.iterations < maxIterations;) {
    g.noalias() = K * x;
    g = b - g;  // -(K x - b): positive where a row wants more pull
    int best = -1;
    for (int i = 0; i < n; ++i)
      if (!passive[i] && !blocked[i] && g[i] / K(i, i) > tolerance &&
          (best < 0 || g[i] / K(i, i) > g[best] / K(best, best)))
        best = i;
    if (best < 0) break;
    passive[best] = 1;
    for (; sol.iterations < maxIterations; ++sol.iterations) {
      solveOnSet(K, b, passive, work, s);
      double alpha = 1;
      for (int i = 0; i < n; ++i)
        if (passive[i] && s[i] <= 0) alpha = std::min(alpha, x[i] / (x[i] - s[i]));
      x += alpha * (s - x);
      if (alpha >= 1) break;
      for (int i = 0; i < n; ++i)
        if (passive[i] && x[i] <= 1e-15 * (1 + x.lpNorm<Eigen::Infinity>()))
          passive[i] = 0, x[i] = 0;
    }
    if (passive[best])
      blocked.assign(n, 0);  // progress: every row may be tried again
    else
      blocked[best] = 1;
  }
}

// Symmetric to rounding (no temporary: this runs every sub-step).
bool isSymmetric(const Eigen::MatrixXd& K) {
  const double tolerance = 1e-12 * K.cwiseAbs().maxCoeff();
  for (int c = 0; c < K.cols(); ++c)
    for (int r = c + 1; r < K.rows(); ++r)
      if (std::abs(K(r, c) - K(c, r)) > tolerance) return false;
  return true;
}

}  // namespace

double minimumNormCompliance(const Eigen::VectorXd& diagonal) {
  // As solveLcp regularises K's diagonal, then makeMinimumNorm.
  double largest = 0;
  for (const double k : diagonal) largest = std::max(largest, k + 1e-12 * (1 + k));
  return kMinimumNormRegularisation * largest;
}

bool rankDeficient(const Eigen::LDLT<Eigen::MatrixXd>& ldlt) {
  const auto d = ldlt.vectorD();
  const double largest = d.cwiseAbs().maxCoeff();
  return !(d.minCoeff() > kRankTolerance * largest);
}

LcpSolution solveLcp(const Eigen::MatrixXd& K, const Eigen::VectorXd& b) {
  LcpWorkspace work;
  LcpSolution sol;
  solveLcp(K, b, work, sol);
  return sol;
}

void solveLcp(const Eigen::MatrixXd& Kin, const Eigen::VectorXd& b, LcpWorkspace& work,
              LcpSolution& sol, bool redundant) {
  const int n = static_cast<int>(b.size());
  // A row that touches only immovable bodies has K_ii = 0: regularise so it stays solvable.
  Eigen::MatrixXd& K = work.K;
  K = Kin;
  for (int i = 0; i < n; ++i) K(i, i) += 1e-12 * (1 + K(i, i));
  if (n == 1 && K(0, 0) > std::numeric_limits<double>::min())
    return solveSingle(K(0, 0), b[0], sol);
  if (n == 2 && !redundant && solveBothTaut(K, Kin, b, sol)) return;

  sol.x.setZero(n);
  sol.iterations = 0;
  sol.residual = 0;
  sol.rankDeficient = false;
  // A cable sliding on a capstan pulls with e^(mu theta) times the tension its constraint row
  // carries: K is then not symmetric (docs/wheels.md) and needs LU instead of LDLT.
  work.symmetric = isSymmetric(K);
  sol.rankDeficient = redundant && makeMinimumNorm(K, work);
  if (sol.rankDeficient) {
    // The rows that pull: first those whose targets ask for pull, then those the solve made
    // pull; their targets are made consistent (projectTargets) and the solve run again until
    // no row outside them pulls.
    std::vector<char>& pulling = work.pulling;
    pulling.resize(n);
    for (int i = 0; i < n; ++i) pulling[i] = b[i] > 0;
    int iterations = 0;
    for (int round = 0; round < 4; ++round) {
      projectTargets(work.plain, b, pulling, work);
      sol.iterations = 0;
      lawsonHanson(K, work.projected, work, sol);
      iterations += sol.iterations;
      bool grown = false;
      for (int i = 0; i < n; ++i)
        if (sol.x[i] > 0 && !pulling[i]) pulling[i] = 1, grown = true;
      if (!grown) break;
    }
    sol.iterations = iterations;
  } else {
    principalPivoting(K, b, work, sol);
  }
  Eigen::VectorXd& w = work.w;
  w.noalias() = Kin.lazyProduct(sol.x);  // the residual against the targets as given
  w -= b;
  for (int i = 0; i < n; ++i) {
    sol.x[i] = std::max(0.0, sol.x[i]);
    sol.residual = std::max(sol.residual, std::abs(std::min(sol.x[i] * K(i, i), w[i])));
  }
}

}  // namespace cablelab

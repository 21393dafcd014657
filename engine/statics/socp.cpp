#include "engine/statics/socp.h"

#include "engine/statics/statics_newton.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace cablelab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kConvergedResidual = 1e-10;  // |net force| / max tension

/// One Lorentz cone Q^3 = {(x0, x1, x2): x0 >= |(x1, x2)|}: slack, dual, NT scaling, direction.
struct Soc {
  double s[3], z[3];    // primal slack and dual variable
  double rz[3];         // this cone's rows of G x + s - h
  double eta, w[3];     // NT scaling W = eta * Wbar(w)
  double lam[3];        // scaled point lambda = W z = W^-1 s
  double V[6];          // W^-2 (symmetric: 00 01 02 11 12 22)
  double xi[3];         // right-hand side part, see solveDirection()
  double ds[3], dz[3];  // search direction
  double corr[3];       // Mehrotra's second-order term (W^-1 ds_aff) o (W dz_aff)
};

/// sqrt(x0^2 - |x1|^2), computed as a product to limit cancellation; <= 0 outside the cone.
inline double coneNorm(const double* x) {
  const double r = std::sqrt(x[1] * x[1] + x[2] * x[2]);
  const double det = (x[0] - r) * (x[0] + r);
  return det > 0 ? std::sqrt(det) : 0.0;
}

inline void wbar(const double* w, const double* v, double* out) {
  const double wv = w[1] * v[1] + w[2] * v[2];
  const double f = v[0] + wv / (1 + w[0]);
  out[0] = w[0] * v[0] + wv;
  out[1] = v[1] + f * w[1];
  out[2] = v[2] + f * w[2];
}

inline void wbarInverse(const double* w, const double* v, double* out) {
  const double wv = w[1] * v[1] + w[2] * v[2];
  const double f = -v[0] + wv / (1 + w[0]);
  out[0] = w[0] * v[0] - wv;
  out[1] = v[1] + f * w[1];
  out[2] = v[2] + f * w[2];
}

/// Nesterov-Todd scaling of a cone with interior s and z. False if either left the interior.
inline bool ntScaling(Soc& c) {
  const double ns = coneNorm(c.s), nz = coneNorm(c.z);
  if (!(ns > 0 && nz > 0)) return false;
  double sb[3], zb[3];
  for (int i = 0; i < 3; ++i) sb[i] = c.s[i] / ns, zb[i] = c.z[i] / nz;
  const double gamma = std::sqrt(0.5 * (1 + sb[0] * zb[0] + sb[1] * zb[1] + sb[2] * zb[2]));
  const double g2 = 0.5 / gamma;
  c.w[0] = (sb[0] + zb[0]) * g2;
  c.w[1] = (sb[1] - zb[1]) * g2;
  c.w[2] = (sb[2] - zb[2]) * g2;
  c.eta = std::sqrt(ns / nz);
  const double inv = nz / ns;  // eta^-2
  const double* w = c.w;
  c.V[0] = inv * (2 * w[0] * w[0] - 1);
  c.V[1] = -2 * inv * w[0] * w[1];
  c.V[2] = -2 * inv * w[0] * w[2];
  c.V[3] = inv * (2 * w[1] * w[1] + 1);
  c.V[4] = 2 * inv * w[1] * w[2];
  c.V[5] = inv * (2 * w[2] * w[2] + 1);
  wbar(c.w, c.z, c.lam);
  for (double& l : c.lam) l *= c.eta;
  return true;
}

/// out = V v for the packed symmetric 3x3 V.
inline void symMul(const double* V, const double* v, double* out) {
  out[0] = V[0] * v[0] + V[1] * v[1] + V[2] * v[2];
  out[1] = V[1] * v[0] + V[3] * v[1] + V[4] * v[2];
  out[2] = V[2] * v[0] + V[4] * v[1] + V[5] * v[2];
}

/// Jordan product u o v = (u.v, u0 v1 + v0 u1).
inline void jordan(const double* u, const double* v, double* out) {
  out[0] = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  out[1] = u[0] * v[1] + v[0] * u[1];
  out[2] = u[0] * v[2] + v[0] * u[2];
}

/// x with lam o x = r (lam interior).
inline void jordanDivide(const double* lam, const double* r, double* x) {
  const double det = lam[0] * lam[0] - lam[1] * lam[1] - lam[2] * lam[2];
  x[0] = (lam[0] * r[0] - lam[1] * r[1] - lam[2] * r[2]) / det;
  x[1] = (r[1] - x[0] * lam[1]) / lam[0];
  x[2] = (r[2] - x[0] * lam[2]) / lam[0];
}

/// Largest alpha with x + alpha d in Q^3 (x interior); kInf when d points into the cone.
inline double maxStepSoc(const double* x, const double* d) {
  const double a = d[0] * d[0] - d[1] * d[1] - d[2] * d[2];
  const double b = 2 * (x[0] * d[0] - x[1] * d[1] - x[2] * d[2]);
  const double c = x[0] * x[0] - x[1] * x[1] - x[2] * x[2];
  if (a >= 0 && d[0] >= 0) return kInf;  // d in the cone
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return kInf;  // never reaches the boundary (only round-off can get here)
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double best = kInf;
  if (a != 0) {
    const double r1 = q / a;
    if (r1 > 0) best = std::min(best, r1);
  }
  if (q != 0) {
    const double r2 = c / q;
    if (r2 > 0) best = std::min(best, r2);
  }
  if (best == kInf && d[0] < 0) best = -x[0] / d[0];
  return best;
}

inline double maxStepLp(double x, double d) {
  return d < 0 ? -x / d : kInf;
}

}  // namespace

struct SocpWorkspace::Cable {
  double a[2], b[2], k, L;  // scaled data
  double la, lb, t;         // primal variables besides p
  double s0, s1, z0, z1;    // orthant cones: t >= 0 and t - la - lb + L >= 0
  double rz0, rz1;          // their rows of G x + s - h
  double d0, d1;            // W^-2 = z / s of the orthant cones
  double xi0, xi1;          // right-hand side parts
  double ds0, ds1, dz0, dz1, corr0, corr1;
  Soc ca, cb;           // (la, p - a) and (lb, p - b)
  double rla, rlb, rt;  // dual residual rows
  double Di[6];         // inverse of the cable's 3x3 block, packed symmetric
  double dla, dlb, dt;  // direction
  double xla, xlb, xt;  // direction before a refinement step
};

SocpWorkspace::SocpWorkspace() = default;
SocpWorkspace::~SocpWorkspace() = default;

namespace {

using Cable = SocpWorkspace::Cable;

/// Solves (P + G^T W^-2 G) dx = rhs given the factorised blocks: the p rows of rhs in rhsP, a
/// cable's rows in its (dla, dlb, dt) on entry; the cable's rows of dx replace them on exit.
void solveReduced(Cable* cab, int n, const double schurInv[3], const double rhsP[2], double dp[2]) {
  double rhs[2] = {rhsP[0], rhsP[1]};
  for (int i = 0; i < n; ++i) {
    const Cable& c = cab[i];
    const double* D = c.Di;
    const double u0 = D[0] * c.dla + D[1] * c.dlb + D[2] * c.dt;
    const double u1 = D[1] * c.dla + D[3] * c.dlb + D[4] * c.dt;
    // Subtract B_i D_i^-1 y_i, where B_i's columns are V_a[1:2,0], V_b[1:2,0], 0.
    rhs[0] -= c.ca.V[1] * u0 + c.cb.V[1] * u1;
    rhs[1] -= c.ca.V[2] * u0 + c.cb.V[2] * u1;
  }
  dp[0] = schurInv[0] * rhs[0] + schurInv[1] * rhs[1];
  dp[1] = schurInv[1] * rhs[0] + schurInv[2] * rhs[1];
  for (int i = 0; i < n; ++i) {
    Cable& c = cab[i];
    const double y0 = c.dla - (c.ca.V[1] * dp[0] + c.ca.V[2] * dp[1]);
    const double y1 = c.dlb - (c.cb.V[1] * dp[0] + c.cb.V[2] * dp[1]);
    const double y2 = c.dt;
    const double* D = c.Di;
    c.dla = D[0] * y0 + D[1] * y1 + D[2] * y2;
    c.dlb = D[1] * y0 + D[3] * y1 + D[4] * y2;
    c.dt = D[2] * y0 + D[4] * y1 + D[5] * y2;
  }
}

/// Search direction for the cones' xi (see socXi) and the residuals, with `refinements` steps
/// of iterative refinement on the first block row P dx + G^T dz = -r_x: the reduced system is
/// ill-conditioned near the end (W^-2 ~ 1 / mu) and one cheap correction restores accuracy.
void solveDirection(Cable* cab, int n, const double schurInv[3], const double rp[2],
                    int refinements, double dp[2]) {
  double rhsP[2] = {-rp[0], -rp[1]};
  for (int i = 0; i < n; ++i) {
    Cable& c = cab[i];
    c.dla = -c.rla - c.xi1 + c.ca.xi[0];
    c.dlb = -c.rlb - c.xi1 + c.cb.xi[0];
    c.dt = -c.rt + c.xi0 + c.xi1;
    rhsP[0] += c.ca.xi[1] + c.cb.xi[1];
    rhsP[1] += c.ca.xi[2] + c.cb.xi[2];
  }
  solveReduced(cab, n, schurInv, rhsP, dp);
  for (int i = 0; i < n; ++i) {
    Cable& c = cab[i];
    // Cone directions: dz = W^-2 G dx + xi, ds = -rz - G dx.
    const double g0 = -c.dt, g1 = c.dla + c.dlb - c.dt;
    c.dz0 = c.d0 * g0 + c.xi0;
    c.dz1 = c.d1 * g1 + c.xi1;
    c.ds0 = -c.rz0 - g0;
    c.ds1 = -c.rz1 - g1;
    const double ga[3] = {-c.dla, -dp[0], -dp[1]};
    const double gb[3] = {-c.dlb, -dp[0], -dp[1]};
    symMul(c.ca.V, ga, c.ca.dz);
    symMul(c.cb.V, gb, c.cb.dz);
    for (int j = 0; j < 3; ++j) {
      c.ca.dz[j] += c.ca.xi[j];
      c.cb.dz[j] += c.cb.xi[j];
      c.ca.ds[j] = -c.ca.rz[j] - ga[j];
      c.cb.ds[j] = -c.cb.rz[j] - gb[j];
    }
  }
  for (int r = 0; r < refinements; ++r) {
    // e = -r_x - P dx - G^T dz; the correction solves the same system with xi = 0, rz = 0.
    double eP[2] = {-rp[0], -rp[1]};
    for (int i = 0; i < n; ++i) {
      Cable& c = cab[i];
      eP[0] += c.ca.dz[1] + c.cb.dz[1];
      eP[1] += c.ca.dz[2] + c.cb.dz[2];
      c.xla = c.dla, c.xlb = c.dlb, c.xt = c.dt;
      c.dla = -c.rla - (c.dz1 - c.ca.dz[0]);
      c.dlb = -c.rlb - (c.dz1 - c.cb.dz[0]);
      c.dt = -c.rt - (c.k * c.xt - c.dz0 - c.dz1);
    }
    double ep[2];
    solveReduced(cab, n, schurInv, eP, ep);
    dp[0] += ep[0];
    dp[1] += ep[1];
    for (int i = 0; i < n; ++i) {
      Cable& c = cab[i];
      const double g0 = -c.dt, g1 = c.dla + c.dlb - c.dt;
      c.dz0 += c.d0 * g0;
      c.dz1 += c.d1 * g1;
      c.ds0 -= g0;
      c.ds1 -= g1;
      const double ga[3] = {-c.dla, -ep[0], -ep[1]};
      const double gb[3] = {-c.dlb, -ep[0], -ep[1]};
      double za[3], zb[3];
      symMul(c.ca.V, ga, za);
      symMul(c.cb.V, gb, zb);
      for (int j = 0; j < 3; ++j) {
        c.ca.dz[j] += za[j], c.cb.dz[j] += zb[j];
        c.ca.ds[j] -= ga[j], c.cb.ds[j] -= gb[j];
      }
      c.dla += c.xla, c.dlb += c.xlb, c.dt += c.xt;
    }
  }
}

/// Largest step keeping every s and z in its cone (capped at 1 / stepFraction's reach).
double maxStep(const Cable* cab, int n) {
  double alpha = kInf;
  for (int i = 0; i < n; ++i) {
    const Cable& c = cab[i];
    alpha =
        std::min({alpha, maxStepLp(c.s0, c.ds0), maxStepLp(c.s1, c.ds1), maxStepLp(c.z0, c.dz0),
                  maxStepLp(c.z1, c.dz1), maxStepSoc(c.ca.s, c.ca.ds), maxStepSoc(c.ca.z, c.ca.dz),
                  maxStepSoc(c.cb.s, c.cb.ds), maxStepSoc(c.cb.z, c.cb.dz)});
  }
  return alpha;
}

/// xi of a second-order cone for the complementarity target r_c: V rz + W^-1 (lam \ r_c).
inline void socXi(Soc& c, const double* rc) {
  double u[3], wu[3];
  jordanDivide(c.lam, rc, u);
  wbarInverse(c.w, u, wu);
  symMul(c.V, c.rz, c.xi);
  const double ie = 1 / c.eta;
  for (int j = 0; j < 3; ++j) c.xi[j] += ie * wu[j];
}

}  // namespace

namespace {

/// Newton steps on E from the interior-point answer, each kept only if it lowers |dE/dp|
/// without raising E: the interior point's p is accurate to about sqrt(gap), Newton squares that.
void polish(const StaticsProblem& problem, Vec2& p, StaticsDerivatives d, double scale,
            int maxSteps, int& taken) {
  for (int i = 0; i < maxSteps && d.maxTension > 0; ++i) {
    const double gnorm = d.gradient.norm();
    if (gnorm <= 1e-14 * d.maxTension) break;
    Eigen::Matrix2d h = d.hessian;
    h.diagonal().array() += levenbergShift(h, gnorm, scale);
    const double det = h(0, 0) * h(1, 1) - h(0, 1) * h(1, 0);
    const Vec2 step(-(h(1, 1) * d.gradient.x() - h(0, 1) * d.gradient.y()) / det,
                    -(h(0, 0) * d.gradient.y() - h(1, 0) * d.gradient.x()) / det);
    if (!step.allFinite()) break;
    const StaticsDerivatives next = staticsDerivatives(problem, p + step);
    if (next.nearestDistance == 0 || next.gradient.norm() >= gnorm ||
        next.energy > d.energy * (1 + 1e-14))
      break;
    p += step;
    d = next;
    ++taken;
  }
}

}  // namespace

void solveStaticsSocp(const StaticsProblem& problem, StaticsResult& result,
                      SocpWorkspace& workspace, const SocpOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int n = int(problem.cables.size());
  auto& cables = workspace.cables_;
  if (int(cables.size()) != n) cables.resize(n);
  Cable* cab = cables.data();

  // Scale to unit length about the fingertips' centroid and unit largest stiffness.
  Vec2 centre = Vec2::Zero();
  double kmax = 0;
  for (const StaticsCable& c : problem.cables) centre += c.a + c.b, kmax = std::max(kmax, c.k);
  centre /= 2.0 * n;
  const double scale = staticsLengthScale(problem);
  const double invScale = 1 / scale;
  const bool warm = options.warmStart && workspace.hasLast_;
  const Vec2 guess = warm ? workspace.lastP_ : staticsInitialGuess(problem);
  double p[2] = {(guess.x() - centre.x()) * invScale, (guess.y() - centre.y()) * invScale};

  // Start: l_ij a margin above |p - p_ij|, t a margin above its bounds; duals that balance
  // the l and t rows exactly (z_ij0 = z_i1, z_i0 + z_i1 = k t).
  const double margin = warm ? 0.1 : 1.0;
  for (int i = 0; i < n; ++i) {
    const StaticsCable& src = problem.cables[i];
    Cable& c = cab[i];
    c.a[0] = (src.a.x() - centre.x()) * invScale, c.a[1] = (src.a.y() - centre.y()) * invScale;
    c.b[0] = (src.b.x() - centre.x()) * invScale, c.b[1] = (src.b.y() - centre.y()) * invScale;
    c.k = src.k / kmax;
    c.L = src.L * invScale;
    c.la = Vec2(p[0] - c.a[0], p[1] - c.a[1]).norm() + margin;
    c.lb = Vec2(p[0] - c.b[0], p[1] - c.b[1]).norm() + margin;
    c.t = std::max(0.0, c.la + c.lb - c.L) + margin;
    c.s0 = c.t;
    c.s1 = c.t - c.la - c.lb + c.L;
    c.ca.s[0] = c.la, c.ca.s[1] = p[0] - c.a[0], c.ca.s[2] = p[1] - c.a[1];
    c.cb.s[0] = c.lb, c.cb.s[1] = p[0] - c.b[0], c.cb.s[2] = p[1] - c.b[1];
    const double zt = 0.5 * c.k * c.t;
    c.z0 = zt, c.z1 = zt;
    c.ca.z[0] = zt, c.ca.z[1] = 0, c.ca.z[2] = 0;
    c.cb.z[0] = zt, c.cb.z[1] = 0, c.cb.z[2] = 0;
  }

  const double degree = 4.0 * n;  // 2 N orthant + 2 N Lorentz cones, each of degree 1
  SocpStats& stats = workspace.stats_;
  stats = SocpStats{};
  int iter = 0;
  double lastGap = kInf;
  for (;; ++iter) {
    // Residuals and the gap.
    double rp[2] = {0, 0};
    double gap = 0, pres = 0, dres = 0;
    for (int i = 0; i < n; ++i) {
      Cable& c = cab[i];
      rp[0] -= c.ca.z[1] + c.cb.z[1];
      rp[1] -= c.ca.z[2] + c.cb.z[2];
      c.rla = c.z1 - c.ca.z[0];
      c.rlb = c.z1 - c.cb.z[0];
      c.rt = c.k * c.t - c.z0 - c.z1;
      c.rz0 = c.s0 - c.t;
      c.rz1 = c.s1 + c.la + c.lb - c.t - c.L;
      c.ca.rz[0] = c.ca.s[0] - c.la;
      c.ca.rz[1] = c.ca.s[1] - (p[0] - c.a[0]);
      c.ca.rz[2] = c.ca.s[2] - (p[1] - c.a[1]);
      c.cb.rz[0] = c.cb.s[0] - c.lb;
      c.cb.rz[1] = c.cb.s[1] - (p[0] - c.b[0]);
      c.cb.rz[2] = c.cb.s[2] - (p[1] - c.b[1]);
      gap += c.s0 * c.z0 + c.s1 * c.z1;
      for (int j = 0; j < 3; ++j) gap += c.ca.s[j] * c.ca.z[j] + c.cb.s[j] * c.cb.z[j];
      dres = std::max({dres, std::abs(c.rla), std::abs(c.rlb), std::abs(c.rt)});
      pres = std::max({pres, std::abs(c.rz0), std::abs(c.rz1), std::abs(c.ca.rz[0]),
                       std::abs(c.ca.rz[1]), std::abs(c.ca.rz[2]), std::abs(c.cb.rz[0]),
                       std::abs(c.cb.rz[1]), std::abs(c.cb.rz[2])});
    }
    dres = std::max({dres, std::abs(rp[0]), std::abs(rp[1])});
    stats.gap = gap, stats.primalResidual = pres, stats.dualResidual = dres;
    if (gap <= options.gapTol && pres <= options.feasTol && dres <= options.feasTol) {
      stats.converged = true;
      break;
    }
    if (iter >= options.maxIterations) break;
    // Stalled at round-off near the goal: the polish below finishes the job.
    if (gap <= 100 * options.gapTol && gap > 0.5 * lastGap) {
      stats.converged = pres <= options.feasTol && dres <= options.feasTol;
      break;
    }
    lastGap = gap;
    const double mu = gap / degree;

    // Scalings, the cables' 3x3 blocks and the 2x2 Schur complement in p.
    double schur[3] = {0, 0, 0};
    bool interior = true;
    for (int i = 0; i < n; ++i) {
      Cable& c = cab[i];
      // Both scalings must be computed (they fill c.ca and c.cb), so no short-circuit.
      const bool insideA = ntScaling(c.ca), insideB = ntScaling(c.cb);
      interior = interior && insideA && insideB;
      c.d0 = c.z0 / c.s0;
      c.d1 = c.z1 / c.s1;
      // Block of (la, lb, t): P + G^T W^-2 G restricted to the cable.
      const double A = c.d1 + c.ca.V[0], B = c.d1, C = -c.d1;
      const double D = c.d1 + c.cb.V[0], E = -c.d1, F = c.d0 + c.d1 + c.k;
      const double c00 = D * F - E * E, c01 = C * E - B * F, c02 = B * E - C * D;
      const double c11 = A * F - C * C, c12 = B * C - A * E, c22 = A * D - B * B;
      const double idet = 1 / (A * c00 + B * c01 + C * c02);
      double* Di = c.Di;
      Di[0] = c00 * idet, Di[1] = c01 * idet, Di[2] = c02 * idet;
      Di[3] = c11 * idet, Di[4] = c12 * idet, Di[5] = c22 * idet;
      const double va0 = c.ca.V[1], va1 = c.ca.V[2], vb0 = c.cb.V[1], vb1 = c.cb.V[2];
      // p block of the cones minus B_i D_i^-1 B_i^T (only the l rows of D_i^-1 matter).
      const double q00 = Di[0] * va0 + Di[1] * vb0, q01 = Di[0] * va1 + Di[1] * vb1;
      const double q10 = Di[1] * va0 + Di[3] * vb0, q11 = Di[1] * va1 + Di[3] * vb1;
      schur[0] += c.ca.V[3] + c.cb.V[3] - (va0 * q00 + vb0 * q10);
      schur[1] += c.ca.V[4] + c.cb.V[4] - (va0 * q01 + vb0 * q11);
      schur[2] += c.ca.V[5] + c.cb.V[5] - (va1 * q01 + vb1 * q11);
    }
    if (!interior) break;  // round-off pushed an iterate onto a cone boundary: stop here
    double sdet = schur[0] * schur[2] - schur[1] * schur[1];
    // Guard: with no curvature along some direction of p (one taut cable and p on its own a-b
    // segment: every point of the segment is a minimiser) the Schur complement is singular and
    // the direction would be NaN. A tiny proximal term picks the nearest minimiser instead.
    if (!(sdet > 1e-12 * std::abs(schur[0] * schur[2]))) {
      const double reg = 1e-9 * (std::abs(schur[0]) + std::abs(schur[2])) + 1e-300;
      schur[0] += reg, schur[2] += reg;
      sdet = schur[0] * schur[2] - schur[1] * schur[1];
    }
    const double schurInv[3] = {schur[2] / sdet, -schur[1] / sdet, schur[0] / sdet};

    // Predictor (affine scaling): complementarity target 0, so W^-1 (lam \ -lam o lam) = -z.
    for (int i = 0; i < n; ++i) {
      Cable& c = cab[i];
      c.xi0 = c.d0 * c.rz0 - c.z0;
      c.xi1 = c.d1 * c.rz1 - c.z1;
      symMul(c.ca.V, c.ca.rz, c.ca.xi);
      symMul(c.cb.V, c.cb.rz, c.cb.xi);
      for (int j = 0; j < 3; ++j) c.ca.xi[j] -= c.ca.z[j], c.cb.xi[j] -= c.cb.z[j];
    }
    double dp[2];
    solveDirection(cab, n, schurInv, rp, options.refinements, dp);
    const double alphaAff = std::min(1.0, maxStep(cab, n));
    double gapAff = 0;
    for (int i = 0; i < n; ++i) {
      const Cable& c = cab[i];
      gapAff += (c.s0 + alphaAff * c.ds0) * (c.z0 + alphaAff * c.dz0) +
                (c.s1 + alphaAff * c.ds1) * (c.z1 + alphaAff * c.dz1);
      for (int j = 0; j < 3; ++j) {
        gapAff += (c.ca.s[j] + alphaAff * c.ca.ds[j]) * (c.ca.z[j] + alphaAff * c.ca.dz[j]) +
                  (c.cb.s[j] + alphaAff * c.cb.ds[j]) * (c.cb.z[j] + alphaAff * c.cb.dz[j]);
      }
    }
    const double ratio = std::clamp(gapAff / gap, 0.0, 1.0);
    const double sigmaMu = ratio * ratio * ratio * mu;

    // Corrector: target sigma mu e minus the predictor's second-order term.
    for (int i = 0; i < n; ++i) {
      Cable& c = cab[i];
      c.xi0 = (c.z0 * c.rz0 - c.s0 * c.z0 - c.ds0 * c.dz0 + sigmaMu) / c.s0;
      c.xi1 = (c.z1 * c.rz1 - c.s1 * c.z1 - c.ds1 * c.dz1 + sigmaMu) / c.s1;
      for (Soc* cone : {&c.ca, &c.cb}) {
        double st[3], zt[3], ll[3], rc[3];
        wbarInverse(cone->w, cone->ds, st);
        wbar(cone->w, cone->dz, zt);  // the eta factors of W^-1 and W cancel in the product
        jordan(st, zt, cone->corr);
        jordan(cone->lam, cone->lam, ll);
        rc[0] = -ll[0] - cone->corr[0] + sigmaMu;
        rc[1] = -ll[1] - cone->corr[1];
        rc[2] = -ll[2] - cone->corr[2];
        socXi(*cone, rc);
      }
    }
    solveDirection(cab, n, schurInv, rp, options.refinements, dp);
    const double alpha = std::min(1.0, options.stepFraction * maxStep(cab, n));

    p[0] += alpha * dp[0];
    p[1] += alpha * dp[1];
    for (int i = 0; i < n; ++i) {
      Cable& c = cab[i];
      c.la += alpha * c.dla, c.lb += alpha * c.dlb, c.t += alpha * c.dt;
      c.s0 += alpha * c.ds0, c.s1 += alpha * c.ds1;
      c.z0 += alpha * c.dz0, c.z1 += alpha * c.dz1;
      for (int j = 0; j < 3; ++j) {
        c.ca.s[j] += alpha * c.ca.ds[j], c.ca.z[j] += alpha * c.ca.dz[j];
        c.cb.s[j] += alpha * c.cb.ds[j], c.cb.z[j] += alpha * c.cb.dz[j];
      }
    }
  }
  stats.iterations = iter;

  result.p = centre + scale * Vec2(p[0], p[1]);
  // Guard: never hand on a non-finite point; the guess is finite (validated input) and the
  // snap / polish below start from it.
  if (!isFinite(result.p)) result.p = guess, stats.converged = false;
  stats.polishSteps = 0;
  // A fingertip point that passes the subgradient test is optimal (E is convex): snap onto it.
  const StaticsDerivatives at = staticsDerivatives(problem, result.p, options.polishSteps > 0);
  if (at.nearest >= 0 && at.nearestDistance <= 1e-3 * scale &&
      fingertipIsMinimiser(problem, at.nearest)) {
    result.p = fingertip(problem, at.nearest);
  } else {
    polish(problem, result.p, at, scale, options.polishSteps, stats.polishSteps);
  }
  workspace.lastP_ = result.p;
  workspace.hasLast_ = true;
  result.iterations = iter;
  result.method = StaticsMethod::Socp;
  result.fellBack = false;
  finishStaticsResult(problem, result);
  // The interior point may stall at round-off just above its gap tolerance; the answer still
  // counts when the snap or the polish brought the force residual down.
  result.converged = stats.converged || result.residual <= kConvergedResidual;
  result.solveMicros =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

StaticsResult solveStaticsSocp(const StaticsProblem& problem, const SocpOptions& options) {
  SocpWorkspace workspace;
  StaticsResult result;
  solveStaticsSocp(problem, result, workspace, options);
  return result;
}

}  // namespace cablelab

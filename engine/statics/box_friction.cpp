#include "engine/statics/box_friction.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "engine/core/capstan.h"

namespace cablelab {

namespace {

constexpr int kMaxStickSolves = 2000;      // stick solve, slide, again (converges geometrically)
constexpr double kSlideTolerance = 1e-12;  // material moved in the last slide, per unit material
constexpr double kPartialStep = 1e-6;      // central differences of the slide condition
constexpr double kStallResidual = 1e-7;    // |net force, torque / size| per unit max tension

struct Spans {
  BoxSegment a, b;
};

Spans spanSegments(const FrictionBoxCable& c, const BoxPose& q) {
  return {boxSegment(q, c.cable.cornerA, c.cable.a), boxSegment(q, c.cable.cornerB, c.cable.b)};
}

double spanStiffness(const FrictionBoxCable& c, double rest) {
  return c.cable.k * c.cable.L / std::max(rest, 1e-12);
}

double spanTension(const FrictionBoxCable& c, double length, double rest) {
  return c.cable.k * materialTension(c.cable.L, length, std::max(rest, 1e-12));
}

// The angle the membrane turns at its corners, each turn counted on the box's side.
double cornerTurns(const FrictionBoxCable& c, const BoxPose& q) {
  const Vec2 centre = q.head<2>();
  const Vec2 cA = centre + rotate(c.cable.cornerA, q[2]),
             cB = centre + rotate(c.cable.cornerB, q[2]);
  if ((cB - cA).norm() < 1e-300 || (cA - c.cable.a).norm() < 1e-300 ||
      (c.cable.b - cB).norm() < 1e-300)
    return 0;
  const Vec2 face = (cB - cA).normalized();
  const Vec2 in = (cA - c.cable.a).normalized(), out = (c.cable.b - cB).normalized();
  const double side = cross(face, centre - cA) < 0 ? -1.0 : 1.0;  // box on the right: clockwise
  auto turn = [&](const Vec2& u, const Vec2& v) {
    return std::max(0.0, side * std::atan2(cross(u, v), u.dot(v)));
  };
  return turn(in, face) + turn(face, out);
}

// The slide condition of a membrane sliding towards span A (direction +1) or B (-1):
// T_tight - e^(mu theta) T_loose, zero while it slides.
double slideCondition(const FrictionBoxCable& c, const BoxPose& q, int direction) {
  const FrictionSpans s = frictionSpans(c, q);
  return direction > 0 ? s.tensionA - s.ratio * s.tensionB : s.tensionB - s.ratio * s.tensionA;
}

// Slides material over the corners where the capstan ratio is broken; returns the material moved
// towards span A (m, negative: towards B).
double slide(FrictionBoxCable& c, const BoxPose& q) {
  const FrictionSpans s = frictionSpans(c, q);
  if (std::max(s.tensionA, s.tensionB) <= s.ratio * std::min(s.tensionA, s.tensionB) * (1 + 1e-12))
    return 0;
  const Spans seg = spanSegments(c, q);
  const double sum = c.restA + c.restB, before = c.restA;
  if (s.tensionA > s.tensionB) {
    c.restA = slideMaterial(c.cable.L, seg.a.length, c.restA, seg.b.length, sum, s.ratio);
    c.restB = sum - c.restA;
  } else {
    c.restB = slideMaterial(c.cable.L, seg.b.length, c.restB, seg.a.length, sum, s.ratio);
    c.restA = sum - c.restB;
  }
  return c.restA - before;
}

}  // namespace

void shareMaterial(std::vector<FrictionBoxCable>& cables, const BoxPose& q) {
  for (FrictionBoxCable& c : cables) {
    const Spans seg = spanSegments(c, q);
    const double run = (c.cable.cornerB - c.cable.cornerA).norm();
    const double whole = seg.a.length + run + seg.b.length;
    c.restA = c.cable.L * seg.a.length / whole;
    c.restB = c.cable.L * seg.b.length / whole;
  }
}

FrictionSpans frictionSpans(const FrictionBoxCable& c, const BoxPose& q) {
  const Spans seg = spanSegments(c, q);
  FrictionSpans s;
  s.tensionA = spanTension(c, seg.a.length, c.restA);
  s.tensionB = spanTension(c, seg.b.length, c.restB);
  s.turn = cornerTurns(c, q);
  s.ratio = std::exp(c.mu * s.turn);
  return s;
}

double frictionBoxEnergy(const std::vector<FrictionBoxCable>& cables, const BoxPose& q,
                         Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian) {
  double energy = 0;
  if (gradient) gradient->setZero();
  if (hessian) hessian->setZero();
  for (const FrictionBoxCable& c : cables) {
    const Spans seg = spanSegments(c, q);
    for (const auto& [s, rest] : {std::pair(&seg.a, c.restA), std::pair(&seg.b, c.restB)}) {
      const double stretch = s->length - rest;
      if (stretch <= 0) continue;  // slack: no energy, no force
      const double k = spanStiffness(c, rest);
      energy += 0.5 * k * stretch * stretch;
      if (gradient) *gradient += k * stretch * s->gradient.transpose();
      if (hessian) *hessian += k * (s->gradient.transpose() * s->gradient + stretch * s->hessian);
    }
  }
  return energy;
}

FrictionBoxResult solveFrictionBoxPose(const std::vector<FrictionBoxCable>& cables,
                                       const BoxPose& start, double size) {
  FrictionBoxResult out;
  out.cables = cables;
  out.pose = start;
  std::vector<double> slid(cables.size(), 0.0);  // material moved towards A over the solve
  double material = 0;
  for (const FrictionBoxCable& c : cables) material = std::max(material, c.cable.L);
  auto maxTension = [&](const BoxPose& q) {
    double t = 0;
    for (const FrictionBoxCable& c : out.cables) {
      const FrictionSpans s = frictionSpans(c, q);
      t = std::max({t, s.tensionA, s.tensionB});
    }
    return t;
  };
  for (out.iterations = 1; out.iterations <= kMaxStickSolves; ++out.iterations) {
    const BoxPoseResult stick = minimiseBoxEnergy(
        [&](const BoxPose& q, Eigen::Vector3d* g, Eigen::Matrix3d* H) {
          return frictionBoxEnergy(out.cables, q, g, H);
        },
        maxTension, out.pose, size, 100);
    out.pose = stick.pose;
    // From a pose already near balance the line search may stall on the energy's rounding just
    // above the solver's tolerance: that is balance enough.
    if (!stick.converged && !(stick.residual <= kStallResidual)) break;
    double moved = 0;
    for (size_t i = 0; i < out.cables.size(); ++i) {
      const double m = slide(out.cables[i], out.pose);
      slid[i] += m;
      moved = std::max(moved, std::abs(m));
    }
    if (moved <= kSlideTolerance * material) {
      out.converged = true;
      break;
    }
  }
  out.spans.clear();
  out.sliding.assign(cables.size(), 0);
  for (size_t i = 0; i < out.cables.size(); ++i) {
    const FrictionSpans s = frictionSpans(out.cables[i], out.pose);
    out.spans.push_back(s);
    // Slid, and still at the ratio (else it slid and then came to hold).
    const int direction = slid[i] > 0 ? 1 : slid[i] < 0 ? -1 : 0;
    if (direction != 0 && std::abs(slideCondition(out.cables[i], out.pose, direction)) <=
                              1e-9 * std::max(s.tensionA, s.tensionB))
      out.sliding[i] = direction;
  }
  return out;
}

// Unknowns z = (q, the sliding membranes' restA); equations F = (grad E, the slide conditions),
// restB = (restA + restB) - restA kept. dz/d tips = -F_z^-1 F_tips. The energy's partials are
// analytic; the slide conditions' (through the corner turns' angles) are central differences.
Eigen::MatrixXd frictionBoxSensitivity(const FrictionBoxResult& eq) {
  const std::vector<FrictionBoxCable>& cables = eq.cables;
  const Eigen::Index n = static_cast<Eigen::Index>(cables.size());
  std::vector<int> slides;
  for (int i = 0; i < n; ++i)
    if (eq.sliding[i] != 0) slides.push_back(i);
  const Eigen::Index m = 3 + static_cast<Eigen::Index>(slides.size());
  Eigen::MatrixXd Fz = Eigen::MatrixXd::Zero(m, m), Ft = Eigen::MatrixXd::Zero(m, 4 * n);
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  frictionBoxEnergy(cables, eq.pose, &g, &H);
  Fz.topLeftCorner<3, 3>() = H;
  for (Eigen::Index i = 0; i < n; ++i) {
    const FrictionBoxCable& c = cables[i];
    const Spans seg = spanSegments(c, eq.pose);
    int e = 0;
    for (const auto& [s, rest] : {std::pair(&seg.a, c.restA), std::pair(&seg.b, c.restB)}) {
      const double k = spanStiffness(c, rest), stretch = s->length - rest;
      if (stretch > 0)
        Ft.block<3, 2>(0, 4 * i + 2 * e) += s->mixedAnchor(k, k * stretch, s->gradient);
      ++e;
    }
  }
  for (size_t j = 0; j < slides.size(); ++j) {
    const int i = slides[j];
    const Eigen::Index row = 3 + static_cast<Eigen::Index>(j);
    const FrictionBoxCable& c = cables[i];
    const Spans seg = spanSegments(c, eq.pose);
    // d grad E / d restA: T_A = k L (l_A / r_A - 1) falls with r_A, T_B rises (r_B = sum - r_A).
    const double kL = c.cable.k * c.cable.L;
    const double dA = seg.a.length > c.restA ? -kL * seg.a.length / (c.restA * c.restA) : 0.0;
    const double dB = seg.b.length > c.restB ? kL * seg.b.length / (c.restB * c.restB) : 0.0;
    Fz.block<3, 1>(0, row) = dA * seg.a.gradient.transpose() + dB * seg.b.gradient.transpose();
    const int direction = eq.sliding[i];
    const double h = kPartialStep;
    for (int d = 0; d < 3; ++d) {
      BoxPose up = eq.pose, down = eq.pose;
      up[d] += h, down[d] -= h;
      Fz(row, d) =
          (slideCondition(c, up, direction) - slideCondition(c, down, direction)) / (2 * h);
    }
    auto withRest = [&](double delta) {
      FrictionBoxCable moved = c;
      moved.restA += delta, moved.restB -= delta;
      return slideCondition(moved, eq.pose, direction);
    };
    Fz(row, row) = (withRest(h) - withRest(-h)) / (2 * h);
    for (int t = 0; t < 4; ++t) {
      FrictionBoxCable up = c, down = c;
      Vec2& pu = t < 2 ? up.cable.a : up.cable.b;
      Vec2& pd = t < 2 ? down.cable.a : down.cable.b;
      pu[t % 2] += h, pd[t % 2] -= h;
      Ft(row, 4 * i + t) =
          (slideCondition(up, eq.pose, direction) - slideCondition(down, eq.pose, direction)) /
          (2 * h);
    }
  }
  if (slides.empty()) return equilibriumSensitivity(H, Ft);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(Fz);
  if (!lu.isInvertible()) return Eigen::MatrixXd::Zero(3, 4 * n);
  return -lu.solve(Ft).topRows(3);
}

}  // namespace cablelab

// The points of cable paths over one implicit midpoint step (midpoint_solver.h), the start pose
// held over the step's Newton iterations.
//
// Each Newton iteration of the midpoint solve takes a row's discrete gradient between q0 and the
// iterate q1 (lengthDiscreteGradient: each point moved along its chord, [I | sinc(dtheta / 2)
// perp(R(theta_mid) r)]) and the iteration matrix at the midpoint pose. Taken from the path, that
// was a copy of the path and the sines and cosines of the start, end and midpoint angle of each
// point, twice, every iteration: 19% of the step of 1024 Atwood machines (docs/performance.md).
// Here the start (each moved body's rotation, each point's position) is taken once a step, and an
// iteration costs one sincos per moved body, of half its turn: the end and midpoint rotations
// follow by the angle-sum formulas, equal to the direct ones to rounding. Paths without circles
// only (the chord form); the solver keeps the general one for the rest.
#pragma once

#include <cmath>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/cable/jacobian_entries.h"

namespace cablelab {

class StepChords {
 public:
  struct Point {
    int body;   // -1: the world
    int moved;  // index of its body among the moved ones, -1: not moved (or the world)
    Vec2 local;
    Vec2 start;     // world position at q0
    Vec2 startArm;  // R(theta0) local
    Vec2 end;       // at q1 (move)
    Vec2 mid;       // at the midpoint pose
    Vec2 turn;      // d(point) / d(theta) over the step: sinc(dtheta / 2) perp(R(theta_mid) r)
  };

  /// Holds the start pose q0; `moved` are the bodies the solve moves, in its dof order. Clears
  /// the paths.
  void start(std::span<const BodyState> q0, std::span<const int> moved) {
    turns_.resize(moved.size());
    for (size_t k = 0; k < moved.size(); ++k) {
      const BodyState& b = q0[moved[k]];
      cosSin(b.angle, turns_[k].c0, turns_[k].s0);
    }
    points_.clear();
    firsts_.assign(1, 0);
  }

  /// Adds a path (no circles) whose bodies are at q0; `movedIndex` maps a body to its index among
  /// the moved ones (-1: not moved). Returns the path's index.
  template <class MovedIndex>
  int addPath(std::span<const WrapPoint> path, std::span<const BodyState> q0,
              MovedIndex movedIndex) {
    for (const WrapPoint& w : path) {
      Point p{w.body, -1, w.local, w.local, Vec2::Zero(), w.local, w.local, Vec2::Zero()};
      if (w.body >= 0) {
        const BodyState& b = q0[w.body];
        p.moved = movedIndex(w.body);
        double c, s;
        if (p.moved >= 0)
          c = turns_[p.moved].c0, s = turns_[p.moved].s0;
        else
          cosSin(b.angle, c, s);
        p.startArm = rotate(w.local, c, s);
        p.start = p.end = p.mid = b.position + p.startArm;
        p.turn = perp(p.startArm);  // a body not moved: sinc(0) = 1, theta_mid = theta0
      }
      points_.push_back(p);
    }
    firsts_.push_back(static_cast<int>(points_.size()));
    return static_cast<int>(firsts_.size()) - 2;
  }

  /// The moved bodies at q1 and at the midpoint pose (both indexed by body, as q0): each held
  /// point's end, midpoint position and turn.
  void move(std::span<const BodyState> q0, std::span<const BodyState> q1,
            std::span<const BodyState> mid, std::span<const int> moved) {
    for (size_t k = 0; k < moved.size(); ++k) {
      Turn& t = turns_[k];
      const double half = 0.5 * (q1[moved[k]].angle - q0[moved[k]].angle);
      double ch, sh;
      cosSin(half, ch, sh);
      t.sinc = std::abs(half) < 1e-8 ? 1.0 - half * half / 6 : sh / half;
      t.cm = t.c0 * ch - t.s0 * sh, t.sm = t.s0 * ch + t.c0 * sh;
      const double c2 = 1 - 2 * sh * sh, s2 = 2 * sh * ch;  // the whole turn
      t.c1 = t.c0 * c2 - t.s0 * s2, t.s1 = t.s0 * c2 + t.c0 * s2;
    }
    for (Point& p : points_) {
      if (p.moved < 0) continue;
      const Turn& t = turns_[p.moved];
      const Vec2 arm = rotate(p.local, t.cm, t.sm);
      p.end = q1[p.body].position + rotate(p.local, t.c1, t.s1);
      p.mid = mid[p.body].position + arm;
      p.turn = t.sinc * perp(arm);
    }
  }

  /// Path i's points.
  std::span<const Point> points(int i) const {
    return std::span<const Point>(points_).subspan(firsts_[i], firsts_[i + 1] - firsts_[i]);
  }

  /// The discrete gradient of path i's length between q0 and q1 (G (q1 - q0) = length(q1) -
  /// length(q0) to rounding) into `g`, one entry per body; returns the length at q1. As
  /// lengthDiscreteGradient (cable_kinematics.cpp) on a path without circles.
  double discreteGradient(int i, std::vector<BodyJacobian>& g) const {
    g.clear();
    const std::span<const Point> path = points(i);
    double length1 = 0;
    for (size_t j = 0; j + 1 < path.size(); ++j) {
      const Point &a = path[j], &b = path[j + 1];
      const Vec2 d0 = b.start - a.start, d1 = b.end - a.end;
      const double sum = d0.norm() + d1.norm();
      length1 += d1.norm();
      if (sum >= 2 * kZeroLength && a.body != b.body) {
        const Vec2 u = (d0 + d1) / sum;
        addJacobian(g, b.body, Vec3(u.x(), u.y(), u.dot(b.turn)));
        addJacobian(g, a.body, -Vec3(u.x(), u.y(), u.dot(a.turn)));
      }
    }
    return length1;
  }

  /// The length's Jacobian J1 of path i at q1 (the last move's), one entry per body, into `g`: as
  /// cableLengthJacobian on the path at q1, from the points' end positions.
  void endJacobian(int i, std::span<const BodyState> q1, std::vector<BodyJacobian>& g) const {
    g.clear();
    const std::span<const Point> path = points(i);
    for (size_t j = 0; j + 1 < path.size(); ++j) {
      const Point &a = path[j], &b = path[j + 1];
      const Vec2 d = b.end - a.end;
      const double len = d.norm();
      if (a.body == b.body || len < kZeroLength) continue;
      const Vec2 u = d / len;
      if (b.body >= 0)
        addJacobian(g, b.body, Vec3(u.x(), u.y(), u.dot(perp(Vec2(b.end - q1[b.body].position)))));
      if (a.body >= 0)
        addJacobian(g, a.body, -Vec3(u.x(), u.y(), u.dot(perp(Vec2(a.end - q1[a.body].position)))));
    }
  }

 private:
  static constexpr double kZeroLength = 1e-12;  // m, as cable_kinematics.cpp: no direction
  struct Turn {
    double c0 = 1, s0 = 0;  // the start rotation
    double c1 = 1, s1 = 0;  // the end one
    double cm = 1, sm = 0;  // the midpoint one
    double sinc = 1;        // sin(dtheta / 2) / (dtheta / 2)
  };
  std::vector<Turn> turns_;    // per moved body
  std::vector<Point> points_;  // the paths' points, path i from firsts_[i] to firsts_[i + 1]
  std::vector<int> firsts_;
};

}  // namespace cablelab

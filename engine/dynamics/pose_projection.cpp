// The pose projection (pose_projection.h; docs/model.md, "Posing"), and World's posing verbs.
#include "engine/dynamics/pose_projection.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "engine/core/small_qp.h"
#include "engine/dynamics/floors.h"
#include "engine/dynamics/joint_projection.h"
#include "engine/dynamics/servo_drive.h"

namespace cablelab {

namespace {

constexpr double kSubMove = 0.02;  // m: the grabbed point's largest advance a projection
constexpr int kMaxSubMoves = 100;  // ... and the most projections a call makes
constexpr double kHeld = 0.01;     // a point that advances less than this share is held back
constexpr int kMaxSteps = 20;      // Gauss-Newton steps a projection
constexpr double kPull = 1e4;      // W, in the dragged body's masses: the others give way first
constexpr double kMaxStep = 0.05;  // m or rad: a longer Gauss-Newton step is cut to this
// m or rad: a step this short has converged (Box2D keeps poses in float: 1e-6 m is its
// resolution at 10 m).
constexpr double kStepDone = 1e-6;
// Spans are posed this much within their rest length, so that Box2D's float poses leave them
// within the solve's slop (kLengthSlop, 1e-5 m) of it.
constexpr double kShort = 5e-6;         // m
constexpr double kTaut = 1e-4;          // m: a span this near its rest length is taut
constexpr double kMet = 1e-6;           // m or rad: a row missed by no more is met
constexpr double kInconsistent = 1e-9;  // m or rad: a QP relaxed by more found its rows at odds

class PoseSolver {
 public:
  PoseSolver(PoseWorld& world, const PoseGoal& goal);
  /// Gauss-Newton steps from the current pose towards `waypoint` (nullptr: the constraints only).
  void project(const Vec2* waypoint);
  /// Where the grabbed point is now (world).
  Vec2 grabbed() const;

 private:
  void chooseBodies();
  /// One Gauss-Newton step; false (nothing moved) where it would not help: too short a step, or
  /// rows that no step meets together (then the last pose that met them all is put back).
  bool step(const Vec2* waypoint);
  void place(const std::vector<BodyState>& pose);
  void addRow(const Eigen::VectorXd& c, double b) {
    rowsC_.push_back(c);
    rowsB_.push_back(b);
  }
  Eigen::VectorXd row(const JointRow& r) const;
  Eigen::VectorXd pointRow(int body, const Vec2& at, const Vec2& direction) const;
  void addCableRows();
  void addFloorRows();
  void addJointRows();

  PoseWorld& w_;
  PoseGoal goal_;
  std::vector<int> dofOf_;         // body -> first of its three dofs (x, y, theta), -1: held
  int n_ = 0;                      // dofs
  Eigen::VectorXd mass_;           // M's diagonal (kg, kg, kg m^2)
  std::vector<double> reference_;  // per joint: body B's angle less body A's when it was made
  std::vector<BodyState> start_;   // q0 of the projection under way
  std::vector<BodyState> met_;     // the last pose of this projection that met every row
  double limit_ = kMaxStep;        // the longest step allowed now (m or rad)
  Eigen::VectorXd previous_;       // the last step taken
  std::vector<JointFrame> frames_;
  std::vector<JointRow> jointRows_;
  std::vector<Eigen::VectorXd> rowsC_;  // constraint rows: c . delta >= b
  std::vector<double> rowsB_;
};

PoseSolver::PoseSolver(PoseWorld& world, const PoseGoal& goal) : w_(world), goal_(goal) {
  // Box2D made each joint at the scene's initial pose (JointDef::anchor), so its reference angle
  // is the two bodies' initial angles' difference.
  auto initialAngle = [&](int body) { return body >= 0 ? w_.scene.bodies[body].angle : 0.0; };
  for (const auto& [a, b] : w_.jointBodies) reference_.push_back(initialAngle(b) - initialAngle(a));
  chooseBodies();
}

// The dofs: the dynamic bodies that rigid cables and joints tie to the dragged one (settling:
// every dynamic body on a rigid cable or a joint). Bodies on elastic cables alone stay put.
void PoseSolver::chooseBodies() {
  const int bodies = static_cast<int>(w_.bodies.size());
  std::vector<std::vector<int>> ties(bodies);
  auto tie = [&](const std::vector<int>& group) {
    for (int a : group)
      for (int b : group)
        if (a >= 0 && b >= 0 && a != b) ties[a].push_back(b);
  };
  std::vector<char> tied(bodies, 0);
  for (const Cable& c : w_.cables) {
    if (c.elastic()) continue;
    std::vector<int> group;
    for (const WrapPoint& p : c.path()) group.push_back(p.body);
    for (int k = 0; k < c.pulleyCount(); ++k) group.push_back(c.pulleyBody(k));
    tie(group);
    for (int b : group)
      if (b >= 0) tied[b] = 1;
  }
  for (const auto& [a, b] : w_.jointBodies) {
    tie({a, b});
    for (int body : {a, b})
      if (body >= 0) tied[body] = 1;
  }
  std::vector<char> in(bodies, 0);
  if (goal_.body >= 0) {
    std::vector<int> todo = {goal_.body};
    in[goal_.body] = 1;
    while (!todo.empty()) {
      const int b = todo.back();
      todo.pop_back();
      for (int next : ties[b])
        if (!in[next] && moves(w_.bodies[next])) in[next] = 1, todo.push_back(next);
    }
  } else {
    in = tied;
  }
  dofOf_.assign(bodies, -1);
  std::vector<double> mass;
  for (int b = 0; b < bodies; ++b) {
    const BodyState& s = w_.bodies[b];
    if (!in[b] || !(s.invMass > 0)) continue;
    dofOf_[b] = n_;
    n_ += 3;
    // A body that may not turn has its turn held by a row; any positive weight will do.
    const double m = 1 / s.invMass;
    mass.insert(mass.end(), {m, m, s.invInertia > 0 ? 1 / s.invInertia : m});
  }
  mass_ = Eigen::Map<const Eigen::VectorXd>(mass.data(), n_);
}

Vec2 PoseSolver::grabbed() const {
  const BodyState& s = w_.bodies[goal_.body];
  return s.position + rotate(goal_.grabLocal, s.angle);
}

Eigen::VectorXd PoseSolver::row(const JointRow& r) const {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n_);
  for (int k = 0; k < 2; ++k)
    if (r.dof[k] >= 0) c.segment<3>(r.dof[k]) += r.coeff[k];
  return c;
}

// length + J delta <= rest - kShort, for every span of every rigid cable (unless it pays out).
void PoseSolver::addCableRows() {
  if (goal_.payOut) return;
  for (const Cable& c : w_.cables) {
    if (c.elastic()) continue;
    for (int k = 0; k < c.spanCount(); ++k) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(n_);
      bool any = false;
      for (const BodyJacobian& e : c.spanKinematics(k).jacobian)
        if (const int d = dofOf_[e.body]; d >= 0) r.segment<3>(d) -= e.d, any = true;
      if (any) addRow(r, c.spanStretch(k) + kShort);
    }
  }
}

// The motion along `direction` of the point `at` (world) fixed on `body`, as a row over the dofs.
Eigen::VectorXd PoseSolver::pointRow(int body, const Vec2& at, const Vec2& direction) const {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n_);
  if (const int d = body >= 0 ? dofOf_[body] : -1; d >= 0)
    c.segment<3>(d) = Vec3(direction.x(), direction.y(),
                           direction.dot(perp(Vec2(at - w_.bodies[body].position))));
  return c;
}

// Floors (floors.h) of the rigid cables: a body pulled up to its pulley stops kFloorLength short
// of it rather than through it, where the segment's direction, and so the length's Jacobian, would
// turn over (a ballast dragged up to its pulley). A point-circle segment also keeps its rim gap.
void PoseSolver::addFloorRows() {
  for (const Cable& c : w_.cables) {
    if (c.elastic() || !hasFloors(c)) continue;
    const std::vector<WrapPoint>& path = c.path();
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      const WrapPoint &p = path[i], &q = path[i + 1];
      const bool dofs =
          (p.body >= 0 && dofOf_[p.body] >= 0) || (q.body >= 0 && dofOf_[q.body] >= 0);
      const double gap = floorGap(p, q);
      if (p.body == q.body || !dofs || !(gap < kFloorWatch) || c.mayEnterHull(i)) continue;
      if (gap > 0) {
        const Vec2 n = (q.arriving() - p.leaving()) / gap;
        addRow(pointRow(q.body, q.arriving(), n) - pointRow(p.body, p.leaving(), n),
               kFloorLength - gap);
      }
      if (const int rim = rimEnd(p, q); rim >= 0) {
        const WrapPoint &circle = rim == 0 ? p : q, &point = rim == 0 ? q : p;
        Vec2 gradient;
        const double rimGapNow =
            rimGap(point.body, point.world, circle.world, circle.radius, gradient);
        addRow(pointRow(point.body, point.world, gradient) -
                   pointRow(circle.body, circle.world, gradient),
               kFloorLength - rimGapNow);
      }
    }
  }
}

// Joint rows (joint_projection.h) held at zero position error, C delta = -error, and limited
// coordinates kept within their limits; a body that may not turn keeps its angle.
void PoseSolver::addJointRows() {
  w_.box2d.jointFrames(w_.scene.joints, w_.jointBodies, frames_);
  for (size_t j = 0; j < frames_.size(); ++j) {
    const JointFrame& f = frames_[j];
    jointRows_.clear();
    appendJointRows(f, w_.bodies, dofOf_, jointRows_);
    if (jointRows_.empty()) continue;
    auto angle = [&](int body) { return body >= 0 ? w_.bodies[body].angle : 0.0; };
    const Vec2 gap = f.anchor - f.anchorA;
    const double turn = angle(f.bodyB) - angle(f.bodyA) - reference_[j];
    std::vector<double> error;
    switch (f.kind) {
      case JointDef::Kind::Revolute:
        error = {gap.x(), gap.y()};
        break;
      case JointDef::Kind::Prismatic:
        error = {perp(f.axis).dot(gap), turn};
        break;
      case JointDef::Kind::Weld:
        error = {gap.x(), gap.y(), turn};
        break;
    }
    for (size_t r = 0; r < error.size() && r < jointRows_.size(); ++r) {
      const Eigen::VectorXd c = row(jointRows_[r]);
      addRow(c, -error[r]);
      addRow(-c, error[r]);
    }
    if (f.limited) {
      const double value = w_.box2d.jointCoordinate(static_cast<int>(j)).value;
      const Eigen::VectorXd c = row(coordinateRow(f, w_.bodies, dofOf_));
      const JointDef& def = w_.scene.joints[j];
      addRow(c, def.lower - value);
      addRow(-c, value - def.upper);
    }
  }
  for (size_t b = 0; b < dofOf_.size(); ++b)
    if (dofOf_[b] >= 0 && w_.bodies[b].invInertia == 0) {
      Eigen::VectorXd c = Eigen::VectorXd::Zero(n_);
      c[dofOf_[b] + 2] = 1;
      addRow(c, 0);
      addRow(-c, 0);
    }
}

// One Gauss-Newton step: the QP of pose_projection.h linearised at the current pose, then the
// bodies moved (in Box2D) and the cables updated. Returns the step's largest component.
bool PoseSolver::step(const Vec2* waypoint) {
  if (n_ == 0) return false;
  const std::vector<BodyState>& bodies = w_.bodies;
  Eigen::MatrixXd H = mass_.asDiagonal();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n_);
  for (size_t b = 0; b < dofOf_.size(); ++b)
    if (const int d = dofOf_[b]; d >= 0) {
      const Vec2 dx = bodies[b].position - start_[b].position;
      const Vec3 dq(dx.x(), dx.y(), bodies[b].angle - start_[b].angle);
      f.segment<3>(d) = mass_.segment<3>(d).cwiseProduct(dq);
    }
  if (waypoint && goal_.body >= 0 && dofOf_[goal_.body] >= 0) {
    const int d = dofOf_[goal_.body];
    const BodyState& s = bodies[goal_.body];
    const Vec2 r = rotate(goal_.grabLocal, s.angle);
    Eigen::Matrix<double, 2, 3> G;
    G << 1, 0, -r.y(), 0, 1, r.x();
    const double W = kPull * mass_[d];
    H.block<3, 3>(d, d) += W * G.transpose() * G;
    f.segment<3>(d) += W * G.transpose() * (s.position + r - *waypoint);
  }
  rowsC_.clear();
  rowsB_.clear();
  addCableRows();
  addFloorRows();
  addJointRows();
  Eigen::MatrixXd C(rowsC_.size(), n_);
  Eigen::VectorXd b(rowsB_.size());
  for (size_t i = 0; i < rowsC_.size(); ++i) C.row(i) = rowsC_[i].transpose(), b[i] = rowsB_[i];
  if (b.size() == 0 || b.maxCoeff() <= kMet) met_ = bodies;
  Eigen::VectorXd delta;
  if (rowsC_.empty()) {
    delta = -H.ldlt().solve(f);
  } else {
    const SmallQpResult qp = solveSmallQp(H, f, C, b, Eigen::VectorXd::Zero(n_));
    // No step meets the rows together: they disagree to first order where they meet (a box
    // pulled up against its wheel, its floor and its span at odds). Relaxed, the QP would loosen
    // every row, the joints' too, a little more each step: stop at the last pose that met them.
    if (qp.slack > kInconsistent) {
      if (!met_.empty()) place(met_);
      return false;
    }
    delta = qp.x;
  }
  const double largest = delta.cwiseAbs().maxCoeff();
  if (!std::isfinite(largest)) return false;
  // Far from linear (a long step): a shorter step along the same direction still meets the
  // linearised rows, which the current pose meets. A step that turns back on the last one has
  // overshot along a curved constraint (a weight sliding round its rope's circle): the limit
  // halves, so that the steps close in instead of swinging across.
  if (previous_.size() == delta.size() && previous_.dot(delta) < 0) limit_ *= 0.5;
  if (largest > limit_) delta *= limit_ / largest;
  previous_ = delta;
  std::vector<BodyState> next = bodies;
  for (size_t i = 0; i < dofOf_.size(); ++i)
    if (const int d = dofOf_[i]; d >= 0) {
      next[i].position += delta.segment<2>(d);
      next[i].angle += delta[d + 2];
    }
  place(next);
  return std::min(largest, limit_) >= kStepDone;
}

// Moves the dof bodies to `pose` (in Box2D), reads them back and updates the cables.
void PoseSolver::place(const std::vector<BodyState>& pose) {
  for (size_t i = 0; i < dofOf_.size(); ++i)
    if (dofOf_[i] >= 0) w_.box2d.placeBody(static_cast<int>(i), pose[i].position, pose[i].angle);
  w_.box2d.readBodies(w_.bodies);
  for (Cable& c : w_.cables) c.update(w_.bodies, &w_.warnings);
}

void PoseSolver::project(const Vec2* waypoint) {
  start_ = w_.bodies;
  limit_ = kMaxStep;
  previous_.resize(0);
  met_.clear();
  for (int s = 0; s < kMaxSteps; ++s)
    if (!step(waypoint)) break;
}

}  // namespace

PoseResult projectPose(PoseWorld& world, const PoseGoal& asked) {
  world.box2d.readBodies(world.bodies);
  const std::vector<BodyState> before = world.bodies;
  PoseGoal goal = asked;
  const bool dragging = goal.body >= 0 && goal.body < static_cast<int>(world.bodies.size()) &&
                        moves(world.bodies[goal.body]);
  if (!dragging) goal.body = -1;  // a static or kinematic body is not posed
  PoseSolver solver(world, goal);
  PoseResult result;
  if (dragging) {
    // Waypoints at most kSubMove ahead of the grabbed point: the wrap selection sees the bodies
    // move continuously. Once the point no longer advances (held back), one last projection
    // towards the target itself finds the nearest pose to it.
    Vec2 at = solver.grabbed();
    for (int k = 0; k < kMaxSubMoves; ++k) {
      const Vec2 gap = goal.target - at;
      const bool last = gap.norm() <= kSubMove;
      const Vec2 waypoint = last ? goal.target : Vec2(at + gap * (kSubMove / gap.norm()));
      solver.project(&waypoint);
      const Vec2 now = solver.grabbed();
      const bool held = (now - at).norm() < kHeld * kSubMove;
      at = now;
      if (last) break;
      if (held) {
        solver.project(&goal.target);
        break;
      }
    }
  }
  solver.project(nullptr);  // whatever the pull left unmet (nothing, as a rule)
  for (size_t c = 0; c < world.cables.size() && goal.payOut; ++c) {
    Cable& cable = world.cables[c];
    double paid = 0;
    for (int k = 0; k < cable.spanCount() && !cable.elastic(); ++k)
      if (const double over = cable.spanStretch(k); over > 0) cable.payOut(k, over), paid += over;
    if (paid > 0) result.paidOut.emplace_back(static_cast<int>(c), paid);
  }
  for (size_t b = 0; b < world.bodies.size(); ++b) {
    const BodyState &s = world.bodies[b], &was = before[b];
    if (s.position == was.position && s.angle == was.angle && static_cast<int>(b) != goal.body)
      continue;
    if (!moves(s)) continue;
    world.box2d.setVelocity(static_cast<int>(b), Vec2::Zero(), 0);  // it was held
    result.moved.push_back(static_cast<int>(b));
  }
  world.box2d.readBodies(world.bodies);
  for (size_t c = 0; c < world.cables.size(); ++c) {
    const Cable& cable = world.cables[c];
    if (cable.elastic()) continue;
    double longest = -INFINITY;
    for (int k = 0; k < cable.spanCount(); ++k) longest = std::max(longest, cable.spanStretch(k));
    if (longest > -kTaut) result.taut.push_back(static_cast<int>(c));
    result.longest = std::max(result.longest, longest);
  }
  if (dragging) {
    result.reached = solver.grabbed();
    result.miss = (result.reached - goal.target).norm();
  }
  return result;
}

PoseResult World::poseBody(int body, const Vec2& grabLocal, const Vec2& target, bool payOut) {
  history_.add({WorldInput::Kind::Pose,
                body,
                payOut ? 1 : 0,
                {grabLocal.x(), grabLocal.y(), target.x(), target.y()}});
  PoseWorld w{scene_, *b2_, cables_, bodies_, jointBodies_, warnings_};
  const PoseResult result = projectPose(w, {body, grabLocal, target, payOut});
  // A servo holds the pose it was given: its target moves to its joint's new coordinate (else on
  // Play it would pull the joint back with energy the pose never had).
  auto moved = [&](int b) {
    return b >= 0 && std::binary_search(result.moved.begin(), result.moved.end(), b);
  };
  for (size_t j = 0; j < scene_.joints.size(); ++j)
    if (scene_.joints[j].servo.enabled && (moved(jointBodies_[j][0]) || moved(jointBodies_[j][1])))
      servoTargets_.hold(j, b2_->jointCoordinate(static_cast<int>(j)).value);
  // What the pose let out is the user's, not a kinematic body's haul: reportPayOuts leaves it.
  paidOutSeen_.resize(cables_.size(), 0.0);
  for (size_t c = 0; c < cables_.size(); ++c) paidOutSeen_[c] = cables_[c].paidOut();
  // The contact forces of the steps before are not those of the new pose (expectContacts).
  std::fill(contactLast_.begin(), contactLast_.end(), Vec3::Zero());
  std::fill(contactExpected_.begin(), contactExpected_.end(), Vec3::Zero());
  b2_->restartContactSum();
  servos_->forgetMotion();  // the pose left its bodies at rest: no servo's joint was held there
  return result;
}

double World::longestRigidStretch() const {
  double longest = -INFINITY;
  for (const Cable& c : cables_)
    for (int k = 0; k < c.spanCount() && !c.elastic(); ++k)
      longest = std::max(longest, c.spanStretch(k));
  return longest;
}

PoseResult World::settlePose() {
  return poseBody(-1, Vec2::Zero(), Vec2::Zero());
}

}  // namespace cablelab

// The joint projection of the cable solver (stage 4): the small LDL^T it factors with, the
// projection in joint coordinates for trees (joint_tree.h) against the Schur complement of the
// joint rows (joint_projection.h), and a cable over a pulley on a welded body (a 3-row block).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "engine/dynamics/joint_limits.h"
#include "engine/dynamics/joint_projection.h"
#include "engine/dynamics/joint_tree.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

TEST(SmallLdlt, SolvesLikeEigensLdltAtEverySizeAndColumnCount) {
  // GCC 12 -O3 unrolled the 3 x 3 solve wrongly for more than one column: a welded body's
  // block (3 rows) then moved under the cable's pull.
  test::Random random(3);
  for (int n = 1; n <= 12; ++n)
    for (int cols = 1; cols <= 4; ++cols) {
      Eigen::MatrixXd A(n, n), B(n, cols);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) A(i, j) = random.uniform(-1, 1);
        for (int c = 0; c < cols; ++c) B(i, c) = random.uniform(-1, 1);
      }
      A = A * A.transpose() + Eigen::MatrixXd::Identity(n, n);
      const Eigen::MatrixXd expected = A.ldlt().solve(B);
      Eigen::MatrixXd factor = A, x = B;
      SmallLdlt ldlt;
      ldlt.factor(factor.data(), n);
      ldlt.solveInPlace(factor.data(), n, x.data(), cols);
      EXPECT_LT((x - expected).norm(), 1e-10 * expected.norm()) << n << " x " << n << ", " << cols;
    }
}

// A random forest of `links` moving bodies, each jointed (revolute, prismatic or weld) to an
// earlier one, to the world, or to a kinematic body that moves; the bodies' masses and the
// anchors at random.
struct RandomTree {
  std::vector<BodyState> bodies;  // the links, then the kinematic root
  std::vector<JointFrame> joints;
  std::vector<int> island, dofOfBody;
  Eigen::VectorXd invM;

  RandomTree(test::Random& random, int links) {
    const int root = links;
    bodies.resize(links + 1);
    for (int b = 0; b < links; ++b) {
      bodies[b].position = random.point(-2, 2);
      bodies[b].invMass = 1 / random.uniform(0.2, 3);
      bodies[b].invInertia = 1 / random.uniform(0.05, 1);
      dofOfBody.push_back(3 * b);
    }
    bodies[root].position = random.point(-2, 2);
    bodies[root].velocity = random.point(-1, 1);
    bodies[root].angularVelocity = random.uniform(-2, 2);
    dofOfBody.push_back(-1);
    for (int b = 0; b < links; ++b) {
      JointFrame j;
      j.kind = static_cast<JointDef::Kind>(random.integer(0, 2));
      const int parent = random.integer(-2, b - 1);  // -2: the world, -1: the kinematic body
      j.bodyA = parent == -1 ? root : parent;
      j.bodyB = b;
      j.anchor = random.point(-2, 2);
      const double angle = random.uniform(0, 6.3);
      j.axis = Vec2(std::cos(angle), std::sin(angle));
      if (random.integer(0, 1)) std::swap(j.bodyA, j.bodyB);  // either side may be the child
      island.push_back(static_cast<int>(joints.size()));
      joints.push_back(j);
    }
    invM.resize(3 * links);
    for (int b = 0; b < links; ++b)
      invM.segment<3>(3 * b) = Vec3(bodies[b].invMass, bodies[b].invMass, bodies[b].invInertia);
  }

  std::vector<JointRow> rows(const JointLimits& limits = JointLimits()) const {
    std::vector<JointRow> r;
    for (size_t j = 0; j < joints.size(); ++j)
      appendJointRows(joints[j], bodies, dofOfBody, r, limits.lock(static_cast<int>(j)));
    return r;
  }
};

TEST(JointTree, LockedJointsMoveAtTheirRateInBothProjections) {
  // A joint at a limit (joint_limits.h) is locked at a rate: the tree's penalty on its
  // coordinate and the Schur complement's extra row give the same velocities, the locked
  // coordinates move at their rates and W's columns leave them still.
  test::Random random(12);
  int locks = 0;
  for (int trial = 0; trial < 40; ++trial) {
    RandomTree t(random, random.integer(1, 7));
    const int n = static_cast<int>(t.invM.size()), m = random.integer(1, 3);
    Eigen::MatrixXd W = Eigen::MatrixXd::Random(n, m);
    Eigen::VectorXd v = 3 * Eigen::VectorXd::Random(n);
    JointLimits limits;
    for (size_t j = 0; j < t.joints.size(); ++j)
      if (t.joints[j].kind != JointDef::Kind::Weld && random.integer(0, 1))
        limits.lockAt(static_cast<int>(j), random.uniform(-2, 2)), ++locks;
    Eigen::MatrixXd schurW = W;
    Eigen::VectorXd schurV = v;
    JointProjection schur;
    schur.projectDiagonal(t.rows(limits), t.invM, schurW, schurV);
    JointTree tree;
    ASSERT_TRUE(tree.build(t.joints, t.island, t.bodies, t.dofOfBody, t.invM)) << trial;
    tree.project(W, v, limits);
    EXPECT_LT((W - schurW).norm(), 1e-6 * (1 + schurW.norm())) << trial;
    EXPECT_LT((v - schurV).norm(), 1e-6 * (1 + schurV.norm())) << trial;
    for (size_t j = 0; j < t.joints.size(); ++j) {
      const std::optional<double> rate = limits.lock(static_cast<int>(j));
      if (!rate) continue;
      const JointRow row = coordinateRow(t.joints[j], t.bodies, t.dofOfBody);
      EXPECT_NEAR(row.dot(v) + row.bias, *rate, 1e-9) << trial;
      for (int c = 0; c < m; ++c) EXPECT_NEAR(row.dot(W.col(c)), 0, 1e-9) << trial;
    }
  }
  EXPECT_GT(locks, 40);
}

TEST(JointTree, ProjectsLikeTheSchurComplementAndTheJointsHold) {
  test::Random random(11);
  for (int trial = 0; trial < 40; ++trial) {
    RandomTree t(random, random.integer(1, 7));
    const int n = static_cast<int>(t.invM.size()), m = random.integer(1, 3);
    Eigen::MatrixXd W(n, m);
    Eigen::VectorXd v(n);
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < m; ++c) W(i, c) = random.uniform(-1, 1);
      v[i] = random.uniform(-3, 3);
    }
    if (trial % 3 == 0) W.col(0).setZero();  // a cable that pulls on none of these bodies
    Eigen::MatrixXd schurW = W;
    Eigen::VectorXd schurV = v;
    const std::vector<JointRow> rows = t.rows();
    JointProjection schur;
    schur.projectDiagonal(rows, t.invM, schurW, schurV);
    JointTree tree;
    ASSERT_TRUE(tree.build(t.joints, t.island, t.bodies, t.dofOfBody, t.invM)) << trial;
    tree.project(W, v, JointLimits());
    EXPECT_LT((W - schurW).norm(), 1e-6 * (1 + schurW.norm())) << trial;  // S's regularisation
    EXPECT_LT((v - schurV).norm(), 1e-6 * (1 + schurV.norm())) << trial;
    // What the joints allow: no joint row moves (W's columns), v* moves as the kinematic root.
    for (const JointRow& row : rows) {
      for (int c = 0; c < m; ++c) EXPECT_NEAR(row.dot(W.col(c)), 0, 1e-9) << trial;
      EXPECT_NEAR(row.dot(v) + row.bias, 0, 1e-9) << trial;
    }
  }
}

TEST(JointTree, LeavesLoopsFloatingGroupsAndFixedRotationsToTheSchurComplement) {
  test::Random random(5);
  RandomTree t(random, 3);
  JointTree tree;
  ASSERT_TRUE(tree.build(t.joints, t.island, t.bodies, t.dofOfBody, t.invM));
  // A second joint from the last link to the world closes a loop.
  RandomTree loop = t;
  JointFrame extra = loop.joints.back();
  extra.bodyA = -1;
  extra.bodyB = 2;
  loop.island.push_back(static_cast<int>(loop.joints.size()));
  loop.joints.push_back(extra);
  EXPECT_FALSE(tree.build(loop.joints, loop.island, loop.bodies, loop.dofOfBody, loop.invM));
  // Two moving bodies jointed to each other only: nothing holds the pair (no root).
  RandomTree floating = t;
  floating.joints = {t.joints[0]};
  floating.joints[0].bodyA = 0;
  floating.joints[0].bodyB = 1;
  floating.island = {0};
  EXPECT_FALSE(tree.build(floating.joints, floating.island, floating.bodies, floating.dofOfBody,
                          floating.invM));
  // A jointed body that cannot turn (fixed rotation: M^-1 = 0 there) has no finite M.
  RandomTree fixed = t;
  fixed.invM[2] = 0;
  EXPECT_FALSE(tree.build(fixed.joints, fixed.island, fixed.bodies, fixed.dofOfBody, fixed.invM));
}

// An Atwood machine (2 kg and 1 kg) over a point pulley on a bracket welded to the world: the
// bracket must not give, so the rope carries 2 m1 m2 g / (m1 + m2), as over a world pulley.
SceneDef weldedAtwood() {
  SceneDef s;
  s.gravity = Vec2(0, -9.81);
  auto body = [](const std::string& name, double mass, const Vec2& at) {
    BodyDef b;
    b.name = name;
    b.mass = mass;
    b.position = at;
    ShapeDef shape;
    shape.radius = 0.1;
    shape.sensor = true;
    b.shapes = {shape};
    return b;
  };
  s.bodies = {body("bracket", 1, Vec2(0, 1)), body("heavy", 2, Vec2(-1, -1)),
              body("light", 1, Vec2(1, -1))};
  JointDef weld;
  weld.kind = JointDef::Kind::Weld;
  weld.name = "weld";
  weld.bodyB = "bracket";
  weld.anchor = Vec2(0.5, 1);
  s.joints = {weld};
  CableDef rope;
  rope.name = "rope";
  rope.start = {"heavy", Vec2::Zero()};
  rope.end = {"light", Vec2::Zero()};
  PulleyDef left, right;
  left.body = right.body = "bracket";
  left.point = Vec2(-1, 0);
  right.point = Vec2(1, 0);
  left.side = right.side = WrapSide::Threaded;
  rope.pulleys = {left, right};
  s.cables = {rope};
  return s;
}

TEST(JointProjection, ARopeOverAWeldedBracketCarriesTheAtwoodTension) {
  for (bool tree : {true, false}) {
    SCOPED_TRACE(tree ? "joint coordinates" : "Schur complement");
    setJointTreeProjection(tree);
    World world(weldedAtwood());
    for (int step = 0; step < 30; ++step) world.step(test::kDt, 1);
    setJointTreeProjection(true);
    EXPECT_NEAR(world.cable(0).tension(), 2 * 2 * 1 * 9.81 / 3, 1e-6);
    EXPECT_LT(std::abs(world.cable(0).stretch()), 1e-6);
    EXPECT_LT(world.body(0).velocity.norm(), 1e-5);
  }
}

TEST(JointProjection, TheRowsMultipliersAreTheImpulsesThatMakeTheProjectedMotion) {
  // Two blocks (bodies 0-1 and 2-3), their rows interleaved so block order is not row order,
  // one with a bias. For loads f on W's columns, the rows' impulses -(S^-1 (C v* + bias) + S^-1
  // C W f), read off the multipliers, must take the free motion v* + W f to the projected one.
  std::srand(36);
  const int dofs = 12, m = 2;
  Eigen::VectorXd invM = Eigen::VectorXd::Random(dofs).cwiseAbs().array() + 0.2;
  auto row = [](int a, int b, double bias) {
    JointRow r;
    r.dof = {a, b};
    r.coeff[0] = Vec3::Random();
    if (b >= 0) r.coeff[1] = Vec3::Random();
    r.bias = bias;
    return r;
  };
  const std::vector<JointRow> rows = {row(0, 3, 0), row(6, 9, 0), row(3, -1, 0.4), row(9, -1, -0.7),
                                      row(6, -1, 0)};
  const Eigen::MatrixXd freeW = Eigen::MatrixXd::Random(dofs, m);
  const Eigen::VectorXd freeV = Eigen::VectorXd::Random(dofs);
  Eigen::MatrixXd W = freeW, multipliers;
  Eigen::VectorXd v = freeV;
  JointProjection projection;
  projection.projectDiagonal(rows, invM, W, v, &multipliers);
  ASSERT_EQ(multipliers.rows(), 5);
  ASSERT_EQ(multipliers.cols(), m + 1);
  const Eigen::Vector2d f(0.7, -1.3);
  Eigen::VectorXd moved = freeV + freeW * f;
  for (size_t r = 0; r < rows.size(); ++r) {
    const double impulse = -(multipliers(r, m) + multipliers.row(r).head(m).dot(f));
    for (int k = 0; k < 2; ++k)
      if (rows[r].dof[k] >= 0)
        moved.segment<3>(rows[r].dof[k]) +=
            impulse * rows[r].coeff[k].cwiseProduct(invM.segment<3>(rows[r].dof[k]));
  }
  const Eigen::VectorXd projected = v + W * f;
  EXPECT_LT((moved - projected).norm(), 1e-9 * projected.norm());
  for (const JointRow& r : rows) EXPECT_NEAR(r.dot(projected) + r.bias, 0, 1e-9);
}

// The hand squeezing and moving the box: both projections are the same map, so the fingers,
// the box and the membranes' tensions follow the same trajectory to rounding.
TEST(JointProjection, TheHandMovesAlikeInJointCoordinatesAndThroughTheSchurComplement) {
  auto run = [](bool tree) {
    setJointTreeProjection(tree);
    World world(makeScene("hand"));
    std::vector<double> states;
    for (int step = 0; step < 120; ++step) {
      if (step == 10)  // close both fingers and slide them forward
        for (int j : {0, 3}) world.setServoTarget(j, j == 0 ? -0.1 : 0.1);
      if (step == 10) world.setServoTarget(1, 0.2), world.setServoTarget(4, 0.2);
      world.step(test::kDt, 4);
      for (int b = 0; b < world.bodyCount(); ++b) {
        const BodyState& s = world.body(b);
        states.insert(states.end(), {s.position.x(), s.position.y(), s.angle});
      }
      for (int c = 0; c < world.cableCount(); ++c) states.push_back(world.cable(c).tension());
    }
    setJointTreeProjection(true);
    return states;
  };
  const std::vector<double> tree = run(true), schur = run(false);
  ASSERT_EQ(tree.size(), schur.size());
  const size_t perStep = tree.size() / 120, poses = perStep - 2, last = tree.size() - perStep;
  double pose = 0, tension = 0, motion = 0;
  for (size_t i = 0; i < tree.size(); ++i) {
    double& worst = i % perStep < poses ? pose : tension;
    worst = std::max(worst, std::abs(tree[i] - schur[i]));
  }
  for (size_t i = 0; i < poses; ++i) motion = std::max(motion, std::abs(tree[last + i] - tree[i]));
  EXPECT_LT(pose, 1e-7);     // m, rad: Box2D's float rounding
  EXPECT_LT(tension, 1e-4);  // N (tens of N): the membranes' damping of 550 N s/m on 1e-8 m/s
  EXPECT_GT(motion, 0.05);   // the fingers moved
}

}  // namespace
}  // namespace cablelab

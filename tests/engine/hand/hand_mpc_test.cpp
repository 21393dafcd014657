// Model-predictive control of the hand (engine/hand/hand_mpc.h, docs/control.md): its
// linearisation and prediction against finite differences and a step-by-step rollout, its
// constraints, and the comparison with the Jacobian controller on held-out targets.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "engine/hand/hand_compare.h"
#include "engine/hand/hand_mpc.h"
#include "engine/hand/hand_tracking.h"
#include "engine/scenes/scene_hand.h"
#include "tests/support/finite_differences.h"

namespace cablelab {
namespace hand_mpc_test {  // named: unity batches join test files

using test::kFdStep;

/// A grasp away from the pinch with both paddles tilted a little.
HandJoints offPinch() {
  HandJoints q;
  q << 0.1, 0.15, -0.05, 0.08, 0.12, -0.06;
  return q;
}

TEST(HandMpc, TensionsMatchFiniteDifferences) {
  const HandController hand{HandModel{}};
  const HandJoints q = offPinch();
  const Vec2 box = hand.predict(q, Vec2(0.3, 0)).box + Vec2(0.01, -0.004);  // off equilibrium
  Eigen::Matrix<double, 2, 6> dq;
  Eigen::Matrix2d dbox;
  const Eigen::Vector2d T = membraneTensions(hand, q, box, 0, &dq, &dbox);
  EXPECT_GT(T.minCoeff(), 10.0);  // both membranes taut: the derivatives are not trivially zero
  for (int j = 0; j < 6; ++j) {
    HandJoints up = q, down = q;
    up[j] += kFdStep, down[j] -= kFdStep;
    const Eigen::Vector2d fd =
        (membraneTensions(hand, up, box) - membraneTensions(hand, down, box)) / (2 * kFdStep);
    EXPECT_LT((fd - dq.col(j)).norm(), 1e-5 * (1 + fd.norm())) << "joint " << j;
  }
  for (int i = 0; i < 2; ++i) {
    Vec2 up = box, down = box;
    up[i] += kFdStep, down[i] -= kFdStep;
    const Eigen::Vector2d fd =
        (membraneTensions(hand, q, up) - membraneTensions(hand, q, down)) / (2 * kFdStep);
    EXPECT_LT((fd - dbox.col(i)).norm(), 1e-5 * (1 + fd.norm())) << "axis " << i;
  }
}

TEST(HandMpc, LinearisationMatchesTheStaticsResolved) {
  // The plan's equilibrium slope J = de/dq against the statics re-solved at q +/- h e_j.
  HandMpc mpc{HandModel{}};
  const HandController hand{HandModel{}};
  const HandJoints q = offPinch();
  const Vec2 box = hand.predict(q, Vec2(0.3, 0)).box;
  const MpcLinearisation lin = mpc.linearise(q, box, Vec2::Zero(), q);
  ASSERT_TRUE(lin.valid);
  EXPECT_LT((lin.equilibrium - box).norm(), 1e-9);  // at rest on the model: no offset
  for (int j = 0; j < 6; ++j) {
    HandJoints up = q, down = q;
    up[j] += kFdStep, down[j] -= kFdStep;
    const Vec2 fd = (hand.predict(up, box).box - hand.predict(down, box).box) / (2 * kFdStep);
    EXPECT_LT((fd - lin.jacobian.col(j)).norm(), 1e-5 * (1 + fd.norm())) << "joint " << j;
  }
}

TEST(HandMpc, PredictionIsTheStepByStepRolloutAndSettlesOnTheStatics) {
  // The affine maps against the same model stepped with plain numbers (servo ramp and lag, then
  // the box's mass, drag and stiffness, implicit Euler), for a random plan from a moving state.
  const HandModel model;
  HandMpcParams params;
  params.horizon = 40;  // 2.1 s: long enough for the box to settle
  HandMpc mpc{model, params};
  const HandController hand{model};
  const HandJoints q = offPinch(), commanded = q + HandJoints::Constant(0.002);
  const Vec2 box = hand.predict(q, Vec2(0.3, 0)).box;
  const MpcLinearisation lin = mpc.linearise(q, box, Vec2(0.02, -0.01), commanded);
  ASSERT_TRUE(lin.valid);
  const MpcPrediction pred = predictHorizon(model, params, lin, commanded);
  const int N = params.horizon;
  Eigen::VectorXd u = 0.01 * Eigen::VectorXd::Random(6 * N);

  const double h = params.period / 8, follow = 1 - std::exp(-h / (2 / std::sqrt(model.servoKp)));
  const double drag = model.boxMass * model.boxDamping;
  HandJoints joints = q, target = commanded;
  Vec2 b = box, v = lin.velocity;
  for (int k = 0; k < N; ++k) {
    const HandJoints next = target + u.segment<6>(6 * k);
    for (int i = 1; i <= 8; ++i) {
      joints += follow * (target + (next - target) * (i / 8.0) + lin.droop - joints);
      const Vec2 e = lin.equilibrium + lin.jacobian * (joints - q);
      const Eigen::Matrix2d A =
          (model.boxMass + h * drag) * Eigen::Matrix2d::Identity() + h * h * lin.stiffness;
      v = A.ldlt().solve(model.boxMass * v + h * lin.stiffness * (e - b));
      b += h * v;
    }
    target = next;
    EXPECT_LT((pred.commanded[k].at(u) - target).norm(), 1e-12) << "step " << k;
    EXPECT_LT((pred.joints[k].at(u) - joints).norm(), 1e-12) << "step " << k;
    EXPECT_LT((pred.box[k].at(u) - b).norm(), 1e-12) << "step " << k;
    EXPECT_LT((pred.velocity[k].at(u) - v).norm(), 1e-11) << "step " << k;
  }
  // Held, a small step of the targets moves the settled box as the statics re-solved does.
  Eigen::VectorXd step = Eigen::VectorXd::Zero(6 * N);
  step.head<6>() << 1e-4, 2e-4, -1e-4, 1e-4, -2e-4, 1e-4;
  const Vec2 moved = pred.box[N - 1].slope * step;
  const Vec2 statics = hand.predict(q + step.head<6>(), box).box - hand.predict(q, box).box;
  EXPECT_LT((moved - statics).norm(), 1e-2 * statics.norm());
}

TEST(HandMpc, QuasiStaticRunRespectsJointAndRateLimits) {
  // A target beyond the fingertips' range: the Jacobian controller's simulated run drives a
  // joint into its limit there (HandMpcTracking below). Here the fingers sit at their targets and
  // the box at the statics at once, not the lagging hand the plan expects, so its constraints
  // conflict at times: every step still keeps within the rate limits and the targets within
  // their limits.
  const HandModel model;
  HandMpc mpc{model};
  const HandController hand{model};
  const HandMpcParams& p = mpc.params();
  const Vec2 target(1.0, 1.0);
  HandJoints q = HandJoints::Zero();
  Vec2 box = hand.predict(q, Vec2::Zero()).box, velocity = Vec2::Zero();
  double moved = 0;
  for (int k = 0; k < 400; ++k) {
    const HandJoints dq = mpc.update(q, BoxPose(box.x(), box.y(), 0), velocity,
                                     BoxPose(target.x(), target.y(), 0), q);
    for (int j = 0; j < 6; ++j) {
      const double rate = (j % 3 == kSlide ? p.slideRate : p.revoluteRate) * p.period;
      ASSERT_LE(std::abs(dq[j]), rate + 1e-9) << "update " << k << " joint " << j;
      ASSERT_GE(q[j] + dq[j], model.lower[j] - 1e-9) << "update " << k << " joint " << j;
      ASSERT_LE(q[j] + dq[j], model.upper[j] + 1e-9) << "update " << k << " joint " << j;
    }
    q += dq;
    const BoxPrediction next = hand.predict(q, box);
    if (!next.smooth) break;
    velocity = (next.box - box) / p.period;
    box = next.box;
    moved = std::max(moved, box.norm());
  }
  EXPECT_GT(moved, 0.5);  // the plan did drive the box towards the target
}

TEST(HandMpcTracking, KeepsOffTheLimitsWherePidHitsThem) {
  TrackOptions o;
  o.target = Vec2(1.0, 1.0);  // beyond the fingertips' range
  o.time = 15;
  o.pid = true;
  const TrackResult pid = runTracking(o);
  o.law = HandLaw::Mpc;
  const TrackResult mpc = runTracking(o);
  EXPECT_GE(pid.limitHits, 1);  // measured: 1
  EXPECT_EQ(mpc.limitHits, 0);
  EXPECT_TRUE(mpc.graspHeld);
  EXPECT_LT(mpc.finalError, 0.005);  // measured: 2.5 mm
  EXPECT_GT(mpc.timeTo5mm, 0);
}

TEST(HandMpcTracking, BeatsPidOnHeldOutTargets) {
  // The goals on 20 targets of a seed the weights were not tuned on (tuned on seed 1):
  // median time to within 5 mm at most 0.6 x PID's, final error no worse, no grasp lost.
  CompareOptions o;
  o.seed = 7;
  o.time = 12;
  const CompareResult r = compareLaws(o);
  const LawSummary &pid = r.jacobianSummary, &mpc = r.mpcSummary;
  ASSERT_GT(pid.medianTimeTo5mm, 0);
  ASSERT_GT(mpc.medianTimeTo5mm, 0);
  EXPECT_LE(mpc.medianTimeTo5mm, 0.6 * pid.medianTimeTo5mm);
  EXPECT_LE(mpc.medianFinalError, pid.medianFinalError + 1e-4);
  EXPECT_LE(mpc.maxFinalError, std::max(pid.maxFinalError, 0.005));
  EXPECT_EQ(mpc.graspLosses, 0);
  EXPECT_EQ(mpc.settled, static_cast<int>(r.targets.size()));
  // Faster than real time: the mean update well within the 0.053 s period.
  EXPECT_LT(mpc.solveMicros, 0.5 * 53000);
}

TEST(HandMpcTracking, AngleTargetsWithFrictionAreReached) {
  // A box that turns, membranes with friction (mu = 0.5; the plan's model is frictionless, its
  // offsets take up the difference): held-out targets (x, y, theta) drawn from a seed nothing was
  // tuned on, |x|, |y| <= 0.4 m, |theta| <= 0.3 rad, reached within 5 mm and 0.02 rad with the
  // grasp held (measured: within 0.05 mm and 8e-5 rad, each within 5 mm after 1.5-2.3 s).
  const HandModel model = handModelWithSettings({{"mu", 0.5}, {"turn", 1}});
  std::mt19937 rng(4141);
  std::uniform_real_distribution<double> xy(-0.4, 0.4), theta(-0.3, 0.3);
  for (int i = 0; i < 4; ++i) {
    TrackOptions o;
    o.target = Vec2(xy(rng), xy(rng));
    o.targetAngle = theta(rng);
    o.law = HandLaw::Mpc;
    o.time = 8;
    const TrackResult r = runTracking(o, model);
    std::printf("target %+.3f %+.3f %+.3f: error %.2e m %.2e rad, within 5 mm after %.2f s\n",
                o.target.x(), o.target.y(), o.targetAngle, r.finalError, r.finalAngleError,
                r.timeTo5mm);
    EXPECT_TRUE(r.graspHeld) << i;
    EXPECT_LT(r.finalError, 0.005) << i;
    EXPECT_LT(r.finalAngleError, 0.02) << i;
    EXPECT_GT(std::abs(r.samples.back().angle), 0.5 * std::abs(o.targetAngle)) << i;
  }
}

}  // namespace hand_mpc_test
}  // namespace cablelab

// The statics-based Jacobian controller of thesis section 4.3 (outer loop).
//
//   db/dq_u = db/dp_ij * dp_ij/dq_u                 (2 x 6: statics sensitivity x fingertip FK)
//   dq_u    = -J+ (k_p e + k_d db/dt + k_i sum e dt) per outer update, J+ = J^T (J J^T + l^2 I)^-1
// with e = b - b_des the manipuland's error. Equation (4.4) gives a joint *rate* from a 2-vector
// and omits the inverse (docs/model.md#controller): q_dot = -J+ (k_p' e + k_d b_dot). There k_d multiplies a
// velocity to give a velocity, so it is dimensionless; k_p' is a rate (1/s). Here the rate is
// integrated over one outer period T (0.053 s):
//   dq = -J+ (k_p e + k_d db + k_i T sum e)      per update,
// with db = b_k - b_(k-1) the box's change over the last period (a derivative averaged over T,
// which filters the membranes' fast ripple out of the box velocity). So k_p = 0.1 is the share
// of the error removed per update (dimensionless; k_p' = k_p / T = 1.9 1/s), k_d = 0.58 is the
// thesis's dimensionless gain as it stands, and k_i is per update per second (1/s). (The first
// implementation multiplied the instantaneous box velocity by k_d in seconds, i.e. a derivative
// gain k_d / T = 11 times the thesis's: the loop went unstable and k_d was set to 0.)
// The box prediction comes from the real statics (solveStatics + staticsSensitivity) on the
// box-to-point reduction (box_reduction.h). The new targets go to the inner PD servos.
// Beyond the thesis (the six joints are redundant for a 2-vector task): the pseudo-inverse is
// weighted (W = diag(1, 1, w_d, 1, 1, w_d)), J+ = W^-1 J^T (J W^-1 J^T + l^2 I)^-1, and the null
// space turns each paddle back towards face-on (theta_p + theta_d -> 0) and keeps the paddles' gap
// at the pinch's, which keeps both membranes wrapping the box face-on, the configuration the
// box-to-point reduction assumes.
#pragma once

#include <Eigen/Core>

#include "engine/hand/hand_kinematics.h"
#include "engine/hand/hand_model.h"
#include "engine/statics/statics.h"

namespace cablelab {

struct HandControllerParams {
  double period = 0.053;  ///< outer-loop period (s)
  double kp = 0.1;        ///< per update, dimensionless (thesis k_p)
  double kd = 0.58;       ///< dimensionless, on the box's change over one period (thesis k_d)
  double ki = 0.0;        ///< per update per second (1/s); > 0 for PID
  double lambda = 0.05;   ///< pseudo-inverse damping (m per rad or m per m)
  double maxError = 0.2;  ///< the error fed to the law is saturated at this length (m): the
                          ///< Jacobian is a local model, one update must not leave its validity
  double integralZone = 0.02;  ///< the integral collects the error only while |e| is below this (m)
  double distalWeight = 4.0;   ///< joint-space weight of the distal joints in the pseudo-inverse
                               ///< (> 1: prefer moving the fingers to tilting the paddles)
  double faceOnGain =
      0.3;  ///< per update: null-space pull back to face-on paddles and the pinch gap
};

/// The integral gain `--pid` uses (1/s per update).
inline constexpr double kHandPidKi = 0.1;

/// db/dq_u (m/rad, m/m), 2 x 6.
using BoxJacobian = Eigen::Matrix<double, 2, 6>;

/// The statics model's prediction at joint values q.
struct BoxPrediction {
  Vec2 box = Vec2::Zero();  ///< equilibrium box centre (m)
  BoxJacobian jacobian = BoxJacobian::Zero();
  bool valid = false;  ///< solver converged and both membranes wrap the box face-on
};

class HandController {
 public:
  explicit HandController(HandModel model, HandControllerParams params = {});

  const HandModel& model() const { return model_; }
  const HandControllerParams& params() const { return params_; }

  /// The statics problem of the box-to-point reduction at joints q (warm start `guess`): the two
  /// membranes as point cables, fingertips shifted by the box corners they wrap.
  StaticsProblem staticsProblem(const HandJoints& q, const Vec2& guess) const;

  /// Equilibrium box centre and db/dq_u at joints q, warm-started at `guess`.
  BoxPrediction predict(const HandJoints& q, const Vec2& guess) const;

  /// Clears the integral and derivative memory.
  void reset() {
    integral_.setZero();
    hasPrevious_ = hasSteering_ = false;
  }

  /// One outer-loop update from the measured joints q and box centre, the target and the joint
  /// targets currently commanded; returns the joint-target increment (rad, m). Call it once per
  /// period: the derivative term uses the box centre of the previous call.
  HandJoints update(const HandJoints& q, const Vec2& box, const Vec2& target,
                    const HandJoints& commanded);

  /// The last update's prediction (for diagnostics).
  const BoxPrediction& lastPrediction() const { return last_; }

 private:
  HandModel model_;
  HandControllerParams params_;
  Vec2 integral_ = Vec2::Zero();
  Vec2 previousBox_ = Vec2::Zero();
  bool hasPrevious_ = false;
  BoxJacobian steering_ = BoxJacobian::Zero();  ///< the last valid prediction's Jacobian
  bool hasSteering_ = false;
  BoxPrediction last_;
};

/// Median wall time of one HandController::update at the pinch pose (us), over `repeats` calls.
double measureControllerUpdateMicros(int repeats = 20000);

}  // namespace cablelab

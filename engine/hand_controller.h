// The statics-based Jacobian controller of thesis section 4.3 (outer loop).
//
//   db/dq_u = db/dp_ij * dp_ij/dq_u                 (2 x 6: statics sensitivity x fingertip FK)
//   dq_u    = -J+ (k_p e + k_d db/dt + k_i sum e dt) per outer update, J+ = J^T (J J^T + l^2 I)^-1
// with e = b - b_des the manipuland's error. Equation (4.4) gives a joint *rate* from a 2-vector
// and omits the inverse (NOTES.md); here the rate is integrated over one outer period, so
// k_p = 0.1 is the share of the error the joints are asked to remove per update (dimensionless,
// 0.1 / 0.053 s = 1.9 1/s), k_d = 0.58 s turns the box velocity into metres of error, and the
// optional k_i (1/s) integrates the error for `--pid`. The new targets go to the inner PD servos.
// Beyond the thesis (the six joints are redundant for a 2-vector task): the pseudo-inverse is
// weighted (W = diag(1, 1, w_d, 1, 1, w_d)), J+ = W^-1 J^T (J W^-1 J^T + l^2 I)^-1, and the null
// space turns each paddle back towards face-on (theta_p + theta_d -> 0) and keeps the paddles' gap
// at the pinch's, which keeps both membranes wrapping the box face-on, the configuration the
// box-to-point reduction assumes.
#pragma once

#include <Eigen/Core>

#include "engine/hand_kinematics.h"
#include "engine/hand_model.h"
#include "engine/point_equilibrium.h"

namespace cablelab {

struct HandControllerParams {
  double period = 0.053;  ///< outer-loop period (s)
  double kp = 0.1;        ///< per update, dimensionless
  /// per update (s). The thesis's 0.58 makes our loop oscillate and lose the box (the membranes'
  /// damping delays the box's response to the fingers, and a derivative on the box fights it),
  /// so the default is 0; pass kThesisKd to reproduce that.
  double kd = 0.0;
  double ki = 0.0;        ///< per update (1/s); > 0 for PID
  double lambda = 0.05;   ///< pseudo-inverse damping (m per rad or m per m)
  double maxError = 0.05; ///< the error fed to the law is saturated at this length (m): the
                          ///< Jacobian is a local model, one update must not leave its validity
  double distalWeight = 4.0;  ///< joint-space weight of the distal joints in the pseudo-inverse
                              ///< (> 1: prefer moving the fingers to tilting the paddles)
  double faceOnGain = 0.3;    ///< per update: null-space pull back to face-on paddles and the pinch gap
};

inline constexpr double kThesisKd = 0.58;

/// The integral gain `--pid` uses (1/s per update).
inline constexpr double kHandPidKi = 0.1;

/// db/dq_u (m/rad, m/m), 2 x 6.
using BoxJacobian = Eigen::Matrix<double, 2, 6>;

/// The statics model's prediction at joint values q.
struct BoxPrediction {
  Vec2 box = Vec2::Zero();                   ///< equilibrium box centre (m)
  BoxJacobian jacobian = BoxJacobian::Zero();
  bool valid = false;  ///< solver converged and both membranes wrap the box face-on
};

class HandController {
 public:
  explicit HandController(HandModel model, HandControllerParams params = {},
                          EquilibriumSolver solver = solvePointEquilibrium);

  const HandModel& model() const { return model_; }
  const HandControllerParams& params() const { return params_; }

  /// The four membranes-as-springs of the box-to-point reduction at joints q.
  std::vector<SpringCable> springs(const HandJoints& q) const;

  /// Equilibrium box centre and db/dq_u at joints q, warm-started at `guess`.
  BoxPrediction predict(const HandJoints& q, const Vec2& guess) const;

  /// Clears the integral term.
  void reset() { integral_.setZero(); }

  /// One outer-loop update from the measured joints q, box centre and velocity, the target and
  /// the joint targets currently commanded; returns the joint-target increment (rad, m).
  HandJoints update(const HandJoints& q, const Vec2& box, const Vec2& boxVelocity, const Vec2& target,
                    const HandJoints& commanded);

  /// The last update's prediction (for diagnostics).
  const BoxPrediction& lastPrediction() const { return last_; }

 private:
  HandModel model_;
  HandControllerParams params_;
  EquilibriumSolver solver_;
  Vec2 integral_ = Vec2::Zero();
  BoxPrediction last_;
};

/// Median wall time of one HandController::update at the pinch pose (us), over `repeats` calls.
double measureControllerUpdateMicros(int repeats = 20000);

}  // namespace cablelab

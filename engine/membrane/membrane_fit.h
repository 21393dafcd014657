// Fitting the membrane model (engine/membrane/membrane_model.h) to force measurements
// (engine/membrane/membrane_data.h): stiffness k and preload from the vertical force component and
// the force direction at each contact point, thesis section 3.2.
//
// Method: one weighted nonlinear least-squares problem over both measurement kinds,
//   minimise  sum_i ((fy_model_i - fy_i) / sigma_fy)^2
//           + sum_i (wrap(angle_model_i - angle_i) / sigma_angle)^2      (angles in degrees,
//                                                                        wrapped to (-180, 180])
// over (k, preload), solved with Eigen's (unsupported) Levenberg-Marquardt from an exact
// linear start (fy is linear in k and k * preload). When a noise level is not given it is
// estimated from that kind's residuals and the problem refitted (iteratively reweighted) until
// the levels settle.
//
// Note on information: while the band is taut the modelled force direction is that of
// -(u1 + u2), which depends on the pulleys and p only. The angle residuals therefore have a zero
// derivative with respect to k and preload: they are part of the objective and reported
// (rms_angle_deg tests the geometry of the model), but k and preload are determined by fy.
//
// Standard errors: covariance = (J_w^T J_w)^-1 with J_w the Jacobian of the weighted residuals
// at the solution. With estimated noise levels, sigma_kind^2 = SSR_kind / (n_kind - h_kind)
// where h_kind is that kind's share of the hat-matrix trace (the parameters it absorbs), so the
// covariance equals the usual s^2 (J^T W J)^-1 scaling. With given noise levels it is used as is.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/membrane/membrane_data.h"
#include "engine/membrane/membrane_model.h"

namespace cablelab {

struct MembraneFitOptions {
  double sigmaFy = 0.0;           ///< noise level of fy (N); <= 0: estimate from the residuals
  double sigmaAngleDeg = 0.0;     ///< noise level of angle_deg (degrees); <= 0: estimate
  int maxRounds = 10;             ///< fit / re-estimate rounds when a noise level is estimated
  int maxEvaluations = 400;       ///< Levenberg-Marquardt residual evaluations per round
  std::string source = "<data>";  ///< names the data in InputError messages
};

struct MembraneFitResult {
  MembraneParams params;                                 ///< fitted k (N/m) and preload (m)
  double kStderr = 0.0;                                  ///< standard error of k (N/m)
  double preloadStderr = 0.0;                            ///< standard error of preload (m)
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  ///< of (k, preload), (2 x 2)
  double rmsFy = 0.0;                                    ///< RMS of fy residuals (N)
  double rmsAngleDeg = 0.0;    ///< RMS of wrapped angle residuals (degrees)
  double sigmaFy = 0.0;        ///< noise level used for fy in the last round (N)
  double sigmaAngleDeg = 0.0;  ///< noise level used for angles in the last round (degrees)
  double chi2PerDof = 0.0;     ///< weighted SSR / (2 rows - 2); ~1 when the levels are right
  int iterations = 0;          ///< LM iterations (Jacobian evaluations), all rounds
  int rounds = 0;              ///< fit rounds (1 when both noise levels are given)
  int rows = 0;                ///< measurements used
};

/// Fits k and preload. Preconditions: g valid, rows validated (see membrane_data.h).
/// Throws InputError(options.source, ...) when the data cannot determine the parameters:
/// fewer than kMinMembraneRows rows, all points at the same stretch (k and preload not
/// separable), or a best fit with k <= 0 (forces that do not pull towards the band).
MembraneFitResult fitMembrane(const MembraneGeometry& g, const std::vector<MembraneSample>& rows,
                              const MembraneFitOptions& options = {});

}  // namespace cablelab

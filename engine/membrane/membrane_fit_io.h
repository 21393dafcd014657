// The membrane fit as `cablelab fit` takes and reports it. The CLI (app/cmd_fit.cpp) and the
// Python module's fit() (python/py_tools.cpp) both go through these, so that they check the
// pulleys and noise levels with the same messages and report the same fields.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "engine/membrane/membrane_data.h"
#include "engine/membrane/membrane_fit.h"

namespace cablelab {

/// --pulleys AX,AY,BX,BY (m) as the geometry; throws InputError("command line", "--pulleys", ...)
/// unless they are 4 finite numbers and A != B.
MembraneGeometry membranePulleys(const std::vector<double>& values);

/// A given noise level: --sigma-fy (N) or --sigma-angle-deg (degrees); throws
/// InputError("command line", option, "must be positive (UNIT) (got v)") unless v > 0.
double membraneSigma(double v, const char* option);

/// The JSON object `cablelab fit` prints: k, preload, rms_fy, rms_angle_deg, k_stderr,
/// preload_stderr, k_preload_correlation, sigma_fy, sigma_angle_deg, sigmas ("given", "partly
/// estimated", "estimated"), chi2_per_dof, iterations, rounds, rows, fit_us (`fitMicros`).
nlohmann::ordered_json membraneFitJson(const MembraneFitResult& fit,
                                       const MembraneFitOptions& options, double fitMicros);

}  // namespace cablelab

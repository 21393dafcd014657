#include "engine/membrane/membrane_fit_io.h"

#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace cablelab {

MembraneGeometry membranePulleys(const std::vector<double>& v) {
  if (v.size() != 4)
    throw InputError(kCommandLine, "--pulleys",
                     "must be AX,AY,BX,BY, 4 finite numbers" + gotValue(double(v.size())));
  MembraneGeometry g{Vec2(v[0], v[1]), Vec2(v[2], v[3])};
  validateMembraneGeometry(g, kCommandLine, "--pulleys");
  return g;
}

double membraneSigma(double v, const char* option) {
  const std::string unit = std::string(option) == "--sigma-fy" ? "N" : "degrees";
  if (!(v > 0) || !std::isfinite(v))
    throw InputError(kCommandLine, option, "must be positive (" + unit + ")" + gotValue(v));
  return v;
}

nlohmann::ordered_json membraneFitJson(const MembraneFitResult& fit,
                                       const MembraneFitOptions& options, double fitMicros) {
  nlohmann::ordered_json j;
  j["k"] = fit.params.k;
  j["preload"] = fit.params.preload;
  j["rms_fy"] = fit.rmsFy;
  j["rms_angle_deg"] = fit.rmsAngleDeg;
  j["k_stderr"] = fit.kStderr;
  j["preload_stderr"] = fit.preloadStderr;
  j["k_preload_correlation"] =
      fit.covariance(0, 1) / std::sqrt(fit.covariance(0, 0) * fit.covariance(1, 1));
  j["sigma_fy"] = fit.sigmaFy;
  j["sigma_angle_deg"] = fit.sigmaAngleDeg;
  j["sigmas"] = (options.sigmaFy > 0 && options.sigmaAngleDeg > 0)   ? "given"
                : (options.sigmaFy > 0 || options.sigmaAngleDeg > 0) ? "partly estimated"
                                                                     : "estimated";
  j["chi2_per_dof"] = fit.chi2PerDof;
  j["iterations"] = fit.iterations;
  j["rounds"] = fit.rounds;
  j["rows"] = fit.rows;
  j["fit_us"] = fitMicros;
  return j;
}

}  // namespace cablelab

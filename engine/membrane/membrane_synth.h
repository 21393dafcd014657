// Synthetic membrane measurements: the model of engine/membrane/membrane_model.h evaluated over a
// grid of contact points, with seeded Gaussian noise on fy and on the force direction. Used to make
// example data sets and to test the fit against known parameters.
//
// Grid, in the band's frame: t = (B - A) / |B - A| along the band, n = t rotated by +90 deg.
// Point (i, j) = A + along_i |AB| t - depth_j |AB| n, with along_i evenly spaced over
// [alongMin, alongMax] and depth_j over [depthMin, depthMax] (fractions of |AB|, ends included).
// Positive depth is on the right of A -> B: below the band when A is left of B. Negative depths
// press from the other side.
//
// Reproducible everywhere: the noise comes from std::mt19937_64 (its output is fixed by the C++
// standard) through our own Box-Muller transform (std::normal_distribution is not portable).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/membrane/membrane_data.h"
#include "engine/membrane/membrane_model.h"

namespace cablelab {

struct MembraneSynthDef {
  MembraneGeometry geometry;   ///< pulleys (m)
  MembraneParams params;       ///< true k (N/m) and preload (m)
  double noiseFy = 0.05;       ///< standard deviation of the noise added to fy (N), >= 0
  double noiseAngleDeg = 1.0;  ///< standard deviation of the angle noise (degrees), >= 0
  std::uint64_t seed = 1;      ///< seeds the noise; the same seed gives the same file
  int nx = 8;                  ///< grid points along the band, >= 1
  int ny = 6;                  ///< grid points in depth, >= 1
  double alongMin = 0.1;       ///< first grid column, fraction of |AB| from A
  double alongMax = 0.9;       ///< last grid column, fraction of |AB| from A
  double depthMin = 0.05;      ///< shallowest row, fraction of |AB| (sign: side, see above)
  double depthMax = 0.35;      ///< deepest row, fraction of |AB|
};

/// Throws InputError(source, field, ...) for a bad def (field names as in the CLI:
/// "k", "preload", "noise_fy", "noise_angle_deg", "grid", "depth", "along", "pulleys").
void validateMembraneSynth(const MembraneSynthDef& def, const std::string& source);

/// nx * ny noisy samples, row-major over (depth, along); angles wrapped to (-180, 180].
/// Precondition: validateMembraneSynth passed.
std::vector<MembraneSample> generateMembraneData(const MembraneSynthDef& def);

}  // namespace cablelab

#include "engine/membrane/membrane_synth.h"

#include <cmath>
#include <numbers>
#include <random>

#include "engine/core/error.h"

namespace cablelab {
namespace {

/// Standard normal deviates from a standard-specified engine, identical on every platform.
class PortableNormal {
 public:
  explicit PortableNormal(std::uint64_t seed) : engine_(seed) {}

  double next() {
    if (hasSpare_) {
      hasSpare_ = false;
      return spare_;
    }
    const double u1 = uniformOpenZero();
    const double u2 = uniformOpenZero();
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * std::numbers::pi * u2;
    spare_ = radius * std::sin(angle);
    hasSpare_ = true;
    return radius * std::cos(angle);
  }

 private:
  /// Uniform in (0, 1]: 53 random bits, never 0 (log(0) would be -inf).
  double uniformOpenZero() { return (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53; }

  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool hasSpare_ = false;
};

double lerpGrid(double lo, double hi, int i, int count) {
  return count == 1 ? 0.5 * (lo + hi) : lo + (hi - lo) * i / (count - 1);
}

}  // namespace

void validateMembraneSynth(const MembraneSynthDef& def, const std::string& source) {
  validateMembraneGeometry(def.geometry, source);
  auto require = [&](bool ok, const char* field, const std::string& what, const std::string& got) {
    if (!ok) throw InputError(source, field, what + got);
  };
  auto pair = [](double a, double b) {
    return " (got (" + formatNumber(a) + ", " + formatNumber(b) + "))";
  };
  require(std::isfinite(def.params.k) && def.params.k > 0, "k", "must be positive and finite",
          gotValue(def.params.k));
  require(std::isfinite(def.params.preload) && def.params.preload >= 0, "preload",
          "must be >= 0 and finite (the band is pre-stretched, never slack)",
          gotValue(def.params.preload));
  require(std::isfinite(def.noiseFy) && def.noiseFy >= 0, "noise_fy", "must be >= 0 and finite",
          gotValue(def.noiseFy));
  require(std::isfinite(def.noiseAngleDeg) && def.noiseAngleDeg >= 0, "noise_angle_deg",
          "must be >= 0 and finite", gotValue(def.noiseAngleDeg));
  require(def.nx >= 1 && def.ny >= 1 && static_cast<long>(def.nx) * def.ny >= kMinMembraneRows &&
              static_cast<long>(def.nx) * def.ny <= 1000000,
          "grid", "needs NX, NY >= 1 and between 3 and 1e6 points in all", pair(def.nx, def.ny));
  require(std::isfinite(def.alongMin) && std::isfinite(def.alongMax), "along", "must be finite",
          pair(def.alongMin, def.alongMax));
  require(std::isfinite(def.depthMin) && std::isfinite(def.depthMax), "depth", "must be finite",
          pair(def.depthMin, def.depthMax));
  // A depth of 0 inside the span puts the point on the band: no force direction.
  require(def.depthMin * def.depthMax > 0, "depth",
          "MIN and MAX must be non-zero and on the same side of the band",
          pair(def.depthMin, def.depthMax));
}

std::vector<MembraneSample> generateMembraneData(const MembraneSynthDef& def) {
  const MembraneGeometry& g = def.geometry;
  const double span = (g.b - g.a).norm();
  const Vec2 along = (g.b - g.a) / span;
  const Vec2 normal = perp(along);
  PortableNormal noise(def.seed);
  std::vector<MembraneSample> rows;
  rows.reserve(static_cast<size_t>(def.nx) * def.ny);
  for (int j = 0; j < def.ny; ++j) {
    const double depth = lerpGrid(def.depthMin, def.depthMax, j, def.ny) * span;
    for (int i = 0; i < def.nx; ++i) {
      const double s = lerpGrid(def.alongMin, def.alongMax, i, def.nx) * span;
      MembraneSample sample;
      sample.p = g.a + s * along - depth * normal;
      const Vec2 force = membraneForce(g, def.params, sample.p);
      sample.fy = force.y() + def.noiseFy * noise.next();
      sample.angleDeg =
          wrapAngleDeg(membraneForceAngleDeg(g, sample.p) + def.noiseAngleDeg * noise.next());
      rows.push_back(sample);
    }
  }
  return rows;
}

}  // namespace cablelab

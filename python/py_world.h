// The World as Python holds it: the engine World plus names and a guard against two threads using
// it at once (run() releases the GIL).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "python/bindings.h"

namespace cablelab::python {

struct PyWorld {
  PyWorld(SceneDef scene, const std::string& source);
  /// Takes over a World already built (a fork or a restored state).
  PyWorld(std::unique_ptr<World> built, const std::string& source);

  std::unique_ptr<World> world;
  std::string source;
  std::vector<std::string> bodyNames, cableNames, jointNames;
  mutable std::atomic<bool> busy{false};

  /// Holds the World for one call; throws RuntimeError if another thread holds it.
  class Busy {
   public:
    explicit Busy(const PyWorld& w);
    ~Busy();

   private:
    const PyWorld& w_;
  };

  int bodyIndex(py::handle which, const std::string& source) const;
  int cableIndex(py::handle which, const std::string& source) const;
  int jointIndex(py::handle which, const std::string& source) const;
};

/// v itself; throws InputError unless finite and within the range Box2D simulates honestly.
double checkedValue(double v, const std::string& source, const std::string& field);

/// x y theta vx vy omega of a body into d[0..5].
void writeBody(const BodyState& b, double* d);

/// One row of a recording (World.run(record=True), rollout): bodies (bodies x 6: x y theta vx
/// vy omega), cables (cables x 3: length, tension, wraps), joints (joints x 2: value, speed).
void writeStateRow(const World& w, double* bodies, double* cables, double* joints);

void bindState(py::module_& m, py::class_<PyWorld>& world);
void bindSensors(py::class_<PyWorld>& world);

}  // namespace cablelab::python

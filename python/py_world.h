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

void bindState(py::module_& m, py::class_<PyWorld>& world);
void bindSensors(py::class_<PyWorld>& world);

}  // namespace cablelab::python

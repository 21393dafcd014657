// Shared pieces of the hand's bindings (py_hand.cpp, py_hand_runs.cpp, py_grasp.cpp).
#pragma once

#include <string>

#include "engine/core/error.h"
#include "engine/hand/hand_model.h"
#include "python/bindings.h"
#include "python/py_world.h"

namespace cablelab::python {

/// Six joint values (rad, m), controller order, from any sequence or array.
HandJoints jointsOf(py::handle q, const std::string& source);
py::array_t<double> jointsArray(const HandJoints& q);

/// The hand scene's joints must be there (a World built from the hand scene).
void requireHand(const PyWorld& w, const std::string& source);

/// "Name(field=value, ...)" over the class's read/write attributes.
std::string fieldsRepr(py::handle self, const char* name);

/// T(**fields): a default T with the given read/write attributes set; an unknown field is an
/// InputError(name, field, "no such field").
template <typename T>
T fromFields(const char* name, const py::kwargs& kw) {
  py::object self = py::cast(T{});
  for (auto [k, v] : kw) {
    const std::string key = py::str(k);
    if (!py::hasattr(self, key.c_str()) || key.rfind("_", 0) == 0)
      throw InputError(name, key, "no such field");
    self.attr(key.c_str()) = v;
  }
  return self.template cast<T>();
}

void bindHandRuns(py::module_& m);
void bindGrasp(py::module_& m);

}  // namespace cablelab::python

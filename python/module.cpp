// The Python module: `import cablelab` (python/cablelab/__init__.py re-exports this _core).
// Errors: cablelab::InputError becomes cablelab.InputError (a ValueError) carrying the same
// one-line message the CLI prints, SimulationError becomes cablelab.SimulationError.
#include "engine/core/error.h"
#include "python/bindings.h"

namespace cablelab::python {

void bindErrors(py::module_& m) {
  // Kept for the life of the process: the translator may run during interpreter shutdown.
  static PyObject* inputError = nullptr;
  static PyObject* simulationError = nullptr;
  inputError = PyErr_NewExceptionWithDoc(
      "cablelab.InputError",
      "Bad input: a scene, file, parameter or argument that cannot be used.\n\n"
      "str(e) is the one line the cablelab CLI prints, 'SOURCE: FIELD: what is wrong';\n"
      "e.source and e.field hold its first two parts.",
      PyExc_ValueError, nullptr);
  simulationError = PyErr_NewExceptionWithDoc(
      "cablelab.SimulationError",
      "A simulation that cannot continue (a non-finite state); the World is left as it was\n"
      "after the failing step.",
      PyExc_RuntimeError, nullptr);
  m.attr("InputError") = py::handle(inputError);
  m.attr("SimulationError") = py::handle(simulationError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(inputError)(py::str(e.what()));
      error.attr("source") = py::str(e.source());
      error.attr("field") = py::str(e.field());
      PyErr_SetObject(inputError, error.ptr());
    } catch (const SimulationError& e) {
      PyErr_SetString(simulationError, e.what());
    }
  });
}

}  // namespace cablelab::python

PYBIND11_MODULE(_core, m) {
  using namespace cablelab::python;
  m.doc() = "The compiled part of cablelab (see help(cablelab)).";
  // The docstrings carry hand-written signatures in Python terms (pybind11's would say
  // "handle" and "cablelab._core.HandModel object at 0x...").
  py::options options;
  options.disable_function_signatures();
  bindErrors(m);
  bindWorld(m);
  bindTools(m);
  bindHand(m);
  bindRender(m);
}

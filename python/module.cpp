// The Python module: `import cablelab` (python/cablelab/__init__.py re-exports this _core).
// Errors: cablelab::InputError becomes cablelab.InputError (a ValueError) carrying the same
// one-line message the CLI prints, SimulationError becomes cablelab.SimulationError.
#include <cstdlib>
#include <cstring>
#include <regex>
#include <string>

#include "engine/core/error.h"
#include "python/bindings.h"

namespace cablelab::python {

namespace {

/// An error the engine words for the command line ("command line: --set m1: ...") in Python's
/// words: the argument's keyword ("argument: m1: ...").
std::pair<std::string, std::string> pythonWords(const InputError& e) {
  if (e.source() != kCommandLine) return {e.source(), e.field()};
  std::string field = e.field();
  if (field.rfind("--set ", 0) == 0) field = field.substr(6);
  while (field.rfind("-", 0) == 0) field = field.substr(1);
  for (char& c : field)
    if (c == '-') c = '_';
  if (field == "SCENE") field = "scene";
  return {"argument", field};
}

/// The hand-written first line "name(args) -> ..." of a function's docstring as CPython's text
/// signature ("name(self, args)\n--\n\n"), so that inspect.signature() and IDEs read the
/// parameters (pybind11's own signatures name C++ types and do not reach inspect). A line whose
/// defaults inspect cannot read (an object, not a literal) is left as it was.
void addTextSignature(py::handle function, bool method, const py::object& signature) {
  if (!PyCFunction_Check(function.ptr())) return;
  PyMethodDef* def = reinterpret_cast<PyCFunctionObject*>(function.ptr())->m_ml;
  if (!def->ml_doc || !def->ml_name) return;
  const std::string doc = def->ml_doc, name = def->ml_name;
  if (doc.rfind(name + "(", 0) != 0) return;
  size_t close = name.size(), depth = 0;
  for (; close < doc.size(); ++close) {
    if (doc[close] == '(') ++depth;
    if (doc[close] == ')' && --depth == 0) break;
  }
  if (close >= doc.size()) return;
  // A first line wrapped inside the parentheses is one signature: runs of blanks become one.
  std::string args;
  for (char ch : doc.substr(name.size() + 1, close - name.size() - 1)) {
    const bool blank = ch == ' ' || ch == '\n';
    if (!blank || (!args.empty() && args.back() != ' ')) args += blank ? ' ' : ch;
  }
  const std::string text =
      name + "(" + (method ? (args.empty() ? "self" : "self, " + args) : args) + ")\n--\n\n" + doc;
  const char* old = def->ml_doc;
  def->ml_doc = strdup(text.c_str());
  try {
    signature(function);
    std::free(const_cast<char*>(old));  // pybind11 allocated it with strdup
  } catch (const py::error_already_set&) {
    std::free(const_cast<char*>(def->ml_doc));
    def->ml_doc = old;
  }
}

void addTextSignatures(py::module_& m) {
  const py::object signature = py::module_::import("inspect").attr("signature");
  for (auto [key, value] : m.attr("__dict__").cast<py::dict>()) {
    if (PyCFunction_Check(value.ptr())) addTextSignature(value, false, signature);
    if (!PyType_Check(value.ptr())) continue;
    for (auto [name, attr] : value.attr("__dict__").cast<py::dict>()) {
      if (PyInstanceMethod_Check(attr.ptr()))
        addTextSignature(PyInstanceMethod_GET_FUNCTION(attr.ptr()), true, signature);
      else if (py::isinstance(attr, py::module_::import("builtins").attr("staticmethod")))
        addTextSignature(attr.attr("__func__"), false, signature);
    }
  }
}

}  // namespace

void bindErrors(py::module_& m) {
  // Kept for the life of the process: the translator may run during interpreter shutdown.
  static PyObject* inputError = nullptr;
  static PyObject* inputTypeError = nullptr;
  static PyObject* simulationError = nullptr;
  inputError = PyErr_NewExceptionWithDoc(
      "cablelab.InputError",
      "Bad input: a scene, file, parameter or argument that cannot be used.\n\n"
      "str(e) is the one line the cablelab CLI prints, 'SOURCE: FIELD: what is wrong';\n"
      "e.source and e.field hold its first two parts.",
      PyExc_ValueError, nullptr);
  // A value of the wrong type ("(got a str)", "(got None)") is also a TypeError, as Python's own
  // functions raise for one; `except cablelab.InputError` catches both.
  py::tuple typeBases = py::make_tuple(py::handle(inputError), py::handle(PyExc_TypeError));
  inputTypeError = PyErr_NewExceptionWithDoc(
      "cablelab.InputTypeError",
      "Bad input of the wrong type (an InputError and a TypeError): str(e) ends '(got a TYPE)'.",
      typeBases.ptr(), nullptr);
  simulationError = PyErr_NewExceptionWithDoc(
      "cablelab.SimulationError",
      "A simulation that cannot continue (a non-finite state); the World is left as it was\n"
      "after the failing step.",
      PyExc_RuntimeError, nullptr);
  m.attr("InputError") = py::handle(inputError);
  m.attr("InputTypeError") = py::handle(inputTypeError);
  m.attr("SimulationError") = py::handle(simulationError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      const auto [source, field] = pythonWords(e);
      const std::string text =
          source == e.source() ? std::string(e.what()) : source + ": " + field + ": " + e.detail();
      static const std::regex wrongType(R"( \(got (an? [A-Za-z_][\w.]*|None)\)$)");
      PyObject* kind = std::regex_search(e.detail(), wrongType) ? inputTypeError : inputError;
      py::object error = py::reinterpret_borrow<py::object>(kind)(py::str(text));
      error.attr("source") = py::str(source);
      error.attr("field") = py::str(field);
      PyErr_SetObject(kind, error.ptr());
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
  // "handle" and "cablelab._core.HandModel object at 0x..."); addTextSignatures() hands them to
  // inspect.signature().
  py::options options;
  options.disable_function_signatures();
  bindErrors(m);
  bindWorld(m);
  bindTools(m);
  bindHand(m);
  bindRender(m);
  bindRollout(m);
  addTextSignatures(m);
}

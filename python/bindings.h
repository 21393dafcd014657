// Shared pieces of the Python module (python/module.cpp): conversions between Python objects,
// JSON and numpy arrays, and the bind functions of each part of the API.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/core/math.h"

namespace cablelab::python {

namespace py = pybind11;

/// A Python value (dict, list, tuple, numpy array, number, bool, str, None) as JSON, the way the
/// scene and statics readers take it. Throws InputError(source, field, ...) for a value JSON
/// cannot hold (a set, an object, NaN or infinity).
nlohmann::json toJson(py::handle value, const std::string& source, const std::string& field = "");

/// JSON as plain Python values (dict keeps the key order).
py::object fromJson(const nlohmann::json& j);
py::object fromJson(const nlohmann::ordered_json& j);

/// A str or an os.PathLike as a path string; throws InputError naming `field` otherwise.
std::string pathString(py::handle value, const std::string& source, const std::string& field);

/// Exactly two finite numbers (a sequence or array) as a Vec2.
Vec2 toVec2(py::handle value, const std::string& source, const std::string& field);

/// Exactly `count` finite numbers from any sequence or array.
std::vector<double> toNumbers(py::handle value, size_t count, const std::string& source,
                              const std::string& field);

/// " (got VALUE)" for a Python value, to end a message (engine/core/error.h's style): a number
/// or text as gotValue() writes it, an array or a list of numbers by its shape ("(got shape
/// (3, 2))"), None/True/False by name, anything else by its type ("(got a dict)").
std::string gotPython(py::handle value);

/// " (got a TYPE)" (" (got None)"), to end a message about a value of the wrong type; the module
/// raises such an InputError as cablelab.InputTypeError, a TypeError too (python/module.cpp).
std::string gotType(py::handle value);

/// " (got NAME=VALUE)": a keyword argument as the caller wrote it (its value's repr, shortened).
std::string gotKeyword(const std::string& name, py::handle value);

/// A real number (int, float or a numpy scalar; not a bool); throws InputError naming `field`
/// and the type given otherwise.
double toNumber(py::handle value, const std::string& source, const std::string& field);

/// A float64 array of the given shape (C order), uninitialised.
py::array_t<double> newArray(std::vector<py::ssize_t> shape);

/// points as an (n, 2) array.
py::array_t<double> pointsArray(const std::vector<Vec2>& points);

void bindErrors(py::module_& m);
void bindWorld(py::module_& m);
void bindTools(py::module_& m);
void bindHand(py::module_& m);
void bindRender(py::module_& m);
void bindRollout(py::module_& m);

}  // namespace cablelab::python

// Python <-> JSON and numpy helpers (python/bindings.h).
#include <cmath>
#include <cstdio>

#include "engine/core/error.h"
#include "python/bindings.h"

namespace cablelab::python {

namespace {

std::string typeName(py::handle value) {
  return py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
}

}  // namespace

nlohmann::json toJson(py::handle value, const std::string& source, const std::string& field) {
  const std::string here = field.empty() ? "(value)" : field;
  if (value.is_none()) return nullptr;
  if (PyBool_Check(value.ptr()) || typeName(value) == "bool_")
    return value.attr("__bool__")().cast<bool>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json out = nlohmann::json::object();
    for (auto [key, item] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key))
        throw InputError(source, here, "keys must be strings (got " + typeName(key) + ")");
      const std::string name = key.cast<std::string>();
      out[name] = toJson(item, source, field.empty() ? name : field + "." + name);
    }
    return out;
  }
  if (py::isinstance<py::array>(value)) return toJson(value.attr("tolist")(), source, field);
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    nlohmann::json out = nlohmann::json::array();
    size_t i = 0;
    for (py::handle item : value)
      out.push_back(toJson(item, source, here + "[" + std::to_string(i++) + "]"));
    return out;
  }
  // Integers (also numpy's) stay integers; every other number becomes a double.
  if (PyIndex_Check(value.ptr())) {
    const py::int_ i(py::reinterpret_borrow<py::object>(value));
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
    if (!overflow) return v;
    const double d = PyLong_AsDouble(i.ptr());  // beyond 64 bits: a double, as JSON reads it
    if (d == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      throw InputError(source, here, "is too large a number" + gotPython(value));
    }
    return d;
  }
  if (PyFloat_Check(value.ptr()) || PyNumber_Check(value.ptr())) {
    const double d = py::float_(value.cast<py::object>()).cast<double>();
    if (!std::isfinite(d)) throw InputError(source, here, "must be finite" + gotValue(d));
    return d;
  }
  throw InputError(source, here, "cannot be read as JSON" + gotType(value));
}

namespace {

template <typename Json>
py::object jsonToPython(const Json& j) {
  switch (j.type()) {
    case nlohmann::detail::value_t::null:
      return py::none();
    case nlohmann::detail::value_t::boolean:
      return py::bool_(j.template get<bool>());
    case nlohmann::detail::value_t::number_integer:
      return py::int_(j.template get<long long>());
    case nlohmann::detail::value_t::number_unsigned:
      return py::int_(j.template get<unsigned long long>());
    case nlohmann::detail::value_t::number_float:
      return py::float_(j.template get<double>());
    case nlohmann::detail::value_t::string:
      return py::str(j.template get<std::string>());
    case nlohmann::detail::value_t::array: {
      py::list out;
      for (const auto& item : j) out.append(jsonToPython(item));
      return out;
    }
    case nlohmann::detail::value_t::object: {
      py::dict out;
      for (const auto& [key, item] : j.items()) out[py::str(key)] = jsonToPython(item);
      return out;
    }
    default:
      return py::none();
  }
}

}  // namespace

py::object fromJson(const nlohmann::json& j) {
  return jsonToPython(j);
}
py::object fromJson(const nlohmann::ordered_json& j) {
  return jsonToPython(j);
}

std::string pathString(py::handle value, const std::string& source, const std::string& field) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__")) {
    py::object path = py::module_::import("os").attr("fspath")(value);
    if (py::isinstance<py::str>(path)) return path.cast<std::string>();
  }
  throw InputError(source, field, "must be a str or a path" + gotType(value));
}

std::vector<double> toNumbers(py::handle value, size_t count, const std::string& source,
                              const std::string& field) {
  const std::string shape = count == 2 ? "[x, y]" : std::to_string(count) + " numbers";
  if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value)) {
    if (!py::isinstance<py::array>(value))
      throw InputError(source, field, "must be " + shape + gotType(value));
  }
  py::array_t<double, py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() != 1 || static_cast<size_t>(a.size()) != count)
    throw InputError(source, field, "must be " + shape + gotPython(value));
  std::vector<double> out(count);
  for (size_t i = 0; i < count; ++i) {
    out[i] = a.at(i);
    if (!std::isfinite(out[i]))
      throw InputError(source, field + "[" + std::to_string(i) + "]",
                       "must be finite" + gotValue(out[i]));
  }
  return out;
}

Vec2 toVec2(py::handle value, const std::string& source, const std::string& field) {
  const auto v = toNumbers(value, 2, source, field);
  return {v[0], v[1]};
}

std::string gotPython(py::handle value) {
  PyObject* o = value.ptr();
  if (value.is_none()) return " (got None)";
  if (PyBool_Check(o)) return o == Py_True ? " (got True)" : " (got False)";
  if (py::isinstance<py::str>(value)) return gotValue(value.cast<std::string>());
  if (PyLong_Check(o)) {
    int overflow = 0;
    const long long i = PyLong_AsLongLongAndOverflow(o, &overflow);
    if (!overflow) return " (got " + std::to_string(i) + ")";
    return " (got an int of " + std::to_string(py::str(value).cast<std::string>().size()) +
           " digits)";
  }
  const bool sequence = py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value);
  if (py::isinstance<py::array>(value) || sequence) {
    py::array a;
    try {
      a = py::array::ensure(value);
    } catch (const py::error_already_set&) {
    }
    PyErr_Clear();  // a ragged list is no array: say its type
    if (a && (a.ndim() > 0 || !sequence)) {
      std::string shape = "(";
      for (py::ssize_t d = 0; d < a.ndim(); ++d)
        shape += (d ? ", " : "") + std::to_string(a.shape(d));
      return " (got shape " + shape + (a.ndim() == 1 ? ",)" : ")") + ")";
    }
  }
  if (PyFloat_Check(o) || (PyNumber_Check(o) && py::hasattr(value, "dtype")))
    return gotValue(py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>());
  return gotType(value);
}

std::string gotType(py::handle value) {
  if (value.is_none()) return " (got None)";
  const std::string type = typeName(value);
  const bool vowel = std::string("aeiou").find(type[0]) != std::string::npos;
  return std::string(vowel ? " (got an " : " (got a ") + type + ")";
}

std::string gotKeyword(const std::string& name, py::handle value) {
  std::string text = py::repr(value).cast<std::string>();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return " (got " + name + "=" + text + ")";
}

double toNumber(py::handle value, const std::string& source, const std::string& field) {
  if (PyBool_Check(value.ptr()) || typeName(value) == "bool_" || !PyNumber_Check(value.ptr()) ||
      py::isinstance<py::array>(value))
    throw InputError(source, field, "must be a number" + gotType(value));
  return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
}

py::array_t<double> newArray(std::vector<py::ssize_t> shape) {
  return py::array_t<double>(shape);
}

py::array_t<double> pointsArray(const std::vector<Vec2>& points) {
  py::array_t<double> out = newArray({static_cast<py::ssize_t>(points.size()), 2});
  double* d = out.mutable_data();
  for (const Vec2& p : points) *d++ = p.x(), *d++ = p.y();
  return out;
}

}  // namespace cablelab::python

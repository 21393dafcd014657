// Shared pieces of the hand's bindings (py_hand.cpp, py_hand_runs.cpp, py_grasp.cpp).
#pragma once

#include <algorithm>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

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

/// The read/write attributes of a value class, sorted (what repr, pickle and fromFields use).
std::vector<std::string> fieldNames(py::handle self);

/// The field a deprecated old name stands for (the class's `_renamed`, {old: new}), or "".
std::string renamedField(py::handle self, const std::string& oldName);

/// Warns (DeprecationWarning, at the caller's line) that `oldName` is now `newName`.
void warnRenamed(const char* className, const std::string& oldName, const std::string& newName);

/// T(**fields): a default T with the given read/write attributes set (each setter validates its
/// value; a deprecated old name sets its new field and warns); an unknown field is an
/// InputError(name, field, "no such field (known: ...)").
template <typename T>
T fromFields(const char* name, const py::dict& kw) {
  py::object self = py::cast(T{});
  const std::vector<std::string> known = fieldNames(self);
  for (auto [k, v] : kw) {
    const std::string key = py::str(k);
    const std::string renamed = renamedField(self, key);
    if (!renamed.empty() && kw.contains(renamed))
      throw InputError(name, key,
                       "give " + renamed + " only (" + key + " is its old name) (got both)");
    if (renamed.empty() && std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (const std::string& f : known) list += (list.empty() ? "" : ", ") + f;
      throw InputError(name, key, "no such field (known: " + list + ")" + gotKeyword(key, v));
    }
    self.attr(key.c_str()) = v;
  }
  return self.template cast<T>();
}

/// What a value class's field accepts; checked whenever it is set (also by T(**fields)).
enum class FieldRule { Finite, NonNegative, Positive };

/// Checks `v` against `rule`; throws InputError(className, field, "must be ... (got v)").
double checkedField(double v, FieldRule rule, const char* className, const char* field);

/// A real number (int, float, numpy scalar; not a bool, complex or array) as a double, else
/// InputError(className, field, "must be a number").
double numberField(py::handle value, const char* className, const char* field);

/// The setter of a value class's field: a number, or an array of numbers each checked; an int
/// field must be given an integer. Errors name the field `name` as the caller spelt it.
template <typename T, typename V>
auto fieldSetter(V T::*member, FieldRule rule, const char* className, const char* name) {
  return [member, rule, className, name](T& t, py::handle value) {
    if constexpr (std::is_same_v<V, double>) {
      t.*member = checkedField(numberField(value, className, name), rule, className, name);
    } else if constexpr (std::is_same_v<V, int>) {
      if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr()))
        throw InputError(className, name, "must be an integer" + gotType(value));
      const double v = py::int_(py::reinterpret_borrow<py::object>(value)).cast<double>();
      if (v > std::numeric_limits<int>::max())
        throw InputError(className, name, "is too large" + gotValue(v));
      t.*member = static_cast<int>(checkedField(v, rule, className, name));
    } else {
      const auto v = toNumbers(value, std::tuple_size_v<V>, className, name);
      V out;
      for (size_t i = 0; i < out.size(); ++i) out[i] = checkedField(v[i], rule, className, name);
      t.*member = out;
    }
  };
}

/// A read/write attribute `name` of a value class whose setter validates.
template <typename T, typename V>
void addField(py::class_<T>& cls, const char* className, const char* name, V T::*member,
              FieldRule rule, const char* doc) {
  cls.def_property(
      name, [member](const T& t) { return t.*member; }, fieldSetter(member, rule, className, name),
      doc);
}

/// `oldName`, a deprecated name of the field `newName` (stored in `member`, checked by `rule`):
/// reading and setting it work as the new name does, with a DeprecationWarning naming the new
/// one (errors name the old one, as the caller wrote it); T(**fields) and old pickles take it too.
/// Left out of the field list (repr, pickle, an error's known names); the class lists the pairs
/// in `_renamed` ({old: new}). The names each quantity has across the CLI, scene parameters and
/// Python: docs/python.md, "One name per quantity".
template <typename T, typename V>
void addRenamedField(py::class_<T>& cls, const char* className, const char* oldName,
                     const char* newName, V T::*member, FieldRule rule) {
  if (!py::hasattr(cls, "_renamed")) cls.attr("_renamed") = py::dict();
  cls.attr("_renamed")[oldName] = newName;
  const auto set = fieldSetter(member, rule, className, oldName);
  cls.def_property(
      oldName,
      [className, oldName, newName, member](const T& t) {
        warnRenamed(className, oldName, newName);
        return t.*member;
      },
      [className, oldName, newName, set](T& t, py::handle value) {
        warnRenamed(className, oldName, newName);
        set(t, value);
      },
      (std::string("deprecated: the old name of ") + newName + " (warns)").c_str());
}

/// What every value class (HandModel, ControllerParams, GraspOptions) has beyond its fields:
/// T(**fields), repr, pickling and copy.copy / deepcopy, all through its read/write attributes.
template <typename T>
void addValueClassMethods(py::class_<T>& cls, const char* className) {
  cls.def(py::init([className](const py::kwargs& kw) { return fromFields<T>(className, kw); }));
  cls.def("__repr__", [className](py::handle self) { return fieldsRepr(self, className); });
  cls.def(py::pickle(
      [](py::handle self) {
        py::dict d;
        for (const std::string& f : fieldNames(self)) d[f.c_str()] = self.attr(f.c_str());
        return d;
      },
      [className](const py::dict& d) { return fromFields<T>(className, d); }));
  cls.def("__copy__", [](const T& t) { return T(t); });
  cls.def("__deepcopy__", [](const T& t, py::handle) { return T(t); });
}

void bindHandRuns(py::module_& m);
void bindGrasp(py::module_& m);

}  // namespace cablelab::python

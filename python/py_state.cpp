// World state you can fork (engine/dynamics/world_state.h): cablelab.WorldState,
// World.get_state / set_state / copy, and pickling of World. A state is the scene plus the
// World's input history; restoring it replays the history, so a fork steps bit for bit as the
// original (docs/python.md, "State").
#include <algorithm>
#include <array>
#include <memory>

#include "engine/core/error.h"
#include "engine/dynamics/world_state.h"
#include "engine/model/scene_json.h"
#include "python/bindings.h"
#include "python/py_world.h"

namespace cablelab::python {

namespace {

constexpr int kStateVersion = 1;          // the pickled layout below
constexpr py::ssize_t kInputColumns = 7;  // kind, index, count, values[4]

/// The history as an (n, 7) float64 array (world_state.h, inputRows): exact, as every index
/// and count is far below 2^53.
py::array_t<double> inputsArray(const std::vector<WorldInput>& inputs) {
  const auto rows = inputRows(inputs);
  py::array_t<double> a = newArray({static_cast<py::ssize_t>(rows.size()), kInputColumns});
  std::copy_n(rows.empty() ? nullptr : rows[0].data(), rows.size() * kInputColumns,
              a.mutable_data());
  return a;
}

std::vector<WorldInput> inputsOf(py::handle array, const std::string& source) {
  auto a = py::array_t<double, py::array::forcecast | py::array::c_style>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(1) != kInputColumns)
    throw InputError(source, "inputs", "must be an (n, 7) array" + gotPython(array));
  std::vector<std::array<double, 7>> rows(static_cast<size_t>(a.shape(0)));
  std::copy_n(a.data(), a.size(), rows.empty() ? nullptr : rows[0].data());
  return inputsFromRows(rows, source, "inputs");
}

/// (version, scene JSON text, source, inputs): what pickle keeps of a state or a World.
py::tuple packState(const WorldState& s) {
  return py::make_tuple(kStateVersion, sceneToJson(s.scene).dump(), s.source,
                        inputsArray(s.inputs));
}

WorldState unpackState(const py::tuple& t) {
  if (t.size() != 4 || t[0].cast<int>() != kStateVersion)
    throw InputError("pickle", "state",
                     "is not a cablelab World state of this version" +
                         (t.size() != 4 ? " (got a tuple of " + std::to_string(t.size()) + ")"
                                        : gotPython(t[0]) + ""));
  const std::string source = t[2].cast<std::string>();
  WorldState s;
  s.scene = sceneFromJson(nlohmann::json::parse(t[1].cast<std::string>()), source);
  s.source = source;
  s.inputs = inputsOf(t[3], source);
  return s;
}

/// The read-only figures of a state (WorldState pickles them too, so unpickling replays nothing).
py::tuple packFigures(const WorldState& s) {
  std::vector<double> bodies;
  for (const BodyState& b : s.bodies)
    bodies.insert(bodies.end(), {b.position.x(), b.position.y(), b.angle, b.velocity.x(),
                                 b.velocity.y(), b.angularVelocity});
  return py::make_tuple(s.time, s.steps, bodies, s.jointValues, s.servoTargets);
}

std::shared_ptr<WorldState> unpackWithFigures(const py::tuple& t) {
  if (t.size() != 5)
    throw InputError(
        "pickle", "state",
        "is not a cablelab WorldState (got a tuple of " + std::to_string(t.size()) + ")");
  auto s = std::make_shared<WorldState>(unpackState(py::make_tuple(t[0], t[1], t[2], t[3])));
  const py::tuple f = t[4].cast<py::tuple>();
  s->time = f[0].cast<double>();
  s->steps = f[1].cast<long>();
  const auto bodies = f[2].cast<std::vector<double>>();
  for (size_t i = 0; i + 6 <= bodies.size(); i += 6) {
    BodyState b;
    b.position = Vec2(bodies[i], bodies[i + 1]), b.angle = bodies[i + 2];
    b.velocity = Vec2(bodies[i + 3], bodies[i + 4]), b.angularVelocity = bodies[i + 5];
    s->bodies.push_back(b);
  }
  s->jointValues = f[3].cast<std::vector<double>>();
  s->servoTargets = f[4].cast<std::vector<double>>();
  return s;
}

std::unique_ptr<PyWorld> restorePyWorld(const WorldState& s) {
  std::unique_ptr<World> world;
  {
    py::gil_scoped_release release;
    world = restoreWorld(s);
  }
  return std::make_unique<PyWorld>(std::move(world), s.source);
}

std::unique_ptr<PyWorld> copyWorld(const PyWorld& self) {
  WorldState s;
  {
    PyWorld::Busy busy(self);
    s = captureState(*self.world, self.source);
  }
  return restorePyWorld(s);
}

py::array_t<double> numbers(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

}  // namespace

void bindState(py::module_& m, py::class_<PyWorld>& c) {
  using namespace pybind11::literals;
  py::class_<WorldState, std::shared_ptr<WorldState>> state(m, "WorldState", R"doc(
The state of a World at one moment, from World.get_state(): everything its next step depends
on (poses, velocities, joint coordinates, servo targets, cable rest lengths and wrap state,
the solvers' warm starts, time and step count). World.set_state(s) or World.from_state(s)
puts a World in it again, bit for bit. Picklable (send it to another process).

It is kept as the scene plus every input the World took since it was built, and restoring
replays those inputs: restoring costs as much as the steps replayed. The attributes below are
copies for reading only.)doc");
  state
      .def_property_readonly(
          "time", [](const WorldState& s) { return s.time; }, "Simulated time (s).")
      .def_property_readonly(
          "step_count", [](const WorldState& s) { return s.steps; }, "Steps taken.")
      .def_property_readonly(
          "scene_name", [](const WorldState& s) { return s.scene.name; }, "The scene's name.")
      .def_property_readonly(
          "body_states",
          [](const WorldState& s) {
            py::array_t<double> a = newArray({static_cast<py::ssize_t>(s.bodies.size()), 6});
            double* d = a.mutable_data();
            for (const BodyState& b : s.bodies) {
              *d++ = b.position.x(), *d++ = b.position.y(), *d++ = b.angle;
              *d++ = b.velocity.x(), *d++ = b.velocity.y(), *d++ = b.angularVelocity;
            }
            return a;
          },
          "ndarray (bodies, 6): x y (m) theta (rad) vx vy (m/s) omega (rad/s) per body.")
      .def_property_readonly(
          "joint_values", [](const WorldState& s) { return numbers(s.jointValues); },
          "ndarray (joints,): joint coordinates (rad or m).")
      .def_property_readonly(
          "servo_targets", [](const WorldState& s) { return numbers(s.servoTargets); },
          "ndarray (joints,): servo targets (rad or m).")
      .def_property_readonly(
          "input_count", [](const WorldState& s) { return s.inputs.size(); },
          "Inputs recorded (a run of equal steps counts once).")
      .def(py::pickle(
          [](const WorldState& s) {
            const py::tuple t = packState(s);
            return py::make_tuple(t[0], t[1], t[2], t[3], packFigures(s));
          },
          [](const py::tuple& t) { return unpackWithFigures(t); }))
      .def("__repr__", [](const WorldState& s) {
        return "<cablelab.WorldState '" + s.scene.name + "' t=" + formatNumber(s.time) +
               " s, step " + std::to_string(s.steps) + ">";
      });

  c.def(
      "get_state",
      [](const PyWorld& self) {
        PyWorld::Busy busy(self);
        return std::make_shared<WorldState>(captureState(*self.world, self.source));
      },
      R"doc(get_state() -> WorldState

The state now, to come back to with set_state() (a rollout, MPC, a search) or to send
to another process (it pickles). Cheap to take; see WorldState.)doc");
  c.def(
      "set_state",
      [](PyWorld& self, const WorldState& s) {
        std::unique_ptr<PyWorld> restored = restorePyWorld(s);
        PyWorld::Busy busy(self);
        if (restored->bodyNames != self.bodyNames || restored->cableNames != self.cableNames ||
            restored->jointNames != self.jointNames)
          throw InputError("set_state", "state",
                           "is of another scene (other bodies, cables or joints); use "
                           "World.from_state(state)" +
                               gotValue(s.scene.name));
        self.world = std::move(restored->world);
        self.source = s.source;
      },
      "state"_a,
      R"doc(set_state(state)

Puts this World in `state` (from get_state() of this World or of one of the same scene):
afterwards it steps bit for bit as the World did from there. Takes as long as the steps
that led to the state (it replays them).)doc");
  c.def_static(
      "from_state", [](const WorldState& s) { return restorePyWorld(s); }, "state"_a,
      "from_state(state) -> World: a new World in `state` (see set_state).");
  c.def("copy", &copyWorld,
        R"doc(copy() -> World

An independent World in the same state: stepped with the same inputs it stays bit for bit
equal to this one. Takes as long as the steps taken so far (see WorldState).)doc");
  c.def("__copy__", &copyWorld);
  c.def(
      "__deepcopy__", [](const PyWorld& self, py::handle) { return copyWorld(self); }, "memo"_a);
  c.def(py::pickle(
      [](const PyWorld& self) {
        PyWorld::Busy busy(self);
        return packState(captureState(*self.world, self.source));
      },
      [](const py::tuple& t) { return restorePyWorld(unpackState(t)); }));
}

}  // namespace cablelab::python

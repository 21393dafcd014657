// cablelab.World: a scene being simulated, its state as numpy arrays (python/bindings.h).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>

#include "engine/core/error.h"
#include "engine/dynamics/world.h"
#include "engine/dynamics/world_state.h"
#include "engine/model/scene_json.h"
#include "engine/scenes/scene_registry.h"
#include "python/bindings.h"
#include "python/py_world.h"

namespace cablelab::python {

namespace {

// Box2D keeps positions and velocities in float: beyond this a value is not simulated honestly
// (and Box2D's own assertions fire), so set_* refuse it, as the scene reader does.
constexpr double kMaxStateValue = 1e12;

std::string namesOf(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

/// An index given as an int or a name; throws InputError naming the kind ("body", ...).
int resolveIndex(py::handle which, int count, const std::vector<std::string>& names,
                 const char* kind, const std::string& source) {
  if (py::isinstance<py::str>(which)) {
    const std::string name = which.cast<std::string>();
    for (int i = 0; i < count; ++i)
      if (names[i] == name) return i;
    throw InputError(source, kind,
                     "no " + std::string(kind) + " of that name (known: " + namesOf(names) + ")" +
                         gotValue(name));
  }
  if (PyIndex_Check(which.ptr())) {
    const long long i = py::int_(py::reinterpret_borrow<py::object>(which)).cast<long long>();
    if (i < 0 || i >= count)
      throw InputError(source, kind,
                       "index out of range 0.." + std::to_string(count - 1) + " (got " +
                           std::to_string(i) + ")");
    return static_cast<int>(i);
  }
  throw InputError(source, kind, "must be an index or a name" + gotType(which));
}

void checkStep(const SceneDef& scene, py::handle dt, py::handle substeps, double& h, int& n) {
  h = scene.dt;
  n = scene.substeps;
  if (!dt.is_none()) {
    h = toNumber(dt, "step", "dt");
    if (!(h > 0 && h <= 1)) throw InputError("step", "dt", "must be in (0, 1] s" + gotValue(h));
  }
  if (!substeps.is_none()) {
    if (!PyIndex_Check(substeps.ptr()) || PyBool_Check(substeps.ptr()))
      throw InputError("step", "substeps", "must be an integer" + gotType(substeps));
    const long long s = py::int_(py::reinterpret_borrow<py::object>(substeps)).cast<long long>();
    if (s < 1 || s > 1000)
      throw InputError("step", "substeps", "must be 1..1000" + gotPython(substeps));
    n = static_cast<int>(s);
  }
}

}  // namespace

double checkedValue(double v, const std::string& source, const std::string& field) {
  if (!std::isfinite(v) || std::abs(v) > kMaxStateValue)
    throw InputError(source, field, "must be finite and within +/-1e12" + gotValue(v));
  return v;
}

void writeBody(const BodyState& b, double* d) {
  d[0] = b.position.x(), d[1] = b.position.y(), d[2] = b.angle;
  d[3] = b.velocity.x(), d[4] = b.velocity.y(), d[5] = b.angularVelocity;
}

void writeStateRow(const World& w, double* bodies, double* cables, double* joints) {
  for (int i = 0; i < w.bodyCount(); ++i) writeBody(w.body(i), bodies + 6 * i);
  for (int i = 0; i < w.cableCount(); ++i) {
    const Cable& c = w.cable(i);
    cables[3 * i] = c.length(), cables[3 * i + 1] = c.tension(), cables[3 * i + 2] = c.wraps();
  }
  for (int i = 0; i < w.jointCount(); ++i) {
    const JointState j = w.joint(i);
    joints[2 * i] = j.value, joints[2 * i + 1] = j.speed;
  }
}

PyWorld::PyWorld(SceneDef scene, const std::string& source)
    : PyWorld(std::make_unique<World>(std::move(scene), source), source) {}

PyWorld::PyWorld(std::unique_ptr<World> built, const std::string& source)
    : world(std::move(built)), source(source) {
  for (const BodyDef& b : world->scene().bodies) bodyNames.push_back(b.name);
  for (int i = 0; i < world->cableCount(); ++i) cableNames.push_back(world->cable(i).name());
  for (const JointDef& j : world->scene().joints) jointNames.push_back(j.name);
}

int PyWorld::bodyIndex(py::handle which, const std::string& source) const {
  return resolveIndex(which, world->bodyCount(), bodyNames, "body", source);
}
int PyWorld::cableIndex(py::handle which, const std::string& source) const {
  return resolveIndex(which, world->cableCount(), cableNames, "cable", source);
}
int PyWorld::jointIndex(py::handle which, const std::string& source) const {
  return resolveIndex(which, world->jointCount(), jointNames, "joint", source);
}

PyWorld::Busy::Busy(const PyWorld& w) : w_(w) {
  if (w_.busy.exchange(true))
    throw std::runtime_error("this World is in use by another thread (run() releases the GIL)");
}
PyWorld::Busy::~Busy() {
  w_.busy = false;
}

namespace {

/// The keywords of World.load checked in Python's words (the CLI says "--set NAME").
std::vector<std::pair<std::string, double>> loadKeywords(const std::string& scene,
                                                         const py::kwargs& params) {
  constexpr const char* kSource = "World.load";
  const SceneInfo* info = findBuiltinScene(scene);
  std::vector<std::pair<std::string, double>> out;
  for (auto [key, value] : params) {
    const std::string k = key.cast<std::string>();
    if (!info)
      throw InputError(kSource, k,
                       "a scene file takes no keywords (edit the file, or change the dict from "
                       "to_dict() and use World.from_dict)" +
                           gotKeyword(k, value));
    const auto param = std::find_if(info->params.begin(), info->params.end(),
                                    [&k](const SceneParam& p) { return p.name == k; });
    if (param == info->params.end()) {
      std::string known;
      for (const SceneParam& p : info->params) known += (known.empty() ? "" : ", ") + p.name;
      throw InputError(kSource, k,
                       "no such keyword for scene '" + scene + "' (known: " +
                           (known.empty() ? "none" : known) + ")" + gotKeyword(k, value));
    }
    if (PyBool_Check(value.ptr()) || !PyNumber_Check(value.ptr()))
      throw InputError(kSource, k, "must be a number" + gotType(value));
    const double v = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
    if (!std::isfinite(v)) throw InputError(kSource, k, "must be finite" + gotValue(v));
    if (param->range == SceneParam::Range::Positive && !(v > 0))
      throw InputError(kSource, k, "must be positive" + gotValue(v));
    if (param->range == SceneParam::Range::NonNegative && v < 0)
      throw InputError(kSource, k, "must be >= 0" + gotValue(v));
    out.emplace_back(k, v);
  }
  return out;
}

std::unique_ptr<PyWorld> loadWorld(py::handle scene, const py::kwargs& params) {
  const std::string name = pathString(scene, "World.load", "scene");
  const auto overrides = loadKeywords(name, params);
  try {
    return std::make_unique<PyWorld>(makeScene(name, overrides), name);
  } catch (const InputError& e) {
    if (e.source() != kCommandLine) throw;
    // A parameter the scene's builder refused ("--set turn: must be 0 or 1") is its keyword;
    // anything else is about the scene ("SCENE: no such built-in scene").
    const std::string set = "--set ";
    const bool param = e.field().rfind(set, 0) == 0;
    throw InputError("World.load", param ? e.field().substr(set.size()) : "scene", e.detail());
  }
}

std::unique_ptr<PyWorld> worldFromDict(py::handle dict, const std::string& source) {
  if (!py::isinstance<py::dict>(dict))
    throw InputError(source, "(scene)", "must be a dict (the scene JSON object)" + gotType(dict));
  return std::make_unique<PyWorld>(sceneFromJson(toJson(dict, source), source), source);
}

/// world.run(): many steps with the GIL released; returns the record or None.
py::object runWorld(PyWorld& self, py::handle time, py::handle steps, py::handle dt,
                    py::handle substeps, bool record) {
  PyWorld::Busy busy(self);
  World& w = *self.world;
  double h;
  int n;
  checkStep(w.scene(), dt, substeps, h, n);
  long count = 0;
  if (time.is_none() == steps.is_none())
    throw InputError("run", "time",
                     "give either time (s) or steps, not both" +
                         std::string(time.is_none() ? " (got neither)" : " (got both)"));
  if (!time.is_none()) {
    const double t = toNumber(time, "run", "time");
    if (!std::isfinite(t) || t < 0 || t > 1e7)
      throw InputError("run", "time", "must be in [0, 1e7] s" + gotValue(t));
    count = std::lround(t / h);
  } else {
    if (!PyIndex_Check(steps.ptr()) || PyBool_Check(steps.ptr()))
      throw InputError("run", "steps", "must be a whole number" + gotType(steps));
    const long long s = py::int_(py::reinterpret_borrow<py::object>(steps)).cast<long long>();
    if (s < 0) throw InputError("run", "steps", "must be >= 0" + gotPython(steps));
    count = static_cast<long>(s);
  }
  if (count > 100000000)
    throw InputError("run", time.is_none() ? "steps" : "time",
                     "more than 1e8 steps; raise dt" + gotPython(time.is_none() ? steps : time));
  const int nb = w.bodyCount(), nc = w.cableCount(), nj = w.jointCount();
  const double rowBytes = 8.0 * (1 + 6 * nb + 3 * nc + 2 * nj);
  if (record && rowBytes * (count + 1) > 4e9)
    throw InputError("run", "record",
                     "the record would take more than 4 GB; record fewer steps (got " +
                         std::to_string(count) + " steps)");

  py::array_t<double> t, bodies, cables, joints;
  double *pt = nullptr, *pb = nullptr, *pc = nullptr, *pj = nullptr;
  if (record) {
    t = newArray({count + 1});
    bodies = newArray({count + 1, nb, 6});
    cables = newArray({count + 1, nc, 3});
    joints = newArray({count + 1, nj, 2});
    pt = t.mutable_data(), pb = bodies.mutable_data(), pc = cables.mutable_data();
    pj = joints.mutable_data();
  }
  auto row = [&] {
    *pt++ = w.time();
    writeStateRow(w, pb, pc, pj);
    pb += 6 * nb, pc += 3 * nc, pj += 2 * nj;
  };
  {
    py::gil_scoped_release release;
    if (record) row();
    auto lastCheck = std::chrono::steady_clock::now();
    for (long i = 0; i < count; ++i) {
      w.step(h, n);
      if (record) row();
      // Let Ctrl-C through about ten times a second.
      if ((i & 255) == 255 &&
          std::chrono::steady_clock::now() - lastCheck > std::chrono::milliseconds(100)) {
        lastCheck = std::chrono::steady_clock::now();
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      }
    }
  }
  if (!record) return py::none();
  py::dict out;
  out["t"] = t;
  out["bodies"] = bodies;
  out["cables"] = cables;
  out["joints"] = joints;
  out["body_names"] = self.bodyNames;
  out["cable_names"] = self.cableNames;
  out["joint_names"] = self.jointNames;
  return out;
}

py::array_t<double> bodyStates(const PyWorld& self, py::object out) {
  PyWorld::Busy busy(self);
  const World& w = *self.world;
  const py::ssize_t n = w.bodyCount();
  py::array_t<double> a;
  if (out.is_none()) {
    a = newArray({n, 6});
  } else {
    if (!py::isinstance<py::array_t<double>>(out))
      throw InputError("body_states", "out", "must be a float64 numpy array" + gotType(out));
    a = out.cast<py::array_t<double>>();
    if (a.ndim() != 2 || a.shape(0) != n || a.shape(1) != 6 || !(a.flags() & py::array::c_style) ||
        !a.writeable())
      throw InputError(
          "body_states", "out",
          "must be a writeable C-contiguous (" + std::to_string(n) + ", 6) float64 array" +
              (a.writeable() ? gotPython(out) : std::string(" (got a read-only array)")));
  }
  double* d = a.mutable_data();
  for (py::ssize_t i = 0; i < n; ++i) writeBody(w.body(static_cast<int>(i)), d + 6 * i);
  return a;
}

void setBodyState(PyWorld& self, py::handle body, py::handle state) {
  PyWorld::Busy busy(self);
  const int i = self.bodyIndex(body, "set_body_state");
  const auto v = toNumbers(state, 6, "set_body_state", "state");
  static const char* fields[6] = {"state[0] (x)",  "state[1] (y)",  "state[2] (theta)",
                                  "state[3] (vx)", "state[4] (vy)", "state[5] (omega)"};
  for (int k = 0; k < 6; ++k) checkedValue(v[k], "set_body_state", fields[k]);
  self.world->setBodyTransform(i, Vec2(v[0], v[1]), v[2]);
  self.world->setBodyVelocity(i, Vec2(v[3], v[4]), v[5]);
  self.world->refreshCables();
}

void setBodyStates(PyWorld& self, py::handle states) {
  PyWorld::Busy busy(self);
  World& w = *self.world;
  auto a = py::array_t<double, py::array::forcecast | py::array::c_style>::ensure(states);
  if (!a || a.ndim() != 2 || a.shape(0) != w.bodyCount() || a.shape(1) != 6)
    throw InputError("set_body_states", "states",
                     "must be a (" + std::to_string(w.bodyCount()) +
                         ", 6) array of x y theta vx vy omega" + gotPython(states));
  const double* d = a.data();
  for (py::ssize_t k = 0; k < a.size(); ++k)
    checkedValue(d[k], "set_body_states",
                 "states[" + std::to_string(k / 6) + ", " + std::to_string(k % 6) + "]");
  for (int i = 0; i < w.bodyCount(); ++i, d += 6) {
    w.setBodyTransform(i, Vec2(d[0], d[1]), d[2]);
    w.setBodyVelocity(i, Vec2(d[3], d[4]), d[5]);
  }
  w.refreshCables();  // lengths, paths and Jacobians of the new poses
}

template <typename F>
py::array_t<double> perCable(const PyWorld& self, F value) {
  PyWorld::Busy busy(self);
  const World& w = *self.world;
  py::array_t<double> a = newArray({w.cableCount()});
  double* d = a.mutable_data();
  for (int i = 0; i < w.cableCount(); ++i) d[i] = value(w.cable(i));
  return a;
}

template <typename F>
py::array_t<double> perJoint(const PyWorld& self, F value) {
  PyWorld::Busy busy(self);
  const World& w = *self.world;
  py::array_t<double> a = newArray({w.jointCount()});
  double* d = a.mutable_data();
  for (int i = 0; i < w.jointCount(); ++i) d[i] = value(w.joint(i));
  return a;
}

py::array_t<double> cablePath(const PyWorld& self, py::handle cable) {
  PyWorld::Busy busy(self);
  const Cable& c = self.world->cable(self.cableIndex(cable, "cable_path"));
  std::vector<Vec2> points;
  for (const WrapPoint& p : c.path()) points.push_back(p.world);
  return pointsArray(points);
}

void setCableParameters(PyWorld& self, py::handle cable, py::object restLength,
                        py::object stiffness, py::object preload, py::object damping) {
  PyWorld::Busy busy(self);
  const int i = self.cableIndex(cable, "set_cable_parameters");
  const CableParameters& d = self.world->cable(i).parameters();
  auto pick = [](const py::object& v, double current) {
    return v.is_none() ? current : v.cast<double>();
  };
  self.world->setCableParameters(i, pick(restLength, d.restLength), pick(stiffness, d.stiffness),
                                 pick(preload, d.preload), pick(damping, d.damping));
}

void setServoTargets(PyWorld& self, py::handle targets) {
  PyWorld::Busy busy(self);
  World& w = *self.world;
  const auto v = toNumbers(targets, w.jointCount(), "set_servo_targets", "targets");
  for (int i = 0; i < w.jointCount(); ++i)
    w.setServoTarget(i,
                     checkedValue(v[i], "set_servo_targets", "targets[" + std::to_string(i) + "]"));
}

py::dict stepStats(const PyWorld& self) {
  PyWorld::Busy busy(self);
  const StepStats& s = self.world->lastStepStats();
  using namespace pybind11::literals;
  return py::dict("step_us"_a = s.stepMicros, "cable_us"_a = s.cableMicros,
                  "wrap_points"_a = s.wrapPoints, "solver_iterations"_a = s.solverIterations,
                  "residual"_a = s.residual, "linearisation_fallbacks"_a = s.linearisationFallbacks,
                  "newton_divergences"_a = s.newtonDivergences, "events"_a = s.events,
                  "midpoint_solves"_a = s.midpointSolves,
                  "midpoint_fallbacks"_a = s.midpointFallbacks, "refinements"_a = s.refinements,
                  "unsettled_islands"_a = s.unsettledIslands, "held_islands"_a = s.heldIslands);
}

}  // namespace

void bindWorld(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<PyWorld> c(
      m, "World",
      R"doc(A scene being simulated: Box2D bodies, joints and contacts plus cablelab's cables.

Build one with World.load("hand") (a built-in scene, see cablelab.scenes()) or
World.load("my_scene.json"), or World.from_dict(d) from the scene JSON as a dict.
Units: metres, kilograms, seconds, radians, newtons. Bodies, cables and joints are
indexed as in the scene (body_names, cable_names, joint_names); every method that
takes one accepts the index or the name.)doc");

  c.def_static("load", &loadWorld, "scene"_a,
               R"doc(load(scene, **params) -> World

A built-in scene by name ("hand", "pulley", ...) or a scene JSON file (str or path).
params are the scene's parameters, as `cablelab run --set NAME=VALUE` takes them,
e.g. World.load("pulley", m_left=2.0) (cablelab.scenes() lists them); the hand's are
HandModel's fields of the same names (World.load("hand", k=300) is HandModel(k=300).world(),
docs/python.md "One name per quantity"). Bad input raises
InputError naming the keyword, e.g. "World.load: m1: no such keyword for scene 'pulley'
(known: L, m_left, m_right)".)doc");
  c.def_static("from_dict", &worldFromDict, "scene"_a, "source"_a = "dict",
               R"doc(from_dict(scene, source="dict") -> World

A World from the scene JSON as a Python dict (the format of engine/model/scene_json.h;
numpy arrays are accepted for lists). source names the dict in InputError messages.)doc");
  c.def(
      "to_dict",
      [](const PyWorld& self, bool current) {
        PyWorld::Busy busy(self);
        return fromJson(sceneToJson(current ? sceneNow(*self.world) : self.world->scene()));
      },
      "current"_a = false,
      R"doc(to_dict(current=False) -> dict

The scene JSON as a dict. current=False: the scene as it was built (initial state).
current=True: the scene now, to continue from here: the bodies' present poses and
velocities, joint coordinates ("value"), servo targets, cable parameters, gravity, time and
step count in place of the initial ones, and a "history" (the scene as built and every input
since) from which World.from_dict() rebuilds this World bit for bit: stepped with the same
inputs, the two stay equal to the last bit (docs/scene-format.md, "Scenes written mid-run").
Edit the fields only after deleting "history" (from_dict refuses a history that does not
lead to them); the World then starts from the fields as written, close to but not bit for
bit this one (Box2D's contacts and the solvers' warm starts start afresh).)doc");

  c.def(
      "step",
      [](PyWorld& self, py::handle dt, py::handle substeps) {
        PyWorld::Busy busy(self);
        double h;
        int n;
        checkStep(self.world->scene(), dt, substeps, h, n);
        self.world->step(h, n);
      },
      "dt"_a = py::none(), "substeps"_a = py::none(),
      R"doc(step(dt=None, substeps=None)

Advances by dt seconds (default: the scene's dt) in `substeps` equal sub-steps (default:
the scene's), exactly as one step of `cablelab run`. Raises SimulationError if the state
becomes non-finite.)doc");
  c.def("run", &runWorld, "time"_a = py::none(), py::kw_only(), "steps"_a = py::none(),
        "dt"_a = py::none(), "substeps"_a = py::none(), "record"_a = false,
        R"doc(run(time=None, *, steps=None, dt=None, substeps=None, record=False) -> dict | None

Many steps in C++ with the GIL released (other Python threads run meanwhile): either
`time` seconds (round(time / dt) steps, as `cablelab run --time`) or `steps` steps.
record=True returns {"t": (n+1,), "bodies": (n+1, bodies, 6) x y theta vx vy omega,
"cables": (n+1, cables, 3) length (m) tension (N) wraps, "joints": (n+1, joints, 2) value
(rad or m) speed, "body_names", "cable_names", "joint_names"},
row 0 being the state before the first step: the same numbers as `cablelab run --csv`.
Ctrl-C interrupts it (KeyboardInterrupt) between steps.)doc");

  c.def_property_readonly(
      "time", [](const PyWorld& self) { return self.world->time(); }, "Simulated time (s).");
  c.def_property_readonly(
      "step_count", [](const PyWorld& self) { return self.world->stepCount(); },
      "Steps taken since the World was built.");
  c.def_property_readonly(
      "dt", [](const PyWorld& self) { return self.world->scene().dt; },
      "The scene's default time step (s).");
  c.def_property_readonly(
      "substeps", [](const PyWorld& self) { return self.world->scene().substeps; },
      "The scene's default sub-steps per step.");
  c.def_property_readonly(
      "name", [](const PyWorld& self) { return self.world->scene().name; }, "The scene's name.");
  c.def_property_readonly(
      "body_names", [](const PyWorld& self) { return self.bodyNames; },
      "Body names, in index order.");
  c.def_property_readonly(
      "cable_names", [](const PyWorld& self) { return self.cableNames; },
      "Cable names, in index order.");
  c.def_property_readonly(
      "joint_names", [](const PyWorld& self) { return self.jointNames; },
      "Joint names, in index order.");
  c.def_property(
      "gravity",
      [](const PyWorld& self) {
        const Vec2 g = self.world->gravity();
        return std::vector<double>{g.x(), g.y()};
      },
      [](PyWorld& self, py::handle g) {
        PyWorld::Busy busy(self);
        self.world->setGravity(toVec2(g, "gravity", "gravity"));
      },
      "Gravity [gx, gy] (m/s^2); assignable.");
  c.def(
      "energy",
      [](const PyWorld& self) {
        PyWorld::Busy busy(self);
        return self.world->energy();
      },
      "energy() -> float: kinetic + gravitational + elastic (membrane) energy (J).");
  c.def_property_readonly(
      "warnings", [](const PyWorld& self) { return self.world->warnings(); },
      "Notes from the geometry guards (zero-length segments merged, ...), newest last.");
  c.def("last_step_stats", &stepStats,
        "last_step_stats() -> dict: timing and solver figures of the last step: step_us, cable_us "
        "(wall time, us), "
        "wrap_points, solver_iterations, residual, linearisation_fallbacks.");

  c.def("body_states", &bodyStates, "out"_a = py::none(),
        R"doc(body_states(out=None) -> ndarray (bodies, 6)

One row per body: x, y (m), theta (rad), vx, vy (m/s), omega (rad/s), of the body origin
in the world frame. One array is filled per call; pass `out` (a float64 C-contiguous
array of that shape) to fill it in place with no allocation.)doc");
  c.def(
      "body_state",
      [](const PyWorld& self, py::handle body) {
        PyWorld::Busy busy(self);
        py::array_t<double> a = newArray({6});
        writeBody(self.world->body(self.bodyIndex(body, "body_state")), a.mutable_data());
        return a;
      },
      "body"_a, "body_state(body) -> ndarray (6,): x y (m) theta (rad) vx vy (m/s) omega (rad/s).");
  c.def("set_body_state", &setBodyState, "body"_a, "state"_a,
        "set_body_state(body, state): teleports a body to state = (x, y, theta, vx, vy, omega) "
        "(m, rad, m/s, rad/s).");
  c.def("set_body_states", &setBodyStates, "states"_a,
        "set_body_states(states): every body at once from a (bodies, 6) array as body_states() "
        "returns it; cable lengths, paths and Jacobians follow at once.");
  c.def(
      "apply_force",
      [](PyWorld& self, py::handle body, py::handle force, py::handle point) {
        PyWorld::Busy busy(self);
        const int i = self.bodyIndex(body, "apply_force");
        const Vec2 f = toVec2(force, "apply_force", "force");
        checkedValue(f.norm(), "apply_force", "force");
        const Vec2 p =
            point.is_none() ? self.world->body(i).position : toVec2(point, "apply_force", "point");
        self.world->applyForce(i, f, p);
      },
      "body"_a, "force"_a, "point"_a = py::none(),
      R"doc(apply_force(body, force, point=None)

Adds force [fx, fy] (N) at a world point [x, y] (m; default the body origin) for the next
step only (call it before every step for a lasting load).)doc");
  c.def(
      "body_index",
      [](const PyWorld& self, py::handle b) { return self.bodyIndex(b, "body_index"); }, "name"_a,
      "body_index(name) -> int: index of a body by name.");
  c.def(
      "begin_drag",
      [](PyWorld& self, py::handle body, py::handle point, double hz) {
        PyWorld::Busy busy(self);
        self.world->beginDrag(self.bodyIndex(body, "begin_drag"),
                              toVec2(point, "begin_drag", "point"), hz);
      },
      "body"_a, "point"_a, "stiffness_hz"_a = 5.0,
      "begin_drag(body, point, stiffness_hz=5): mouse-style drag (as in the sandbox): a soft "
      "spring (stiffness_hz, Hz) from a world "
      "point on the body to the drag target.");
  c.def(
      "drag_to",
      [](PyWorld& self, py::handle p) {
        PyWorld::Busy busy(self);
        self.world->dragTo(toVec2(p, "drag_to", "target"));
      },
      "target"_a, "drag_to(target): moves the drag target [x, y] (m).");
  c.def(
      "end_drag",
      [](PyWorld& self) {
        PyWorld::Busy busy(self);
        self.world->endDrag();
      },
      "end_drag(): releases the drag.");

  c.def(
      "cable_lengths",
      [](const PyWorld& s) { return perCable(s, [](const Cable& c) { return c.length(); }); },
      "cable_lengths() -> ndarray (cables,): lengths (m).");
  c.def(
      "cable_tensions",
      [](const PyWorld& s) { return perCable(s, [](const Cable& c) { return c.tension(); }); },
      "cable_tensions() -> ndarray (cables,): tensions of the last step (N); 0 when slack.");
  c.def(
      "cable_paid_out",
      [](const PyWorld& s) { return perCable(s, [](const Cable& c) { return c.paidOut(); }); },
      "cable_paid_out() -> ndarray (cables,): rest length each rigid cable has paid out since the "
      "start (m): a kinematic body hauled it against bodies that could not give way (a load at its "
      "pulley), and the World warned.");
  c.def(
      "cable_wraps",
      [](const PyWorld& s) {
        return perCable(s, [](const Cable& c) { return double(c.wraps()); });
      },
      "cable_wraps() -> ndarray (cables,): pulley wrap points in use per cable (the CSV's "
      "NAME.wraps), as floats.");
  c.def("cable_path", &cablePath, "cable"_a,
        "cable_path(cable) -> ndarray (k, 2): the cable's current path in world coordinates (m), "
        "start anchor, the k - 2 wrap points in order, end anchor. A circle pulley's wrap point "
        "and a drum end are the circle's centre: the rope leaves it along a tangent, its radius "
        "away (a direction taken from these points is off by radius / segment length).");
  c.def(
      "wrap_points",
      [](const PyWorld& self, py::handle cable) {
        PyWorld::Busy busy(self);
        const Cable& c = self.world->cable(self.cableIndex(cable, "wrap_points"));
        std::vector<Vec2> points;
        for (size_t i = 1; i + 1 < c.path().size(); ++i) points.push_back(c.path()[i].world);
        return pointsArray(points);
      },
      "cable"_a,
      "wrap_points(cable) -> ndarray (wraps, 2): the pulley points the cable wraps now, in path "
      "order, world coordinates (m; a circle pulley's is its centre); cable_path() adds the two "
      "anchors.");
  c.def(
      "cable_paths",
      [](const PyWorld& self) {
        py::list out;
        for (int i = 0; i < self.world->cableCount(); ++i) out.append(cablePath(self, py::int_(i)));
        return out;
      },
      "cable_paths() -> list of (k, 2) arrays: cable_path() of every cable.");
  c.def(
      "cable_parameters",
      [](const PyWorld& self, py::handle cable) {
        PyWorld::Busy busy(self);
        const CableParameters& p =
            self.world->cable(self.cableIndex(cable, "cable_parameters")).parameters();
        py::dict d;
        d["rest_length"] = p.restLength;
        d["stiffness"] = p.stiffness;
        d["preload"] = p.preload;
        d["damping"] = p.damping;
        return d;
      },
      "cable"_a,
      "cable_parameters(cable) -> dict: the live rest_length (m), stiffness (N/m, 0 = rigid), "
      "preload (m) and damping (N s/m).");
  c.def("set_cable_parameters", &setCableParameters, "cable"_a, py::kw_only(),
        "rest_length"_a = py::none(), "stiffness"_a = py::none(), "preload"_a = py::none(),
        "damping"_a = py::none(),
        "set_cable_parameters(cable, *, rest_length=None, stiffness=None, preload=None, "
        "damping=None): live edits of rest_length (m), stiffness (N/m, 0 = rigid), preload (m) "
        "and damping (N s/m); None keeps the current value.");

  c.def(
      "joint_values",
      [](const PyWorld& s) { return perJoint(s, [](const JointState& j) { return j.value; }); },
      "joint_values() -> ndarray (joints,): angle (rad) or translation (m) of each joint.");
  c.def(
      "joint_speeds",
      [](const PyWorld& s) { return perJoint(s, [](const JointState& j) { return j.speed; }); },
      "joint_speeds() -> ndarray (joints,): rad/s or m/s.");
  c.def(
      "servo_targets",
      [](const PyWorld& s) {
        return perJoint(s, [](const JointState& j) { return j.servoTarget; });
      },
      "servo_targets() -> ndarray (joints,): servo targets (rad or m); only joints with a servo "
      "follow them.");
  c.def(
      "set_servo_target",
      [](PyWorld& self, py::handle joint, double target) {
        PyWorld::Busy busy(self);
        self.world->setServoTarget(self.jointIndex(joint, "set_servo_target"),
                                   checkedValue(target, "set_servo_target", "target"));
      },
      "joint"_a, "target"_a, "set_servo_target(joint, target): the servo's target (rad or m).");
  c.def("set_servo_targets", &setServoTargets, "targets"_a,
        "set_servo_targets(targets): every joint's servo target at once (rad or m).");
  bindState(m, c);
  bindSensors(c);
  c.def("__repr__", [](const PyWorld& self) {
    return "<cablelab.World '" + self.world->scene().name +
           "' t=" + std::to_string(self.world->time()) + " s, " +
           std::to_string(self.world->bodyCount()) + " bodies, " +
           std::to_string(self.world->cableCount()) + " cables>";
  });
}

}  // namespace cablelab::python

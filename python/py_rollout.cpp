// cablelab.rollout: many Worlds stepped side by side on a thread pool with the GIL released,
// recorded into numpy arrays (N worlds, T steps, ...). Each World is stepped by one thread at a
// time and sees exactly the calls of `w.set_servo_targets(...); w.step()` in a loop, so the
// numbers do not depend on the thread count.
#include <algorithm>
#include <exception>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "engine/core/error.h"
#include "python/bindings.h"
#include "python/py_world.h"
#include "python/worker_pool.h"

namespace cablelab::python {

namespace {

constexpr const char* kSource = "rollout";

/// The arrays being filled, one slab per world; plain pointers so the threads touch no Python.
struct Recording {
  py::array_t<double> t, bodies, cables, joints;
  double *pt, *pb, *pc, *pj;
  long steps;
  int nb, nc, nj;

  Recording(int worlds, long steps, int nb, int nc, int nj)
      : t(newArray({worlds, steps})),
        bodies(newArray({worlds, steps, nb, 6})),
        cables(newArray({worlds, steps, nc, 3})),
        joints(newArray({worlds, steps, nj, 2})),
        pt(t.mutable_data()),
        pb(bodies.mutable_data()),
        pc(cables.mutable_data()),
        pj(joints.mutable_data()),
        steps(steps),
        nb(nb),
        nc(nc),
        nj(nj) {
    // Touched here, before the threads start: a page's first write faults into the kernel, and
    // faults of threads sharing one address space queue on its lock.
    for (py::array_t<double>* a : {&t, &bodies, &cables, &joints})
      std::fill_n(a->mutable_data(), a->size(), 0.0);
  }

  /// Row `step` of world `i`: the state after that step.
  void write(int i, long step, const World& w) {
    const long row = i * steps + step;
    pt[row] = w.time();
    writeStateRow(w, pb + row * nb * 6, pc + row * nc * 3, pj + row * nj * 2);
  }
};

std::vector<PyWorld*> worldList(py::handle worlds) {
  if (!py::isinstance<py::sequence>(worlds) || py::isinstance<py::str>(worlds))
    throw InputError(kSource, "worlds", "must be a list of World" + gotType(worlds));
  std::vector<PyWorld*> out;
  for (py::handle item : worlds.cast<py::sequence>()) {
    if (!py::isinstance<PyWorld>(item))
      throw InputError(kSource, "worlds[" + std::to_string(out.size()) + "]",
                       "must be a World" + gotType(item));
    PyWorld* w = item.cast<PyWorld*>();
    const auto same = std::find(out.begin(), out.end(), w);
    if (same != out.end())
      throw InputError(kSource, "worlds[" + std::to_string(out.size()) + "]",
                       "the same World as worlds[" + std::to_string(same - out.begin()) +
                           "] (copy() it to run two) (got the same World twice)");
    out.push_back(w);
  }
  if (out.empty())
    throw InputError(kSource, "worlds", "must hold at least one World (got an empty list)");
  const World& first = *out[0]->world;
  for (size_t i = 1; i < out.size(); ++i) {
    const World& w = *out[i]->world;
    if (w.bodyCount() != first.bodyCount() || w.cableCount() != first.cableCount() ||
        w.jointCount() != first.jointCount())
      throw InputError(
          kSource, "worlds[" + std::to_string(i) + "]",
          "has other numbers of bodies, cables or joints than worlds[0] (the "
          "recording is one array) (got " +
              std::to_string(w.bodyCount()) + ", " + std::to_string(w.cableCount()) + ", " +
              std::to_string(w.jointCount()) + ", not " + std::to_string(first.bodyCount()) + ", " +
              std::to_string(first.cableCount()) + ", " + std::to_string(first.jointCount()) + ")");
  }
  return out;
}

int threadCount(py::handle threads, size_t worlds) {
  long n = std::max(1u, std::thread::hardware_concurrency());
  if (!threads.is_none()) {
    if (!PyIndex_Check(threads.ptr()) || PyBool_Check(threads.ptr()))
      throw InputError(kSource, "threads", "must be an integer" + gotType(threads));
    n = py::int_(py::reinterpret_borrow<py::object>(threads)).cast<long>();
    if (n < 1 || n > 1024) throw InputError(kSource, "threads", "must be 1..1024" + gotValue(n));
  }
  return static_cast<int>(std::min<long>(n, static_cast<long>(worlds)));
}

/// controls as a C-contiguous (N, T, joints) float64 array, every value checked.
py::array_t<double> controlArray(py::handle controls, size_t worlds, long steps, int joints) {
  auto a = py::array_t<double, py::array::forcecast | py::array::c_style>::ensure(controls);
  if (!a || a.ndim() != 3 || a.shape(0) != static_cast<py::ssize_t>(worlds) ||
      a.shape(1) != steps || a.shape(2) != joints)
    throw InputError(kSource, "controls",
                     "must be an array of shape (worlds, steps, joints) = (" +
                         std::to_string(worlds) + ", " + std::to_string(steps) + ", " +
                         std::to_string(joints) + ") of servo targets, or a callable" +
                         gotPython(controls));
  const double* d = a.data();
  for (py::ssize_t k = 0; k < a.size(); ++k) {
    try {
      checkedValue(d[k], kSource, "controls");  // a short name: no allocation per value
    } catch (const InputError&) {
      checkedValue(d[k], kSource, "controls (flat index " + std::to_string(k) + ")");
    }
  }
  return a;
}

/// The first failure (by world) rethrown, naming the world.
void rethrowFirst(const std::vector<std::exception_ptr>& errors) {
  for (size_t i = 0; i < errors.size(); ++i) {
    if (!errors[i]) continue;
    try {
      std::rethrow_exception(errors[i]);
    } catch (const SimulationError& e) {
      throw SimulationError("rollout: worlds[" + std::to_string(i) + "]: " + e.what());
    }
  }
}

py::dict rollout(py::handle worldsArg, long steps, py::handle controls, py::handle threadsArg) {
  const std::vector<PyWorld*> worlds = worldList(worldsArg);
  if (steps < 0 || steps > 100000000)
    throw InputError(kSource, "steps", "must be 0..1e8" + gotValue(steps));
  std::vector<std::unique_ptr<PyWorld::Busy>> held;
  for (PyWorld* w : worlds) held.push_back(std::make_unique<PyWorld::Busy>(*w));
  const int n = static_cast<int>(worlds.size());
  const World& first = *worlds[0]->world;
  const int nb = first.bodyCount(), nc = first.cableCount(), nj = first.jointCount();
  if (8.0 * n * steps * (1 + 6 * nb + 3 * nc + 2 * nj) > 4e9)
    throw InputError(kSource, "steps", "the recording would take more than 4 GB" + gotValue(steps));

  const bool policy = !controls.is_none() && PyCallable_Check(controls.ptr());
  const bool hasTable = !controls.is_none() && !policy;
  py::array_t<double> table;  // default-constructed: an empty array, not a null handle
  if (hasTable) table = controlArray(controls, worlds.size(), steps, nj);
  const double* targets = hasTable ? table.data() : nullptr;

  Recording rec(n, steps, nb, nc, nj);
  std::vector<std::exception_ptr> errors(n);
  WorkerPool pool(threadCount(threadsArg, worlds.size()));
  // One step of world i, its servo targets taken from `row` (nullptr: left as they are).
  auto stepWorld = [&](int i, long step, const double* row) {
    World& w = *worlds[i]->world;
    if (row)
      for (int j = 0; j < nj; ++j) w.setServoTarget(j, row[j]);
    w.step(w.scene().dt, w.scene().substeps);
    rec.write(i, step, w);
  };

  if (!policy) {
    // Each world runs all its steps on one thread.
    py::gil_scoped_release release;
    pool.forEach(n, [&](int i) {
      try {
        for (long s = 0; s < steps; ++s)
          stepWorld(i, s, targets ? targets + (i * steps + s) * nj : nullptr);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    });
  } else {
    // controls(step, bodies) -> (N, joints) targets, once a step for all worlds together.
    py::array_t<double> bodies = newArray({n, nb, 6});
    for (long s = 0; s < steps; ++s) {
      double* b = bodies.mutable_data();
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < nb; ++k) writeBody(worlds[i]->world->body(k), b + (i * nb + k) * 6);
      py::object answer = controls(s, bodies);
      auto a = py::array_t<double, py::array::forcecast | py::array::c_style>::ensure(answer);
      if (!a || a.ndim() != 2 || a.shape(0) != n || a.shape(1) != nj)
        throw InputError(kSource, "controls",
                         "the callable must return an array of shape (worlds, joints) = (" +
                             std::to_string(n) + ", " + std::to_string(nj) + ") at step " +
                             std::to_string(s) + gotPython(answer));
      for (py::ssize_t k = 0; k < a.size(); ++k)
        checkedValue(a.data()[k], kSource, "controls(" + std::to_string(s) + ", ...) result");
      const double* row = a.data();
      py::gil_scoped_release release;
      pool.forEach(n, [&](int i) {
        if (errors[i]) return;
        try {
          stepWorld(i, s, row + i * nj);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      });
      if (std::any_of(errors.begin(), errors.end(), [](auto& e) { return bool(e); })) break;
    }
  }
  rethrowFirst(errors);

  py::dict out;
  out["t"] = rec.t;
  out["bodies"] = rec.bodies;
  out["cables"] = rec.cables;
  out["joints"] = rec.joints;
  out["body_names"] = worlds[0]->bodyNames;
  out["cable_names"] = worlds[0]->cableNames;
  out["joint_names"] = worlds[0]->jointNames;
  return out;
}

}  // namespace

void bindRollout(py::module_& m) {
  using namespace pybind11::literals;
  m.def("rollout", &rollout, "worlds"_a, "steps"_a, "controls"_a = py::none(),
        "threads"_a = py::none(),
        R"doc(rollout(worlds, steps, controls=None, threads=None) -> dict

Steps every World in `worlds` (a list; equal numbers of bodies, cables and joints) `steps`
times in place, each at its scene's dt and sub-steps, on `threads` threads (default: the
machine's cores) with the GIL released. Each World gives bit for bit what
`w.set_servo_targets(c); w.step()` in a loop gives, whatever the thread count.
controls: None (servo targets left as they are), an array (worlds, steps, joints) of servo
targets set before each step, or a callable controls(step, bodies) -> (worlds, joints)
called before each step with bodies (worlds, bodies, 6) x y theta vx vy omega (the
worlds wait for it, so a policy in Python costs a pause per step).
Returns {"t": (N, T), "bodies": (N, T, bodies, 6) x y theta vx vy omega, "cables":
(N, T, cables, 3) length (m) tension (N) wraps, "joints": (N, T, joints, 2) value speed,
"body_names", "cable_names", "joint_names"}: row k is the state after step k+1 (the
layout of World.run(record=True) without its row 0). A SimulationError names the first
failing world; the others have run on.)doc");
}

}  // namespace cablelab::python

// The hand experiments from Python: track() and reach() take `cablelab track` and `cablelab
// reach`'s options, checked by the same code (engine/hand/hand_io.h, so the same messages), and
// return the CLI's JSON fields plus the samples and per-target results as numpy arrays. Both run
// with the GIL released.
#include <chrono>
#include <cmath>
#include <optional>

#include "engine/core/error.h"
#include "engine/core/parse.h"
#include "engine/hand/hand_io.h"
#include "python/py_hand.h"

namespace cablelab::python {

namespace {

/// An option given as the CLI's text ("0.1,0.2": the CLI's parser and messages) or as numbers.
std::vector<double> optionNumbers(py::handle v, size_t count, const char* option,
                                  const char* shape) {
  if (py::isinstance<py::str>(v))
    return parseNumberList(v.cast<std::string>(), count, kCommandLine, option, shape);
  return toNumbers(v, count, kCommandLine, option);
}

std::optional<Vec2> optionVec2(py::handle v, const char* option) {
  if (v.is_none()) return std::nullopt;
  const auto n = optionNumbers(v, 2, option, "X,Y");
  return Vec2(n[0], n[1]);
}

/// Calls back into Python about every 0.1 s from a run with the GIL released: progress(done,
/// total) when given, and raises KeyboardInterrupt out of the run on Ctrl-C.
class Progress {
 public:
  explicit Progress(py::handle callback)
      : callback_(py::reinterpret_borrow<py::object>(callback)) {}
  ~Progress() {
    py::gil_scoped_acquire gil;
    callback_ = py::object();
  }
  void operator()(long done, long total) {
    const auto now = std::chrono::steady_clock::now();
    if (done < total && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!callback_.is_none()) callback_(done, total);
  }

 private:
  py::object callback_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

std::vector<TargetChange> targetChanges(py::handle changes) {
  std::vector<TargetChange> out;
  if (changes.is_none()) return out;
  int i = 0;
  for (py::handle c : changes) {
    const std::string field = "changes[" + std::to_string(i++) + "]";
    if (!py::isinstance<py::sequence>(c) || py::isinstance<py::str>(c) || py::len(c) != 2)
      throw InputError("track", field,
                       "must be (t, (x, y)): time (s) and target (m)" + gotPython(c));
    const auto pair = py::reinterpret_borrow<py::sequence>(c);
    const double t = toNumber(pair[0], "track", field);
    if (!std::isfinite(t) || t < 0 || (!out.empty() && t < out.back().t))
      throw InputError("track", field, "t must be finite, >= 0 and in time order" + gotValue(t));
    out.push_back({t, toVec2(pair[1], "track", field)});
  }
  return out;
}

py::dict trackCall(py::handle target, py::handle ramp, py::handle start, double time, bool pid,
                   py::handle changes, const HandModel& hand,
                   const HandControllerParams& controller, const GraspOptions& grasp,
                   py::handle progress, const std::string& law, int horizon) {
  TrackRequest request;
  if (!target.is_none()) {
    // (x, y) or (x, y, theta), as numbers or the CLI's text.
    const bool three = py::isinstance<py::sequence>(target) && !py::isinstance<py::str>(target) &&
                       py::len(target) == 3;
    setTarget(request,
              py::isinstance<py::str>(target)
                  ? targetNumbers(target.cast<std::string>(), kCommandLine, "--target")
                  : toNumbers(target, three ? 3 : 2, kCommandLine, "--target"),
              kCommandLine, "--target");
  }
  if (!ramp.is_none()) {
    const auto v = optionNumbers(ramp, 3, "--ramp", "X,Y,SECONDS");
    request.ramp = {v[0], v[1], v[2]};
  }
  request.start = optionVec2(start, "--start");
  request.time = time;
  request.pid = pid;
  request.law = handLaw(law, "track", "law");
  request.horizon = checkedHorizon(horizon, "track", "horizon");
  TrackOptions options = trackOptions(request, hand);
  options.changes = targetChanges(changes);
  options.controller = controller;
  options.grasp = grasp;
  TrackResult r;
  {
    Progress onStep(progress);
    py::gil_scoped_release release;
    r = runTracking(options, hand, std::ref(onStep));
  }
  py::dict out = fromJson(trackSummary(r, options.law));
  const py::ssize_t n = static_cast<py::ssize_t>(r.samples.size());
  py::array_t<double> t = newArray({n}), tension = newArray({n});
  py::array_t<double> angle = newArray({n}), targetAngle = newArray({n});
  py::array_t<double> tg = newArray({n, 2}), box = newArray({n, 2}), ref = newArray({n, 2});
  for (py::ssize_t i = 0; i < n; ++i) {
    const TrackSample& s = r.samples[i];
    t.mutable_at(i) = s.t;
    tension.mutable_at(i) = s.tension;
    angle.mutable_at(i) = s.angle, targetAngle.mutable_at(i) = s.targetAngle;
    tg.mutable_at(i, 0) = s.target.x(), tg.mutable_at(i, 1) = s.target.y();
    box.mutable_at(i, 0) = s.box.x(), box.mutable_at(i, 1) = s.box.y();
    ref.mutable_at(i, 0) = s.reference.x(), ref.mutable_at(i, 1) = s.reference.y();
  }
  out["t"] = t;
  out["target"] = tg;
  out["box"] = box;
  out["tension"] = tension;
  out["reference"] = ref;
  out["angle"] = angle;
  out["target_angle"] = targetAngle;
  out["start_tension"] = r.startTension;
  out["final_joints"] = jointsArray(r.finalJoints);
  return out;
}

/// The per-target results as columns: the CSV's x, y, object_reached, fingertip_reachable and
/// the rest of ReachTarget.
py::dict targetColumns(const ReachResult& r) {
  const py::ssize_t n = static_cast<py::ssize_t>(r.targets.size());
  py::array_t<double> x = newArray({n}), y = newArray({n}), error = newArray({n});
  py::array_t<double> simTime = newArray({n});
  py::array_t<bool> reached(n), tip(n), qs(n), sim(n), held(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const ReachTarget& t = r.targets[i];
    x.mutable_at(i) = t.point.x(), y.mutable_at(i) = t.point.y();
    reached.mutable_at(i) = objectReached(r, t), tip.mutable_at(i) = t.fingertip;
    qs.mutable_at(i) = t.quasiStatic, sim.mutable_at(i) = t.simulated;
    error.mutable_at(i) = t.error, held.mutable_at(i) = t.graspHeld;
    simTime.mutable_at(i) = t.simulatedTime;
  }
  py::dict out;
  out["x"] = x, out["y"] = y;
  out["object_reached"] = reached, out["fingertip_reachable"] = tip;
  out["quasi_static"] = qs, out["simulated"] = sim;
  out["error"] = error, out["grasp_held"] = held, out["simulated_time"] = simTime;
  return out;
}

py::dict reachCall(int grid, const std::string& model, bool pd, py::handle threads,
                   const HandModel& hand, py::handle progress, const std::string& law,
                   int horizon) {
  int count = 0;
  if (!threads.is_none()) {
    count = threads.cast<int>();
    if (count < 1 || count > 256)
      throw InputError("reach", "threads", "must be a whole number in [1, 256]" + gotValue(count));
  }
  const ReachOptions options = reachOptions(grid, model, pd, count, handLaw(law, "reach", "law"),
                                            checkedHorizon(horizon, "reach", "horizon"));
  ReachResult r;
  {
    // Ctrl-C stops the sweep once the runs under way have finished.
    Progress onProgress(progress);
    py::gil_scoped_release release;
    r = runReach(options, hand, std::ref(onProgress));
  }
  py::dict out = fromJson(reachSummary(r, options));
  out["targets"] = targetColumns(r);
  out["object_set"] = pointsArray(r.objectPoints);
  out["fingertip_set"] = pointsArray(r.fingertipPoints);
  out["quasi_static_set"] = pointsArray(r.quasiStaticPoints);
  out["lower"] = std::vector<double>{r.lower.x(), r.lower.y()};
  out["upper"] = std::vector<double>{r.upper.x(), r.upper.y()};
  return out;
}

/// Some targets of reach()'s grid, evaluated by the engine's own per-target code: the work unit
/// of `cablelab reach --scheduler` (python/cablelab/_reach_on_dask.py).
py::list reachTargetsCall(const std::vector<int>& indices, int grid, const std::string& model,
                          bool pd, const HandModel& hand) {
  const ReachOptions options = reachOptions(grid, model, pd, 1);
  ReachResult r = reachGrid(options, hand);
  for (int k : indices)
    if (k < 0 || k >= r.points)
      throw InputError("_reach_targets", "indices", "must be in [0, grid^2)" + gotValue(k));
  {
    py::gil_scoped_release release;
    for (int k : indices) evaluateReachTarget(hand, options, r.targets[k]);
  }
  py::list out;
  for (int k : indices) {
    const ReachTarget& t = r.targets[k];
    out.append(
        py::make_tuple(k, t.simulated, t.quasiStatic, t.error, t.graspHeld, t.simulatedTime));
  }
  return out;
}

}  // namespace

void bindHandRuns(py::module_& m) {
  using namespace pybind11::literals;
  m.def("track", &trackCall, py::kw_only(), "target"_a = py::none(), "ramp"_a = py::none(),
        "start"_a = py::none(), "time"_a = 15.0, "pid"_a = false, "changes"_a = py::none(),
        "hand"_a = HandModel{}, "controller"_a = HandControllerParams{}, "grasp"_a = GraspOptions{},
        "progress"_a = py::none(), "law"_a = "jacobian", "horizon"_a = HandMpcParams{}.horizon,
        R"doc(track(*, target=None, ramp=None, start=None, time=15, pid=False, changes=None,
      hand=HandModel(), controller=ControllerParams(), grasp=GraspOptions(),
      progress=None, law="jacobian", horizon=6) -> dict

Figure 4-5, as `cablelab track`: the hand closes a pinch grasp about the box at `start`,
then the Jacobian controller drives it to `target` [x, y] (m) or [x, y, theta] (theta in
rad; needs hand=HandModel(turn=True)), or along `ramp` (x, y, seconds) from the start. Each of target, ramp and start is numbers or the CLI's text
("0.1,0.2"); start defaults to (0, 0), or (0.1, 0.1) for a target within 5 cm of it.
time: simulated seconds. pid: add the integral term (k_i = PID_KI). law: the outer loop,
"jacobian" or "mpc" (model-predictive control planning `horizon` updates ahead; the CLI's
--controller and --horizon). changes: later target
steps [(t, (x, y)), ...] in time order (not in the CLI). progress(done, total): called
about every 0.1 s. Bad options raise InputError with the CLI's message; Ctrl-C stops the
run (KeyboardInterrupt). Runs with the GIL released.

Returns the CLI's JSON fields: final_error, rms_error, start_error (m), final_angle_error,
rms_angle_error, final_angle (rad), grasp_time (s),
grasp_held, losses, start, final_box (m), max_tension (N), events [{t, what}], controller,
time_to_5mm (s or None), overshoot (m), joint_limit_hits, controller_solve_us,
controller_solve_max_us (us); and the
samples, one per step from t = 0: t (s), target, box, reference ((n, 2), m), angle,
target_angle ((n,), rad), tension ((n,), N, the larger membrane's); start_tension (N), final_joints (6, rad/m).)doc");
  m.def("reach", &reachCall, py::kw_only(), "grid"_a = 50, "model"_a = "simulation", "pd"_a = false,
        "threads"_a = py::none(), "hand"_a = HandModel{}, "progress"_a = py::none(),
        "law"_a = "jacobian", "horizon"_a = HandMpcParams{}.horizon,
        R"doc(reach(*, grid=50, model="simulation", pd=False, threads=None, hand=HandModel(),
      progress=None, law="jacobian", horizon=6) -> dict

Figure 4-4, as `cablelab reach`: the box positions the controller reaches on a grid x grid
window, against the fingertips' range. model "simulation": every target is a full run of
track(target=..., pid=not pd), reached within 5 mm with the grasp held; "quasi-static":
the statics model stands in for the hand. law, horizon: the simulated runs' outer loop, as
track()'s. threads: default one per core.
progress(done, total) about every 0.1 s. Runs with the GIL released; Ctrl-C stops it
(KeyboardInterrupt) once the runs under way have finished.

Returns the CLI's JSON fields (object_area, fingertip_area, quasi_static_area (m^2), ratio,
points, model, law, object_points, fingertip_points, quasi_static_points, beyond_fingertips
(counts), threads, simulated_s, seconds); targets: per-target columns (numpy arrays, grid
row by row from the lower left): x, y (m), object_reached, fingertip_reachable (the CLI's
CSV), quasi_static, simulated, grasp_held (bool), error (m), simulated_time (s); the sets
object_set, fingertip_set, quasi_static_set ((n, 2), m); lower, upper (the window, m).)doc");
  m.def("_reach_targets", &reachTargetsCall, "indices"_a, py::kw_only(), "grid"_a, "model"_a,
        "pd"_a, "hand"_a = HandModel{},
        R"doc(_reach_targets(indices, *, grid, model, pd, hand=HandModel()) -> list

The targets `indices` of reach(grid=..., model=..., pd=..., hand=...)'s grid (row by row from
the lower left), each evaluated as reach() does: [(index, simulated, quasi_static, error (m),
grasp_held, simulated_time (s))]. The work unit of `cablelab reach --scheduler`.)doc");
}

}  // namespace cablelab::python

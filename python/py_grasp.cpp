// cablelab.HandGrasp: the engine's grasp sequence (engine/hand/hand_grasp.h) stepping a hand World
// from Python: open, close the pinch, control, notice a lost grasp, re-grasp. The outer-loop law
// may be a Python function in place of the Jacobian controller: the sequence still spreads its
// updates over the period, clamps them into the joint limits and handles losing the box.
#include <cmath>
#include <optional>

#include "engine/core/error.h"
#include "engine/hand/hand_grasp.h"
#include "engine/hand/hand_kinematics.h"
#include "python/py_hand.h"

namespace cablelab::python {

namespace {

/// The sequence and the World it steps (kept alive as long as the sequence).
struct PyGrasp {
  PyGrasp(py::object worldObject, const HandModel& hand, const HandControllerParams& params,
          const GraspOptions& options)
      : grasp(hand, params, options),
        object(std::move(worldObject)),
        world(object.cast<PyWorld&>()),
        hand(hand) {
    PyWorld::Busy busy(world);
    requireHand(world, "HandGrasp");
    if (!grasp.attach(*world.world))
      throw InputError(
          "HandGrasp", "world",
          "is not the hand scene (no box or membranes)" + gotValue(world.world->scene().name));
  }
  HandGrasp grasp;
  py::object object;
  PyWorld& world;
  HandModel hand;
};

const char* phaseName(HandGrasp::Phase p) {
  switch (p) {
    case HandGrasp::Phase::Opening:
      return "opening";
    case HandGrasp::Phase::Closing:
      return "closing";
    case HandGrasp::Phase::Control:
      return "control";
    case HandGrasp::Phase::Lost:
      return "lost";
    case HandGrasp::Phase::Failed:
      return "failed";
  }
  return "?";
}

/// A Python law(q, box, commanded) -> dq as the engine's GraspLaw (called with the GIL held).
GraspLaw lawOf(py::handle law) {
  if (law.is_none()) return {};
  if (!PyCallable_Check(law.ptr()))
    throw InputError("HandGrasp", "law",
                     "must be a function law(q, box, commanded) -> dq" + gotType(law));
  py::object f = py::reinterpret_borrow<py::object>(law);
  return [f](const HandJoints& q, const Vec2& box, const HandJoints& commanded) {
    return jointsOf(f(jointsArray(q), py::array_t<double>(2, box.data()), jointsArray(commanded)),
                    "law");
  };
}

std::optional<Vec2> targetOf(py::handle target) {
  if (target.is_none()) return std::nullopt;
  return toVec2(target, "HandGrasp", "target");
}

void beforeStep(PyGrasp& g, py::handle target, py::handle law) {
  const std::optional<Vec2> t = targetOf(target);
  const GraspLaw f = lawOf(law);
  PyWorld::Busy busy(g.world);
  g.grasp.beforeStep(*g.world.world, t, f);
}

void afterStep(PyGrasp& g) {
  PyWorld::Busy busy(g.world);
  g.grasp.afterStep(*g.world.world);
}

void stepGrasp(PyGrasp& g, py::handle target, py::handle law) {
  const std::optional<Vec2> t = targetOf(target);
  const GraspLaw f = lawOf(law);
  PyWorld::Busy busy(g.world);
  World& w = *g.world.world;
  g.grasp.beforeStep(w, t, f);
  w.step(w.scene().dt, w.scene().substeps);
  g.grasp.afterStep(w);
}

void bindOptions(py::module_& m) {
  py::class_<GraspOptions> c(m, "GraspOptions",
                             "GraspOptions(**fields): timing of the hand's grasp sequence (s); "
                             "read/write attributes.");
  using R = FieldRule;
  const char* n = "GraspOptions";
  addField(c, n, "open_time", &GraspOptions::openTime, R::NonNegative,
           "s to swing open before a re-grasp");
  addField(c, n, "close_time", &GraspOptions::closeTime, R::Positive,
           "s to swing from the open pose to the pinch");
  addField(c, n, "settle_time", &GraspOptions::settleTime, R::NonNegative,
           "s after the closing ramp before the outer loop starts");
  addField(c, n, "stop_time", &GraspOptions::stopTime, R::NonNegative,
           "s held still after losing the box, before re-grasping");
  addField(c, n, "max_regrasps", &GraspOptions::maxRegrasps, R::NonNegative,
           "re-grasps before giving up (phase 'failed')");
  addValueClassMethods(c, n);
}

}  // namespace

void bindGrasp(py::module_& m) {
  using namespace pybind11::literals;
  bindOptions(m);
  py::class_<PyGrasp> c(
      m, "HandGrasp",
      R"doc(HandGrasp(world, hand=HandModel(), controller=ControllerParams(), options=GraspOptions())

The hand's grasp sequence, the one `cablelab track`, `cablelab reach` and the sandbox run,
stepping `world` (a hand scene: HandModel.world()). Phases: "closing" (servo targets ramp
from the open pose to the pinch; the grasp has closed once both membranes wrap the box),
"control" (outer-loop updates every controller.period s, each spread over one period),
"lost" (a membrane unwrapped or went slack: the fingers stop, then re-grasp: "opening",
"closing"), "failed" (after options.max_regrasps re-grasps).

Per step:  g.before_step(target, law); world.step(); g.after_step()   (or g.step(...))
The update is law(q, box, commanded) -> dq when a law is given (a custom controller: the
measured joints q (6, rad/m), box centre (2, m) and the joint targets now, returning the
joint-target increment), else the Jacobian controller's towards target (m); with neither
the hand holds. track() is this loop with the controller and a fixed target.)doc");
  c.def(py::init([](py::object world, const HandModel& hand, const HandControllerParams& params,
                    const GraspOptions& options) {
          if (!py::isinstance<PyWorld>(world))
            throw InputError("HandGrasp", "world", "must be a cablelab.World" + gotType(world));
          return std::make_unique<PyGrasp>(world, hand, params, options);
        }),
        "world"_a, "hand"_a = HandModel{}, "controller"_a = HandControllerParams{},
        "options"_a = GraspOptions{});
  c.def(
      "begin",
      [](PyGrasp& g, py::handle start) {
        const Vec2 s = toVec2(start, "HandGrasp.begin", "start");
        if (!pinchWithinLimits(g.hand, s))
          throw InputError("HandGrasp.begin", "start",
                           "the fingers cannot pinch the box there (got " + formatNumber(s.x()) +
                               "," + formatNumber(s.y()) + ")");
        PyWorld::Busy busy(g.world);
        g.grasp.begin(*g.world.world, s);
      },
      "start"_a,
      "begin(start): teleports the box to start [x, y] (m, at rest) and the fingers to the open "
      "pose about it, and starts closing.");
  c.def(
      "begin_pinched",
      [](PyGrasp& g) {
        PyWorld::Busy busy(g.world);
        g.grasp.beginPinched(*g.world.world);
      },
      "begin_pinched(): the world already pinches the box (the hand scene as built): the grasp "
      "counts as closed now and control starts after options.settle_time.");
  c.def("before_step", &beforeStep, "target"_a = py::none(), "law"_a = py::none(),
        "before_step(target=None, law=None): runs the outer loop when an update is due and sets "
        "the servo targets; call it before world.step().");
  c.def("after_step", &afterStep,
        "after_step(): notices the grasp closing and a lost grasp; call it after world.step().");
  c.def("step", &stepGrasp, "target"_a = py::none(), "law"_a = py::none(),
        "step(target=None, law=None): before_step, one world step (the scene's dt and "
        "substeps), after_step.");
  c.def_property_readonly(
      "phase", [](const PyGrasp& g) { return phaseName(g.grasp.phase()); },
      "'opening', 'closing', 'control', 'lost' or 'failed'");
  c.def_property_readonly(
      "controlling", [](const PyGrasp& g) { return g.grasp.controlling(g.world.world->time()); },
      "the outer loop runs at the world's present time");
  c.def_property_readonly(
      "grasp_time", [](const PyGrasp& g) { return g.grasp.graspTime(); },
      "s; -1 until the grasp first closes");
  c.def_property_readonly(
      "control_start", [](const PyGrasp& g) { return g.grasp.controlStart(); },
      "s the outer loop starts at; inf until known");
  c.def_property_readonly(
      "held", [](const PyGrasp& g) { return g.grasp.held(); },
      "False once the box was lost after the grasp closed");
  c.def_property_readonly(
      "losses", [](const PyGrasp& g) { return g.grasp.losses(); },
      "times the box was lost after the grasp had closed");
  c.def_property_readonly(
      "updates", [](const PyGrasp& g) { return g.grasp.updates(); }, "outer-loop updates so far");
  c.def_property_readonly(
      "events",
      [](const PyGrasp& g) {
        py::list out;
        for (const GraspEvent& e : g.grasp.events())
          out.append(py::dict("t"_a = e.t, "what"_a = e.what));
        return out;
      },
      "[{t (s), what}]: 'grasp closed', 'top membrane unwrapped', 're-grasp', ...");
  c.def_property_readonly(
      "commanded", [](const PyGrasp& g) { return jointsArray(g.grasp.commanded()); },
      "the latest joint targets (6, rad/m) the updates ramp to");
  c.def_property_readonly(
      "controller", [](PyGrasp& g) -> HandController& { return g.grasp.controller(); },
      py::return_value_policy::reference_internal,
      "the sequence's HandController (status() after each update)");
  c.def_property_readonly(
      "world", [](const PyGrasp& g) { return g.object; }, "the World the sequence steps");
  c.def(
      "joints",
      [](const PyGrasp& g) {
        PyWorld::Busy busy(g.world);
        return jointsArray(g.grasp.joints(*g.world.world));
      },
      "joints() -> ndarray (6,): the hand's actuated joints (rad, m), controller order.");
}

}  // namespace cablelab::python

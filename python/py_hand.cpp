// The two-finger hand of chapter 4: its model, the Jacobian controller's gains and statics model,
// and the hand's joints in a World (engine/hand/). The experiments are in py_hand_runs.cpp, the
// grasp sequence in py_grasp.cpp.
#include "python/py_hand.h"

#include <cmath>

#include "engine/core/error.h"
#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_grasp.h"
#include "engine/hand/hand_model.h"

namespace cablelab::python {

HandJoints jointsOf(py::handle q, const std::string& source) {
  const auto v = toNumbers(q, 6, source, "q");
  HandJoints out;
  for (int i = 0; i < 6; ++i) out[i] = v[i];
  return out;
}

py::array_t<double> jointsArray(const HandJoints& q) {
  return py::array_t<double>(6, q.data());
}

std::vector<std::string> fieldNames(py::handle self) {
  std::vector<std::string> out;
  const py::handle type = py::type::handle_of(self);
  for (py::handle key : py::module_::import("builtins").attr("sorted")(type.attr("__dict__"))) {
    const std::string k = key.cast<std::string>();
    const py::object attr = type.attr(key);
    if (k.rfind("_", 0) != 0 && py::hasattr(attr, "fset") && !attr.attr("fset").is_none() &&
        renamedField(self, k).empty())
      out.push_back(k);
  }
  return out;
}

std::string renamedField(py::handle self, const std::string& oldName) {
  const py::object renamed = py::getattr(py::type::handle_of(self), "_renamed", py::none());
  if (renamed.is_none() || !renamed.contains(oldName)) return "";
  return renamed[py::str(oldName)].cast<std::string>();
}

void warnRenamed(const char* className, const std::string& oldName, const std::string& newName) {
  const std::string text = std::string(className) + ": " + oldName + ": deprecated, use " +
                           newName + " (one name per quantity: docs/python.md)";
  if (PyErr_WarnEx(PyExc_DeprecationWarning, text.c_str(), 1) != 0) throw py::error_already_set();
}

std::string fieldsRepr(py::handle self, const char* name) {
  std::string out = std::string(name) + "(";
  for (const std::string& k : fieldNames(self))
    out += (out.back() == '(' ? "" : ", ") + k + "=" +
           py::repr(self.attr(k.c_str())).cast<std::string>();
  return out + ")";
}

double checkedField(double v, FieldRule rule, const char* className, const char* field) {
  if (!std::isfinite(v)) throw InputError(className, field, "must be finite" + gotValue(v));
  if (rule == FieldRule::NonNegative && v < 0)
    throw InputError(className, field, "must be >= 0" + gotValue(v));
  if (rule == FieldRule::Positive && !(v > 0))
    throw InputError(className, field, "must be positive" + gotValue(v));
  return v;
}

double numberField(py::handle value, const char* className, const char* field) {
  if (PyBool_Check(value.ptr()) || !PyNumber_Check(value.ptr()))
    throw InputError(className, field, "must be a number" + gotType(value));
  const double v = PyFloat_AsDouble(value.ptr());
  if (v == -1.0 && PyErr_Occurred()) {  // a complex number, an array of several
    PyErr_Clear();
    throw InputError(className, field,
                     "must be a number" + gotValue(py::repr(value).cast<std::string>()));
  }
  return v;
}

void requireHand(const PyWorld& w, const std::string& source) {
  for (const char* name : kHandJointNames)
    if (w.world->findJoint(name) < 0)
      throw InputError(source, "world",
                       std::string("is not the hand scene (no joint '") + name + "')" +
                           gotValue(w.world->scene().name));
}

void bindHand(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<HandModel> model(m, "HandModel", R"doc(HandModel(**fields)

The two-finger hand of chapter 4: dimensions (m), masses (kg), membrane stiffness (N/m),
damping (N s/m) and preload (m), servo gain, joint limits (rad, m). One model feeds the
hand scene, the controller and the experiments. Fields are read/write attributes, checked
when set; HandModel(k=300) changes one from the default. The fields the hand scene also
takes have its names (World.load("hand", k=300) is the same hand): k, damping, preload,
box_mass, mu, turn. `stiffness` is k's old name (deprecated: it warns).)doc");
  {
    using R = FieldRule;
    const char* n = "HandModel";
    addField(model, n, "base_x", &HandModel::baseX, R::Finite, "x of both proximal joints (m)");
    addField(model, n, "base_y", &HandModel::baseY, R::Positive,
             "|y| of the proximal joints and paddle centres at q = 0 (m)");
    addField(model, n, "link_length", &HandModel::linkLength, R::Positive,
             "base to distal joint at slide 0 (m)");
    addField(model, n, "paddle_half_width", &HandModel::paddleHalfWidth, R::Positive,
             "membrane corners at +/- this along the paddle (m)");
    addField(model, n, "paddle_offset", &HandModel::paddleOffset, R::Finite,
             "corner offset from the distal joint towards the box (m)");
    addField(model, n, "box_half_size", &HandModel::boxHalfSize, R::Positive,
             "the square manipuland's half side (m)");
    addField(model, n, "box_mass", &HandModel::boxMass, R::Positive, "kg");
    addField(model, n, "box_damping", &HandModel::boxDamping, R::NonNegative,
             "box linear damping, the table's drag (1/s)");
    addField(model, n, "link_mass", &HandModel::linkMass, R::Positive, "kg");
    addField(model, n, "slider_mass", &HandModel::sliderMass, R::Positive, "kg");
    addField(model, n, "paddle_mass", &HandModel::paddleMass, R::Positive, "kg");
    addField(model, n, "k", &HandModel::stiffness, R::Positive,
             "membrane stiffness k_s (N/m; the scene's k)");
    addRenamedField(model, n, "stiffness", "k", &HandModel::stiffness, R::Positive);
    addField(model, n, "damping", &HandModel::damping, R::NonNegative, "membrane damping (N s/m)");
    addField(model, n, "preload", &HandModel::preload, R::NonNegative, "membrane pre-stretch (m)");
    addField(model, n, "servo_kp", &HandModel::servoKp, R::Positive,
             "inner PD stiffness per unit effective inertia (1/s^2)");
    addField(model, n, "lower", &HandModel::lower, R::Finite,
             "joint lower limits, 6 (rad, m), controller order");
    addField(model, n, "upper", &HandModel::upper, R::Finite, "joint upper limits, 6 (rad, m)");
    addField(model, n, "mu", &HandModel::friction, R::NonNegative,
             "membrane-box friction at the box's corners (the scene's mu; 0: none, the thesis's)");
    model.def_property(
        "turn", [](const HandModel& h) { return h.turn; },
        [n](HandModel& h, py::handle value) {
          // True/False, or the scene's 1/0; anything else is a mistake, not a truth value.
          const char* rule = "must be True or False (or the scene's 1 or 0)";
          if (!PyBool_Check(value.ptr()) && !PyNumber_Check(value.ptr()))
            throw InputError(n, "turn", rule + gotValue(py::repr(value).cast<std::string>()));
          const double v =
              PyBool_Check(value.ptr()) ? value.ptr() == Py_True : numberField(value, n, "turn");
          if (v != 0 && v != 1) throw InputError(n, "turn", rule + gotValue(v));
          h.turn = v == 1;
        },
        "the box may turn (the scene's turn=1); track() then takes an angle");
    addValueClassMethods(model, n);
  }
  model
      .def(
          "open_pose", [](const HandModel& h) { return jointsArray(h.openPose()); },
          "open_pose() -> ndarray (6,): the non-grasping start pose, joint values (rad, m) in "
          "controller order "
          "(top proximal, slide, distal, then bottom).")
      .def(
          "clamp",
          [](const HandModel& h, py::handle q) {
            return jointsArray(h.clamp(jointsOf(q, "clamp")));
          },
          "q"_a, "clamp(q) -> ndarray (6,): q clamped into the joint limits.")
      .def(
          "world",
          [](const HandModel& h) { return std::make_unique<PyWorld>(buildHandScene(h), "hand"); },
          "world() -> World: the hand scene built from this model, at the pinch pose q = 0.");
  m.attr("HAND_JOINT_NAMES") =
      py::make_tuple(kHandJointNames[0], kHandJointNames[1], kHandJointNames[2], kHandJointNames[3],
                     kHandJointNames[4], kHandJointNames[5]);
  m.attr("HAND_BOX") = kHandBoxName;
  m.attr("HAND_CABLES") = py::make_tuple(kHandCableNames[0], kHandCableNames[1]);

  py::class_<HandControllerParams> params(
      m, "ControllerParams",
      "ControllerParams(**fields): gains of the hand's Jacobian "
      "controller (thesis 4.3); read/write attributes.");
  {
    using R = FieldRule;
    using P = HandControllerParams;
    const char* n = "ControllerParams";
    addField(params, n, "period", &P::period, R::Positive, "outer-loop period (s)");
    addField(params, n, "kp", &P::kp, R::NonNegative, "share of the error removed per update");
    addField(params, n, "kd", &P::kd, R::NonNegative,
             "dimensionless, on the box's change over one period");
    addField(params, n, "ki", &P::ki, R::NonNegative, "per update per second (1/s); > 0 for PID");
    addField(params, n, "lambda_", &P::lambda, R::NonNegative, "pseudo-inverse damping");
    addField(params, n, "lag_share", &P::lagShare, R::Positive,
             "share of the membranes' room the moving box may lag by (sets the speed limit)");
    addField(params, n, "wrap_margin", &P::wrapMargin, R::NonNegative,
             "the reference stops this far before the face-on wrap is lost (m)");
    addField(params, n, "lead_limit", &P::leadLimit, R::Positive,
             "the reference slows once the box is this far off the reference model (m)");
    addField(params, n, "distal_weight", &P::distalWeight, R::Positive,
             "joint-space weight of the distal joints");
    addField(params, n, "face_on_gain", &P::faceOnGain, R::NonNegative,
             "null-space pull to face-on paddles, per update");
    addValueClassMethods(params, n);
  }
  m.attr("PID_KI") = kHandPidKi;

  py::class_<HandController>(m, "HandController",
                             R"doc(HandController(hand=HandModel(), controller=ControllerParams())

The statics-based Jacobian controller of thesis 4.3 (the outer loop `cablelab track` runs).
update() once per controller.period with the measured joints and box centre returns the
joint-target increment; predict() gives the statics model's box and db/dq.)doc")
      .def(py::init<HandModel, HandControllerParams>(), "hand"_a = HandModel{},
           "controller"_a = HandControllerParams{})
      .def(
          "update",
          [](HandController& c, py::handle q, py::handle box, py::handle target,
             py::handle commanded) {
            return jointsArray(c.update(jointsOf(q, "update"), toVec2(box, "update", "box"),
                                        toVec2(target, "update", "target"),
                                        jointsOf(commanded, "update")));
          },
          "q"_a, "box"_a, "target"_a, "commanded"_a,
          "update(q, box, target, commanded) -> dq: measured joints q (6, rad/m), box centre and "
          "target (m), joint targets commanded now; returns the joint-target increment (6).")
      .def(
          "predict",
          [](const HandController& c, py::handle q, py::handle guess) {
            const BoxPrediction p =
                c.predict(jointsOf(q, "predict"), toVec2(guess, "predict", "guess"));
            py::array_t<double> jac = newArray({2, 6});
            for (int r = 0; r < 2; ++r)
              for (int k = 0; k < 6; ++k) jac.mutable_at(r, k) = p.jacobian(r, k);
            py::dict out;
            out["box"] = py::array_t<double>(2, p.box.data());
            out["jacobian"] = jac;
            out["valid"] = p.valid;
            return out;
          },
          "q"_a, "guess"_a = py::make_tuple(0.0, 0.0),
          "predict(q, guess=(0, 0)) -> {box (m), jacobian (2 x 6, db/dq), valid}: the statics "
          "model's equilibrium box centre at joints q, warm-started at guess.")
      .def("reset", &HandController::reset, "reset(): clears the integral and derivative memory.")
      .def(
          "status",
          [](const HandController& c) {
            const ControllerStatus& s = c.status();
            auto vec = [](const Vec2& v) { return py::array_t<double>(2, v.data()); };
            return py::dict("reference"_a = vec(s.reference), "expected"_a = vec(s.expected),
                            "error"_a = vec(s.error), "integral"_a = vec(s.integral),
                            "speed_limit"_a = s.speedLimit, "rate_limited"_a = s.rateLimited,
                            "joints_at_limit"_a = s.jointsAtLimit);
          },
          "status() -> dict: what the last update did: reference r, expected (where the box "
          "model, driven by r, has the box), error (box - expected), integral (m s), "
          "speed_limit (m/s), rate_limited, joints_at_limit.");

  m.def(
      "hand_joints",
      [](const PyWorld& w) {
        PyWorld::Busy busy(w);
        requireHand(w, "hand_joints");
        return jointsArray(readHandJoints(*w.world));
      },
      "world"_a,
      "hand_joints(world) -> ndarray (6,): the hand's actuated joints (rad, m), controller order.");
  m.def(
      "place_hand",
      [](PyWorld& w, py::handle q, const HandModel& model) {
        PyWorld::Busy busy(w);
        requireHand(w, "place_hand");
        placeHand(*w.world, model, jointsOf(q, "place_hand"));
      },
      "world"_a, "q"_a, "hand"_a = HandModel{},
      "place_hand(world, q, hand=HandModel()): teleports the fingers to joints q (velocities "
      "zeroed) and sets the servo targets to q.");
  bindGrasp(m);
  bindHandRuns(m);
}

}  // namespace cablelab::python

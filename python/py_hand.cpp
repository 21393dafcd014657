// The two-finger hand of chapter 4: its model, the Jacobian controller's gains and statics model,
// and the hand's joints in a World (engine/hand/). The experiments are in py_hand_runs.cpp, the
// grasp sequence in py_grasp.cpp.
#include "python/py_hand.h"
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

std::string fieldsRepr(py::handle self, const char* name) {
  std::string out = std::string(name) + "(";
  bool first = true;
  for (py::handle key :
       py::module_::import("builtins").attr("sorted")(py::type::handle_of(self).attr("__dict__"))) {
    const std::string k = key.cast<std::string>();
    if (k.rfind("_", 0) == 0 || !py::hasattr(py::type::handle_of(self).attr(key), "__set__"))
      continue;
    out += (first ? "" : ", ") + k + "=" + py::repr(self.attr(key)).cast<std::string>();
    first = false;
  }
  return out + ")";
}

void requireHand(const PyWorld& w, const std::string& source) {
  for (const char* name : kHandJointNames)
    if (w.world->findJoint(name) < 0)
      throw InputError(source, "world",
                       std::string("is not the hand scene (no joint '") + name + "')");
}

void bindHand(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<HandModel> model(m, "HandModel", R"doc(HandModel(**fields)

The two-finger hand of chapter 4: dimensions (m), masses (kg), membrane stiffness (N/m),
damping (N s/m) and preload (m), servo gain, joint limits (rad, m). One model feeds the
hand scene, the controller and the experiments. Fields are read/write attributes;
HandModel(stiffness=300) changes one from the default.)doc");
  model.def(py::init([](const py::kwargs& kw) { return fromFields<HandModel>("HandModel", kw); }))
      .def_readwrite("base_x", &HandModel::baseX, "x of both proximal joints (m)")
      .def_readwrite("base_y", &HandModel::baseY,
                     "|y| of the proximal joints and paddle centres at q = 0 (m)")
      .def_readwrite("link_length", &HandModel::linkLength, "base to distal joint at slide 0 (m)")
      .def_readwrite("paddle_half_width", &HandModel::paddleHalfWidth,
                     "membrane corners at +/- this along the paddle (m)")
      .def_readwrite("paddle_offset", &HandModel::paddleOffset,
                     "corner offset from the distal joint towards the box (m)")
      .def_readwrite("box_half_size", &HandModel::boxHalfSize,
                     "the square manipuland's half side (m)")
      .def_readwrite("box_mass", &HandModel::boxMass, "kg")
      .def_readwrite("box_damping", &HandModel::boxDamping,
                     "box linear damping, the table's drag (1/s)")
      .def_readwrite("link_mass", &HandModel::linkMass, "kg")
      .def_readwrite("slider_mass", &HandModel::sliderMass, "kg")
      .def_readwrite("paddle_mass", &HandModel::paddleMass, "kg")
      .def_readwrite("stiffness", &HandModel::stiffness, "membrane stiffness (N/m)")
      .def_readwrite("damping", &HandModel::damping, "membrane damping (N s/m)")
      .def_readwrite("preload", &HandModel::preload, "membrane pre-stretch (m)")
      .def_readwrite("servo_kp", &HandModel::servoKp,
                     "inner PD stiffness per unit effective inertia (1/s^2)")
      .def_readwrite("lower", &HandModel::lower, "joint lower limits, 6 (rad, m), controller order")
      .def_readwrite("upper", &HandModel::upper, "joint upper limits, 6 (rad, m)")
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
  model.def("__repr__", [](py::handle self) { return fieldsRepr(self, "HandModel"); });
  m.attr("HAND_JOINT_NAMES") =
      py::make_tuple(kHandJointNames[0], kHandJointNames[1], kHandJointNames[2], kHandJointNames[3],
                     kHandJointNames[4], kHandJointNames[5]);
  m.attr("HAND_BOX") = kHandBoxName;
  m.attr("HAND_CABLES") = py::make_tuple(kHandCableNames[0], kHandCableNames[1]);

  py::class_<HandControllerParams> params(
      m, "ControllerParams",
      "ControllerParams(**fields): gains of the hand's Jacobian "
      "controller (thesis 4.3); read/write attributes.");
  params
      .def(py::init([](const py::kwargs& kw) {
        return fromFields<HandControllerParams>("ControllerParams", kw);
      }))
      .def_readwrite("period", &HandControllerParams::period, "outer-loop period (s)")
      .def_readwrite("kp", &HandControllerParams::kp, "share of the error removed per update")
      .def_readwrite("kd", &HandControllerParams::kd,
                     "dimensionless, on the box's change over one period")
      .def_readwrite("ki", &HandControllerParams::ki, "per update per second (1/s); > 0 for PID")
      .def_readwrite("lambda_", &HandControllerParams::lambda, "pseudo-inverse damping")
      .def_readwrite(
          "lag_share", &HandControllerParams::lagShare,
          "share of the membranes' room the moving box may lag by (sets the speed limit)")
      .def_readwrite("wrap_margin", &HandControllerParams::wrapMargin,
                     "the reference stops this far before the face-on wrap is lost (m)")
      .def_readwrite("lead_limit", &HandControllerParams::leadLimit,
                     "the reference slows once the box is this far off the reference model (m)")
      .def_readwrite("distal_weight", &HandControllerParams::distalWeight,
                     "joint-space weight of the distal joints")
      .def_readwrite("face_on_gain", &HandControllerParams::faceOnGain,
                     "null-space pull to face-on paddles, per update");
  params.def("__repr__", [](py::handle self) { return fieldsRepr(self, "ControllerParams"); });
  m.attr("PID_KI") = kHandPidKi;

  py::class_<HandController>(m, "HandController",
                             R"doc(HandController(model=HandModel(), params=ControllerParams())

The statics-based Jacobian controller of thesis 4.3 (the outer loop `cablelab track` runs).
update() once per params.period with the measured joints and box centre returns the
joint-target increment; predict() gives the statics model's box and db/dq.)doc")
      .def(py::init<HandModel, HandControllerParams>(), "model"_a = HandModel{},
           "params"_a = HandControllerParams{})
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
      "world"_a, "q"_a, "model"_a = HandModel{},
      "place_hand(world, q, model=HandModel()): teleports the fingers to joints q (velocities "
      "zeroed) and sets the servo targets to q.");
  bindGrasp(m);
  bindHandRuns(m);
}

}  // namespace cablelab::python

// What a World's sensors read (issue 39, item 2): per-span cable tensions, joint rates and servo
// forces, contact forces per body pair, each cable's Jacobian and J-dot-v; and posing by joint
// values. Shapes and units are in each docstring.
#include <vector>

#include "engine/core/error.h"
#include "engine/dynamics/joint_posing.h"
#include "python/bindings.h"
#include "python/py_world.h"

namespace cablelab::python {

namespace {

py::array_t<double> jointColumn(const PyWorld& self, double JointState::*field) {
  PyWorld::Busy busy(self);
  const World& w = *self.world;
  py::array_t<double> a = newArray({w.jointCount()});
  for (int i = 0; i < w.jointCount(); ++i) a.mutable_at(i) = w.joint(i).*field;
  return a;
}

py::array_t<double> cableJacobian(const PyWorld& self, py::handle cable) {
  PyWorld::Busy busy(self);
  const World& w = *self.world;
  const Cable& c = w.cable(self.cableIndex(cable, "cable_jacobian"));
  py::array_t<double> a = newArray({w.bodyCount(), 3});
  std::fill(a.mutable_data(), a.mutable_data() + a.size(), 0.0);
  for (const BodyJacobian& e : c.kinematics().jacobian)
    for (int k = 0; k < 3; ++k) a.mutable_at(e.body, k) += e.d[k];
  return a;
}

py::dict contactForces(const PyWorld& self) {
  PyWorld::Busy busy(self);
  const std::vector<ContactForce> forces = self.world->contactForces();
  const auto n = static_cast<py::ssize_t>(forces.size());
  py::array_t<double> force = newArray({n, 2}), point = newArray({n, 2}), normal = newArray({n, 2});
  py::array_t<int> bodies({n, py::ssize_t(2)});
  py::list pairs;
  auto name = [&](int b) { return b < 0 ? std::string("world") : self.bodyNames[b]; };
  for (py::ssize_t i = 0; i < n; ++i) {
    const ContactForce& f = forces[i];
    bodies.mutable_at(i, 0) = f.bodyA, bodies.mutable_at(i, 1) = f.bodyB;
    for (int k = 0; k < 2; ++k) {
      force.mutable_at(i, k) = f.force[k];
      point.mutable_at(i, k) = f.point[k];
      normal.mutable_at(i, k) = f.normal[k];
    }
    pairs.append(py::make_tuple(name(f.bodyA), name(f.bodyB)));
  }
  py::dict out;
  out["pairs"] = pairs;
  out["bodies"] = bodies;
  out["force"] = force;
  out["point"] = point;
  out["normal"] = normal;
  return out;
}

void setJointValuesCall(PyWorld& self, py::handle values, bool servoTargets) {
  PyWorld::Busy busy(self);
  World& w = *self.world;
  const std::vector<double> q = toNumbers(values, w.jointCount(), "set_joint_values", "values");
  setJointValues(w, q, "set_joint_values");
  if (servoTargets)
    for (int j = 0; j < w.jointCount(); ++j) w.setServoTarget(j, q[j]);
}

}  // namespace

void bindSensors(py::class_<PyWorld>& c) {
  using namespace pybind11::literals;
  c.def(
      "cable_span_tensions",
      [](const PyWorld& self, py::handle cable) {
        PyWorld::Busy busy(self);
        const Cable& c = self.world->cable(self.cableIndex(cable, "cable_span_tensions"));
        py::array_t<double> a = newArray({c.spanCount()});
        for (int k = 0; k < c.spanCount(); ++k) a.mutable_at(k) = c.spanTension(k);
        return a;
      },
      "cable"_a,
      R"doc(cable_span_tensions(cable) -> ndarray (spans,)

Tension of each span of the cable over the last step (N), in path order. A cable is one span
unless a no-slip or capstan wheel, or a polygon with friction, splits it: round a capstan the
two sides differ by up to e^(mu theta). cable_tensions() gives the largest of them.)doc");
  c.def(
      "cable_corner_tensions",
      [](const PyWorld& self, py::handle cable) {
        PyWorld::Busy busy(self);
        const Cable& c = self.world->cable(self.cableIndex(cable, "cable_corner_tensions"));
        std::vector<CornerTension> all, corners;
        for (int k = 0; k + 1 < c.spanCount(); ++k) {
          c.cornerTensions(k, corners);
          all.insert(all.end(), corners.begin(), corners.end());
        }
        py::array_t<double> a = newArray({static_cast<py::ssize_t>(all.size()), 3});
        for (size_t i = 0; i < all.size(); ++i) {
          const auto row = static_cast<py::ssize_t>(i);
          a.mutable_at(row, 0) = all[i].turn;
          a.mutable_at(row, 1) = all[i].tensionIn;
          a.mutable_at(row, 2) = all[i].tensionOut;
        }
        return a;
      },
      "cable"_a,
      R"doc(cable_corner_tensions(cable) -> ndarray (corners, 3)

One row per engaged corner of the cable's polygon pulleys with friction ("mu"), in path order:
the angle the cable turns there (rad), the tension arriving and the tension leaving (N). While
the rope slides, each corner's two tensions are in the ratio e^(mu theta_i); while it holds,
each corner takes the same share of its friction. Empty without such polygons.)doc");
  c.def(
      "joint_rates", [](const PyWorld& s) { return jointColumn(s, &JointState::speed); },
      "joint_rates() -> ndarray (joints,): joint coordinate rates (rad/s or m/s); the same as "
      "joint_speeds().");
  c.def(
      "joint_forces", [](const PyWorld& s) { return jointColumn(s, &JointState::force); },
      R"doc(joint_forces() -> ndarray (joints,)

The force (prismatic, N) or torque (revolute, N m) each joint's servo applied over the last
step, on body B (body A gets the opposite), averaged over its sub-steps; 0 for joints
without a servo. A servo holding a rod of mass m and length l level against gravity
reports m g l / 2.)doc");
  c.def("contact_forces", &contactForces,
        R"doc(contact_forces() -> dict

Box2D's contact forces over its last step (the last sub-step), one row per pair of bodies
in touch: "pairs" (list of (name_a, name_b), "world" for the static ground), "bodies"
((n, 2) int indices, -1 for the world, a < b), "force" ((n, 2), N, on body b from body a),
"point" ((n, 2), m, where it acts) and "normal" ((n, 2), unit, from a to b).)doc");
  c.def("cable_jacobian", &cableJacobian, "cable"_a,
        R"doc(cable_jacobian(cable) -> ndarray (bodies, 3)

J = d length / d (x, y, theta) of every body (m/m, m/m, m/rad; x, y the body origin,
theta its angle), at the current pose and wrap points: the cable's length rate is
sum(J * body_states()[:, 3:6]). Rows of bodies the cable does not touch are zero.)doc");
  c.def(
      "cable_jdot_v",
      [](const PyWorld& self, py::handle cable) {
        PyWorld::Busy busy(self);
        const World& w = *self.world;
        const Cable& c = w.cable(self.cableIndex(cable, "cable_jdot_v"));
        // The solvers keep only length and J; J-dot v is worked out here on the path as it is.
        std::vector<BodyState> bodies;
        for (int i = 0; i < w.bodyCount(); ++i) bodies.push_back(w.body(i));
        std::vector<WrapPoint> path(c.path().begin(), c.path().end());
        return cableKinematics(path, bodies).jdotV;
      },
      "cable"_a,
      R"doc(cable_jdot_v(cable) -> float

J-dot v (m/s^2) at the current pose, velocities and wrap points: the part of the length's
second derivative that the velocities alone give, d^2 length / dt^2 = J a + J-dot v
(a the bodies' accelerations (x, y, theta)).)doc");
  c.def("set_joint_values", &setJointValuesCall, "values"_a, py::kw_only(),
        "servo_targets"_a = true,
        R"doc(set_joint_values(values, *, servo_targets=True)

Poses the bodies so that each joint's coordinate is values[j] (rad or m, joint_names order;
welds ignore theirs): from the world outwards, each joint turns or slides everything beyond
it. The bodies moved come to rest; with servo_targets, the servos are set to hold the pose.
Cable lengths, paths and Jacobians follow at once. Joints must form trees (no loops).)doc");
}

}  // namespace cablelab::python

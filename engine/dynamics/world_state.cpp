// Capture and restore of a World's state by its history (world_state.h).
#include "engine/dynamics/world_state.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/model/scene_json.h"

namespace cablelab {

namespace {

/// Turns a scene written now gives a drum end that has paid all its cable out (turns must be > 0).
constexpr double kLeastDrumTurns = 1e-9;

}  // namespace

WorldState captureState(const World& world, const std::string& source) {
  WorldState s;
  s.scene = world.scene();
  s.source = source;
  s.inputs = world.history().inputs();
  s.time = world.time();
  s.steps = world.stepCount();
  for (int i = 0; i < world.bodyCount(); ++i) s.bodies.push_back(world.body(i));
  for (int i = 0; i < world.jointCount(); ++i) {
    const JointState j = world.joint(i);
    s.jointValues.push_back(j.value);
    s.servoTargets.push_back(j.servoTarget);
  }
  return s;
}

namespace {

void checkIndex(int index, int count, const char* kind, size_t input, const std::string& source) {
  if (index < 0 || index >= count)
    throw InputError(
        source, "inputs[" + std::to_string(input) + "]",
        std::string("names no ") + kind + " of the scene" + gotValue(static_cast<double>(index)));
}

}  // namespace

void replayInputs(World& world, const std::vector<WorldInput>& inputs, const std::string& source) {
  using Kind = WorldInput::Kind;
  for (size_t n = 0; n < inputs.size(); ++n) {
    const WorldInput& in = inputs[n];
    const int i = in.index;
    const auto& v = in.values;
    switch (in.kind) {
      case Kind::Step:
        for (long k = 0; k < in.count; ++k) world.step(v[0], i);
        break;
      case Kind::BodyTransform:
        checkIndex(i, world.bodyCount(), "body", n, source);
        world.setBodyTransform(i, Vec2(v[0], v[1]), v[2]);
        break;
      case Kind::BodyVelocity:
        checkIndex(i, world.bodyCount(), "body", n, source);
        world.setBodyVelocity(i, Vec2(v[0], v[1]), v[2]);
        break;
      case Kind::RefreshCables:
        world.refreshCables();
        break;
      case Kind::Force:
        checkIndex(i, world.bodyCount(), "body", n, source);
        world.applyForce(i, Vec2(v[0], v[1]), Vec2(v[2], v[3]));
        break;
      case Kind::BeginDrag:
        checkIndex(i, world.bodyCount(), "body", n, source);
        world.beginDrag(i, Vec2(v[0], v[1]), v[2]);
        break;
      case Kind::DragTo:
        world.dragTo(Vec2(v[0], v[1]));
        break;
      case Kind::EndDrag:
        world.endDrag();
        break;
      case Kind::CableParameters:
        checkIndex(i, world.cableCount(), "cable", n, source);
        world.setCableParameters(i, v[0], v[1], v[2], v[3]);
        break;
      case Kind::ServoTarget:
        checkIndex(i, world.jointCount(), "joint", n, source);
        if (in.count == 0)
          world.setServoTargetAtOnce(i, v[0]);
        else
          world.setServoTarget(i, v[0]);
        break;
      case Kind::Gravity:
        world.setGravity(Vec2(v[0], v[1]));
        break;
      case Kind::WrapSkipping:
        world.setWrapSkipping(i != 0);
        break;
      case Kind::MidpointPerIsland:
        world.setMidpointPerIsland(i != 0);
        break;
      case Kind::JointEnergyKept:
        world.setJointEnergyKept(i != 0);
        break;
      case Kind::Pose:
        if (i >= 0) checkIndex(i, world.bodyCount(), "body", n, source);
        world.poseBody(i, Vec2(v[0], v[1]), Vec2(v[2], v[3]), in.count != 0);
        break;
    }
  }
}

SceneDef sceneNow(const World& world) {
  const SceneDef& built = world.scene();
  SceneDef s = built;
  s.gravity = world.gravity();
  for (int i = 0; i < world.bodyCount(); ++i) {
    const BodyState& b = world.body(i);
    s.bodies[i].position = b.position, s.bodies[i].angle = b.angle;
    s.bodies[i].velocity = b.velocity, s.bodies[i].angularVelocity = b.angularVelocity;
  }
  for (int i = 0; i < world.jointCount(); ++i) {
    const JointState j = world.joint(i);
    JointDef& d = s.joints[i];
    d.anchor = j.anchorB;
    d.value = j.value;
    d.servo.target = j.servoTarget;
    // A prismatic axis turns with body A.
    const int a = findBodyIndex(built, d.bodyA);
    if (a >= 0) d.axis = rotate(d.axis, world.body(a).angle - built.bodies[a].angle);
  }
  for (int i = 0; i < world.cableCount(); ++i) {
    const CableParameters& live = world.cable(i).parameters();
    CableDef& c = s.cables[i];
    c.restLength = live.restLength, c.stiffness = live.stiffness;
    c.preload = live.preload, c.damping = live.damping;
    // The turns wound now, not the ones authored: built from the authored ones the cable would
    // start as much shorter as it has wound since (docs/python.md). An auto pulley keeps its 0
    // (turns need a side); a drum that paid all out keeps a sliver (turns must be > 0).
    const Cable& cable = world.cable(i);
    for (size_t k = 0; k < c.pulleys.size(); ++k) {
      PulleyDef& p = c.pulleys[k];
      if (p.kind != PulleyDef::Kind::Point && p.side != WrapSide::Auto)
        p.turns = cable.woundTurns(static_cast<int>(k));
    }
    if (c.start.radius > 0) c.start.turns = std::max(cable.drumTurns(true), kLeastDrumTurns);
    if (c.end.radius > 0) c.end.turns = std::max(cable.drumTurns(false), kLeastDrumTurns);
  }
  s.time = world.time();
  s.stepCount = world.stepCount();
  auto history = std::make_shared<SceneHistory>();
  history->origin = built;
  history->inputs = inputRows(world.history().inputs());
  s.history = std::move(history);
  return s;
}

namespace {

/// What sceneNow writes of the state (not the names, view or default step, free to edit).
nlohmann::json stateFields(const SceneDef& scene) {
  nlohmann::json j = sceneToJson(scene);
  for (const char* key : {"name", "description", "view", "dt", "substeps", "history"}) j.erase(key);
  return j;
}

}  // namespace

void resumeHistory(World& world, const SceneDef& written, const std::string& source) {
  replayInputs(world, inputsFromRows(written.history->inputs, source), source);
  const nlohmann::json reached = stateFields(sceneNow(world)), given = stateFields(written);
  if (reached == given) return;
  std::string differ = "its state";
  for (const auto& [key, value] : given.items())
    if (!reached.contains(key) || reached.at(key) != value) {
      differ = key;
      break;
    }
  throw InputError(source, "history",
                   "does not lead to the scene's " + differ +
                       " (edited after the scene was written?): remove \"history\" to start "
                       "from the fields as written");
}

std::vector<std::array<double, 7>> inputRows(const std::vector<WorldInput>& inputs) {
  std::vector<std::array<double, 7>> rows;
  rows.reserve(inputs.size());
  for (const WorldInput& in : inputs)
    rows.push_back({static_cast<double>(in.kind), static_cast<double>(in.index),
                    static_cast<double>(in.count), in.values[0], in.values[1], in.values[2],
                    in.values[3]});
  return rows;
}

std::vector<WorldInput> inputsFromRows(const std::vector<std::array<double, 7>>& rows,
                                       const std::string& source, const std::string& field) {
  std::vector<WorldInput> out;
  out.reserve(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    const bool whole = r[0] == std::floor(r[0]) && r[1] == std::floor(r[1]) &&
                       r[2] == std::floor(r[2]) && std::abs(r[1]) < 1e9 && r[2] < 1e15;
    if (!whole || r[0] < 0 || r[0] > static_cast<double>(WorldInput::Kind::Last) || r[2] < 0)
      throw InputError(source, field + "[" + std::to_string(i) + "]",
                       "is not a World input (kind 0.." +
                           std::to_string(static_cast<int>(WorldInput::Kind::Last)) +
                           ", whole index and count)" + " (got kind " + formatNumber(r[0]) +
                           ", index " + formatNumber(r[1]) + ", count " + formatNumber(r[2]) + ")");
    out.emplace_back(static_cast<WorldInput::Kind>(static_cast<int>(r[0])), static_cast<int>(r[1]),
                     static_cast<long>(r[2]), std::array<double, 4>{r[3], r[4], r[5], r[6]});
  }
  return out;
}

std::unique_ptr<World> restoreWorld(const WorldState& state) {
  auto world = std::make_unique<World>(state.scene, state.source);
  replayInputs(*world, state.inputs, state.source);
  return world;
}

}  // namespace cablelab

// Capture and restore of a World's state by its history (world_state.h).
#include "engine/dynamics/world_state.h"

#include "engine/core/error.h"

namespace cablelab {

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

std::unique_ptr<World> restoreWorld(const WorldState& state) {
  auto world = std::make_unique<World>(state.scene, state.source);
  replayInputs(*world, state.inputs, state.source);
  return world;
}

}  // namespace cablelab

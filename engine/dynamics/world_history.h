// WorldHistory: every input a World took since it was built, in order (steps, teleports, forces,
// servo targets, live edits). Box2D's contact caches and the cable solver's warm starts cannot be
// copied out of a World, but the World is deterministic: the scene plus this history rebuilds it
// bit for bit (world_state.h, docs/python.md "State").
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace cablelab {

/// One input to a World. `index` is the body, cable or joint it names (Step: the sub-steps;
/// the switches: 0 or 1); `values` its numbers in the order of the World method's arguments.
struct WorldInput {
  enum class Kind : std::uint8_t {
    Step,               ///< values[0] = dt (s), index = sub-steps, `count` steps in a row
    BodyTransform,      ///< x, y (m), angle (rad)
    BodyVelocity,       ///< vx, vy (m/s), omega (rad/s)
    RefreshCables,      ///<
    Force,              ///< fx, fy (N), at world point x, y (m)
    BeginDrag,          ///< x, y (m), stiffness (Hz)
    DragTo,             ///< x, y (m)
    EndDrag,            ///<
    CableParameters,    ///< rest length (m), stiffness (N/m), preload (m), damping (N s/m)
    ServoTarget,        ///< target (rad or m); count = 0 where it takes effect at once
    Gravity,            ///< gx, gy (m/s^2)
    WrapSkipping,       ///< index = on
    MidpointPerIsland,  ///< index = on
    JointEnergyKept,    ///< index = on
    Pose,  ///< index = body (-1: settlePose), grab x, y (body frame, m), target x, y (m);
           ///< count = 1 where the pose pays the cables out, else 0
    Last = Pose
  };
  WorldInput(Kind kind = Kind::Step, int index = 0, long count = 1,
             std::array<double, 4> values = {})
      : kind(kind), index(index), count(count), values(values) {}
  Kind kind;
  int index;
  long count;
  std::array<double, 4> values;
};

class WorldHistory {
 public:
  /// Appends an input; a step with the same dt and sub-steps as the one before only counts up.
  void add(const WorldInput& input) {
    if (input.kind == WorldInput::Kind::Step && !inputs_.empty()) {
      WorldInput& last = inputs_.back();
      if (last.kind == input.kind && last.index == input.index && last.values == input.values) {
        last.count += input.count;
        return;
      }
    }
    inputs_.push_back(input);
  }
  const std::vector<WorldInput>& inputs() const { return inputs_; }

 private:
  std::vector<WorldInput> inputs_;
};

}  // namespace cablelab

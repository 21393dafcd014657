// Rewind by replay (world_rewind.h).
#include "engine/dynamics/world_rewind.h"

#include <stdexcept>

#include "engine/dynamics/world.h"
#include "engine/dynamics/world_state.h"

namespace cablelab {

std::vector<WorldInput> inputsThroughStep(const std::vector<WorldInput>& inputs, long steps) {
  std::vector<WorldInput> out;
  long taken = 0;
  for (const WorldInput& in : inputs) {
    if (taken == steps) return out;  // the inputs after the last step wanted belong to the next
    if (in.kind != WorldInput::Kind::Step) {
      out.push_back(in);
      continue;
    }
    WorldInput part = in;  // a run of equal steps: cut it where the count is reached
    part.count = std::min(in.count, steps - taken);
    taken += part.count;
    out.push_back(part);
  }
  if (taken < steps)
    throw std::out_of_range("rewind: the history holds " + std::to_string(taken) + " steps, not " +
                            std::to_string(steps));
  return out;
}

std::unique_ptr<World> rewoundWorld(const SceneDef& scene, const std::vector<WorldInput>& inputs,
                                    long steps, const std::string& source) {
  auto world = std::make_unique<World>(scene, source);
  replayInputs(*world, inputsThroughStep(inputs, steps), source);
  return world;
}

}  // namespace cablelab

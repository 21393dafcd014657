// Cable islands for the choice of solve (docs/cables.md, "When it applies"): cables that pull on a
// common moving body are one island. Static and kinematic bodies join nothing: they move as
// prescribed whatever the tensions. Joints are left out: a jointed body keeps its island from the
// energy-consistent solve anyway, and the main solve unites jointed bodies itself.
// Private to engine/dynamics.
#pragma once

#include <span>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab {

class CableIslands {
 public:
  /// Partitions the cables that pull on a moving body; `whole` puts them all in one island (the
  /// whole-world choice the engine made before islands, kept for comparison).
  void build(std::span<const BodyState> bodies, std::span<const Cable> cables, bool whole);

  int count() const { return static_cast<int>(first_.size()) - 1; }
  /// Whether some cable pulls on moving bodies none of which is `excluded`: without one no
  /// island can go to the midpoint solve, and the partition is not needed (a hand's step).
  static bool anyFree(std::span<const BodyState> bodies, std::span<const Cable> cables,
                      std::span<const char> excluded);

  /// Island i's cables, in cable order.
  std::span<const int> cables(int i) const {
    return std::span<const int>(members_).subspan(first_[i], first_[i + 1] - first_[i]);
  }
  /// Cables that pull on no moving body (in no island): no solve needs them, their tension is 0.
  std::span<const int> idle() const { return idle_; }

 private:
  std::vector<int> parent_;        // union-find over bodies
  std::vector<int> islandOfRoot_;  // root body -> island, -1: none yet
  std::vector<int> islandOf_;      // cable -> island, -1: idle
  std::vector<int> members_;       // the islands' cables, island after island
  std::vector<int> first_ = {0};   // island i's cables: members_[first_[i], first_[i + 1])
  std::vector<int> idle_;
};

}  // namespace cablelab

// Cable islands: union-find over the moving bodies the cables pull on (cable_islands.h).
#include "engine/dynamics/cable_islands.h"

#include "engine/dynamics/disjoint_sets.h"

namespace cablelab {

namespace {

// Calls f(body) for every moving body the cable pulls on (each span's, as the main solve does:
// a wheel that grips the cable is in its spans).
template <class F>
void forPulledBodies(const Cable& cable, std::span<const BodyState> bodies, F&& f) {
  for (int k = 0; k < cable.spanCount(); ++k)
    for (const auto& e : cable.spanKinematics(k).jacobian)
      if (moves(bodies[e.body])) f(e.body);
}

}  // namespace

bool CableIslands::anyFree(std::span<const BodyState> bodies, std::span<const Cable> cables,
                           std::span<const char> excluded) {
  for (const Cable& c : cables) {
    bool pulls = false, free = true;
    for (int k = 0; k < c.spanCount() && free; ++k)
      for (const auto& e : c.spanKinematics(k).jacobian)
        if (moves(bodies[e.body])) {
          pulls = true;
          if (excluded[e.body]) {
            free = false;  // a hand's cables stop at their first body
            break;
          }
        }
    if (pulls && free) return true;
  }
  return false;
}

void CableIslands::build(std::span<const BodyState> bodies, std::span<const Cable> cables,
                         bool whole) {
  const int n = static_cast<int>(bodies.size());
  parent_.resize(n);
  for (int b = 0; b < n; ++b) parent_[b] = b;
  islandOf_.assign(cables.size(), -1);
  idle_.clear();
  int last = -1;  // with `whole`: a body of the cables seen so far
  for (size_t i = 0; i < cables.size(); ++i) {
    int first = -1;
    forPulledBodies(cables[i], bodies, [&](int body) {
      if (first >= 0) unite(parent_, first, body);
      first = body;
    });
    if (first < 0) {
      idle_.push_back(static_cast<int>(i));
      continue;
    }
    if (whole && last >= 0) unite(parent_, last, first);
    last = first;
    islandOf_[i] = first;  // a body for now; its island below
  }
  // Islands numbered in the order of their first cable; members_ sorted by island (counting).
  islandOfRoot_.assign(n, -1);
  int islands = 0;
  for (int& island : islandOf_)
    if (island >= 0) {
      int& id = islandOfRoot_[findRoot(parent_, island)];
      if (id < 0) id = islands++;
      island = id;
    }
  first_.assign(islands + 1, 0);
  for (int island : islandOf_)
    if (island >= 0) ++first_[island + 1];
  for (int i = 0; i < islands; ++i) first_[i + 1] += first_[i];
  members_.resize(first_[islands]);
  std::vector<int>& fill = islandOfRoot_;  // reused: the next free slot of each island
  fill.assign(first_.begin(), first_.end() - 1);
  for (size_t i = 0; i < islandOf_.size(); ++i)
    if (islandOf_[i] >= 0) members_[fill[islandOf_[i]]++] = static_cast<int>(i);
}

}  // namespace cablelab

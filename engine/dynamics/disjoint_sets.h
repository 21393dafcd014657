// Disjoint sets over indices (union-find with path halving): the cable solver's islands and the
// joint projection's blocks. Private to engine/dynamics.
#pragma once

#include <algorithm>
#include <vector>

namespace cablelab {

/// The set's representative of `i`; `parent[i] == i` for a representative.
inline int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

/// Joins the sets of a and b; the smaller index becomes the representative.
inline void unite(std::vector<int>& parent, int a, int b) {
  a = findRoot(parent, a), b = findRoot(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

}  // namespace cablelab

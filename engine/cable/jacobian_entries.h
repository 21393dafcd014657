// A cable's Jacobian is a short list of per-body entries (a path touches few bodies), kept sorted
// by body so that two lists of the same bodies line up entry by entry.
#pragma once

#include <utility>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab {

/// Adds d to the body's entry (none for the world, body -1). A new entry moves down to its
/// place: cheaper than sorting at the end for a few bodies.
inline void addJacobian(std::vector<BodyJacobian>& jac, int body, const Vec3& d) {
  if (body < 0) return;
  for (auto& e : jac)
    if (e.body == body) {
      e.d += d;
      return;
    }
  jac.push_back({body, d});
  for (size_t i = jac.size() - 1; i > 0 && jac[i - 1].body > body; --i)
    std::swap(jac[i - 1], jac[i]);
}

}  // namespace cablelab

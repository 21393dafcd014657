// A rigid cable stretched by a contact within the step (docs/cables.md, "Contacts and the rope"):
// Box2D's contacts act after the cable solve, which moved the bodies without the knock (two
// polygons riding in one rope's loops knocking each other, a polygon hitting an anchor it touches),
// and the knock sends them off along the rope: it ran up to 5.7 cm long. Such a cable is
// caught after Box2D's step, as its solve would have had it seen the knock: the bodies are moved
// back onto its length along M^-1 J^T, and what is left of their rate out along it is taken off
// (an inelastic catch). Private to engine/dynamics.
#pragma once

#include <span>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab {

/// m: a rigid cable a contact made longer than its rest length by more than this is caught.
inline constexpr double kContactStretch = 1e-4;
/// m: a rigid cable that pulled over the step and ends it slack by more than this gives back the
/// pull that made it slack.
inline constexpr double kContactSlack = 1e-3;

/// Catches every rigid cable of one span that ends the step more than kContactStretch longer
/// than its rest length, some of whose moving bodies a contact pushed or held in the step
/// (`knocked`, per body) and none of which is jointed (`jointed`, per body: the joints would have
/// to move with it). Moves and slows those bodies in `bodies` (marking them in `moved`, sized to
/// bodies) and refreshes the cables' lengths. One that pulled over the step of `dt` (its tension)
/// and ends it more than kContactSlack slack gives back as much of that pull as leaves it at its
/// rest length. Returns whether it moved any.
bool catchCablesStretchedByContacts(std::span<Cable> cables, std::span<BodyState> bodies,
                                    std::span<const char> knocked, std::span<const char> jointed,
                                    double dt, std::vector<char>& moved);

}  // namespace cablelab

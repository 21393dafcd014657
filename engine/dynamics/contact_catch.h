// A rigid cable stretched by a contact within the step (docs/cables.md, "Contacts and the rope"):
// Box2D's contacts act after the cable solve, which moved the bodies without the knock (two
// polygons riding in one rope's loops knocking each other, a polygon hitting an anchor it touches),
// and the knock sends them off along the rope: it ran up to 5.7 cm long. Such a cable is
// caught after Box2D's step, as its solve would have had it seen the knock: the bodies are moved
// back onto its length along M^-1 J^T, and what is left of their rate out along it is taken off
// (an inelastic catch). Private to engine/dynamics.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab {

class Box2DBridge;

/// m: a rigid cable a contact made longer than its rest length by more than this is caught; less
/// is left to the stabilisation share of the next steps. (Caught from 0.1 to 3 mm on, the squares
/// of tests/data/polygons/polygons_in_rope_loops.json took other paths, on which a wrap change was
/// found late, a square fell past the rope its pulley order cannot join, or a main solve that did
/// not settle on a contact threw one: docs/cables.md, "Contacts and the rope".)
inline constexpr double kContactStretch = 5e-3;

/// Catches every rigid cable of one span that ends the step more than kContactStretch longer
/// than its rest length, some of whose moving bodies a contact pushed or held in the step
/// (`knocked`, per body) and none of which is jointed (`jointed`, per body: the joints would have
/// to move with it). Moves and slows those bodies in `bodies` (marking them in `moved`, sized to
/// bodies; the cables' lengths are worked out again at the next selection). Returns whether it
/// moved any.
bool catchCablesStretchedByContacts(std::span<Cable> cables, std::span<BodyState> bodies,
                                    std::span<const char> knocked, std::span<const char> jointed,
                                    std::vector<char>& moved);

/// After a Box2D step: catches (catchCablesStretchedByContacts) the rigid cables on bodies that
/// were in a touching contact at the start of the step (`touching`, per body) or after it, or that
/// a contact pushed in it, and hands the moved bodies' poses and velocities back to Box2D.
void catchContactStretch(Box2DBridge& b2, std::vector<Cable>& cables,
                         std::vector<BodyState>& bodies,
                         const std::vector<std::array<int, 2>>& jointBodies,
                         std::span<const char> touching);

}  // namespace cablelab

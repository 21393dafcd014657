// Posing a World by its joint coordinates (any scene whose joints form trees: a finger, an arm,
// a wheel on its axle): set_joint_values in Python, placeHand's general form.
#pragma once

#include <span>
#include <string>

#include "engine/dynamics/world.h"

namespace cablelab {

/// Teleports the bodies so that joint j's coordinate is q[j] (rad or m), for every joint, with
/// the velocities of the bodies moved set to zero, and refreshes the cables. Joints are taken
/// from the world outwards: each turns (revolute) or slides (prismatic) its outer body and
/// everything jointed beyond it rigidly about its anchor or along its axis; welds take no value
/// (q[j] is ignored). Throws InputError (source `source`) if the joints form a loop, so that
/// one joint's move would pull another apart, or q has the wrong size or a non-finite value.
void setJointValues(World& world, std::span<const double> q, const std::string& source);

}  // namespace cablelab

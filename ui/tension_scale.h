// The tension colour scale of a scene: fixed per scene, so that a colour means the same
// newtons before and after a reset, in the sandbox, in snapshots and in recordings.
//
// Needs: the engine (World). The scale is what the scene is expected to carry, from its loads,
// rounded up to a "nice" number (1, 2 or 5 times a power of ten); no simulation.
#pragma once

#include "engine/model/scene.h"

namespace cablelab::ui {

/// The least colour-bar maximum (N) of loadTensionScale(): a scene with next to no load (a new
/// one) does not colour numerical noise of micronewtons.
inline constexpr double kLeastTensionScale = 1.0;

/// The sandbox's colour-bar maximum (N) for `scene`, from its loads: the weights m |g| of its
/// moving bodies summed (but those a joint ties to the ground, which carries them), plus m v^2 / L
/// for those that start moving (L: the shortest rigid cable), or the largest cable tension at the
/// start when that is more (an elastic band's preload); rounded up to a "nice" number, at least
/// kLeastTensionScale. No simulation: the same scene always gets the same scale, whatever a run
/// does.
double loadTensionScale(const SceneDef& scene);

}  // namespace cablelab::ui

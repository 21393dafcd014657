// The tension colour scale of a scene: fixed per scene, so that a colour means the same
// newtons before and after a reset, in the sandbox, in snapshots and in recordings.
//
// Needs: the engine (World). The scale is what the scene is expected to carry: a throwaway
// copy of the scene runs for a short probe time without user input, and its largest cable
// tension, rounded up to a "nice" number (1, 2 or 5 times a power of ten), tops the bar.
#pragma once

#include "engine/model/scene.h"

namespace cablelab::ui {

/// The probe length (s) expectedTensionScale() simulates.
inline constexpr double kTensionProbeSeconds = 2.0;

/// Colour-bar maximum (N) for `scene`: niceCeil of the largest tension in the first
/// kTensionProbeSeconds of an undisturbed run (at the scene's dt and substeps); 1 N when no
/// cable pulls or the probe run fails.
double expectedTensionScale(const SceneDef& scene);

}  // namespace cablelab::ui

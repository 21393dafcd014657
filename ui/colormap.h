// Colour scale for cable tension, shared by the cable colours and the legend bar.
//
// Needs: ui/overlay.h (Colour). Pure functions, no GL.
#pragma once

#include "ui/overlay.h"

namespace cablelab::ui {

/// Maps t in [0, 1] (clamped) along blue -> cyan -> green -> yellow -> red.
Colour tensionColour(double t);

/// The smallest "nice" number (1, 2 or 5 times a power of ten) >= value; 1 for value <= 0.
double niceCeil(double value);

/// The largest "nice" step (1, 2 or 5 times a power of ten) <= value; value must be > 0.
double niceFloor(double value);

}  // namespace cablelab::ui

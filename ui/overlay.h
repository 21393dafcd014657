// Overlay: what the app draws on top of a scene (controller targets, arrows, notes).
//
// Needs: engine/core/math.h only. Plain data owned by the caller and passed to the renderer each
// frame; the renderer keeps nothing. Colours are RGBA in [0, 1].
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/core/math.h"

namespace cablelab::ui {

using Colour = std::array<float, 4>;  ///< r, g, b, a in [0, 1]

struct Overlay {
  /// A cross at a world point (a controller target), with an optional label.
  struct Target {
    Vec2 position = Vec2::Zero();  ///< m
    std::string label;
    Colour colour{0.85f, 0.1f, 0.55f, 1.0f};
    Vec2 labelOffset{12, -18};  ///< px: the label's preferred top-left corner from the cross
  };
  /// An arrow between two world points (a drag spring, a force, a commanded velocity).
  struct Arrow {
    Vec2 from = Vec2::Zero(), to = Vec2::Zero();  ///< m
    std::string label;
    Colour colour{0.2f, 0.2f, 0.2f, 1.0f};
  };
  /// Text at a world point.
  struct Text {
    Vec2 position = Vec2::Zero();  ///< m
    std::string text;
    Colour colour{0.1f, 0.1f, 0.1f, 1.0f};
  };

  /// One line of the marker key: a sample of `marker` in `colour`, then `label`.
  struct Key {
    enum class Marker { Cross, Arrow, DashedCross };
    Marker marker = Marker::Cross;
    std::string label;
    Colour colour{0.2f, 0.2f, 0.2f, 1.0f};
  };

  std::vector<Target> targets;
  std::vector<Arrow> arrows;
  std::vector<Text> texts;
  /// Lines of text in the top-left corner of the viewport (screen space).
  std::vector<std::string> notes;
  /// Keys of the overlay's markers, shown in the marker legend with the renderer's own.
  std::vector<Key> keys;
  /// A warning banner across the top of the viewport (a guard fired, a cable overstretched).
  std::string banner;
};

}  // namespace cablelab::ui

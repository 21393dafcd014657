// The one palette of a GIF clip, chosen from its first frame. A rendered scene is mostly flat
// fills that keep their colours from frame to frame (the background, the bodies, the colour
// bar with every tension colour), so one palette serves the whole clip: no palette per frame,
// and a pixel that did not change keeps its index (no flicker between frames, nothing for the
// next frame to rewrite). A median cut (giflib's GifQuantizeBuffer) splits colour space by pixel
// count and merged a light body fill into the background (a weight drawn as an outline), so the
// colours are picked greedily instead: the commonest first, then always the one whose pixels lie
// farthest from the palette so far (pixel count times squared distance), which keeps every flat
// fill exactly and still covers the rare colours.
//
// Needs: ui/image.h only. Colours are grouped by their top 5 bits per channel (32768 groups); a
// group's palette colour is the mean of its pixels, exact for a flat fill.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "ui/image.h"

namespace cablelab::ui {

class GifPalette {
 public:
  using Rgb = std::array<std::uint8_t, 3>;

  /// At most `size` (1..256) colours for `image` (RGB; alpha ignored).
  GifPalette(const Image& image, int size) : GifPalette(std::vector<const Image*>{&image}, size) {}
  /// At most `size` colours for the pixels of all `images` together.
  GifPalette(const std::vector<const Image*>& images, int size);

  /// The palette, commonest colour first.
  const std::vector<Rgb>& colours() const { return colours_; }

  /// The index of the palette colour nearest to `rgb` (squared RGB distance from its group's
  /// mean in the first frame, or from the group's centre for a colour the first frame lacked).
  std::uint8_t indexOf(const std::uint8_t* rgb) {
    const int g = groupOf(rgb);
    if (entryOf_[g] < 0) entryOf_[g] = nearest(centreOf(g));
    return static_cast<std::uint8_t>(entryOf_[g]);
  }

  static int groupOf(const std::uint8_t* p) {
    return (p[0] >> 3) << 10 | (p[1] >> 3) << 5 | p[2] >> 3;
  }

 private:
  static Rgb centreOf(int group);
  int nearest(const Rgb& colour) const;

  std::vector<Rgb> colours_;
  std::vector<std::int16_t> entryOf_;  ///< per group: its palette index, -1 until first asked
};

}  // namespace cablelab::ui

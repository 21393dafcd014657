#include "ui/gif_palette.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace cablelab::ui {
namespace gif_palette {

constexpr int kGroups = 1 << 15;

long squaredDistance(const GifPalette::Rgb& a, const GifPalette::Rgb& b) {
  long d = 0;
  for (int c = 0; c < 3; ++c) d += (long{a[c]} - b[c]) * (long{a[c]} - b[c]);
  return d;
}

}  // namespace gif_palette

GifPalette::GifPalette(const std::vector<const Image*>& images, int size)
    : entryOf_(gif_palette::kGroups, -1) {
  using namespace gif_palette;
  if (size < 1 || size > 256) throw std::invalid_argument("GIF palette size must be 1..256");
  std::vector<std::uint32_t> count(kGroups, 0);
  std::vector<std::array<std::uint64_t, 3>> sum(kGroups, {0, 0, 0});
  for (const Image* image : images)
    for (int y = 0; y < image->height; ++y)
      for (int x = 0; x < image->width; ++x) {
        const std::uint8_t* p = image->pixel(x, y);
        const int g = groupOf(p);
        ++count[g];
        for (int c = 0; c < 3; ++c) sum[g][c] += p[c];
      }
  struct Group {
    int id;
    double count;
    Rgb mean;
    long distance;  ///< squared, to the nearest palette colour so far
  };
  std::vector<Group> groups;
  for (int g = 0; g < kGroups; ++g) {
    if (!count[g]) continue;
    Rgb mean;
    for (int c = 0; c < 3; ++c)
      mean[c] = static_cast<std::uint8_t>((sum[g][c] + count[g] / 2) / count[g]);
    groups.push_back({g, static_cast<double>(count[g]), mean, std::numeric_limits<long>::max()});
  }
  // Greedy: the group whose pixels are worst served so far (count x squared distance; the
  // commonest first, while every distance is still "infinite").
  while (static_cast<int>(colours_.size()) < size) {
    const Group* best = nullptr;
    double bestScore = 0;
    for (const Group& g : groups) {
      const double score = g.count * static_cast<double>(g.distance);
      if (g.distance > 0 && (!best || score > bestScore)) best = &g, bestScore = score;
    }
    if (!best) break;  // every colour of the image is in the palette
    const Rgb chosen = best->mean;
    entryOf_[best->id] = static_cast<std::int16_t>(colours_.size());
    colours_.push_back(chosen);
    for (Group& g : groups) g.distance = std::min(g.distance, squaredDistance(g.mean, chosen));
  }
  if (colours_.empty()) colours_.push_back({0, 0, 0});  // an empty image
  for (const Group& g : groups)
    if (entryOf_[g.id] < 0) entryOf_[g.id] = static_cast<std::int16_t>(nearest(g.mean));
}

GifPalette::Rgb GifPalette::centreOf(int group) {
  return {static_cast<std::uint8_t>((group >> 10 & 31) << 3 | 4),
          static_cast<std::uint8_t>((group >> 5 & 31) << 3 | 4),
          static_cast<std::uint8_t>((group & 31) << 3 | 4)};
}

int GifPalette::nearest(const Rgb& colour) const {
  int best = 0;
  long bestDistance = std::numeric_limits<long>::max();
  for (size_t e = 0; e < colours_.size(); ++e) {
    const long d = gif_palette::squaredDistance(colour, colours_[e]);
    if (d < bestDistance) best = static_cast<int>(e), bestDistance = d;
  }
  return best;
}

}  // namespace cablelab::ui

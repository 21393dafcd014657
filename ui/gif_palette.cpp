#include "ui/gif_palette.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace cablelab::ui {
namespace gif_palette {

constexpr int kGroups = 1 << 15;

int groupOf(const std::uint8_t* p) {
  return (p[0] >> 3) << 10 | (p[1] >> 3) << 5 | p[2] >> 3;
}

}  // namespace gif_palette

IndexedPixels indexColours(const Image& image, int x, int y, int w, int h) {
  using namespace gif_palette;
  std::vector<std::uint32_t> count(kGroups, 0);
  std::vector<std::array<std::uint64_t, 3>> sum(kGroups, {0, 0, 0});
  for (int row = y; row < y + h; ++row)
    for (int col = x; col < x + w; ++col) {
      const std::uint8_t* p = image.pixel(col, row);
      const int g = groupOf(p);
      ++count[g];
      for (int c = 0; c < 3; ++c) sum[g][c] += p[c];
    }
  std::vector<int> used;
  for (int g = 0; g < kGroups; ++g)
    if (count[g]) used.push_back(g);
  const size_t kept = std::min<size_t>(used.size(), 256);
  std::partial_sort(used.begin(), used.begin() + kept, used.end(), [&](int a, int b) {
    return count[a] != count[b] ? count[a] > count[b] : a < b;
  });

  IndexedPixels out;
  std::vector<int> entryOf(kGroups, -1);
  for (size_t i = 0; i < kept; ++i) {
    const int g = used[i];
    std::array<std::uint8_t, 3> rgb;
    for (int c = 0; c < 3; ++c)
      rgb[c] = static_cast<std::uint8_t>((sum[g][c] + count[g] / 2) / count[g]);
    out.palette.push_back(rgb);
    entryOf[g] = static_cast<int>(i);
  }
  // The rarer groups: the nearest palette colour to their mean (squared RGB distance).
  for (size_t i = kept; i < used.size(); ++i) {
    const int g = used[i];
    long best = std::numeric_limits<long>::max();
    for (size_t e = 0; e < out.palette.size(); ++e) {
      long d = 0;
      for (int c = 0; c < 3; ++c) {
        const long v = static_cast<long>(sum[g][c] / count[g]) - out.palette[e][c];
        d += v * v;
      }
      if (d < best) best = d, entryOf[g] = static_cast<int>(e);
    }
  }
  out.indices.resize(static_cast<size_t>(w) * h);
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col)
      out.indices[static_cast<size_t>(row) * w + col] =
          static_cast<std::uint8_t>(entryOf[groupOf(image.pixel(x + col, y + row))]);
  return out;
}

}  // namespace cablelab::ui

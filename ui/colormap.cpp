#include "ui/colormap.h"

#include <algorithm>
#include <cmath>

namespace cablelab::ui {

Colour tensionColour(double t) {
  static constexpr float stops[5][3] = {{0.15f, 0.25f, 0.85f},
                                        {0.0f, 0.7f, 0.85f},
                                        {0.1f, 0.75f, 0.2f},
                                        {0.95f, 0.8f, 0.1f},
                                        {0.85f, 0.1f, 0.1f}};
  const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4.0;
  const int i = std::min(static_cast<int>(x), 3);
  const float f = static_cast<float>(x - i);
  Colour c{0, 0, 0, 1};
  for (int k = 0; k < 3; ++k) c[k] = stops[i][k] + f * (stops[i + 1][k] - stops[i][k]);
  return c;
}

double niceCeil(double value) {
  if (!(value > 0) || !std::isfinite(value)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(value)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= value * (1 - 1e-12)) return m * p;
  return 10 * p;
}

double niceFloor(double value) {
  const double p = std::pow(10.0, std::floor(std::log10(value)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= value * (1 + 1e-12)) return m * p;
  return p;
}

}  // namespace cablelab::ui

#include "ui/cable_spans.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cablelab::ui {
namespace {

WheelRow wheelRow(const Cable& cable, int k) {
  const SpanLink& link = cable.link(k);
  WheelRow w;
  w.span = k;
  w.pulley = link.pulley;
  w.grip = link.grip;
  w.mu = link.mu;
  w.wrapAngle = link.wrapAngle;
  w.slipped = link.slipped;
  const double a = cable.spanTension(k), b = cable.spanTension(k + 1);
  const double low = std::min(a, b), high = std::max(a, b);
  w.ratio = low > 0 ? high / low : 0.0;
  char text[160];
  if (link.grip == Grip::Capstan) {
    w.capstanRatio = std::exp(link.mu * link.wrapAngle);
    w.state = link.slipped ? "slipping" : "holding";
    std::snprintf(text, sizeof text, "wheel %d: %s, theta %.3f rad, ratio %.4g (e^(mu theta) %.4g)",
                  link.pulley, w.state.c_str(), link.wrapAngle, w.ratio, w.capstanRatio);
  } else {
    w.state = "no slip";
    std::snprintf(text, sizeof text, "wheel %d: no slip, theta %.3f rad, ratio %.4g", link.pulley,
                  link.wrapAngle, w.ratio);
  }
  w.text = text;
  return w;
}

}  // namespace

SpanTable spanTable(const Cable& cable) {
  SpanTable table;
  if (cable.spanCount() < 2) return table;
  for (int k = 0; k < cable.spanCount(); ++k) {
    SpanRow row;
    row.span = k;
    row.tension = cable.spanTension(k);
    row.length = cable.spanKinematics(k).length;
    char text[96];
    std::snprintf(text, sizeof text, "span %d: %.4g N, %.4f m%s", k, row.tension, row.length,
                  row.tension <= 0 ? " (slack)" : "");
    row.text = text;
    table.spans.push_back(row);
    if (k + 1 < cable.spanCount()) table.wheels.push_back(wheelRow(cable, k));
  }
  return table;
}

}  // namespace cablelab::ui

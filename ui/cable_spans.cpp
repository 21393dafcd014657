#include "ui/cable_spans.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cablelab::ui {
namespace {

CornerRow cornerRow(const CornerTension& c, double mu) {
  CornerRow row;
  row.vertex = c.vertex;
  row.turn = c.turn;
  row.tensionIn = c.tensionIn;
  row.tensionOut = c.tensionOut;
  const double low = std::min(c.tensionIn, c.tensionOut),
               high = std::max(c.tensionIn, c.tensionOut);
  row.ratio = low > 0 ? high / low : 0.0;
  row.capstanRatio = std::exp(mu * c.turn);
  char text[160];
  std::snprintf(text, sizeof text,
                "  corner %d: turns %.3f rad, %.4g N -> %.4g N, pull ratio %.4g (slips at %.4g)",
                c.vertex, c.turn, c.tensionIn, c.tensionOut, row.ratio, row.capstanRatio);
  row.text = text;
  return row;
}

WheelRow wheelRow(const Cable& cable, int k) {
  const SpanLink& link = cable.link(k);
  WheelRow w;
  w.span = k;
  w.pulley = cable.scenePulley(link.pulley);
  w.grip = link.grip;
  w.mu = link.mu;
  w.wrapAngle = link.wrapAngle;
  w.slipped = link.slipped;
  const double a = cable.spanTension(k), b = cable.spanTension(k + 1);
  const double low = std::min(a, b), high = std::max(a, b);
  w.ratio = low > 0 ? high / low : 0.0;
  char text[160];
  std::vector<CornerTension> corners;
  cable.cornerTensions(k, corners);
  const char* what = corners.empty() ? "wheel" : "polygon";
  if (link.grip == Grip::Capstan) {
    w.capstanRatio = std::exp(link.mu * link.wrapAngle);
    w.state = link.slipped ? "slipping" : "holding";
    std::snprintf(text, sizeof text, "%s %d: %s, wrapped %.3f rad, pull ratio %.4g (slips at %.4g)",
                  what, w.pulley, w.state.c_str(), link.wrapAngle, w.ratio, w.capstanRatio);
    for (const CornerTension& c : corners) w.corners.push_back(cornerRow(c, link.mu));
  } else {
    w.state = "no slip";
    std::snprintf(text, sizeof text, "wheel %d: no slip, wrapped %.3f rad, pull ratio %.4g",
                  w.pulley, link.wrapAngle, w.ratio);
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

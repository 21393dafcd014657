// The Inspector's span table: a cable split by the wheels that grip it (no slip, capstan) and the
// polygons with friction into spans, each with its own tension (docs/wheels.md,
// docs/polygon_friction.md), and what each wheel or polygon between two spans does.
// Plain data and the text lines the panel shows, so that the tests read what a user reads.
#pragma once

#include <string>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab::ui {

struct SpanRow {
  int span = 0;
  double tension = 0;  ///< N
  double length = 0;   ///< m
  std::string text;    ///< the line the Inspector shows
};

/// One corner of a polygon with friction: the tensions on either side of it.
struct CornerRow {
  int vertex = -1;
  double turn = 0;          ///< rad, the angle the cable turns there
  double tensionIn = 0;     ///< N
  double tensionOut = 0;    ///< N
  double ratio = 0;         ///< larger / smaller of the two (0 if one is slack)
  double capstanRatio = 0;  ///< e^(mu theta_i): the most friction holds at this corner
  std::string text;         ///< the line the Inspector shows
};

/// The wheel (or polygon with friction) between spans `span` and `span` + 1.
struct WheelRow {
  int span = 0;
  int pulley = -1;
  Grip grip = Grip::NoSlip;
  double mu = 0;
  double wrapAngle = 0;     ///< rad
  double ratio = 0;         ///< larger / smaller of the two spans' tensions (0 if one is slack)
  double capstanRatio = 0;  ///< e^(mu theta): the most friction holds (capstan wheels)
  bool slipped = false;     ///< the last solve let the cable slide on the wheel
  std::string state;        ///< "no slip", "holding", "slipping"
  std::string text;         ///< the line the Inspector shows
  std::vector<CornerRow> corners;  ///< a polygon's engaged corners in path order (else none)
};

struct SpanTable {
  std::vector<SpanRow> spans;    ///< empty for a cable that is one span
  std::vector<WheelRow> wheels;  ///< spans.size() - 1 of them
};

/// The spans and wheels of `cable` as the Inspector lists them.
SpanTable spanTable(const Cable& cable);

}  // namespace cablelab::ui

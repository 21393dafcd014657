#include "ui/renderer.h"

#include <GL/gl.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ui/colormap.h"
#include "ui/label_layout.h"
#include "ui/palette.h"
#include "ui/scene_bounds.h"

namespace cablelab::ui {
namespace {

constexpr Colour kGridMinor{0.89f, 0.89f, 0.87f, 1};
constexpr Colour kGridAxis{0.72f, 0.72f, 0.70f, 1};
constexpr Colour kSelected{0.95f, 0.75f, 0.0f, 1};

struct BodyColours {
  Colour fill, outline;
};

BodyColours coloursFor(BodyType type) {
  switch (type) {
    case BodyType::Static:
      return {{0.76f, 0.79f, 0.72f, 1}, {0.36f, 0.41f, 0.31f, 1}};
    case BodyType::Kinematic:
      return {{0.66f, 0.78f, 0.95f, 1}, {0.2f, 0.35f, 0.62f, 1}};
    case BodyType::Dynamic:
      return {{0.98f, 0.80f, 0.56f, 1}, {0.62f, 0.36f, 0.1f, 1}};
  }
  return {{1, 0, 1, 1}, {0, 0, 0, 1}};
}

void colour(const Colour& c, float alpha = 1) {
  glColor4f(c[0], c[1], c[2], c[3] * alpha);
}
void vertex(const Vec2& p) {
  glVertex2d(p.x(), p.y());
}

/// Draws the stateless pieces in world coordinates; every size in pixels goes through `px`.
class Painter {
 public:
  Painter(const Camera& camera, ImDrawList* text, float scale)
      : cam_(camera), text_(text), scale_(scale) {}
  /// Metres of `pixels` screen pixels at the current line scale.
  double px(double pixels) const { return pixels * scale_ * cam_.metresPerPixel; }

  void line(const Vec2& a, const Vec2& b, const Colour& c, float width) const {
    glLineWidth(width * scale_);
    colour(c);
    glBegin(GL_LINES);
    if (keepOff_.empty()) {
      vertex(a);
      vertex(b);
    } else {  // an overlay: only its parts off the screen pieces (ui/overlay_clip.h), kept
      // half the line's width and its smoothed edge away from them
      const double grow = 0.5 * width * scale_ + 1;
      std::vector<LabelBox> grown = keepOff_;
      for (LabelBox& g : grown) g = {g.x0 - grow, g.y0 - grow, g.x1 + grow, g.y1 + grow};
      for (const ScreenSegment& s : partsOutside(cam_.toScreen(a), cam_.toScreen(b), grown)) {
        vertex(cam_.toWorld(s.a));
        vertex(cam_.toWorld(s.b));
        if (drawnLines_) drawnLines_->push_back(s);
      }
    }
    glEnd();
  }

  /// From now on lines keep off `boxes` (px), and what they draw is added to `drawn`.
  void keepOff(std::vector<LabelBox> boxes, std::vector<ScreenSegment>* drawn) const {
    keepOff_ = std::move(boxes);
    drawnLines_ = drawn;
  }

  /// Dashes of `on` px separated by `off` px; `phase` carries the pattern across segments.
  void dashed(const Vec2& a, const Vec2& b, const Colour& c, float width, double& phase) const {
    const double on = px(7), off = px(5), period = on + off;
    const double length = (b - a).norm();
    if (length <= 0) return;
    const Vec2 u = (b - a) / length;
    glLineWidth(width * scale_);
    colour(c);
    glBegin(GL_LINES);
    double s = -std::fmod(phase, period);
    for (; s < length; s += period) {
      const double s0 = std::max(s, 0.0), s1 = std::min(s + on, length);
      if (s1 > s0) {
        vertex(a + u * s0);
        vertex(a + u * s1);
      }
    }
    glEnd();
    phase += length;
  }

  void polygon(const std::vector<Vec2>& points, const Colour* fill, const Colour& outline,
               float width) const {
    if (points.size() < 2) return;
    if (fill) {
      colour(*fill);
      glBegin(GL_TRIANGLE_FAN);
      for (const Vec2& p : points) vertex(p);
      glEnd();
    }
    if (!keepOff_.empty()) {  // an overlay's outline, piece by piece
      for (size_t k = 0; k < points.size(); ++k)
        line(points[k], points[(k + 1) % points.size()], outline, width);
      return;
    }
    glLineWidth(width * scale_);
    colour(outline);
    glBegin(GL_LINE_LOOP);
    for (const Vec2& p : points) vertex(p);
    glEnd();
  }

  std::vector<Vec2> circlePoints(const Vec2& c, double r) const {
    const int n = std::clamp(static_cast<int>(r / cam_.metresPerPixel), 16, 64);
    std::vector<Vec2> points;
    points.reserve(n);
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      points.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
    }
    return points;
  }

  void disc(const Vec2& c, double r, const Colour& fill) const {
    colour(fill);
    glBegin(GL_TRIANGLE_FAN);
    for (const Vec2& p : circlePoints(c, r)) vertex(p);
    glEnd();
  }

  void square(const Vec2& c, double halfPixels, const Colour& fill) const {
    const double h = px(halfPixels);
    colour(fill);
    glBegin(GL_QUADS);
    vertex(c + Vec2(-h, -h));
    vertex(c + Vec2(h, -h));
    vertex(c + Vec2(h, h));
    vertex(c + Vec2(-h, h));
    glEnd();
  }

  void arrow(const Vec2& from, const Vec2& to, const Colour& c, float width) const {
    line(from, to, c, width);
    const double length = (to - from).norm();
    if (length < px(2)) return;
    const Vec2 u = (to - from) / length;
    const double head = std::min(px(10), 0.5 * length);
    line(to, to - head * rotate(u, 0.45), c, width);
    line(to, to - head * rotate(u, -0.45), c, width);
  }

  /// Queues a label at `world` + `offsetPx` (preferred place); placeLabels() draws them all.
  void label(const Vec2& world, const std::string& s, const Colour& c,
             Vec2 offsetPx = {6, -16}) const {
    if (!text_ || s.empty()) return;
    labels_.push_back({cam_.toScreen(world), offsetPx, s, c});
  }

  /// A body's shape (world points) that labels keep off.
  void obstacle(const std::vector<Vec2>& worldPoints) const {
    if (!text_) return;
    LabelObstacle& o = obstacles_.emplace_back();
    o.reserve(worldPoints.size());
    for (const Vec2& p : worldPoints) o.push_back(cam_.toScreen(p));
  }

  /// A cable's straight piece (world points) that labels keep off: a strip `halfPx` either
  /// side of it, reaching `halfPx` past its ends (the end dots).
  void strip(const Vec2& from, const Vec2& to, double halfPx) const {
    if (!text_) return;
    const Vec2 a = cam_.toScreen(from), b = cam_.toScreen(to);
    if ((b - a).norm() < 1e-9) return;
    const Vec2 along = halfPx * (b - a).normalized(), across(-along.y(), along.x());
    obstacles_.push_back(
        {a - along + across, b + along + across, b + along - across, a - along - across});
    ++strips_;
  }

  /// A marker (a target's or the statics' cross in its circle, `radiusPx` round `world`) that
  /// labels and their leader lines keep off as they keep off the bars: a label across the
  /// marker hides what it marks.
  void marker(const Vec2& world, double radiusPx) const {
    if (!text_) return;
    const Vec2 c = cam_.toScreen(world);
    const double r = radiusPx * scale_ + 2;  // the circle's line and a little room
    markers_.push_back({c.x() - r, c.y() - r, c.x() + r, c.y() + r});
  }

  /// Draws the queued labels where label_layout.h puts them inside `view` (px): off the bodies,
  /// each other, the markers and `reserved`, a leader line to those placed away from their
  /// anchor; a label with no such place is left out. Adds what it drew to `drawn`.
  void placeLabels(const LabelBox& view, std::vector<LabelBox> reserved, DrawnView& drawn) const {
    if (!text_) return;
    drawn.markers = markers_;
    reserved.insert(reserved.end(), markers_.begin(), markers_.end());
    // A thing out of view (a close-up's far weight, ui/presentation.h) has no label: a leader
    // line across the view to the edge would point at nothing.
    const auto outOfView = [&](const Label& l) {
      const Vec2& a = l.anchor;
      const bool out = a.x() < view.x0 || a.x() > view.x1 || a.y() < view.y0 || a.y() > view.y1;
      drawn.hiddenLabels += out;
      return out;
    };
    labels_.erase(std::remove_if(labels_.begin(), labels_.end(), outOfView), labels_.end());
    std::vector<LabelRequest> requests;
    requests.reserve(labels_.size());
    for (const Label& l : labels_) {
      const ImVec2 size = ImGui::CalcTextSize(l.text.c_str());
      requests.push_back({l.anchor, l.offset, size.x, size.y});
    }
    const auto placed = ui::placeLabels(requests, obstacles_, view, 4 * scale_, reserved);
    for (size_t k = 0; k < labels_.size(); ++k) {
      const LabelBox& b = placed[k].box;
      if (!placed[k].shown) {
        ++drawn.hiddenLabels;
        continue;
      }
      drawn.labels.push_back(b);
      for (size_t k2 = obstacles_.size() - strips_; k2 < obstacles_.size(); ++k2)
        if (crossesConvex(b, obstacles_[k2])) {
          ++drawn.labelsOnCables;
          break;
        }
      const ImU32 colour = toImU32(labels_[k].colour);
      if (placed[k].leader) {
        const Vec2& a = labels_[k].anchor;
        const ImVec2 near(static_cast<float>(std::clamp(a.x(), b.x0, b.x1)),
                          static_cast<float>(std::clamp(a.y(), b.y0, b.y1)));
        for (const ScreenSegment& s : partsOutside(a, Vec2(near.x, near.y), reserved)) {
          text_->AddLine(ImVec2(static_cast<float>(s.a.x()), static_cast<float>(s.a.y())),
                         ImVec2(static_cast<float>(s.b.x()), static_cast<float>(s.b.y())),
                         (colour & 0x00FFFFFF) | 0x99000000, scale_);
          drawn.overlayLines.push_back(s);
        }
      }
      text_->AddText(ImVec2(static_cast<float>(b.x0), static_cast<float>(b.y0)), colour,
                     labels_[k].text.c_str());
    }
    labels_.clear();
    obstacles_.clear();
    markers_.clear();
    strips_ = 0;
  }

  const Camera& camera() const { return cam_; }
  ImDrawList* text() const { return text_; }
  float scale() const { return scale_; }

 private:
  struct Label {
    Vec2 anchor, offset;  ///< px
    std::string text;
    Colour colour;
  };
  const Camera& cam_;
  ImDrawList* text_;
  float scale_;
  mutable std::vector<Label> labels_;
  mutable size_t strips_ = 0;  ///< the last obstacles_ are cables' strips
  mutable std::vector<LabelObstacle> obstacles_;
  mutable std::vector<LabelBox> markers_;  ///< px: kept clear like `reserved`
  mutable std::vector<LabelBox> keepOff_;  ///< the screen pieces overlay lines keep off
  mutable std::vector<ScreenSegment>* drawnLines_ = nullptr;
};

Vec2 bodyPoint(const World& world, int body, const Vec2& local) {
  if (body < 0) return local;
  const BodyState& s = world.body(body);
  return s.position + rotate(local, s.angle);
}

double gridStep(const Camera& cam) {
  return niceCeil(60.0 * cam.metresPerPixel);
}

void drawGrid(const Painter& paint) {
  const Camera& cam = paint.camera();
  const double step = gridStep(cam);
  const long i0 = static_cast<long>(std::floor(cam.left() / step));
  const long i1 = static_cast<long>(std::ceil(cam.right() / step));
  const long j0 = static_cast<long>(std::floor(cam.bottom() / step));
  const long j1 = static_cast<long>(std::ceil(cam.top() / step));
  if (i1 - i0 > 2000 || j1 - j0 > 2000) return;
  // Axis-aligned lines gain nothing from smoothing, and on a software rasteriser a smooth line
  // is a textured quad: the grid, the longest lines, draws without it.
  glDisable(GL_LINE_SMOOTH);
  for (long i = i0; i <= i1; ++i)
    paint.line({i * step, cam.bottom()}, {i * step, cam.top()}, i == 0 ? kGridAxis : kGridMinor, 1);
  for (long j = j0; j <= j1; ++j)
    paint.line({cam.left(), j * step}, {cam.right(), j * step}, j == 0 ? kGridAxis : kGridMinor, 1);
  glEnable(GL_LINE_SMOOTH);
}

void drawBodies(const World& world, const RenderOptions& options, const Painter& paint) {
  const auto& bodies = world.scene().bodies;
  for (int i = 0; i < world.bodyCount(); ++i) {
    const BodyColours c = coloursFor(bodies[i].type);
    const bool selected = i == options.selectedBody || i == world.draggedBody();
    const Colour& outline = selected ? kSelected : c.outline;
    const float width = selected ? 3.0f : 1.5f;
    for (const ShapeDef& shape : bodies[i].shapes) {
      Colour fill = c.fill;
      if (shape.sensor) fill[3] = 0.35f;
      if (shape.kind == ShapeDef::Kind::Circle) {
        const Vec2 centre = bodyPoint(world, i, shape.center);
        const std::vector<Vec2> rim = paint.circlePoints(centre, shape.radius);
        paint.polygon(rim, &fill, outline, width);
        paint.obstacle(rim);
        // A radius shows the rotation.
        const Vec2 edge = bodyPoint(world, i, shape.center + Vec2(shape.radius, 0));
        paint.line(centre, edge, outline, 1.0f);
      } else {
        std::vector<Vec2> points;
        for (const Vec2& v : shape.vertices) points.push_back(bodyPoint(world, i, v));
        paint.polygon(points, &fill, outline, width);
        paint.obstacle(points);
      }
    }
    if (options.labels && !bodies[i].name.empty() && bodies[i].type != BodyType::Static)
      paint.label(world.body(i).position, bodies[i].name, {0.3f, 0.3f, 0.3f, 1}, {4, 2});
  }
}

/// The polygon a polygon pulley wraps: its own vertices or the body's first polygon shape.
std::vector<Vec2> pulleyPolygon(const World& world, const PulleyDef& pulley) {
  std::vector<Vec2> local = pulley.vertices;
  const int body = findBodyIndex(world.scene(), pulley.body);
  if (local.empty() && body >= 0)
    for (const ShapeDef& s : world.scene().bodies[body].shapes)
      if (s.kind == ShapeDef::Kind::Polygon) {
        local = s.vertices;
        break;
      }
  for (Vec2& v : local) v = bodyPoint(world, body, v);
  return local;
}

/// Pulleys a cable is wrapped on now are drawn in full colour, the others faded.
void drawPulleys(const World& world, const Painter& paint) {
  const auto& cables = world.scene().cables;
  for (size_t c = 0; c < cables.size(); ++c)
    for (size_t k = 0; k < cables[c].pulleys.size(); ++k) {
      const PulleyDef& pulley = cables[c].pulleys[k];
      const bool engaged = static_cast<int>(c) < world.cableCount() &&
                           world.cable(static_cast<int>(c)).sceneEngaged(static_cast<int>(k));
      const Colour colour = engaged ? kPulley : kPulleyIdle;
      if (pulley.kind == PulleyDef::Kind::Polygon) {
        const std::vector<Vec2> points = pulleyPolygon(world, pulley);
        paint.polygon(points, nullptr, colour, 2.5f);
        for (const Vec2& p : points) paint.disc(p, paint.px(2.5), colour);
      } else if (pulley.kind == PulleyDef::Kind::Circle) {
        // A rim and a spoke: the spoke shows a wheel turning.
        const int body = findBodyIndex(world.scene(), pulley.body);
        const Vec2 c = bodyPoint(world, body, pulley.point);
        paint.polygon(paint.circlePoints(c, pulley.radius), nullptr, colour, 2.5f);
        paint.line(c, bodyPoint(world, body, pulley.point + Vec2(0, pulley.radius)), colour, 2.0f);
        paint.disc(c, paint.px(2.5), colour);
      } else {
        const Vec2 p = bodyPoint(world, findBodyIndex(world.scene(), pulley.body), pulley.point);
        const Colour white{1, 1, 1, 1};
        paint.disc(p, paint.px(6), colour);
        paint.disc(p, paint.px(3.5), white);
      }
    }
}

void drawJoints(const World& world, const Painter& paint) {
  for (int i = 0; i < world.jointCount(); ++i) {
    const JointState j = world.joint(i);
    const JointDef& def = world.scene().joints[i];
    paint.line(j.anchorA, j.anchorB, kJoint, 1.5f);
    switch (j.kind) {
      case JointDef::Kind::Revolute:
        paint.polygon(paint.circlePoints(j.anchorB, paint.px(5)), nullptr, kJoint, 2.0f);
        break;
      case JointDef::Kind::Prismatic: {
        const Vec2 axis = def.axis.norm() > 0 ? Vec2(def.axis.normalized()) : Vec2(1, 0);
        paint.line(j.anchorB - paint.px(14) * axis, j.anchorB + paint.px(14) * axis, kJoint, 2.0f);
        paint.square(j.anchorB, 3, kJoint);
        break;
      }
      case JointDef::Kind::Weld:
        paint.square(j.anchorB, 4, kJoint);
        break;
    }
  }
}

/// Half the width (px) of the strip labels keep off along a cable's line `width` wide (2 px clear).
double cableStripHalfWidth(float width, const Painter& paint) {
  return 0.5 * width * paint.scale() + 2;
}

/// The cable lying on a circle: from the tangent point round by the wrap angle (an interior
/// circle), or the turns wound on a drum (a path's end). Each whole turn after the first is a
/// ring of its own, a line's width and a gap outside the one before (up to three), and the
/// count is labelled ("2 turns"): drawn over each other, two turns read as one.
void drawCableArc(const WrapPoint& p, bool atStart, bool atEnd, const Colour& colour, float width,
                  const Painter& paint) {
  const double r = std::abs(p.radius), s = p.radius > 0 ? -1.0 : 1.0;  // s: angle's sense
  const Vec2 t = atStart ? p.tangentOut : p.tangentIn;
  const double from = std::atan2(t.y() - p.world.y(), t.x() - p.world.x());
  // A path's start on a drum: the wound part runs backwards from where the cable leaves.
  const double sense = atStart ? -s : s;
  const double arc = std::max(0.0, p.arc);
  const int loops = std::min(3, static_cast<int>(arc / (2 * M_PI) + 1e-6));
  const double gap = paint.px(width + 3);  // ring to ring: the line's width and 3 px clear
  // On the rim, joining the straight pieces: the part of a turn and the first whole turn; the
  // other whole turns outside it.
  const double perRing = std::max(48.0, 2 * M_PI * r / paint.px(4));  // a piece every 4 px
  for (int ring = 0; ring < std::max(loops, 1); ++ring) {
    const double span = ring == 0 ? arc - 2 * M_PI * std::max(loops - 1, 0) : 2 * M_PI;
    if (span <= 1e-9) continue;
    const double radius = r + gap * ring;
    const int n = std::max(2, static_cast<int>(perRing * span / (2 * M_PI)) + 1);
    Vec2 previous = p.world + radius * Vec2(std::cos(from), std::sin(from));
    for (int i = 1; i <= n; ++i) {
      const double a = from + sense * span * i / n;
      const Vec2 next = p.world + radius * Vec2(std::cos(a), std::sin(a));
      paint.line(previous, next, colour, width);
      paint.strip(previous, next, cableStripHalfWidth(width, paint));  // labels keep off it too
      previous = next;
    }
  }
  if (loops == 0) return;
  const double turns = std::round(arc / M_PI) / 2;  // to a half turn
  char text[32];
  std::snprintf(text, sizeof text, turns == 1 ? "%.3g turn" : "%.3g turns", turns);
  paint.label(p.world + Vec2(r + gap * (loops - 1), 0), text, {0.3f, 0.3f, 0.3f, 1}, {6, -8});
}

/// The arrow length per newton of the force arrows: the colour bar's top tension is a tenth
/// of the view's height.
double metresPerNewton(const Camera& cam, double scale) {
  return 0.1 * cam.height * cam.metresPerPixel / std::max(scale, 1e-9);
}

void drawCables(const World& world, const RenderOptions& options, double scale,
                const Painter& paint) {
  constexpr Colour kPlain{0.25f, 0.25f, 0.3f, 1};
  for (int i = 0; i < world.cableCount(); ++i) {
    const Cable& cable = world.cable(i);
    const auto& path = cable.path();
    const bool selected = i == options.selectedCable;
    const float width = selected ? 4.5f : 3.0f;
    const bool stretched = options.overstretch && overstretched(cable);
    if (stretched)  // a wide red halo under the cable
      for (size_t k = 1; k < path.size(); ++k)
        paint.line(path[k - 1].world, path[k].world, kStretchHalo, 12.0f);
    double phase = 0;
    // Straight pieces run between tangent points; each carries its span's tension.
    for (size_t k = 1; k < path.size(); ++k) {
      const Vec2 from = path[k - 1].radius == 0 ? path[k - 1].world : path[k - 1].tangentOut;
      const Vec2 to = path[k].radius == 0 ? path[k].world : path[k].tangentIn;
      const double tension = cable.segmentTension(k - 1);
      paint.strip(from, to, cableStripHalfWidth(width, paint));
      if (tension <= 0)
        paint.dashed(from, to, kSlack, width - 1, phase);
      else
        paint.line(from, to, options.tensions ? tensionColour(tension / scale) : kPlain, width);
    }
    for (size_t k = 0; k < path.size(); ++k)
      if (path[k].radius != 0)
        drawCableArc(path[k], k == 0, k + 1 == path.size(),
                     options.tensions
                         ? tensionColour(cable.segmentTension(k == 0 ? 0 : k - 1) / scale)
                         : kPlain,
                     width, paint);
    if (options.wrapPoints)
      for (const WrapPoint& p : path) {
        const Colour dark{0.15f, 0.15f, 0.15f, 1};
        if (p.kind == WrapPoint::Kind::Anchor)
          paint.disc(p.world, paint.px(3.5), dark);
        else
          paint.square(p.world, 3, dark);
      }
    if (options.forces && path.size() >= 2 && !cable.slack() && cable.tension() > 0) {
      // The cable pulls each end body along its first (last) segment.
      const double l = cable.tension() * metresPerNewton(paint.camera(), scale);
      for (int end = 0; end < 2; ++end) {
        const Vec2 a = end == 0 ? path[0].world : path.back().world;
        const Vec2 b = end == 0 ? path[1].world : path[path.size() - 2].world;
        if ((b - a).norm() > 1e-12) paint.arrow(a, a + l * (b - a).normalized(), kForceArrow, 2.0f);
      }
    }
    if (stretched && !path.empty()) {
      char text[96];
      std::snprintf(text, sizeof text, "%s overstretched +%.3f m", cable.name().c_str(),
                    cable.length() - cable.restLength());
      paint.label(path[path.size() / 2].world, text, {0.8f, 0.0f, 0.1f, 1});
    } else if (selected && !path.empty()) {
      paint.label(path.front().world, cable.name(), kSlack);
    }
  }
}

void drawOverlay(const Overlay& overlay, const Painter& paint) {
  for (const Overlay::Arrow& a : overlay.arrows) {
    paint.arrow(a.from, a.to, a.colour, 2.0f);
    paint.label(a.to, a.label, a.colour);
  }
  for (const Overlay::Target& t : overlay.targets) {
    const double s = paint.px(8);
    paint.line(t.position + Vec2(-s, -s), t.position + Vec2(s, s), t.colour, 2.5f);
    paint.line(t.position + Vec2(-s, s), t.position + Vec2(s, -s), t.colour, 2.5f);
    paint.polygon(paint.circlePoints(t.position, paint.px(11)), nullptr, t.colour, 1.5f);
    paint.marker(t.position, 11);
    paint.label(t.position, t.label, t.colour, t.labelOffset);
  }
  for (const Overlay::Text& t : overlay.texts) paint.label(t.position, t.text, t.colour, {0, 0});
}

/// Where labels may not go: the screen pieces, and a collapsed side panel's title bar reaching
/// into the top of the free area (`keyTop` tall).
std::vector<LabelBox> reservedForLabels(const FurnitureLayout& furniture,
                                        const RenderOptions& options) {
  std::vector<LabelBox> reserved = furniture.occupied();
  if (options.keyTop > 0)
    reserved.push_back(
        {furniture.x, furniture.y, furniture.x + furniture.w, furniture.y + options.keyTop});
  return reserved;
}

}  // namespace

bool overstretched(const Cable& cable) {
  const double over = cable.length() - cable.restLength();
  return cable.elastic() ? over > kOverstretchElastic * cable.restLength() : over > kOverstretch;
}

double tensionScaleFor(const World& world, const RenderOptions& options) {
  if (options.tensionScale > 0) return options.tensionScale;
  double largest = 0;
  for (int i = 0; i < world.cableCount(); ++i)
    if (std::isfinite(world.cable(i).tension()))
      largest = std::max(largest, world.cable(i).tension());
  return niceCeil(largest);
}

DrawnView drawWorld(const World& world, const Camera& camera, const Overlay& overlay,
                    const RenderOptions& options, ImDrawList* text) {
  glClearColor(kBackground[0], kBackground[1], kBackground[2], kBackground[3]);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_TEXTURE_2D);
  const bool clip = options.clipToFree && options.freeWidth > 0 && options.freeHeight > 0;
  if (clip) {  // GL's window origin is the bottom left
    glEnable(GL_SCISSOR_TEST);
    glScissor(static_cast<GLint>(options.freeX),
              static_cast<GLint>(camera.height - options.freeY - options.freeHeight),
              static_cast<GLsizei>(options.freeWidth), static_cast<GLsizei>(options.freeHeight));
  } else {
    glDisable(GL_SCISSOR_TEST);
  }
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_LINE_SMOOTH);
  glHint(GL_LINE_SMOOTH_HINT, GL_NICEST);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(camera.left(), camera.right(), camera.bottom(), camera.top(), -1, 1);

  const Painter paint(camera, text, std::max(options.lineScale, 0.25f));
  const double scale = tensionScaleFor(world, options);
  DrawnView drawn;
  drawn.scene = screenBox(sceneBounds(world), camera);
  drawn.furniture = layoutFurniture(world, overlay, options, camera, text != nullptr, drawn.scene);
  if (options.grid) drawGrid(paint);
  drawBodies(world, options, paint);
  drawPulleys(world, paint);
  drawJoints(world, paint);
  drawCables(world, options, scale, paint);
  paint.keepOff(reservedForLabels(drawn.furniture, options), &drawn.overlayLines);
  drawOverlay(overlay, paint);
  paint.keepOff({}, nullptr);
  const bool free = options.freeWidth > 0 && options.freeHeight > 0;
  paint.placeLabels(
      free ? LabelBox{options.freeX, options.freeY, options.freeX + options.freeWidth,
                      options.freeY + options.freeHeight}
           : LabelBox{0, 0, static_cast<double>(camera.width), static_cast<double>(camera.height)},
      reservedForLabels(drawn.furniture, options), drawn);
  drawFurniture(drawn.furniture, overlay, options, scale, camera, text);
  glDisable(GL_LINE_SMOOTH);
  glDisable(GL_SCISSOR_TEST);
  return drawn;
}

}  // namespace cablelab::ui

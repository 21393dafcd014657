#include "ui/renderer.h"

#include <GL/gl.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ui/colormap.h"
#include "ui/label_layout.h"

namespace cablelab::ui {
namespace {

constexpr Colour kBackground{0.97f, 0.97f, 0.95f, 1};
constexpr Colour kGridMinor{0.89f, 0.89f, 0.87f, 1};
constexpr Colour kGridAxis{0.72f, 0.72f, 0.70f, 1};
constexpr Colour kSlack{0.55f, 0.55f, 0.55f, 1};
constexpr Colour kPulley{0.9f, 0.45f, 0.0f, 1};
constexpr Colour kPulleyIdle{0.95f, 0.75f, 0.55f, 1};  // a pulley the cable does not touch now
constexpr Colour kJoint{0.25f, 0.25f, 0.3f, 1};
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

ImU32 toImU32(const Colour& c) {
  auto b = [](float v) { return static_cast<int>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
  return IM_COL32(b(c[0]), b(c[1]), b(c[2]), b(c[3]));
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
    vertex(a);
    vertex(b);
    glEnd();
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

  /// Draws the queued labels where label_layout.h puts them inside `view` (px): off the bodies
  /// and each other, a leader line to those placed away from their anchor.
  void placeLabels(const LabelBox& view) const {
    if (!text_) return;
    std::vector<LabelRequest> requests;
    requests.reserve(labels_.size());
    for (const Label& l : labels_) {
      const ImVec2 size = ImGui::CalcTextSize(l.text.c_str());
      requests.push_back({l.anchor, l.offset, size.x, size.y});
    }
    const auto placed = ui::placeLabels(requests, obstacles_, view, 4 * scale_);
    for (size_t k = 0; k < labels_.size(); ++k) {
      const LabelBox& b = placed[k].box;
      const ImU32 colour = toImU32(labels_[k].colour);
      if (placed[k].leader) {
        const Vec2& a = labels_[k].anchor;
        const ImVec2 near(static_cast<float>(std::clamp(a.x(), b.x0, b.x1)),
                          static_cast<float>(std::clamp(a.y(), b.y0, b.y1)));
        text_->AddLine(ImVec2(static_cast<float>(a.x()), static_cast<float>(a.y())), near,
                       (colour & 0x00FFFFFF) | 0x99000000, scale_);
      }
      text_->AddText(ImVec2(static_cast<float>(b.x0), static_cast<float>(b.y0)), colour,
                     labels_[k].text.c_str());
    }
    labels_.clear();
    obstacles_.clear();
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
  mutable std::vector<LabelObstacle> obstacles_;
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
                           world.cable(static_cast<int>(c)).engaged(static_cast<int>(k));
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

/// The cable lying on a circle: from the tangent point round by the wrap angle (an interior
/// circle), or the turns wound on a drum (a path's end), drawn as one turn a little outside the
/// rim per extra turn, up to three.
void drawCableArc(const WrapPoint& p, bool atStart, bool atEnd, const Colour& colour, float width,
                  const Painter& paint) {
  const double r = std::abs(p.radius), s = p.radius > 0 ? -1.0 : 1.0;  // s: angle's sense
  const Vec2 t = atStart ? p.tangentOut : p.tangentIn;
  const double from = std::atan2(t.y() - p.world.y(), t.x() - p.world.x());
  // A path's start on a drum: the wound part runs backwards from where the cable leaves.
  const double sense = atStart ? -s : s;
  const double arc = std::max(0.0, p.arc);
  const int loops = std::min(3, static_cast<int>(arc / (2 * M_PI)));
  for (int loop = 0; loop <= loops; ++loop) {
    const double span = loop < loops ? 2 * M_PI : arc - 2 * M_PI * loops;
    const double radius = r + (atStart || atEnd ? paint.px(2.5) * loop : 0.0);
    const int n = std::max(2, static_cast<int>(48 * span / (2 * M_PI)) + 1);
    Vec2 previous = p.world + radius * Vec2(std::cos(from), std::sin(from));
    for (int i = 1; i <= n; ++i) {
      const double a = from + sense * span * i / n;
      const Vec2 next = p.world + radius * Vec2(std::cos(a), std::sin(a));
      paint.line(previous, next, colour, width);
      previous = next;
    }
  }
}

/// The arrow length per newton of the force arrows: the colour bar's top tension is a tenth
/// of the view's height.
double metresPerNewton(const Camera& cam, double scale) {
  return 0.1 * cam.height * cam.metresPerPixel / std::max(scale, 1e-9);
}

void drawCables(const World& world, const RenderOptions& options, double scale,
                const Painter& paint) {
  constexpr Colour kPlain{0.25f, 0.25f, 0.3f, 1};
  constexpr Colour kStretch{0.9f, 0.0f, 0.1f, 0.35f};
  for (int i = 0; i < world.cableCount(); ++i) {
    const Cable& cable = world.cable(i);
    const auto& path = cable.path();
    const bool selected = i == options.selectedCable;
    const float width = selected ? 4.5f : 3.0f;
    const bool stretched = options.overstretch && overstretched(cable);
    if (stretched)  // a wide red halo under the cable
      for (size_t k = 1; k < path.size(); ++k)
        paint.line(path[k - 1].world, path[k].world, kStretch, 12.0f);
    double phase = 0;
    // Straight pieces run between tangent points; each carries its span's tension.
    for (size_t k = 1; k < path.size(); ++k) {
      const Vec2 from = path[k - 1].radius == 0 ? path[k - 1].world : path[k - 1].tangentOut;
      const Vec2 to = path[k].radius == 0 ? path[k].world : path[k].tangentIn;
      const double tension = cable.segmentTension(k - 1);
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
      const Colour arrow{0.55f, 0.1f, 0.6f, 1};
      for (int end = 0; end < 2; ++end) {
        const Vec2 a = end == 0 ? path[0].world : path.back().world;
        const Vec2 b = end == 0 ? path[1].world : path[path.size() - 2].world;
        if ((b - a).norm() > 1e-12) paint.arrow(a, a + l * (b - a).normalized(), arrow, 2.0f);
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
    paint.label(t.position, t.label, t.colour, {12, -18});
  }
  for (const Overlay::Text& t : overlay.texts) paint.label(t.position, t.text, t.colour, {0, 0});
}

std::string format(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, value);
  return buffer;
}

/// The free screen rectangle (px) the screen-space pieces are placed in.
struct Frame {
  float x, y, w, h;
  float lineHeight;  ///< of the text font (px)
};

void quad(float x0, float y0, float x1, float y1) {
  glBegin(GL_QUADS);
  glVertex2f(x0, y0);
  glVertex2f(x1, y0);
  glVertex2f(x1, y1);
  glVertex2f(x0, y1);
  glEnd();
}

void drawScaleBar(const Camera& cam, const Frame& f, ImDrawList* text) {
  const double step = gridStep(cam);
  const float length = static_cast<float>(step / cam.metresPerPixel);
  const float x0 = f.x + 16, y0 = f.y + f.h - 18;
  glLineWidth(2.0f);
  glColor4f(0.15f, 0.15f, 0.15f, 1);
  glBegin(GL_LINES);
  glVertex2f(x0, y0);
  glVertex2f(x0 + length, y0);
  glVertex2f(x0, y0 - 5);
  glVertex2f(x0, y0 + 5);
  glVertex2f(x0 + length, y0 - 5);
  glVertex2f(x0 + length, y0 + 5);
  glEnd();
  if (text)
    text->AddText(ImVec2(x0 + length + 6, y0 - 0.5f * f.lineHeight), IM_COL32(40, 40, 40, 255),
                  (format("%g", step) + " m").c_str());
}

/// A horizontal colour bar in the bottom-right corner, where scenes are seldom drawn.
void drawTensionBar(double scale, const Frame& f, ImDrawList* text) {
  const float lh = f.lineHeight, barH = std::max(10.0f, 0.7f * lh);
  const float barW = std::clamp(0.3f * f.w, 90.0f, 12 * lh);
  const float slackW = text ? ImGui::CalcTextSize("slack").x + 34 : 80;
  const float x0 = f.x + f.w - barW - 24, y0 = f.y + f.h - 1.6f * lh - barH;
  glColor4f(kBackground[0], kBackground[1], kBackground[2], 0.85f);
  quad(x0 - slackW - 8, y0 - 1.5f * lh, x0 + barW + 20, y0 + barH + 1.5f * lh);
  glBegin(GL_QUADS);
  const int n = 32;
  for (int k = 0; k < n; ++k) {
    const float a = static_cast<float>(k) / n, b = static_cast<float>(k + 1) / n;
    colour(tensionColour(a));
    glVertex2f(x0 + barW * a, y0 + barH);
    glVertex2f(x0 + barW * a, y0);
    colour(tensionColour(b));
    glVertex2f(x0 + barW * b, y0);
    glVertex2f(x0 + barW * b, y0 + barH);
  }
  glEnd();
  glLineWidth(1.0f);
  glColor4f(0.2f, 0.2f, 0.2f, 1);
  glBegin(GL_LINE_LOOP);
  glVertex2f(x0, y0);
  glVertex2f(x0 + barW, y0);
  glVertex2f(x0 + barW, y0 + barH);
  glVertex2f(x0, y0 + barH);
  glEnd();
  glBegin(GL_LINES);
  for (int k = 0; k <= 4; ++k) {
    glVertex2f(x0 + barW * k / 4.0f, y0 + barH);
    glVertex2f(x0 + barW * k / 4.0f, y0 + barH + 3);
  }
  // Slack sample, left of the bar: a dashed grey stroke.
  glColor4f(kSlack[0], kSlack[1], kSlack[2], 1);
  for (int k = 0; k < 3; ++k) {
    glVertex2f(x0 - slackW + 8.0f * k, y0 + 0.5f * barH);
    glVertex2f(x0 - slackW + 5 + 8.0f * k, y0 + 0.5f * barH);
  }
  glEnd();
  if (!text) return;
  const ImU32 ink = IM_COL32(40, 40, 40, 255);
  text->AddText(ImVec2(x0, y0 - 1.25f * lh), ink, "tension (N)");
  text->AddText(ImVec2(x0 - slackW + 28, y0 + 0.5f * (barH - lh)), ink, "slack");
  for (int k = 0; k <= 4; k += 2) {
    const std::string label = format("%.3g", scale * k / 4);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    text->AddText(ImVec2(x0 + barW * k / 4.0f - 0.5f * w, y0 + barH + 4), ink, label.c_str());
  }
}

/// One row of the marker key: which sample to draw, its colour, its text.
struct KeyRow {
  enum class Sample {
    Anchor,
    WrapPoint,
    PointPulley,
    PulleyInUse,
    PulleyIdle,
    Cross,
    Arrow,
    DashedCross,
    Stretch
  };
  Sample sample;
  Colour colour;
  std::string label;
};

void drawSample(const KeyRow& row, float cx, float cy, float s) {
  const Colour& c = row.colour;
  auto disc = [&](float r, const Colour& fill) {
    colour(fill);
    glBegin(GL_TRIANGLE_FAN);
    for (int k = 0; k < 20; ++k)
      glVertex2f(cx + r * std::cos(2 * M_PI * k / 20), cy + r * std::sin(2 * M_PI * k / 20));
    glEnd();
  };
  auto segment = [&](float x0, float y0, float x1, float y1, float width) {
    glLineWidth(width * s);
    colour(c);
    glBegin(GL_LINES);
    glVertex2f(x0, y0);
    glVertex2f(x1, y1);
    glEnd();
  };
  const float h = 8 * s;
  switch (row.sample) {
    case KeyRow::Sample::Anchor:
      disc(3.5f * s, c);
      break;
    case KeyRow::Sample::WrapPoint:
      colour(c);
      quad(cx - 3 * s, cy - 3 * s, cx + 3 * s, cy + 3 * s);
      break;
    case KeyRow::Sample::PointPulley:
      disc(6 * s, c);
      disc(3.5f * s, {1, 1, 1, 1});
      break;
    case KeyRow::Sample::PulleyInUse:
    case KeyRow::Sample::PulleyIdle:
      segment(cx - h, cy, cx + h, cy, 2.5f);
      break;
    case KeyRow::Sample::Stretch:
      segment(cx - h, cy, cx + h, cy, 10.0f);
      break;
    case KeyRow::Sample::Arrow:
      segment(cx - h, cy, cx + h, cy, 2);
      segment(cx + h, cy, cx + h - 0.6f * h, cy - 0.4f * h, 2);
      segment(cx + h, cy, cx + h - 0.6f * h, cy + 0.4f * h, 2);
      break;
    case KeyRow::Sample::Cross:
    case KeyRow::Sample::DashedCross:
      segment(cx - 0.8f * h, cy - 0.8f * h, cx + 0.8f * h, cy + 0.8f * h, 2.5f);
      segment(cx - 0.8f * h, cy + 0.8f * h, cx + 0.8f * h, cy - 0.8f * h, 2.5f);
      break;
  }
}

/// The key of every marker on screen, top-right of the free area.
void drawMarkerKey(const World& world, const Overlay& overlay, const RenderOptions& options,
                   const Frame& f, ImDrawList* text) {
  if (!text) return;
  std::vector<KeyRow> rows;
  bool point = false, polygon = false, stretched = false;
  for (const CableDef& c : world.scene().cables)
    for (const PulleyDef& p : c.pulleys)
      (p.kind == PulleyDef::Kind::Point ? point : polygon) = true;
  for (int i = 0; i < world.cableCount(); ++i) stretched |= overstretched(world.cable(i));
  const Colour dark{0.15f, 0.15f, 0.15f, 1};
  if (options.wrapPoints && world.cableCount() > 0) {
    rows.push_back({KeyRow::Sample::Anchor, dark, "cable end"});
    rows.push_back({KeyRow::Sample::WrapPoint, dark, "wrap point"});
  }
  if (point) rows.push_back({KeyRow::Sample::PointPulley, kPulley, "point pulley"});
  if (polygon) {
    rows.push_back({KeyRow::Sample::PulleyInUse, kPulley, "pulley, cable on it"});
    rows.push_back({KeyRow::Sample::PulleyIdle, kPulleyIdle, "pulley, cable off it"});
  }
  bool revolute = false;
  for (const JointDef& j : world.scene().joints) revolute |= j.kind == JointDef::Kind::Revolute;
  if (revolute) rows.push_back({KeyRow::Sample::PointPulley, kJoint, "revolute joint"});
  if (options.forces && world.cableCount() > 0)
    rows.push_back({KeyRow::Sample::Arrow, {0.55f, 0.1f, 0.6f, 1}, "cable force"});
  if (options.overstretch && stretched)
    rows.push_back({KeyRow::Sample::Stretch, {0.9f, 0.0f, 0.1f, 0.35f}, "overstretched cable"});
  for (const Overlay::Key& k : overlay.keys) {
    const KeyRow::Sample sample =
        k.marker == Overlay::Key::Marker::Arrow ? KeyRow::Sample::Arrow : KeyRow::Sample::Cross;
    rows.push_back({sample, k.colour, k.label});
  }
  if (rows.empty()) return;
  const float lh = f.lineHeight, s = options.lineScale, sampleW = 24 * s;
  float width = 0;
  for (const KeyRow& r : rows) width = std::max(width, ImGui::CalcTextSize(r.label.c_str()).x);
  // The key gives way on a small view: it would hide the scene (the View toggle brings it back
  // once the window is larger).
  if (width + sampleW + 16 > 0.4f * f.w) return;
  const float x1 = f.x + f.w - 8, x0 = x1 - width - sampleW - 16, y0 = f.y + 8 + options.keyTop;
  const float rowH = std::max(lh + 2, 16 * s);
  glColor4f(kBackground[0], kBackground[1], kBackground[2], 0.85f);
  quad(x0, y0, x1, y0 + rows.size() * rowH + 8);
  for (size_t k = 0; k < rows.size(); ++k) {
    const float cy = y0 + 4 + (k + 0.5f) * rowH;
    drawSample(rows[k], x0 + 6 + 0.5f * sampleW, cy, s);
    text->AddText(ImVec2(x0 + 10 + sampleW, cy - 0.5f * lh), IM_COL32(40, 40, 40, 255),
                  rows[k].label.c_str());
  }
}

/// A pale yellow strip across the top of the free area.
void drawBanner(const std::string& banner, const Frame& f, ImDrawList* text) {
  if (banner.empty() || !text) return;
  const ImVec2 size = ImGui::CalcTextSize(banner.c_str(), nullptr, false, f.w - 40);
  const float w = size.x + 20, x0 = f.x + 0.5f * (f.w - w), y0 = f.y + 6;
  glColor4f(1.0f, 0.91f, 0.55f, 0.95f);
  quad(x0, y0, x0 + w, y0 + size.y + 10);
  glLineWidth(1.5f);
  glColor4f(0.7f, 0.45f, 0.0f, 1);
  glBegin(GL_LINE_LOOP);
  glVertex2f(x0, y0);
  glVertex2f(x0 + w, y0);
  glVertex2f(x0 + w, y0 + size.y + 10);
  glVertex2f(x0, y0 + size.y + 10);
  glEnd();
  text->AddText(nullptr, 0, ImVec2(x0 + 10, y0 + 5), IM_COL32(90, 50, 0, 255), banner.c_str(),
                nullptr, f.w - 40);
}

/// Screen-space pieces: the orthographic matrix is switched to pixels (y down).
void drawScreenSpace(const World& world, const Overlay& overlay, const RenderOptions& options,
                     double scale, const Camera& cam, ImDrawList* text) {
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, cam.width, cam.height, 0, -1, 1);
  const bool whole = options.freeWidth <= 0 || options.freeHeight <= 0;
  Frame f{whole ? 0.0f : options.freeX, whole ? 0.0f : options.freeY,
          whole ? cam.width : options.freeWidth, whole ? cam.height : options.freeHeight,
          text ? ImGui::GetTextLineHeight() : 13.0f};
  if (text)
    for (size_t i = 0; i < overlay.notes.size(); ++i)
      text->AddText(ImVec2(f.x + 8, f.y + 8 + (f.lineHeight + 2) * i), IM_COL32(40, 40, 40, 255),
                    overlay.notes[i].c_str());
  if (options.grid) drawScaleBar(cam, f, text);
  if (options.legend && world.cableCount() > 0) drawTensionBar(scale, f, text);
  if (options.markerLegend) drawMarkerKey(world, overlay, options, f, text);
  drawBanner(overlay.banner, f, text);
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

void drawWorld(const World& world, const Camera& camera, const Overlay& overlay,
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
  if (options.grid) drawGrid(paint);
  drawBodies(world, options, paint);
  drawPulleys(world, paint);
  drawJoints(world, paint);
  drawCables(world, options, scale, paint);
  drawOverlay(overlay, paint);
  const bool free = options.freeWidth > 0 && options.freeHeight > 0;
  paint.placeLabels(
      free ? LabelBox{options.freeX, options.freeY, options.freeX + options.freeWidth,
                      options.freeY + options.freeHeight}
           : LabelBox{0, 0, static_cast<double>(camera.width), static_cast<double>(camera.height)});
  drawScreenSpace(world, overlay, options, scale, camera, text);
  glDisable(GL_LINE_SMOOTH);
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace cablelab::ui

// Spans: a cable split by the wheels that grip it (no slip, capstan), docs/wheels.md.
//
// Each span runs from one end or gripping wheel to the next; at a wheel it ends on a material
// mark of the wheel, so its length counts the arc from the tangent point to the mark and the
// wheel's angle enters its constraint. The mark is moved back to the middle of the contact at
// every update, with the rest lengths shifted by the same r dphi, so the constraint values do not
// change and the arcs stay bounded however far the wheel turns. When the solver let the cable
// slide on a wheel, the rest lengths of its two spans are shared out again (the slide stays).
#include <cmath>

#include "engine/cable/cable.h"

namespace cablelab {

void Cable::splitIntoSpans(std::span<const BodyState> bodies, const std::vector<size_t>& splits) {
  double total = params_.restLength;
  if (!spans_.empty()) {
    total = 0;
    for (const Span& s : spans_) total += s.rest;
  }
  spans_.assign(splits.size() + 1, Span{});
  links_.assign(splits.size(), SpanLink{});
  std::vector<WrapPoint> wheels;  // each split wheel with its mark at the contact's middle
  for (size_t k = 0; k < splits.size(); ++k) {
    WrapPoint w = path_[splits[k]];
    const double s = w.radius > 0 ? 1.0 : -1.0;
    const Vec2 t = w.tangentIn - w.world;
    const double beta = std::atan2(t.y(), t.x());
    const double angle = w.body >= 0 ? bodies[w.body].angle : 0.0;
    w.mark = beta - s * 0.5 * w.arc - angle;
    w.arc *= 0.5;
    wheels.push_back(w);
    const PulleyDef& pd = def_->pulleys[w.pulley];
    links_[k] = {w.pulley, pd.grip, pd.mu, 2 * w.arc, false};
  }
  double lengths = 0;
  for (size_t k = 0; k < spans_.size(); ++k) {
    Span& span = spans_[k];
    span.first = k == 0 ? 0 : splits[k - 1];
    span.last = k == splits.size() ? path_.size() - 1 : splits[k];
    span.path.assign(path_.begin() + span.first, path_.begin() + span.last + 1);
    if (k > 0) span.path.front() = wheels[k - 1];
    if (k < splits.size()) span.path.back() = wheels[k];
    cableLengthJacobian(span.path, bodies, span.kin);
    span.tension = tension_;
    lengths += span.kin.length;
  }
  // The stretch is shared in proportion to the spans' lengths.
  const double excess = lengths - total;
  for (Span& span : spans_)
    span.rest = span.kin.length - (lengths > 0 ? excess * span.kin.length / lengths : 0.0);
}

// Moves each wheel's mark to the middle of its contact, shifting rest length to match.
void Cable::rebaseMarks() {
  for (size_t k = 0; k < links_.size(); ++k) {
    WrapPoint& in = spans_[k].path.back();
    WrapPoint& out = spans_[k + 1].path.front();
    const double wrap = in.arc + out.arc;
    const double shift = in.arc - 0.5 * wrap;
    const double r = std::abs(in.radius), s = in.radius > 0 ? 1.0 : -1.0;
    in.mark += s * shift;
    out.mark = in.mark;
    in.arc -= shift;
    out.arc += shift;
    spans_[k].rest -= r * shift;
    spans_[k + 1].rest += r * shift;
    spans_[k].kin.length -= r * shift;
    spans_[k + 1].kin.length += r * shift;
    links_[k].wrapAngle = wrap;
  }
}

void Cable::updateSpans(std::span<const BodyState> bodies) {
  std::vector<size_t> splits;
  std::vector<int> ids;
  for (size_t i = 1; i + 1 < path_.size(); ++i)
    if (path_[i].pulley >= 0 && pulleys_[path_[i].pulley].grips) {
      splits.push_back(i);
      ids.push_back(path_[i].pulley);
    }
  if (splits.empty()) {
    if (!spans_.empty()) {
      double total = 0;
      for (const Span& s : spans_) total += s.rest;
      params_.restLength = total;
    }
    spans_.clear();
    links_.clear();
    splitPulleys_.clear();
    return;
  }
  if (ids != splitPulleys_ || spans_.empty()) {
    splitIntoSpans(bodies, splits);
    splitPulleys_ = ids;
    return;
  }
  for (size_t k = 0; k < spans_.size(); ++k) {
    Span& span = spans_[k];
    const WrapPoint front = span.path.front(), back = span.path.back();
    span.first = k == 0 ? 0 : splits[k - 1];
    span.last = k + 1 == spans_.size() ? path_.size() - 1 : splits[k];
    span.path.assign(path_.begin() + span.first, path_.begin() + span.last + 1);
    // A wheel's mark and arc on each side belong to the span, not to the whole path.
    if (k > 0) span.path.front().mark = front.mark, span.path.front().arc = front.arc;
    if (k + 1 < spans_.size()) span.path.back().mark = back.mark, span.path.back().arc = back.arc;
    cableLengthJacobian(span.path, bodies, span.kin);
  }
  // After a slide, the two spans share their stretch again: the slide is kept.
  for (size_t k = 0; k < links_.size(); ++k) {
    if (!links_[k].slipped) continue;
    const double excess = spanStretch(static_cast<int>(k)) + spanStretch(static_cast<int>(k) + 1);
    spans_[k].rest = spans_[k].kin.length - 0.5 * excess;
    spans_[k + 1].rest = spans_[k + 1].kin.length - 0.5 * excess;
    links_[k].slipped = false;
  }
  rebaseMarks();
}

}  // namespace cablelab

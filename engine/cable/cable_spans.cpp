// Spans: a cable split by the wheels that grip it (no slip, capstan), docs/wheels.md.
//
// Each span runs from one end or gripping wheel to the next; at a wheel it ends on a material
// mark of the wheel, so its length counts the arc from the tangent point to the mark and the
// wheel's angle enters its constraint. The mark is moved back to the middle of the contact at
// every update, with the rest lengths shifted by the same r dphi, so the constraint values do not
// change and the arcs stay bounded however far the wheel turns. When the solver let the cable
// slide on a wheel, the rest lengths of its two spans are shared out again (the slide stays).
//
// A polygon with friction splits the cable at its corners (docs/polygon_friction.md): one span
// ends on its first engaged corner and the next starts on its last; the rope between them is
// stuck to the rigid polygon while it holds, and slides over all its corners at once.
#include <algorithm>
#include <cmath>

#include "engine/cable/cable.h"
#include "engine/core/capstan.h"

namespace cablelab {

void Cable::splitIntoSpans(std::span<const BodyState> bodies, const std::vector<Split>& splits) {
  // Rigid: the rest length; elastic: the unstretched material.
  double total = elastic() ? materialLength() : params_.restLength;
  if (!spans_.empty()) {
    total = cornerRest_;
    for (const Span& s : spans_) total += s.rest;
  }
  const double corner = cornerLength(splits);
  if (!elastic()) total -= corner;  // the rope between a polygon's corners is stuck: no stretch
  spans_.assign(splits.size() + 1, Span{});
  links_.assign(splits.size(), SpanLink{});
  std::vector<WrapPoint> wheels;  // each split wheel with its mark at the contact's middle
  for (size_t k = 0; k < splits.size(); ++k) {
    WrapPoint w = path_[splits[k].in];
    const PulleyDef& pd = def_->pulleys[w.pulley];
    if (w.kind != WrapPoint::Kind::Circle) {  // a polygon: the spans end on its corners
      double turn = 0;
      for (size_t i = splits[k].in; i <= splits[k].out; ++i) turn += cornerTurn(i);
      links_[k] = {w.pulley, pd.grip, pd.mu, turn, false};
      wheels.push_back(w);
      continue;
    }
    const double s = w.radius > 0 ? 1.0 : -1.0;
    const Vec2 t = w.tangentIn - w.world;
    const double beta = std::atan2(t.y(), t.x());
    const double angle = w.body >= 0 ? bodies[w.body].angle : 0.0;
    w.mark = beta - s * 0.5 * w.arc - angle;
    w.arc *= 0.5;
    wheels.push_back(w);
    links_[k] = {w.pulley, pd.grip, pd.mu, 2 * w.arc, false};
  }
  double lengths = 0;
  for (size_t k = 0; k < spans_.size(); ++k) {
    Span& span = spans_[k];
    span.first = k == 0 ? 0 : splits[k - 1].out;
    span.last = k == splits.size() ? path_.size() - 1 : splits[k].in;
    span.path.assign(path_.begin() + span.first, path_.begin() + span.last + 1);
    if (k > 0 && wheels[k - 1].kind == WrapPoint::Kind::Circle) span.path.front() = wheels[k - 1];
    if (k < splits.size()) span.path.back() = wheels[k];
    cableLengthJacobian(span.path, bodies, span.kin);
    span.tension = tension_;
    lengths += span.kin.length;
  }
  if (elastic()) {
    // One strain throughout: each piece, the one between the corners too, gets material in
    // proportion to its length, so every span starts with the unsplit cable's tension.
    const double whole = lengths + corner;
    for (Span& span : spans_) span.rest = whole > 0 ? total * span.kin.length / whole : 0.0;
    shareCornerRope(splits, whole > 0 && total > 0 ? whole / total : 1.0);
    return;
  }
  // The stretch is shared in proportion to the spans' lengths.
  const double excess = lengths - total;
  for (Span& span : spans_)
    span.rest = span.kin.length - (lengths > 0 ? excess * span.kin.length / lengths : 0.0);
}

// Moves each wheel's mark to the middle of its contact, shifting rest length to match.
void Cable::rebaseMarks() {
  for (size_t k = 0; k < links_.size(); ++k) {
    if (spans_[k].path.back().kind != WrapPoint::Kind::Circle) {  // a polygon: no mark
      links_[k].wrapAngle = 0;
      for (size_t i = spans_[k].last; i <= spans_[k + 1].first; ++i)
        links_[k].wrapAngle += cornerTurn(i);
      continue;
    }
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
  std::vector<Split>& splits = splits_;
  splits.clear();
  std::vector<int> ids;
  for (size_t i = 1; i + 1 < path_.size(); ++i) {
    const int pulley = path_[i].pulley;
    if (pulley < 0 || !pulleys_[pulley].grips) continue;
    if (!ids.empty() && ids.back() == pulley && splits.back().out + 1 == i) {
      splits.back().out = i;  // the next corner of the same polygon
      continue;
    }
    splits.push_back({i, i});
    ids.push_back(pulley);
  }
  if (splits.empty()) {
    if (!spans_.empty()) {
      double total = cornerRest_;
      for (const Span& s : spans_) total += s.rest;
      params_.restLength = total + (elastic() ? params_.preload : 0.0);
    }
    spans_.clear();
    links_.clear();
    splitPulleys_.clear();
    cornerRopes_.clear();
    cornerRest_ = 0;
    return;
  }
  // (A cable made elastic by a parameter edit has no corner rope yet: it splits afresh.)
  if (ids != splitPulleys_ || spans_.empty() ||
      (elastic() && cornerRopes_.size() != splits.size())) {
    splitIntoSpans(bodies, splits);
    splitPulleys_ = ids;
    if (!elastic()) cornerRest_ = cornerLength(splits);
    return;
  }
  spanBefore_.assign(spans_.size(), -1.0);
  for (size_t k = 0; k < spans_.size(); ++k) {
    Span& span = spans_[k];
    const WrapPoint front = span.path.front(), back = span.path.back();
    const size_t first = k == 0 ? 0 : splits[k - 1].out;
    const size_t last = k + 1 == spans_.size() ? path_.size() - 1 : splits[k].in;
    // A polygon's chain grew or shrank at this span's end: the rope at its corners is stuck
    // (docs/polygon_friction.md), so a rigid span keeps its stretch, measured on its old path;
    // an elastic one trades material with the corner rope (moveCornerRope).
    const bool moved = (k > 0 && path_[first].vertex != front.vertex) ||
                       (k + 1 < spans_.size() && path_[last].vertex != back.vertex);
    double before = 0;
    if (moved) {
      cableLengthJacobian(span.path, bodies, spanScratch_);
      before = spanScratch_.length;
    }
    span.first = first;
    span.last = last;
    span.path.assign(path_.begin() + span.first, path_.begin() + span.last + 1);
    // A wheel's mark and arc on each side belong to the span, not to the whole path.
    if (k > 0) span.path.front().mark = front.mark, span.path.front().arc = front.arc;
    if (k + 1 < spans_.size()) span.path.back().mark = back.mark, span.path.back().arc = back.arc;
    cableLengthJacobian(span.path, bodies, span.kin);
    if (moved && elastic())
      spanBefore_[k] = before;
    else if (moved)
      span.rest += span.kin.length - before;
  }
  // Elastic: the material the moved pieces carry between the spans and the corners.
  if (elastic())
    moveCornerRope(splits);
  else
    cornerRest_ = cornerLength(splits);
  // After a slide, the two spans share their stretch again: the slide is kept (an elastic
  // cable's by the strains the solve found, where refresh has not yet).
  if (elastic()) shareSlidMaterial();
  for (size_t k = 0; k < links_.size(); ++k) {
    if (!links_[k].slipped) continue;
    const double excess = spanStretch(static_cast<int>(k)) + spanStretch(static_cast<int>(k) + 1);
    spans_[k].rest = spans_[k].kin.length - 0.5 * excess;
    spans_[k + 1].rest = spans_[k + 1].kin.length - 0.5 * excess;
    links_[k].slipped = false;
  }
  rebaseMarks();
  if (elastic()) slideElasticSpans(), slideCornerRope();
}

double Cable::materialLength() const {
  // A rest length at or under the preload has no material to split: keep a sliver.
  return std::max(params_.restLength - params_.preload, 1e-6 * std::abs(params_.restLength) + 1e-9);
}

double Cable::spanScale(int k) const {
  if (spans_.empty() || !elastic()) return 1.0;
  return materialLength() / std::max(spans_[k].rest, 1e-12);
}

// Spans the solver left stuck (each holding its material) that end the step past the ratio (a
// corner joined or left): where their tensions break T_high <= e^(mu theta) T_low, material slides
// over the corners from the slacker span to the tighter one until the ratio is e^(mu theta)
// exactly: a return mapping, as in plasticity. (Slides the solve found: shareSlidMaterial.)
void Cable::slideElasticSpans() {
  const double material = materialLength();
  for (size_t k = 0; k < links_.size(); ++k) {
    if (links_[k].grip != Grip::Capstan) continue;
    Span &a = spans_[k], &b = spans_[k + 1];
    const double ratio = std::exp(links_[k].mu * std::max(0.0, links_[k].wrapAngle));
    const double ta = materialTension(material, a.kin.length, a.rest);
    const double tb = materialTension(material, b.kin.length, b.rest);
    if (std::max(ta, tb) <= ratio * std::min(ta, tb) * (1 + 1e-12)) continue;
    Span& tight = ta > tb ? a : b;
    Span& loose = ta > tb ? b : a;
    const double sum = a.rest + b.rest;
    tight.rest =
        slideMaterial(material, tight.kin.length, tight.rest, loose.kin.length, sum, ratio);
    loose.rest = sum - tight.rest;
  }
}

// The solver slid the spans of each run of slipped links as one row, each span to its own strain
// e_k (slidStrain). Their material, which the slide keeps in sum, is shared out so that at the
// lengths now the strains are s e_k, one factor s for the run (s = 1 to a rounding of the end
// pose): the tensions keep the solved ratio (docs/polygon_friction.md, "Elastic cables").
void Cable::shareSlidMaterial() {
  for (size_t k = 0; k < links_.size(); ++k) {
    if (!links_[k].slipped) continue;
    size_t last = k;  // the run's spans: k .. last
    while (last < links_.size() && links_[last].slipped) links_[last++].slipped = false;
    double material = 0, largest = 0, lengths = 0;
    for (size_t j = k; j <= last; ++j) {
      material += spans_[j].rest;
      lengths += spans_[j].kin.length;
      largest = std::max(largest, spans_[j].slidStrain);
    }
    if (!(largest > 0)) {
      // Slid slack (no tension held the rope on the corners): no span keeps a stretch the solve
      // did not give it, all share one slack strain.
      if (lengths < material && lengths > 0)
        for (size_t j = k; j <= last; ++j)
          spans_[j].rest = spans_[j].kin.length * material / lengths;
      k = last;
      continue;
    }
    // Newton on sum l_k / (1 + s e_k) = material, decreasing and convex in s.
    double s = 1;
    for (int iteration = 0; iteration < 8; ++iteration) {
      double f = -material, slope = 0;
      for (size_t j = k; j <= last; ++j) {
        const double e = std::max(spans_[j].slidStrain, 0.0), q = 1 + s * e;
        f += spans_[j].kin.length / q;
        slope -= spans_[j].kin.length * e / (q * q);
      }
      if (!(slope < 0)) break;
      const double next = std::max(s - f / slope, 0.5 * s - 0.5 / largest);  // keeps 1 + s e > 0
      if (std::abs(next - s) <= 1e-14 * std::abs(s)) break;
      s = next;
    }
    for (size_t j = k; j <= last; ++j)
      spans_[j].rest = spans_[j].kin.length / (1 + s * std::max(spans_[j].slidStrain, 0.0));
    k = last;
  }
}

double Cable::cornerTurn(size_t i) const {
  const Vec2 &a = kin_.directions[i - 1], &b = kin_.directions[i];
  const double turn = std::atan2(cross(a, b), a.dot(b));  // + counter-clockwise
  return std::max(0.0, pulleys_[path_[i].pulley].side == WrapSide::Right ? turn : -turn);
}

double Cable::cornerLength(const std::vector<Split>& splits) const {
  double length = 0;
  for (const Split& s : splits)
    for (size_t i = s.in; i < s.out; ++i) length += (path_[i + 1].world - path_[i].world).norm();
  return length;
}

void Cable::cornerTensions(int k, std::vector<CornerTension>& out) const {
  out.clear();
  if (k < 0 || k + 1 >= static_cast<int>(spans_.size())) return;
  const size_t first = spans_[k].last, last = spans_[k + 1].first;
  if (path_[first].kind != WrapPoint::Kind::Vertex) return;
  double total = 0;
  for (size_t i = first; i <= last; ++i) total += cornerTurn(i);
  const double in = spans_[k].tension, outer = spans_[k + 1].tension;
  // The tension after a share s of the turn: geometric between the spans' (linear if one is
  // slack, which no friction holds).
  auto at = [&](double s) {
    return in > 0 && outer > 0 ? in * std::pow(outer / in, s) : in + s * (outer - in);
  };
  double turned = 0;
  for (size_t i = first; i <= last; ++i) {
    CornerTension c;
    c.vertex = path_[i].vertex;
    c.turn = cornerTurn(i);
    c.tensionIn = at(total > 0 ? turned / total : 0.0);
    turned += c.turn;
    c.tensionOut = i == last ? outer : at(total > 0 ? turned / total : 1.0);
    out.push_back(c);
  }
}

}  // namespace cablelab

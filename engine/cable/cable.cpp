// Wrap-point selection with guards (rules in cable.h) and the cable's parameters.
#include "engine/cable/cable.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "engine/cable/circle_wrap.h"
#include "engine/cable/wrap.h"
#include "engine/cable/wrap_hold.h"
#include "engine/core/error.h"

namespace cablelab {

namespace {

std::string cableField(int index, const std::string& rest) {
  return "cables[" + std::to_string(index) + "]" + rest;
}

WrapPoint terminal(int body, const AnchorDef& a) {
  WrapPoint p{a.radius > 0 ? WrapPoint::Kind::Circle : WrapPoint::Kind::Anchor, body, a.point};
  p.radius = a.side == WrapSide::Right ? -a.radius : a.radius;
  p.arc = 2 * M_PI * a.turns;
  return p;
}

// m: how far a segment's ends may stray from straight lines between two updates (sweptOverPulley).
constexpr double kSweepMargin = 0.05;

// Whether the segment from path point `host` to the next, moving from where `previous` (the path
// at the last update) had its ends, swept over the circle (c, reach): c lies within reach of the
// convex hull of the four ends, which holds every segment between them. An end not in `previous`
// answers yes. A segment whose ends passed each other (a bob on a slack rope flying over its
// anchor) turns its direction over, and a pulley on its line far from it changes side without the
// segment ever reaching it: joined, the wrap round it jumped the length by a metre
// (docs/cables.md, "Guards"). Asked of pulleys fixed in the world: one on a body moves through
// the segment itself.
bool sweptOverPulley(std::span<const WrapPoint> previous, std::span<const WrapPoint> path,
                     size_t host, const Vec2& c, double reach) {
  auto before = [&](size_t i) -> const WrapPoint* {
    if (i == 0) return &previous.front();
    if (i + 1 == path.size()) return &previous.back();
    for (size_t k = 1; k + 1 < previous.size(); ++k)
      if (previous[k].pulley == path[i].pulley && previous[k].vertex == path[i].vertex)
        return &previous[k];
    return nullptr;
  };
  const WrapPoint *a0 = before(host), *b0 = before(host + 1);
  if (previous.size() < 2 || !a0 || !b0) return true;
  const Vec2 q[4] = {a0->leaving(), b0->arriving(), path[host].leaving(),
                     path[host + 1].arriving()};
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const Vec2 d = q[j] - q[i];
      const double t =
          d.squaredNorm() > 0 ? std::clamp((c - q[i]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      if ((q[i] + t * d - c).norm() <= reach) return true;
      for (int k = j + 1; k < 4; ++k) {
        const double s1 = cross(q[j] - q[i], c - q[i]), s2 = cross(q[k] - q[j], c - q[j]),
                     s3 = cross(q[i] - q[k], c - q[k]);
        if ((s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0)) return true;
      }
    }
  return false;
}

}  // namespace

Cable::Cable(const SceneDef& scene, int index, const std::string& source)
    : def_(&scene.cables[index]),
      params_{def_->restLength, def_->stiffness, def_->preload, def_->damping} {
  auto resolve = [&](const std::string& name, const std::string& field) {
    const int b = findBodyIndex(scene, name);
    if (b == -2)
      throw InputError(source, cableField(index, field), "unknown body" + gotValue(name));
    return b;
  };
  startBody_ = resolve(def_->start.body, ".start.body");
  endBody_ = resolve(def_->end.body, ".end.body");
  start_ = terminal(startBody_, def_->start);
  end_ = terminal(endBody_, def_->end);
  startDrum_ = {def_->start.point, def_->start.radius};
  endDrum_ = {def_->end.point, def_->end.radius};
  for (size_t j = 0; j < def_->pulleys.size(); ++j) {
    const PulleyDef& pd = def_->pulleys[j];
    const std::string field = ".pulleys[" + std::to_string(j) + "]";
    PulleyState ps;
    ps.body = resolve(pd.body, field + ".body");
    ps.side = pd.side;
    ps.autoSide = pd.side == WrapSide::Auto;
    if (ps.autoSide) ps.side = WrapSide::Left;
    ps.polygon = pd.kind == PulleyDef::Kind::Polygon;
    ps.circle = pd.kind == PulleyDef::Kind::Circle;
    if (ps.polygon) {
      ps.local = pulleyPolygon(scene, pd);
      if (!isConvexCCW(ps.local))
        throw InputError(source, cableField(index, field + ".vertices"),
                         "polygon pulley needs a convex counter-clockwise polygon");
      if (ps.side == WrapSide::Threaded)
        throw InputError(
            source, cableField(index, field + ".side"),
            "a polygon pulley cannot be threaded (use left, right or auto)" + gotValue("threaded"));
    } else {
      ps.local = {pd.point};
    }
    if (ps.circle) ps.radius = pd.radius;
    ps.grips = gripsCable(pd);
    ps.turns = pd.turns;
    ps.world = ps.local;
    // A circle or polygon the scene winds the cable round (turns > 0) is in the path from the
    // start, even where the straight cable would miss it (a rope laid over a pulley above).
    ps.engaged = ps.side == WrapSide::Threaded ||
                 (!ps.local.empty() && ps.turns > 0 && (ps.circle || ps.polygon));
    ps.arc = ps.initialArc();
    pulleys_.push_back(std::move(ps));
  }
  order_.resize(pulleys_.size());
  std::iota(order_.begin(), order_.end(), 0);
  rank_ = order_;
  namedPulleys_ = static_cast<int>(pulleys_.size());
  findTiedEnds();
  addSecondPlaces();
}

void Cable::setParameters(const CableParameters& parameters) {
  // Spans share a change of the rest length equally.
  for (Span& s : spans_) s.rest += (parameters.restLength - params_.restLength) / spans_.size();
  params_ = parameters;
}

void Cable::payOut(int k, double length) {
  if (!spans_.empty()) spans_[k].rest += length;
  params_.restLength += length;
  paidOut_ += length;
}

double Cable::stretch() const {
  return kin_.length - params_.restLength + (elastic() ? params_.preload : 0.0);
}

void Cable::setTension(double t) {
  tension_ = t;
  for (Span& s : spans_) s.tension = t;
}

std::span<const WrapPoint> Cable::spanPath(int k) const {
  return spans_.empty() ? std::span<const WrapPoint>(path_) : spans_[k].path;
}

const CableKinematics& Cable::spanKinematics(int k) const {
  return spans_.empty() ? kin_ : spans_[k].kin;
}

double Cable::spanStretch(int k) const {
  return spans_.empty() ? stretch() : spans_[k].kin.length - spans_[k].rest;
}

void Cable::setSpanTension(int k, double t) {
  if (spans_.empty()) {
    tension_ = t;
    return;
  }
  spans_[k].tension = t;
  tension_ = 0;
  for (const Span& s : spans_) tension_ = std::max(tension_, s.tension);
}

double Cable::segmentTension(size_t i) const {
  for (size_t k = 0; k < spans_.size(); ++k) {
    if (i < spans_[k].last) return spans_[k].tension;
    if (k + 1 < spans_.size() && i < spans_[k + 1].first) {
      std::vector<CornerTension> corners;  // between two corners of a polygon with friction
      cornerTensions(static_cast<int>(k), corners);
      return corners[i - spans_[k].last].tensionOut;
    }
  }
  return tension_;
}

void Cable::placePulleys(std::span<const BodyState> bodies) {
  for (PulleyState& p : pulleys_) {
    if (p.body < 0) {
      p.world = p.local;
      continue;
    }
    // One cos/sin per pulley, not per vertex.
    const BodyState& b = bodies[p.body];
    double c, s;
    cosSin(b.angle, c, s);
    for (size_t v = 0; v < p.local.size(); ++v) p.world[v] = b.position + rotate(p.local[v], c, s);
  }
}

// Node n of the chain: 0 = start anchor, 1..P = pulley n-1, P+1 = end anchor. A circle's
// contact points are those of the last update (the polygon chain only needs them roughly).
Vec2 Cable::entryPoint(int node, const std::vector<std::vector<int>>& chains) const {
  if (node == 0) return path_.front().leaving();
  if (node == static_cast<int>(pulleys_.size()) + 1) return path_.back().arriving();
  const PulleyState& p = pulleys_[node - 1];
  const auto& c = chains[node - 1];
  if (!p.polygon) return p.world[0];
  if (c.empty() && p.tiedEnd != 0) return p.tiedEnd > 0 ? end_.world : start_.world;
  if (c.empty()) {
    Vec2 centroid = Vec2::Zero();
    for (const Vec2& v : p.world) centroid += v;
    return centroid / static_cast<double>(p.world.size());
  }
  return p.world[c.front()];
}

// Whether node's entry and exit points are where the path touches it (not an empty polygon's
// centre).
bool Cable::touchesPath(int node, const std::vector<std::vector<int>>& chains) const {
  if (node == 0 || node == static_cast<int>(pulleys_.size()) + 1) return true;
  const PulleyState& p = pulleys_[node - 1];
  return !p.polygon || p.tiedEnd != 0 || !chains[node - 1].empty();
}

Vec2 Cable::exitPoint(int node, const std::vector<std::vector<int>>& chains) const {
  if (node >= 1 && node <= static_cast<int>(pulleys_.size()) && pulleys_[node - 1].polygon &&
      !chains[node - 1].empty())
    return pulleys_[node - 1].world[chains[node - 1].back()];
  return entryPoint(node, chains);
}

// Seeds the chains of engaged neighbouring polygons with their common tangent (it holds whether
// their hulls are apart or overlap). True if the path has neighbouring polygons.
bool Cable::seedCommonTangents(std::vector<std::vector<int>>& chains) const {
  bool any = false;
  for (size_t n = 1; n + 2 < nodes_.size(); ++n) {
    const PulleyState &first = pulleys_[nodes_[n] - 1], &second = pulleys_[nodes_[n + 1] - 1];
    if (!first.polygon || !second.polygon) continue;
    any = true;
    int from, into;
    if (!commonTangent(first.world, first.side, second.world, second.side, from, into)) continue;
    chains[nodes_[n] - 1].push_back(from);  // after its entry from a polygon before it, if any
    chains[nodes_[n + 1] - 1].assign(1, into);
  }
  return any;
}

// Whether chain node `node` (0 start, 1..P pulley, P+1 end) may be pressed into its neighbouring
// polygon's hull and hold the chain end there: a point fixed in the world, or a neighbouring
// polygon's corner (docs/cables.md, "Points inside a hull"). A point on another body drops it.
bool Cable::holdsAgainst(int node) const {
  if (node == 0) return start_.body < 0;
  if (node == static_cast<int>(pulleys_.size()) + 1) return end_.body < 0;
  const PulleyState& p = pulleys_[node - 1];
  return p.polygon || p.body < 0;
}

// Rebuilds path_ from the engaged pulleys. Returns false if a polygon had to leave.
bool Cable::buildPath(std::vector<std::string>* warnings) {
  const int count = static_cast<int>(pulleys_.size());
  std::vector<int>& nodes = nodes_;
  nodes.assign(1, 0);
  for (const int j : order_)
    if (pulleys_[j].engaged) nodes.push_back(j + 1);
  nodes.push_back(count + 1);

  // Polygon chains depend on their neighbours' contact points. Neighbouring polygons start from
  // their common tangent, and a few passes settle a chain of three or more.
  std::vector<std::vector<int>>& chains = chains_;
  chains.resize(count);
  for (std::vector<int>& c : chains) c.clear();
  const bool neighbouringPolygons = seedCommonTangents(chains);
  const int passes = neighbouringPolygons ? 4 : 1;
  for (int pass = 0; pass < passes; ++pass)
    for (size_t n = 1; n + 1 < nodes.size(); ++n) {
      PulleyState& p = pulleys_[nodes[n] - 1];
      if (!p.polygon) continue;
      const Vec2 a = exitPoint(nodes[n - 1], chains);
      const Vec2 b = entryPoint(nodes[n + 1], chains);
      // The chain that continues the last update's wrap (more than half a turn when the
      // polygon swung round past an end anchor), holding its end where a terminal that may be
      // pressed into the hull is inside it; a spool's chain runs to the corner its rope is tied at.
      const auto turn =
          p.tiedEnd != 0 ? tiedChain(p, a, b, chains[nodes[n] - 1])
                         : wrapChainHeld(a, b, p.world, p.side, p.arc, holdsAgainst(nodes[n - 1]),
                                         holdsAgainst(nodes[n + 1]), p.hold, chains[nodes[n] - 1]);
      if (turn) p.arc = *turn;
      // Between real contacts (not a neighbour's centre) a polygon the path no longer bends round
      // leaves now. Kept to the last pass, its empty chain would make its centre the neighbour's
      // terminal, that neighbour's chain would bend the path round it again, and the two would
      // take turns over the passes (docs/cables.md, "Points inside a hull").
      if (turn && neighbouringPolygons && chains[nodes[n] - 1].empty() && p.tiedEnd == 0 &&
          touchesPath(nodes[n - 1], chains) && touchesPath(nodes[n + 1], chains)) {
        p.engaged = false;
        p.previousDepth = 0;
        p.arc = 0;
        return false;
      }
      if (!turn) {
        p.engaged = false;
        p.dropped = true;
        p.arc = 0;
        if (warnings)
          warnings->push_back("cable '" + def_->name + "': pulley " + std::to_string(nodes[n] - 1) +
                              " left the path: a neighbouring point lies inside its hull");
        return false;
      }
    }
  // A neighbouring polygon the path no longer bends round leaves before the next build takes its
  // centre as its neighbour's terminal (leaveRound would see its empty chain only after that).
  if (neighbouringPolygons)
    for (size_t n = 1; n + 1 < nodes.size(); ++n) {
      PulleyState& p = pulleys_[nodes[n] - 1];
      if (!p.polygon || !chains[nodes[n] - 1].empty()) continue;
      p.engaged = false;
      p.previousDepth = 0;
      p.arc = 0;
      return false;
    }

  // Keep the terminals' last contact points (circle tangents) for the next build.
  if (!path_.empty()) {
    start_.tangentOut = path_.front().tangentOut;
    end_.tangentIn = path_.back().tangentIn;
  }
  path_.clear();
  path_.push_back(start_);
  for (size_t n = 1; n + 1 < nodes.size(); ++n) {
    const int j = nodes[n] - 1;
    const PulleyState& p = pulleys_[j];
    if (p.circle) {
      WrapPoint w{WrapPoint::Kind::Circle, p.body, p.local[0], p.world[0], j, -1};
      w.radius = p.signedRadius();
      w.arc = p.arc;
      path_.push_back(w);
    } else if (!p.polygon) {
      path_.push_back({WrapPoint::Kind::Point, p.body, p.local[0], p.world[0], j, -1});
    } else {
      for (int v : chains[j])
        path_.push_back({WrapPoint::Kind::Vertex, p.body, p.local[v], p.world[v], j, v});
    }
  }
  path_.push_back(end_);
  return true;
}

bool Cable::mayEnterHull(size_t i) const {
  // A point fixed in the world holds the chain end it is pressed in at (holdsAgainst). A
  // neighbouring polygon's corner holds it too, but the floor between two polygons' corners
  // stays: it keeps the corners apart where they would sweep into each other's hulls.
  const WrapPoint &p = path_[i], &q = path_[i + 1];
  if (p.body == q.body) return false;
  return (p.kind == WrapPoint::Kind::Vertex && q.body < 0) ||
         (q.kind == WrapPoint::Kind::Vertex && p.body < 0);
}

// Leave: the path no longer bends around the pulley. Returns true if one left.
bool Cable::leaveRound() {
  for (size_t i = 1; i + 1 < path_.size(); ++i) {
    const int j = path_[i].pulley;
    PulleyState& p = pulleys_[j];
    if (p.side == WrapSide::Threaded || p.polygon) continue;
    bool gone;
    if (p.circle) {
      gone = path_[i].arc < 0;
    } else {
      // The turn at a point, continuous over time: past half a turn (the cable doubled back round
      // it, e.g. swung round past an end anchor) it stays; it leaves when the turn goes below 0.
      const Vec2 in = p.world[0] - path_[i - 1].leaving(),
                 out = path_[i + 1].arriving() - p.world[0];
      p.arc = continuedPointTurn(in, out, p.side, p.arc);
      gone = p.arc < 0;
    }
    if (gone) {
      p.engaged = false;
      p.previousDepth = -1e-300;
      p.arc = 0;
      return true;
    }
  }
  // Polygons with an empty chain have left already in the path (no vertex emitted); one the
  // cable is tied to stays (its end is on it).
  for (size_t j = 0; j < pulleys_.size(); ++j) {
    PulleyState& p = pulleys_[j];
    if (!p.engaged || !p.polygon || p.tiedEnd != 0) continue;
    const bool inPath = std::any_of(path_.begin(), path_.end(), [j](const WrapPoint& w) {
      return w.pulley == static_cast<int>(j);
    });
    if (!inPath) {
      p.engaged = false;
      // It left on the old path, its last corner on the straight segment. A hull left lying
      // across that segment (a hold had wrapped it from the far side) came from the wrap side:
      // it joins only after clearing the segment, or the fresh walk round its far side would
      // jump the length (docs/cables.md, "Points inside a hull").
      size_t host = 0;
      while (host + 2 < path_.size() && rank_[path_[host + 1].pulley] < rank_[j]) ++host;
      const bool across =
          segmentCutsPolygon(path_[host].leaving(), path_[host + 1].arriving(), p.world);
      p.previousDepth = across ? 1.0 : 0.0;
      p.arc = 0;
      return true;
    }
  }
  return false;
}

// Join: a disengaged pulley that crossed its host segment from the non-wrap side (an auto
// pulley: from either side, and it wraps on the side it came from). Returns true if one joined.
bool Cable::joinRound(std::vector<std::string>* warnings) {
  size_t host = 0;  // path index of the last point before pulley j
  for (const int j : order_) {
    PulleyState& p = pulleys_[j];
    if (idleSecondPlace(j)) continue;
    if (p.engaged) {
      // One riding its neighbour's hull may move its place (pulley_order.cpp).
      if (joinsAnySegment(j) && joinCrossedSegment(j)) return true;
      while (host + 1 < path_.size() - 1 && path_[host + 1].pulley == static_cast<int>(j)) ++host;
      continue;
    }
    // A free polygon crossing another segment joins it (pulley_order.cpp).
    if (joinsAnySegment(j) && joinCrossedSegment(j)) return true;
    if (besideItsOtherPlace(j, path_[host], path_[host + 1])) continue;
    const Vec2 a = path_[host].leaving();
    const Vec2 b = path_[host + 1].arriving();
    const Vec2 ab = b - a;
    const double len = ab.norm();
    // A circle whose disc holds an end of the segment (a bob on a slack rope flew into it) has no
    // taut path round it: joined, the path had a point inside the circle, and its length grew
    // with the point's turn about the centre while J left the point out (docs/floors.md, "The
    // disc of a round pulley").
    auto endInDisc = [&](const Vec2& centre) {
      const double r = std::abs(p.radius);
      return !firstUpdate_ && !p.polygon && ((a - centre).norm() < r || (b - centre).norm() < r);
    };
    // Auto: the centre's side of the segment decides, and a change of side is a crossing.
    if (p.autoSide) {
      Vec2 centre = Vec2::Zero();
      for (const Vec2& v : p.world) centre += v;
      centre /= static_cast<double>(p.world.size());
      const double left = len > 0 ? cross(ab, centre - a) / len : 0.0;
      const double t = len > 0 ? (centre - a).dot(ab) / (len * len) : -1;
      const double was = firstUpdate_ ? left : p.previousLeft;
      p.previousLeft = left;
      p.side = was <= 0 ? WrapSide::Left : WrapSide::Right;
      const bool within = t > 0 && t < 1;
      const bool touches =
          p.polygon ? segmentCutsPolygon(a, b, p.world) : within && std::abs(left) < p.radius;
      const bool crossed =
          within && !firstUpdate_ && (left > 0) != (was > 0) &&
          (p.polygon || p.body >= 0 ||
           sweptOverPulley(previousPath_, path_, host, centre, p.radius + kSweepMargin));
      if ((touches || crossed) && !endInDisc(centre)) {
        p.engaged = true;
        p.arc = 0;
        p.hold = ChainHold{};
        return true;
      }
      continue;
    }
    double depth = -1e300;
    for (const Vec2& v : p.world) depth = std::max(depth, wrapSideDistance(a, b, v, p.side));
    depth += p.radius;
    bool cuts;
    if (p.polygon) {
      // With a point fixed in the world inside the hull there is no taut path round the polygon
      // to join: the segment "cuts" it only because it ends inside (docs/cables.md, "Points
      // inside a hull").
      auto fixedInside = [&](const WrapPoint& w, const Vec2& x) {
        return w.body < 0 && insideConvex(x, p.world);
      };
      cuts = segmentCutsPolygon(a, b, p.world) && !fixedInside(path_[host], a) &&
             !fixedInside(path_[host + 1], b);
    } else {
      const double t = len > 0 ? (p.world[0] - a).dot(ab) / (len * len) : -1;
      cuts = t > 0 && t < 1 && (firstUpdate_ ? depth >= 0 : depth > 0) && !endInDisc(p.world[0]);
    }
    bool crossed = firstUpdate_ ||
                   (p.previousDepth <= 0 && (p.polygon || p.body >= 0 ||
                                             sweptOverPulley(previousPath_, path_, host, p.world[0],
                                                             std::abs(p.radius) + kSweepMargin)));
    p.previousDepth = depth;
    // A polygon a guard dropped rejoins once a taut path round it exists again.
    if (p.dropped && cuts && !crossed) {
      // Only where the drop is undone, not round the far side of a polygon that went through.
      crossed =
          wrapChain(a, b, p.world, p.side, rejoinChain_) &&
          chainLength(a, b, p.world, rejoinChain_) - (b - a).norm() <= p.dropCut + kLengthJump;
      if (crossed && warnings)
        warnings->push_back("cable '" + def_->name + "': pulley " + std::to_string(j) +
                            " rejoined the path (a guard had dropped it)");
    }
    if (!cuts && depth <= 0) p.dropped = false;
    if (cuts && crossed) {
      p.engaged = true;
      p.dropped = false;
      p.hold = ChainHold{};
      p.segmentDepths.clear();
      // A circle joins at zero wrap; at the start its wrap is the one it was wound with. A
      // point or a polygon joins at zero turn.
      p.arc = firstUpdate_ && p.circle ? p.initialArc() : 0.0;
      return true;
    }
  }
  return false;
}

void Cable::storeArcs() {
  for (const WrapPoint& w : path_)
    if (w.kind == WrapPoint::Kind::Circle && w.pulley >= 0) pulleys_[w.pulley].arc = w.arc;
  start_.arc = path_.front().arc;
  end_.arc = path_.back().arc;
}

// A drum's end is fixed `turns` turns back from where the cable first touches it.
void Cable::placeDrumMarks(std::span<const BodyState> bodies) {
  for (WrapPoint* w : {&path_.front(), &path_.back()}) {
    if (w->radius == 0) continue;
    const bool atStart = w == &path_.front();
    w->arc = 2 * M_PI * (atStart ? def_->start.turns : def_->end.turns);
    const Vec2 t = atStart ? w->tangentOut : w->tangentIn;
    const double beta = std::atan2(t.y() - w->world.y(), t.x() - w->world.x());
    const double s = w->radius > 0 ? 1.0 : -1.0;
    const double angle = w->body >= 0 ? bodies[w->body].angle : 0.0;
    // End: arc = s (beta - mark); start: arc = s (mark - beta) (circle_wrap.h).
    w->mark = (atStart ? beta + s * w->arc : beta - s * w->arc) - angle;
    (atStart ? start_ : end_).mark = w->mark;
  }
}

// Wound -> a point at the mark when the arc turns negative (the cable is all paid out); point ->
// wound again when the segment into the mark starts to cut the drum, on the side it meets it.
// Both changes happen where the length and its gradient are continuous (arc 0, tangent at mark).
bool Cable::updateDrumEnd(WrapPoint& end, bool atStart, std::span<const BodyState> bodies) {
  const Drum& drum = atStart ? startDrum_ : endDrum_;
  if (drum.radius == 0) return false;
  const WrapPoint& here = atStart ? path_.front() : path_.back();
  const WrapPoint& next = atStart ? path_[1] : path_[path_.size() - 2];
  if (end.kind == WrapPoint::Kind::Circle) {
    if (here.arc >= 0) return false;
    end.kind = WrapPoint::Kind::Anchor;
    end.radius = 0;
    end.arc = 0;
    end.local = drum.centre + drum.radius * Vec2(std::cos(end.mark), std::sin(end.mark));
    return true;
  }
  const Vec2 mark = worldPoint(bodies, end.body, end.local);
  const Vec2 centre = worldPoint(bodies, end.body, drum.centre);
  const Vec2 other = atStart ? next.arriving() : next.leaving();
  const Vec2 u = atStart ? Vec2(other - mark) : Vec2(mark - other);  // walking the cable
  const Vec2 outward = mark - centre;
  // The cable runs into the disc just before (end) or after (start) the mark.
  const bool cuts = atStart ? u.dot(outward) < 0 : u.dot(outward) > 0;
  if (!cuts) return false;
  end.kind = WrapPoint::Kind::Circle;
  end.local = drum.centre;
  end.radius = cross(u, centre - mark) < 0 ? drum.radius : -drum.radius;
  end.arc = 0;
  return true;
}

void Cable::refresh(std::span<const BodyState> bodies) {
  // kin_ is that of these poses already (a cable that skips has no spans).
  if (skipValid_ && kinematicsCurrent(bodies)) return;
  cableLengthJacobian(path_, bodies, kin_);
  for (Span& s : spans_) cableLengthJacobian(s.path, bodies, s.kin);
  // The stretches reported belong to the end of the step: an elastic slide's included, and so is
  // the slide of stuck spans that end past the capstan ratio (a span caught taut beside a slack
  // one is not left holding a stretch no friction can hold).
  if (elastic()) shareSlidMaterial(), slideElasticSpans(), slideCornerRope();
  if (skipValid_) noteKinematicsPoses(bodies);
}

// The length the path before this update has on `bodies`.
double Cable::previousLength(std::span<const BodyState> bodies) {
  cableLengthJacobian(previousPath_, bodies, previousKin_);
  return previousKin_.length;
}

// Every wrap change is meant to happen on the old path (docs/cables.md); one that was not (a
// guard acting, a crossing found late) and moved the length by more than kLengthJump says so.
void Cable::reportLengthJump(std::span<const BodyState> bodies,
                             std::vector<std::string>* warnings) {
  if (firstUpdate_ || !warnings) return;
  bool same = previousPath_.size() == path_.size();
  for (size_t i = 0; same && i < path_.size(); ++i)
    same = previousPath_[i].pulley == path_[i].pulley && previousPath_[i].vertex == path_[i].vertex;
  if (same) return;
  const double before = previousLength(bodies);
  if (std::abs(kin_.length - before) <= kLengthJump) return;
  char jump[64];
  std::snprintf(jump, sizeof jump, "%.6g m", kin_.length - before);
  // A polygon whose chain emptied with a jump moved off the cable within one update (cable.h).
  for (size_t j = 0; j < pulleys_.size(); ++j)
    if (pulleys_[j].polygon && engagedBefore_[j] && !pulleys_[j].engaged && !pulleys_[j].dropped) {
      warnings->push_back("cable '" + def_->name + "': pulley " + std::to_string(j) +
                          " released with a jump (it moved off the cable within one update, " +
                          "further than its wrap can follow): the length moved by " + jump);
      return;
    }
  warnings->push_back("cable '" + def_->name + "': a wrap change moved the length by " + jump +
                      " (not on the old path: a guard acted or a crossing was found late)");
}

void Cable::update(std::span<const BodyState> select, std::span<const BodyState> bodies,
                   std::vector<std::string>* warnings) {
  if (skipping_ && skipValid_ && keepWrapSet(select, bodies)) {
    // All finishUpdate() would do: a kept set has no zero-length segment (keepWrapSet) and no
    // spans (skipEligible), and the first update is never a kept one.
    ++skippedSelections_;
    reportedZeroLength_ = false;
    return;
  }
  kinPosesValid_ = false;  // the full selection works kin_ out anew
  placePulleys(select);
  if (path_.empty()) path_ = {start_, end_};
  previousPath_ = path_;
  // The terminals where they are now (a polygon's chain is built against them).
  start_.world = path_.front().world = worldPoint(select, start_.body, start_.local);
  end_.world = path_.back().world = worldPoint(select, end_.body, end_.local);
  if (start_.radius == 0) path_.front().tangentOut = start_.tangentOut = start_.world;
  if (end_.radius == 0) path_.back().tangentIn = end_.tangentIn = end_.world;
  // Settle the engaged set on `select`: leaves first, then joins, until nothing changes.
  // Circles need the path's tangent points and arcs to decide; points and polygons do not.
  const bool curved =
      start_.radius != 0 || end_.radius != 0 ||
      std::any_of(pulleys_.begin(), pulleys_.end(), [](const PulleyState& p) { return p.circle; });
  const int count = static_cast<int>(pulleys_.size());
  droppedBefore_.resize(count);
  engagedBefore_.resize(count);
  for (int j = 0; j < count; ++j) {
    droppedBefore_[j] = pulleys_[j].dropped;
    engagedBefore_[j] = pulleys_[j].engaged;
  }
  for (int round = 0; round < 2 * count + 2; ++round) {
    if (!buildPath(warnings)) continue;
    if (curved) {
      cableLengthJacobian(path_, select, kin_);
      if (firstUpdate_) {
        placeDrumMarks(select);
        cableLengthJacobian(path_, select, kin_);
      }
      storeArcs();
    }
    if (leaveRound()) continue;
    if (!joinRound(warnings)) break;
  }
  // Drum ends that ran out of cable, or that the cable wraps again.
  const bool startChanged = updateDrumEnd(start_, true, select);  // both ends, always
  const bool endChanged = updateDrumEnd(end_, false, select);
  const bool drumChanged = startChanged || endChanged;
  if (drumChanged) buildPath(warnings);
  // Length, J and J-dot-v on `bodies`.
  if (!curved || drumChanged || select.data() != bodies.data()) {
    cableLengthJacobian(path_, bodies, kin_);
    if (curved) storeArcs();
  }
  // What a drop in this update took out is what a later rejoin may put back.
  for (int j = 0; j < count; ++j)
    if (pulleys_[j].dropped && !droppedBefore_[j])
      pulleys_[j].dropCut = std::max(0.0, previousLength(bodies) - kin_.length);
  reportLengthJump(bodies, warnings);
  if (firstUpdate_) reportPulleysLeftOut(bodies, warnings);
  finishUpdate(bodies, warnings);
  buildSkipCertificate(select);
}

void Cable::finishUpdate(std::span<const BodyState> bodies, std::vector<std::string>* warnings) {
  if (warnings && kin_.zeroLengthSegments > 0 && !reportedZeroLength_)
    warnings->push_back(
        "cable '" + def_->name + "': " + std::to_string(kin_.zeroLengthSegments) +
        " zero-length segment(s) (coincident points, or a point inside a circle) left "
        "out of the Jacobian");
  reportedZeroLength_ = kin_.zeroLengthSegments > 0;
  if (firstUpdate_ && params_.restLength < 0) params_.restLength = kin_.length;
  updateSpans(bodies);
  firstUpdate_ = false;
}

}  // namespace cablelab

// Wrap-point selection with guards (rules in cable.h) and the cable's parameters.
#include "engine/cable/cable.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/cable/wrap.h"
#include "engine/core/error.h"

namespace cablelab {

namespace {

std::string cableField(int index, const std::string& rest) {
  return "cables[" + std::to_string(index) + "]" + rest;
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
  for (size_t j = 0; j < def_->pulleys.size(); ++j) {
    const PulleyDef& pd = def_->pulleys[j];
    const std::string field = ".pulleys[" + std::to_string(j) + "]";
    PulleyState ps;
    ps.body = resolve(pd.body, field + ".body");
    ps.side = pd.side;
    ps.polygon = pd.kind == PulleyDef::Kind::Polygon;
    if (ps.polygon) {
      ps.local = pd.vertices;
      if (ps.local.empty() && ps.body >= 0)
        for (const ShapeDef& s : scene.bodies[ps.body].shapes)
          if (s.kind == ShapeDef::Kind::Polygon) {
            ps.local = s.vertices;
            break;
          }
      if (!isConvexCCW(ps.local))
        throw InputError(source, cableField(index, field + ".vertices"),
                         "polygon pulley needs a convex counter-clockwise polygon");
      if (ps.side == WrapSide::Threaded)
        throw InputError(source, cableField(index, field + ".side"),
                         "a polygon pulley cannot be threaded (use left or right)");
    } else {
      ps.local = {pd.point};
    }
    ps.world = ps.local;
    ps.engaged = ps.side == WrapSide::Threaded;
    pulleys_.push_back(std::move(ps));
  }
}

double Cable::stretch() const {
  return kin_.length - params_.restLength + (elastic() ? params_.preload : 0.0);
}

void Cable::placePulleys(std::span<const BodyState> bodies) {
  for (PulleyState& p : pulleys_) {
    if (p.body < 0) {
      p.world = p.local;
      continue;
    }
    // One cos/sin per pulley, not per vertex.
    const BodyState& b = bodies[p.body];
    const double c = std::cos(b.angle), s = std::sin(b.angle);
    for (size_t v = 0; v < p.local.size(); ++v) p.world[v] = b.position + rotate(p.local[v], c, s);
  }
}

// Node n of the chain: 0 = start anchor, 1..P = pulley n-1, P+1 = end anchor.
Vec2 Cable::entryPoint(int node, const std::vector<std::vector<int>>& chains) const {
  if (node == 0) return path_.front().world;
  if (node == static_cast<int>(pulleys_.size()) + 1) return path_.back().world;
  const PulleyState& p = pulleys_[node - 1];
  const auto& c = chains[node - 1];
  if (!p.polygon) return p.world[0];
  if (c.empty()) {
    Vec2 centroid = Vec2::Zero();
    for (const Vec2& v : p.world) centroid += v;
    return centroid / static_cast<double>(p.world.size());
  }
  return p.world[c.front()];
}

Vec2 Cable::exitPoint(int node, const std::vector<std::vector<int>>& chains) const {
  if (node >= 1 && node <= static_cast<int>(pulleys_.size()) && pulleys_[node - 1].polygon &&
      !chains[node - 1].empty())
    return pulleys_[node - 1].world[chains[node - 1].back()];
  return entryPoint(node, chains);
}

// Rebuilds path_ from the engaged pulleys. Returns false if a polygon had to leave.
bool Cable::buildPath(std::vector<std::string>* warnings) {
  const int count = static_cast<int>(pulleys_.size());
  std::vector<int>& nodes = nodes_;
  nodes.assign(1, 0);
  for (int j = 0; j < count; ++j)
    if (pulleys_[j].engaged) nodes.push_back(j + 1);
  nodes.push_back(count + 1);

  // Polygon chains depend on their neighbours' contact points; neighbouring polygons need a few
  // passes to settle on the common tangent.
  std::vector<std::vector<int>>& chains = chains_;
  chains.resize(count);
  for (std::vector<int>& c : chains) c.clear();
  bool neighbouringPolygons = false;
  for (size_t n = 1; n + 2 < nodes.size(); ++n)
    neighbouringPolygons |= pulleys_[nodes[n] - 1].polygon && pulleys_[nodes[n + 1] - 1].polygon;
  const int passes = neighbouringPolygons ? 4 : 1;
  for (int pass = 0; pass < passes; ++pass)
    for (size_t n = 1; n + 1 < nodes.size(); ++n) {
      PulleyState& p = pulleys_[nodes[n] - 1];
      if (!p.polygon) continue;
      const Vec2 a = exitPoint(nodes[n - 1], chains);
      const Vec2 b = entryPoint(nodes[n + 1], chains);
      if (!wrapChain(a, b, p.world, p.side, chains[nodes[n] - 1])) {
        p.engaged = false;
        p.dropped = true;
        if (warnings)
          warnings->push_back("cable '" + def_->name + "': pulley " + std::to_string(nodes[n] - 1) +
                              " left the path: a neighbouring point lies inside its hull");
        return false;
      }
    }

  WrapPoint start{WrapPoint::Kind::Anchor, startBody_, def_->start.point,
                  path_.front().world,     -1,         -1};
  WrapPoint end{WrapPoint::Kind::Anchor, endBody_, def_->end.point, path_.back().world, -1, -1};
  path_.clear();
  path_.push_back(start);
  for (size_t n = 1; n + 1 < nodes.size(); ++n) {
    const int j = nodes[n] - 1;
    const PulleyState& p = pulleys_[j];
    if (!p.polygon) {
      path_.push_back({WrapPoint::Kind::Point, p.body, p.local[0], p.world[0], j, -1});
      continue;
    }
    for (int v : chains[j])
      path_.push_back({WrapPoint::Kind::Vertex, p.body, p.local[v], p.world[v], j, v});
  }
  path_.push_back(end);
  return true;
}

// Every wrap change is meant to happen on the old path (docs/cables.md); one that was not (a
// guard acting, a crossing found late) and moved the length by more than kLengthJump says so.
void Cable::reportLengthJump(double before, std::vector<std::string>* warnings) const {
  if (firstUpdate_ || !warnings || std::abs(kin_.length - before) <= kLengthJump) return;
  bool same = signature_.size() == path_.size();
  for (size_t i = 0; same && i < path_.size(); ++i)
    same = signature_[i].first == path_[i].pulley && signature_[i].second == path_[i].vertex;
  if (same) return;
  char jump[64];
  std::snprintf(jump, sizeof jump, "%.6g m", kin_.length - before);
  // A polygon whose chain emptied with a jump was hooked: the cable bent round it further than a
  // hull chain between its neighbours can hold (it swung round beyond an end anchor).
  for (size_t j = 0; j < pulleys_.size(); ++j)
    if (pulleys_[j].polygon && engagedBefore_[j] && !pulleys_[j].engaged && !pulleys_[j].dropped) {
      warnings->push_back("cable '" + def_->name + "': pulley " + std::to_string(j) +
                          " released while the cable still hooks round it (it turned beyond " +
                          "what a taut path between its neighbours can wrap, e.g. past an end " +
                          "anchor): the length moved by " + jump);
      return;
    }
  warnings->push_back("cable '" + def_->name + "': a wrap change moved the length by " + jump +
                      " (not on the old path: a guard acted or a crossing was found late)");
}

void Cable::update(std::span<const BodyState> select, std::span<const BodyState> bodies,
                   std::vector<std::string>* warnings) {
  placePulleys(select);
  if (path_.empty()) path_.resize(2);
  path_.front().world = worldPoint(select, startBody_, def_->start.point);
  path_.back().world = worldPoint(select, endBody_, def_->end.point);

  // The path before re-selection, for the length-jump check below.
  double before = 0;
  signature_.clear();
  for (size_t i = 0; i < path_.size(); ++i) {
    signature_.push_back({path_[i].pulley, path_[i].vertex});
    if (i > 0)
      before += (worldPoint(bodies, path_[i].body, path_[i].local) -
                 worldPoint(bodies, path_[i - 1].body, path_[i - 1].local))
                    .norm();
  }

  // Settle the engaged set: leaves first, then joins, until nothing changes.
  const int count = static_cast<int>(pulleys_.size());
  droppedBefore_.resize(count);
  engagedBefore_.resize(count);
  for (int j = 0; j < count; ++j) {
    droppedBefore_[j] = pulleys_[j].dropped;
    engagedBefore_[j] = pulleys_[j].engaged;
  }
  for (int round = 0; round < 2 * count + 2; ++round) {
    if (!buildPath(warnings)) continue;
    bool changed = false;
    // Leave: the path no longer bends around the pulley.
    for (size_t i = 1; i + 1 < path_.size() && !changed; ++i) {
      const int j = path_[i].pulley;
      PulleyState& p = pulleys_[j];
      if (p.side == WrapSide::Threaded || p.polygon) continue;
      const double depth =
          wrapSideDistance(path_[i - 1].world, path_[i + 1].world, p.world[0], p.side);
      if (depth < 0) {
        p.engaged = false;
        p.previousDepth = depth;
        changed = true;
      }
    }
    // Polygons with an empty chain have left already in the path (no vertex emitted).
    for (int j = 0; j < count && !changed; ++j) {
      PulleyState& p = pulleys_[j];
      if (!p.engaged || !p.polygon) continue;
      const bool inPath = std::any_of(path_.begin(), path_.end(),
                                      [j](const WrapPoint& w) { return w.pulley == j; });
      if (!inPath) {
        p.engaged = false;
        p.previousDepth = 0;
        changed = true;
      }
    }
    if (changed) continue;
    // Join: a disengaged pulley that crossed its host segment from the non-wrap side.
    size_t host = 0;  // path index of the last point before pulley j
    for (int j = 0; j < count && !changed; ++j) {
      PulleyState& p = pulleys_[j];
      if (p.engaged) {
        while (host + 1 < path_.size() - 1 && path_[host + 1].pulley == j) ++host;
        continue;
      }
      const Vec2 a = path_[host].world;
      const Vec2 b = path_[host + 1].world;
      double depth = -1e300;
      for (const Vec2& v : p.world) depth = std::max(depth, wrapSideDistance(a, b, v, p.side));
      bool cuts;
      if (p.polygon) {
        cuts = segmentCutsPolygon(a, b, p.world);
      } else {
        const Vec2 ab = b - a;
        const double t = ab.squaredNorm() > 0 ? (p.world[0] - a).dot(ab) / ab.squaredNorm() : -1;
        cuts = t > 0 && t < 1 && (firstUpdate_ ? depth >= 0 : depth > 0);
      }
      bool crossed = firstUpdate_ || p.previousDepth <= 0;
      p.previousDepth = depth;
      // A polygon a guard dropped rejoins once a taut path round it exists again.
      if (p.dropped && cuts && !crossed) {
        // Only where the drop is undone, not round the far side of a polygon that went through.
        crossed = wrapChain(a, b, p.world, p.side, rejoinChain_) &&
                  chainLength(a, b, p.world, rejoinChain_) - (b - a).norm() <=
                      p.dropCut + kLengthJump;
        if (crossed && warnings)
          warnings->push_back("cable '" + def_->name + "': pulley " + std::to_string(j) +
                              " rejoined the path (a guard had dropped it)");
      }
      if (!cuts && depth <= 0) p.dropped = false;
      if (cuts && crossed) {
        p.engaged = true;
        p.dropped = false;
        changed = true;
      }
    }
    if (!changed) break;
  }

  cableKinematics(path_, bodies, kin_);
  // What a drop in this update took out is what a later rejoin may put back.
  for (int j = 0; j < count; ++j)
    if (pulleys_[j].dropped && !droppedBefore_[j])
      pulleys_[j].dropCut = std::max(0.0, before - kin_.length);
  reportLengthJump(before, warnings);
  if (warnings && kin_.zeroLengthSegments > 0 && !reportedZeroLength_)
    warnings->push_back("cable '" + def_->name + "': " + std::to_string(kin_.zeroLengthSegments) +
                        " zero-length segment(s) (coincident points) left out of the Jacobian");
  reportedZeroLength_ = kin_.zeroLengthSegments > 0;
  if (firstUpdate_ && params_.restLength < 0) params_.restLength = kin_.length;
  firstUpdate_ = false;
}

}  // namespace cablelab

// Skipping the wrap selection and the event search while the wrap set cannot change
// (docs/cables.md, "Skipping").
//
// Every change of a cable's wrap set is a sign change of one of the signed distances that
// nextEvent() watches (cable_events.cpp): a polygon's next vertex from the segment entering or
// leaving its chain, a wrap point from the line through its neighbours, a free polygon's corners
// from the other segments. A full update records each of those distances at its selection pose.
// Later, with every point's displacement from that pose bounded by the bodies' displacement (|dx| +
// |r| |dtheta|, plus the sub-step's motion for the event search), a distance whose start value
// exceeds the most the displacement can change it keeps its sign along the straight path in pose
// space to the new pose, so the selection there keeps the wrap set and the search finds nothing.
// Only cables whose pulleys are all engaged points or polygons (no circles, auto sides, dropped
// pulleys, threaded polygons, drum ends, spans, or neighbouring polygons) take part; the others
// always take the full path. While skipping, a length and J (and the turns kept from them) are not
// worked out again for poses of the path's bodies that are, bit for bit, those they were worked out
// on (the step's refresh and the next sub-step see the same poses, and so do sub-steps in which
// Box2D moved no body of the path, as for most of the hand's run). Most checks take one comparison
// a body: a certificate's allowance, a displacement that no test's bound can reach.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "engine/cable/cable.h"
#include "engine/cable/wrap.h"

namespace cablelab {

namespace {

// Whether a test (p's distance from the line a-b) holds with a, b and p moved by at most da, db
// and dp from the certificate's pose.
// The bound integrates d/dt cross(n, p - a) as sideCannotChange (crossing.cpp) does, with the
// displacements in place of speed times h: |n'| <= |b' - a'| / |b - a| along the way. Every
// operation is monotone in the displacements (IEEE rounding is), so what holds at some
// displacements holds, computed, at any smaller ones.
bool testHolds(double length, double arm, double margin, double da, double db, double dp) {
  const double shortest = length - da - db;
  if (!(shortest > 0)) return false;
  const double reach = arm + dp + da;
  const double bound = dp + da + (da + db) * reach / shortest;
  return margin > 1.01 * bound + 1e-12;
}

// A displacement that every point of the test may have (-1: none). With all three equal to a,
// margin / 1.01 - 1e-12 > bound multiplied out by shortest > 0 is linear in a; the value is
// checked on the computed test itself, at a little more than the allowance.
double testAllowance(double length, double arm, double margin) {
  const double m = (margin - 1e-12) / 1.01;
  if (!(m > 0)) return -1;
  double a = 0.999 * m * length / (2 * (m + length + arm));
  for (int tries = 0; tries < 4; ++tries, a *= 0.5) {
    const double over = 1.0001 * a;
    if (testHolds(length, arm, margin, over, over, over)) return a;
  }
  return -1;
}

// Bit for bit: the same inputs give kinematics the same bits (even -0 against +0).
bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

}  // namespace

void Cable::setSkipping(bool on) {
  skipping_ = on;
  if (!on) skipValid_ = false;
}

bool Cable::skipEligible() const {
  if (start_.radius != 0 || end_.radius != 0 || startDrum_.radius != 0 || endDrum_.radius != 0 ||
      !spans_.empty())
    return false;
  for (size_t j = 0; j < pulleys_.size(); ++j) {
    const PulleyState& p = pulleys_[j];
    if (idleSecondPlace(static_cast<int>(j))) continue;
    if (!p.engaged || p.circle || p.autoSide || p.dropped || p.tiedEnd != 0 || p.hold.holdingFrom ||
        p.hold.holdingInto || (p.polygon && p.side == WrapSide::Threaded))
      return false;
    // Neighbouring polygons settle their common tangent over several passes (buildPath).
    if (const size_t next = rank_[j] + 1; p.polygon && next < pulleys_.size() &&
                                          pulleys_[order_[next]].polygon &&
                                          !idleSecondPlace(order_[next]))
      return false;
  }
  return path_.size() >= 2;
}

void Cable::buildSkipCertificate(std::span<const BodyState> pose) {
  skipValid_ = false;
  skipTests_.clear();
  skipBodies_.clear();
  skipTurns_.clear();
  if (!skipping_ || !skipEligible()) return;
  skipAllowance_ = std::numeric_limits<double>::infinity();
  auto bodyIndex = [&](int body) {
    for (size_t k = 0; k < skipBodies_.size(); ++k)
      if (skipBodies_[k].body == body) return static_cast<int>(k);
    skipBodies_.push_back(body < 0 ? SkipBody{-1, Vec2::Zero(), 0.0}
                                   : SkipBody{body, pose[body].position, pose[body].angle});
    return static_cast<int>(skipBodies_.size()) - 1;
  };
  // p's distance from the line a-b; false when the segment is degenerate (no certificate).
  auto add = [&](const WrapPoint& a, const WrapPoint& b, int body, const Vec2& local) {
    const Vec2 wa = worldPoint(pose, a.body, a.local), wb = worldPoint(pose, b.body, b.local);
    const Vec2 wp = worldPoint(pose, body, local);
    const double length = (wb - wa).norm();
    if (!(length > 0)) return false;
    const SkipTest t{bodyIndex(a.body),
                     bodyIndex(b.body),
                     bodyIndex(body),
                     a.local.norm(),
                     b.local.norm(),
                     local.norm(),
                     std::abs(cross(wb - wa, wp - wa)) / length,
                     (wp - wa).norm(),
                     length};
    skipTests_.push_back(t);
    for (const auto& [k, r] : {std::pair{t.a, t.ra}, std::pair{t.b, t.rb}, std::pair{t.p, t.rp}})
      skipBodies_[k].reach = std::max(skipBodies_[k].reach, r);
    skipAllowance_ = std::min(skipAllowance_, testAllowance(t.length, t.arm, t.margin));
    return true;
  };
  // The same distances as nextEvent(): chain ends' next vertices against their segments...
  for (size_t i = 0; i + 1 < path_.size(); ++i) {
    const WrapPoint& a = path_[i];
    const WrapPoint& b = path_[i + 1];
    if (a.kind == WrapPoint::Kind::Vertex && b.kind == WrapPoint::Kind::Vertex &&
        a.pulley == b.pulley)
      continue;
    for (const WrapPoint* end : {&a, &b}) {
      if (end->kind != WrapPoint::Kind::Vertex) continue;
      const PulleyState& p = pulleys_[end->pulley];
      const int v = chainEndNeighbour(*end, end == &b);
      if (!add(a, b, p.body, p.local[v])) return;
    }
  }
  // ...a free polygon's corners against every other segment it may join (pulley_order.cpp;
  // unwatched, a knocked corner passed a strand unsearched: docs/knocks.md, "A corner crossing
  // another strand while the search is skipped")...
  for (size_t i = 0; i + 1 < path_.size(); ++i) {
    if (chainEdge(i)) continue;
    const WrapPoint& a = path_[i];
    const WrapPoint& b = path_[i + 1];
    for (int j = 0; j < static_cast<int>(pulleys_.size()); ++j) {
      const PulleyState& p = pulleys_[j];
      if (!p.engaged || !joinsAnySegment(j) || a.pulley == j || b.pulley == j ||
          (p.twin >= 0 && (a.pulley == p.twin || b.pulley == p.twin)))
        continue;
      for (const Vec2& corner : p.local)
        if (!add(a, b, p.body, corner)) return;
    }
  }
  // ...and every wrap point against the line through its neighbours.
  for (size_t i = 1; i + 1 < path_.size(); ++i)
    if (pulleys_[path_[i].pulley].side != WrapSide::Threaded &&
        !add(path_[i - 1], path_[i + 1], path_[i].body, path_[i].local))
      return;
  // The turns keepWrapSet() keeps: each pulley's, from the segment into its first path point to
  // the one out of its last (a polygon's run of vertices). A threaded pulley never leaves and its
  // turn is not kept (leaveRound).
  for (size_t i = 1; i + 1 < path_.size(); ++i) {
    const int j = path_[i].pulley;
    const PulleyState& p = pulleys_[j];
    size_t k = i;
    while (p.polygon && k + 2 < path_.size() && path_[k + 1].pulley == j) ++k;
    if (p.side != WrapSide::Threaded)
      skipTurns_.push_back({j, static_cast<int>(i) - 1, static_cast<int>(k),
                            p.side == WrapSide::Right ? -1.0 : 1.0, 0.0});
    i = k;
  }
  // Per-call scratch, sized once; the world never moves.
  skipMotion_.assign(skipBodies_.size(), Vec2::Zero());
  // The bodies whose poses kin_ is a function of (kinematicsCurrent).
  kinPoses_.clear();
  for (const WrapPoint& w : path_)
    if (w.body >= 0 && std::none_of(kinPoses_.begin(), kinPoses_.end(),
                                    [&](const SkipBody& k) { return k.body == w.body; }))
      kinPoses_.push_back({w.body, pose[w.body].position, pose[w.body].angle});
  skipValid_ = true;
}

// Displacements are bounded per body; a body's bound on its farthest tested point, within the
// certificate's allowance, covers every test (testHolds is monotone), else each test is checked.
bool Cable::wrapSetCertain(std::span<const BodyState> pose, double h) const {
  bool within = skipAllowance_ >= 0;
  for (size_t k = 0; k < skipBodies_.size(); ++k) {
    const SkipBody& c = skipBodies_[k];
    if (c.body < 0) continue;
    const BodyState& b = pose[c.body];
    // At h = 0 (a selection pose) the velocities add nothing.
    const Vec2 m = h == 0 ? Vec2((b.position - c.position).norm(), std::abs(b.angle - c.angle))
                          : Vec2((b.position - c.position).norm() + h * b.velocity.norm(),
                                 std::abs(b.angle - c.angle) + h * std::abs(b.angularVelocity));
    skipMotion_[k] = m;
    within &= m.x() + c.reach * m.y() <= skipAllowance_;
  }
  if (within) return true;
  auto moved = [&](int k, double r) { return skipMotion_[k].x() + r * skipMotion_[k].y(); };
  for (const SkipTest& t : skipTests_)
    if (!testHolds(t.length, t.arm, t.margin, moved(t.a, t.ra), moved(t.b, t.rb), moved(t.p, t.rp)))
      return false;
  return true;
}

// The selection's result when the wrap set stays: the same path, its kinematics on `bodies`, and
// the turn angles it keeps over time. The certificate keeps every wrap point's own turn in the
// wrap sense, so a pulley's turn is the angle from its incoming to its outgoing direction, on the
// branch nearest the last one (what walkTurning sums vertex by vertex on a full update). False
// (the full update runs) when the certificate does not cover `select`, or a turn straightens.
bool Cable::keepWrapSet(std::span<const BodyState> select, std::span<const BodyState> bodies) {
  if (!wrapSetCertain(select, 0)) return false;
  if (kinematicsCurrent(bodies)) {
    // Nothing moved since this kept the turns: the same directions give the same turns.
    if (turnsCurrent_) return true;
  } else {
    cableLengthJacobian(path_, bodies, kin_);
    noteKinematicsPoses(bodies);
  }
  if (kin_.zeroLengthSegments > 0) return false;
  for (SkipTurn& t : skipTurns_) {
    const PulleyState& p = pulleys_[t.pulley];
    const Vec2& in = kin_.directions[t.in];
    const Vec2& out = kin_.directions[t.out];
    const double raw = -t.sign * std::atan2(cross(in, out), in.dot(out));
    // round() of a value within half a turn is +-0 (its sign): the call only off that branch.
    const double turns = (p.arc - raw) / (2 * M_PI);
    t.arc =
        raw + 2 * M_PI * (std::abs(turns) < 0.5 ? std::copysign(0.0, turns) : std::round(turns));
    if (p.polygon ? t.arc <= kStraightWrapTurn : t.arc < 0) return false;
  }
  for (const SkipTurn& t : skipTurns_) pulleys_[t.pulley].arc = t.arc;
  turnsCurrent_ = true;
  return true;
}

bool Cable::kinematicsCurrent(std::span<const BodyState> bodies) const {
  if (!kinPosesValid_) return false;
  for (const SkipBody& k : kinPoses_) {
    const BodyState& b = bodies[k.body];
    if (!sameBits(b.position.x(), k.position.x()) || !sameBits(b.position.y(), k.position.y()) ||
        !sameBits(b.angle, k.angle))
      return false;
  }
  return true;
}

// The path, and so its bodies, stays while the certificate does (buildSkipCertificate).
void Cable::noteKinematicsPoses(std::span<const BodyState> bodies) {
  for (SkipBody& k : kinPoses_) {
    k.position = bodies[k.body].position;
    k.angle = bodies[k.body].angle;
  }
  kinPosesValid_ = true;
  turnsCurrent_ = false;
}

}  // namespace cablelab

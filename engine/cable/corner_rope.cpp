// The rope stuck between the engaged corners of a polygon with friction, on an elastic cable
// (docs/polygon_friction.md, "Elastic cables"): material moves between it and the spans only
// where a corner joins or leaves a chain's end.
//
// A piece that joins takes the rope its span gave up, at the span's strain: the span keeps its
// tension and the piece holds the stretch it had. A slack span is not stretched anywhere, so it
// gives the piece its straight length (taking it at the span's strain, metres of slack material
// went onto the corners and came back at another strain, and the masses fell through the band).
// A piece that leaves gives its span back exactly what it holds, so a corner that joins and
// leaves again moves no material (giving back at the span's or the rope's strain pumped it).
// Neither creates stretch energy: the join keeps each piece's strain, and the leave mixes two
// strains into one, which only lowers sum r f(l / r - 1) (f convex, increasing). Each corner
// also holds its two sides to its own capstan ratio (slideCornerRope), pieces included.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/core/capstan.h"

namespace cablelab {

namespace {

// The corners path[in..out] holds, in order: one chain of a polygon with friction.
std::vector<int> chainCorners(std::span<const WrapPoint> path, size_t in, size_t out) {
  std::vector<int> corners;
  for (size_t i = in; i <= out; ++i) corners.push_back(path[i].vertex);
  return corners;
}

}  // namespace

double Cable::cornerGap(int pulley, int a, int b) const {
  const std::vector<Vec2>& v = pulleys_[pulley].local;
  return (v[a] - v[b]).norm();
}

void Cable::shareCornerRope(const std::vector<Split>& splits, double stretchRatio) {
  cornerRopes_.assign(splits.size(), CornerRope{});
  cornerRest_ = 0;
  for (size_t k = 0; k < splits.size(); ++k) {
    if (path_[splits[k].in].kind != WrapPoint::Kind::Vertex) continue;  // a wheel
    CornerRope& rope = cornerRopes_[k];
    rope.pulley = path_[splits[k].in].pulley;
    rope.vertices = chainCorners(path_, splits[k].in, splits[k].out);
    for (size_t i = 0; i + 1 < rope.vertices.size(); ++i) {
      rope.rests.push_back(cornerGap(rope.pulley, rope.vertices[i], rope.vertices[i + 1]) /
                           stretchRatio);
      cornerRest_ += rope.rests.back();
    }
  }
}

void Cable::moveCornerRope(const std::vector<Split>& splits) {
  const size_t n = spans_.size();
  spanGained_.assign(n, 0.0);  // material the leaving pieces give each span back
  spanLeft_.assign(n, 0.0);    // their lengths, which the span's path took up again
  // Pieces that joined, by the span they take from: (link, piece, length).
  struct Joined {
    size_t link, piece, span;
    double length;
  };
  std::vector<Joined> joined;
  for (size_t k = 0; k < splits.size(); ++k) {
    CornerRope& rope = cornerRopes_[k];
    if (path_[splits[k].in].kind != WrapPoint::Kind::Vertex) continue;  // a wheel
    const std::vector<int> vertices = chainCorners(path_, splits[k].in, splits[k].out);
    if (vertices == rope.vertices || rope.vertices.empty()) continue;
    const size_t oldPieces = rope.vertices.size() - 1, newPieces = vertices.size() - 1;
    // The corners both chains hold: a run, each chain being a run of the polygon's corners.
    size_t i0 = 0, j0 = 0, common = 0;
    for (size_t i = 0; i < rope.vertices.size() && common == 0; ++i) {
      const auto at = std::find(vertices.begin(), vertices.end(), rope.vertices[i]);
      if (at == vertices.end()) continue;
      i0 = i, j0 = at - vertices.begin();
      while (i0 + common < rope.vertices.size() && j0 + common < vertices.size() &&
             rope.vertices[i0 + common] == vertices[j0 + common])
        ++common;
    }
    std::vector<double> rests(newPieces, 0.0);
    auto leave = [&](size_t piece, size_t span) {
      spanGained_[span] += rope.rests[piece];
      spanLeft_[span] += cornerGap(rope.pulley, rope.vertices[piece], rope.vertices[piece + 1]);
    };
    auto join = [&](size_t piece, size_t span) {
      joined.push_back(
          {k, piece, span, cornerGap(rope.pulley, vertices[piece], vertices[piece + 1])});
    };
    if (common > 0) {
      // Before the run the chain's start moved (span k's side), after it its end (span k + 1's).
      for (size_t p = 0; p < i0; ++p) leave(p, k);
      for (size_t p = 0; p < j0; ++p) join(p, k);
      for (size_t p = 0; p + 1 < common; ++p) rests[j0 + p] = rope.rests[i0 + p];
      for (size_t p = i0 + common - 1; p < oldPieces; ++p) leave(p, k + 1);
      for (size_t p = j0 + common - 1; p < newPieces; ++p) join(p, k + 1);
    } else {
      // No corner in common (the chain rolled on by a corner or more within one update): the
      // old pieces go to the span that grew, the new ones take from the one that shrank, and so
      // does the rope that passed over the corners between them.
      const double growA = spanBefore_[k] >= 0 ? spans_[k].kin.length - spanBefore_[k] : 0.0;
      const double growB =
          spanBefore_[k + 1] >= 0 ? spans_[k + 1].kin.length - spanBefore_[k + 1] : 0.0;
      const size_t grew = growA >= growB ? k : k + 1, shrank = growA >= growB ? k + 1 : k;
      for (size_t p = 0; p < oldPieces; ++p) leave(p, grew);
      for (size_t p = 0; p < newPieces; ++p) join(p, shrank);
      // Passed over: what the shrinking span lost beyond the new pieces, moved at its strain.
      double newLength = 0;
      for (size_t p = 0; p < newPieces; ++p)
        newLength += cornerGap(rope.pulley, vertices[p], vertices[p + 1]);
      const double before = spanBefore_[shrank];
      if (before > 0) {
        const double passed = std::max(0.0, before - spans_[shrank].kin.length - newLength) *
                              std::min(1.0, spans_[shrank].rest / before);
        spanGained_[shrank] -= passed;
        spanGained_[grew] += passed;
      }
    }
    rope.vertices = vertices;
    rope.rests = std::move(rests);
  }
  for (size_t s = 0; s < n; ++s) {
    Span& span = spans_[s];
    double joinedLength = 0;
    for (const Joined& j : joined)
      if (j.span == s) joinedLength += j.length;
    double take = 0;
    const double before = spanBefore_[s];
    if (joinedLength > 0 && before > 0) {
      // The rope the span's path gave up to the joining pieces, at the span's strain (at its
      // length where the span was slack): the span keeps its strain.
      const double given = std::max(0.0, before - span.kin.length + spanLeft_[s]);
      take = given * std::min(1.0, span.rest / before);
      take = std::min(take, 0.999 * (span.rest + spanGained_[s]));  // a span keeps material
      for (const Joined& j : joined)
        if (j.span == s) cornerRopes_[j.link].rests[j.piece] = take * j.length / joinedLength;
    }
    span.rest += spanGained_[s] - take;
  }
  cornerRest_ = 0;
  for (const CornerRope& rope : cornerRopes_)
    for (const double r : rope.rests) cornerRest_ += r;
}

// Each corner holds while T_high <= e^(mu theta_i) T_low between the rope on its two sides (a
// span or a piece): where one does not, rope slides over it from the slacker side to the tighter
// until the ratio is exact (slideMaterial, as slideElasticSpans does between the spans), corner
// after corner until all hold. Each slide lowers the stretch energy; a piece split at a tension
// its spans no longer hold gives its stretch up instead of keeping it.
void Cable::slideCornerRope() {
  const double material = materialLength();
  for (size_t k = 0; k < cornerRopes_.size(); ++k) {
    CornerRope& rope = cornerRopes_[k];
    const size_t pieces = rope.rests.size();
    if (pieces == 0 || links_[k].grip != Grip::Capstan) continue;
    // The rope on each side of corner j (j = 0 .. pieces): element j before it, j + 1 after;
    // element 0 is span k, element pieces + 1 span k + 1, the pieces between.
    auto length = [&](size_t e) {
      if (e == 0) return spans_[k].kin.length;
      if (e == pieces + 1) return spans_[k + 1].kin.length;
      return cornerGap(rope.pulley, rope.vertices[e - 1], rope.vertices[e]);
    };
    auto rest = [&](size_t e) -> double& {
      if (e == 0) return spans_[k].rest;
      if (e == pieces + 1) return spans_[k + 1].rest;
      return rope.rests[e - 1];
    };
    for (int sweep = 0; sweep < kCornerSweeps; ++sweep) {
      bool slid = false;
      for (size_t j = 0; j <= pieces; ++j) {
        const double ratio = std::exp(links_[k].mu * cornerTurn(spans_[k].last + j));
        const double la = length(j), lb = length(j + 1);
        double &ra = rest(j), &rb = rest(j + 1);
        const double ta = materialTension(material, la, ra);
        const double tb = materialTension(material, lb, rb);
        if (std::max(ta, tb) <= ratio * std::min(ta, tb) * (1 + 1e-9)) continue;
        const double sum = ra + rb;
        if (ta > tb) {
          ra = slideMaterial(material, la, ra, lb, sum, ratio);
          rb = sum - ra;
        } else {
          rb = slideMaterial(material, lb, rb, la, sum, ratio);
          ra = sum - rb;
        }
        slid = true;
      }
      if (!slid) break;
    }
  }
  cornerRest_ = 0;
  for (const CornerRope& rope : cornerRopes_)
    for (const double r : rope.rests) cornerRest_ += r;
}

double Cable::elasticEnergy() const {
  if (!elastic()) return 0;
  if (spans_.empty()) return 0.5 * params_.stiffness * std::pow(std::max(0.0, stretch()), 2);
  // Each piece a spring of its own material r: stiffness k L / r (Cable::spanStiffness).
  const double material = materialLength();
  auto spring = [&](double length, double rest) {
    if (!(rest > 0)) return 0.0;
    const double over = std::max(0.0, length - rest);
    return 0.5 * params_.stiffness * material / rest * over * over;
  };
  double e = 0;
  for (const Span& s : spans_) e += spring(s.kin.length, s.rest);
  for (const CornerRope& rope : cornerRopes_)
    for (size_t i = 0; i < rope.rests.size(); ++i)
      e += spring(cornerGap(rope.pulley, rope.vertices[i], rope.vertices[i + 1]), rope.rests[i]);
  return e;
}

}  // namespace cablelab

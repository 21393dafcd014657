// Stage 4b of the cable solve (cable_solver.cpp): rows whose start-of-step J has lost its say
// pull along J at the pose the free motion reaches; the path a span takes at a pose.
#include "engine/dynamics/cable_solver_stages.h"

#include <algorithm>

#include "engine/cable/wrap.h"
#include "engine/dynamics/floors.h"

namespace cablelab::cable_stages {

namespace {

// A joining point that the free motion bends the cable round by more than this (sin of the turn)
// within a nominal sub-step (a step cut at the join is shorter: the turn over it is scaled) joins
// fast: pulling along J0, which has no share of it, the solve stops the
// cable with the other bodies while the point goes on (a puck at 5 m/s caught by a rope whose
// far end is on a pivoted arm: +8.5% energy; at 20 m/s: 13.5 kJ from 200 J). Slower joins keep
// J0: the share, a guess at the step's average, changes the energy at every wrap change of a
// hexagon swinging on its pivot (0.025 rad a step), for the worse as often as not. At 1 m/s
// (0.033 rad) the puck's catch gains 1.1%.
constexpr double kFastJoinTurn = 0.1;
constexpr double kJoinSay = 100;

// Whether path point i (a point pulley or polygon vertex on a moving body, wrapped) bends the
// cable by almost nothing: it has just joined, or is about to leave.
bool nearlyStraight(const Cable& cable, std::span<const WrapPoint> path,
                    std::span<const Vec2> directions, size_t i) {
  const WrapPoint& w = path[i];
  if (w.pulley < 0 || w.body < 0 || w.kind == WrapPoint::Kind::Circle ||
      cable.wrapSide(w.pulley) == WrapSide::Threaded)
    return false;
  const Vec2 &in = directions[i - 1], &out = directions[i];
  return std::abs(cross(in, out)) < 1e-3 && in.dot(out) > 0;
}

}  // namespace

// J0 W(:, r): how far a unit impulse of row r moves its own length (1/kg), W as stages 2-4 left
// it. 0 where the joints leave the row no say.
double rowSay(Workspace& ws, std::span<const BodyState> bodies, std::span<const Cable> cables,
              int r) {
  double say = 0;
  forStartJacobians(ws, bodies, cables, r, [&](const auto& jacobian, double) {
    for (const auto& e : jacobian)
      if (const int d = ws.dofs.ofBody[e.body]; d >= 0) say += e.d.dot(ws.W.block<3, 1>(d, r));
  });
  return say;
}

// The span's path at `bodies` as the cable will take it (into ws.path, its length and J into
// ws.kin): a point pulley that the motion carried to its unwrapped side is left out, as the cable
// leaves it there. A path bent backwards round it would be longer, and Newton would pull to hold
// a length the cable never has (a rope straightening between fixed points: 9e9 N).
void pathAhead(Workspace& ws, const Cable& cable, int span, std::span<const BodyState> bodies) {
  const std::span<const WrapPoint> source = cable.spanPath(span);
  ws.path.assign(source.begin(), source.end());
  cableLengthJacobian(ws.path, bodies, ws.kin);
  for (size_t i = 1; i + 1 < ws.path.size(); ++i) {
    const WrapPoint& w = ws.path[i];
    if (w.kind != WrapPoint::Kind::Point || w.pulley < 0 ||
        cable.wrapSide(w.pulley) == WrapSide::Threaded)
      continue;
    // As the cable's own leave rule (Cable::leaveRound): a point that the cable doubled back
    // round past half a turn stays (with the sign alone, a point that hooked a ballast's cable
    // beyond its end pulley left the prediction, the solve saw a slack cable and let it go: the
    // rigid cable grew to 60 m).
    const Vec2 in = w.world - ws.path[i - 1].leaving(), out = ws.path[i + 1].arriving() - w.world;
    if (continuedPointTurn(in, out, cable.wrapSide(w.pulley), cable.pointTurn(w.pulley)) >= 0)
      continue;
    ws.path.erase(ws.path.begin() + static_cast<std::ptrdiff_t>(i));
    cableLengthJacobian(ws.path, bodies, ws.kin);
    i = 0;
  }
}

// 4b. Rows whose start-of-step J has lost its say: a point that just joined has no share of J0
// (theorem 1), and the joints may take the rest (a cable's end on an arm pivoted at its
// pulley). Pulling along J0 such a row needs unbounded impulses (1e24 N were seen), or throws
// the one body that can give cable (an arm spun to 236 rad/s by a puck it did not stop). A row
// with no say at all (J0 W = 0) pulls along J at the pose v* reaches instead; a row whose wrap
// point joins fast (v* bends the cable round it by more than kFastJoinTurn a sub-step) gives that
// point half the share of J it has there. Newton still solves the end-of-step length. True if
// any row was redirected (then stages 2-4 run again).
bool redirectBlockedRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  const int m = static_cast<int>(ws.rows.size());
  ws.ahead.assign(m, 0);
  bool any = false, moved = false;
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment >= 0 || row.first != row.last) continue;
    const Cable& cable = cables[row.cable];
    const std::span<const WrapPoint> span = cable.spanPath(row.first);
    const std::span<const Vec2> directions = cable.spanKinematics(row.first).directions;
    int joining = -1;  // a nearly straight wrap point on a dof
    double reach = 0;  // the largest M^-1 on the row's bodies
    for (size_t i = 0; i < span.size(); ++i) {
      const int d = span[i].body >= 0 ? ws.dofs.ofBody[span[i].body] : -1;
      if (d < 0) continue;
      reach = std::max(reach, ws.invM[d]);
      if (i > 0 && i + 1 < span.size() && nearlyStraight(cable, span, directions, i))
        joining = static_cast<int>(i);
    }
    const double authority = ws.JW0(r, r);  // the row's say (rowSay: no row pulls ahead yet)
    const bool blocked = authority <= 1e-9 * reach;
    if (joining < 0 && !blocked) continue;
    if (!moved) {
      ws.free.assign(ws.predicted.begin(), ws.predicted.end());
      for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
        const BodyState& b = in.bodies[ws.dofs.body[k]];
        BodyState& f = ws.free[ws.dofs.body[k]];
        f.position = b.position + in.h * ws.vStar.segment<2>(3 * k);
        f.angle = b.angle + in.h * ws.vStar[3 * k + 2];
      }
      ws.aheadJacobian.resize(m);
      moved = true;
    }
    pathAhead(ws, cable, row.first, ws.free);
    if (joining < 0) {  // no say at all: the whole row pulls along J there
      ws.aheadJacobian[r] = ws.kin.jacobian;
      ws.ahead[r] = 1;
      any = true;
      continue;
    }
    // A joining point must still be on the path there, bent further onto its wrap side and by
    // more than kFastJoinTurn. It then gets half the share of J it has there, dL/dp = u_in -
    // u_out (the share grows from 0 over the step); the rest of the row keeps J0 (J there for
    // every body made a hexagon on its pivot lose 3 times the energy at wrap changes).
    const WrapPoint& w = span[joining];
    const auto kept = std::find_if(ws.path.begin(), ws.path.end(), [&](const WrapPoint& p) {
      return p.pulley == w.pulley && p.kind == w.kind && p.vertex == w.vertex;
    });
    if (kept == ws.path.end() || kept == ws.path.begin() || kept + 1 == ws.path.end()) continue;
    const size_t i = static_cast<size_t>(kept - ws.path.begin());
    const Vec2 pull = ws.kin.directions[i - 1] - ws.kin.directions[i];
    const Vec2 arm = kept->world - ws.free[w.body].position;
    const Vec3 share = 0.5 * Vec3(pull.x(), pull.y(), pull.dot(perp(arm)));
    // Slow joins keep J0, unless the rest of the row has less than kJoinSay times the say the
    // point would have (its share's M^-1 norm): a rope whose far end is on an arm pivoted 1 cm
    // beside its pulley (3e-4 against 3e-4) caught a puck at 1 m/s and gained 9 times the throw's
    // energy; a hexagon's vertex joining its rope holds 1e-4 against the weight's 1.
    const double turn = std::abs(cross(ws.kin.directions[i - 1], ws.kin.directions[i]));
    const Vec3 inverse = ws.invM.segment<3>(ws.dofs.ofBody[w.body]);
    if (turn <= std::abs(cross(directions[joining - 1], directions[joining])) ||
        (turn < kFastJoinTurn * in.share &&
         authority >= kJoinSay * share.dot(inverse.cwiseProduct(share))))
      continue;
    std::vector<BodyJacobian>& jacobian = ws.aheadJacobian[r];
    jacobian = cable.spanKinematics(row.first).jacobian;
    const auto entry = std::find_if(jacobian.begin(), jacobian.end(),
                                    [&](const BodyJacobian& e) { return e.body == w.body; });
    if (entry == jacobian.end())
      jacobian.push_back({w.body, share});
    else
      entry->d += share;
    ws.ahead[r] = 1;
    any = true;
  }
  return any;
}

}  // namespace cablelab::cable_stages

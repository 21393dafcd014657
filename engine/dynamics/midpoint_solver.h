// The energy-consistent cable solve: implicit midpoint with discrete gradients
// (docs/cables.md, "Energy").
//
// Box2D integrates symplectic Euler, q1 = q0 + h v1, whose measured energy swings by about
// omega h / 2 of the energy of a mode omega: a puck caught by a cable (omega h ~ 0.5 at 60 Hz)
// or a bouncing elastic rope loses or gains tens of per cent per bounce. For the bodies the
// cables move this solve makes the step an implicit midpoint one instead:
//     q1 = q0 + h (v0 + v1) / 2,    M (v1 - v0) = h F_ext - G^T P,
// where G is the discrete gradient of each cable's length between q0 and q1
// (G (q1 - q0) = length(q1) - length(q0) exactly) and P is the impulse: a rigid cable keeps
// its length, an elastic one pulls with the discrete gradient of its energy,
// (V(phi1) - V(phi0)) / (phi1 - phi0). Kinetic plus potential energy is then conserved exactly
// by the step (gravity is constant), up to the Newton tolerance. Box2D still does the moving: it
// is given the force that makes its velocity (v0 + v1) / 2, and the bodies get the other half,
// v1 - (v0 + v1) / 2, after its step (`kicks`).
//
// Newton on (v_b, P) with the geometric stiffness in the iteration matrix converges in a few
// steps even where the cable's transverse mode is far from resolved (a puck caught at 50 m/s).
// The choice is made per cable island (cable_islands.h: cables sharing a moving body). It takes
// an island when some cable of it is elastic or has a pulley on a moving body (straight cables
// over fixed pulleys keep Box2D's own integration, which the Box2D pulley-joint comparison
// relies on) and no body its cables move is jointed (the joint projection would have to be
// redone per iteration) or touching a contact; the main solve takes the other islands, and an
// island whose Newton does not settle. An elastic cable whose axial mode the step does not
// resolve (omega h > kMaxElasticOmegaH) pulls with its spring at the end of the step instead of
// the discrete gradient: that damps the mode, never gains, and keeps the slow swing exact (unless
// it wraps or passes over a moving body, whose sideways mode is as stiff: the main solve). So
// undamped parts of a busy world keep their energy beside jointed and touching ones (within 5e-6 of
// their kinetic energy over 12 s in the busy test scene, where the whole-world choice lost 70-90%;
// docs/cables.md, "Long runs").
#pragma once

#include <span>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "engine/cable/cable.h"
#include "engine/dynamics/block_diagonal_inverse.h"
#include "engine/dynamics/step_chords.h"
#include "engine/dynamics/tension_solver.h"

namespace cablelab {

class MidpointSolver {
 public:
  /// Largest omega h of an elastic cable's axial mode bound (elasticMode, reached only where the
  /// cable folds back on itself) the solve keeps exactly: faster springs are not resolved by the
  /// step and pull with their tension at the end of the step, which damps them (stable at any k).
  static constexpr double kMaxElasticOmegaH = 4.0;
  /// An island of more cables with such a spring (a rope of stiff links) keeps the main solve,
  /// whose sparse path takes big islands (sparse_island.h, the same default size) and whose
  /// spring damps the mode too: this solve is dense, O(n^3) a Newton iteration.
  static constexpr int kMaxCablesWithUnresolvedSpring = 32;

  /// Whether this solve should take the step of the cables `which` (an island, cable_islands.h):
  /// some cable is elastic, has a pulley on a moving body (wrapped or not), is a loop on one body
  /// that turns, has a segment short enough to need a floor (a body nearing its pulley), or is
  /// rigid and swings across itself or off the line of `gravity` (m/s^2) (straight cables
  /// between fixed pulleys and different bodies, running only along themselves, keep Box2D's
  /// own integration), or is rigid, runs over pulleys, swings and has been taut for
  /// kSettledTautSteps (setTautSteps; docs/swings.md),
  /// and no moved body is `excluded` (jointed or in contact). `h` is the step about to be
  /// taken, `subStep` the sub-step it is part of (a cut or a refinement takes a part of it): a
  /// rigid cable's swing is judged over the sub-step, so every part of it keeps one rule.
  bool applies(std::span<const BodyState> bodies, std::span<const Cable> cables,
               std::span<const int> which, std::span<const char> excluded, double h, double subStep,
               const Vec2& gravity);

  /// Per cable, how many whole steps in a row it has ended taut (World::recordRates): a rigid
  /// rope over pulleys that swings takes this solve once it has stayed taut for
  /// kSettledTautSteps, and a rope just caught from slack keeps the main solve's catch
  /// (docs/swings.md). Empty: none counts as settled.
  void setTautSteps(std::span<const int> steps) { tautSteps_ = steps; }
  /// Steps a rope must have ended taut before its swing over pulleys takes this solve.
  static constexpr int kSettledTautSteps = 4;

  /// Sets the tensions of the cables `which`, adds the force Box2D needs over h to `forces`
  /// ((fx, fy, torque) per body) and the velocity each body they move must get after Box2D's
  /// step to `kicks`; other bodies and cables are left alone. `share` is h over the nominal
  /// sub-step (CableSolveInput::share). Its cost is the island's, not the world's.
  /// Returns the iterations used, or -1 (nothing changed) if they did not converge, or at once
  /// when the rows the first iteration's impulses pull on are redundant (`redundant()`), or
  /// when a floor row pushes (`floorHit()`): that is an impact, which the midpoint rule would
  /// turn into an elastic bounce; the main solve stops the body at its pulley instead.
  int solve(std::span<const BodyState> bodies, std::span<Cable> cables, std::span<const int> which,
            const Vec2& gravity, double h, double share, std::span<Vec3> forces,
            std::span<Vec3> kicks);

  /// The end-of-step velocity (vx, vy, omega) of each body the last solve moved, appended to
  /// `ends`: World sets them after Box2D's step, whose float velocity update would leave a body at
  /// rest moving at 1e-8 m/s.
  void appendEnds(std::vector<std::pair<int, Vec3>>& ends) const;

  /// The fastest transverse mode of the cables `which` (rad/s), from their tensions and segment
  /// curvatures over the lightest body they move: sqrt(T sum(1 / |d|) / m).
  static double transverseMode(std::span<const BodyState> bodies, std::span<const Cable> cables,
                               std::span<const int> which);

  /// A fast catch resolved: `dt`, or where the transverse mode turns more than `maxOmegaDt` over
  /// it, a midpoint step that does not, so that J v after it is off by little (docs/cables.md,
  /// "Energy"). Round fixed pegs the sub-step's equal parts: a short rest left the next step a
  /// rate it could not be matched to (docs/swings.md, "The fast catch near a peg").
  static double fastCatchStep(std::span<const BodyState> bodies, std::span<const Cable> cables,
                              std::span<const int> which, double dt, double maxOmegaDt);

  /// Whether every point between the ends of the cables `which` is fixed (on the world or a body
  /// the solve does not move) and every cable is rigid: a pendulum round pegs, not a rope loop
  /// round free pulleys nor an elastic rope (whose knocks, docs/floors.md, keep the old cut).
  static bool fixedBetweenEnds(std::span<const BodyState> bodies, std::span<const Cable> cables,
                               std::span<const int> which);

  /// Whether the last solve gave up at once on redundant rows (Newton on their split of the
  /// impulses cannot settle; the main solve takes the minimum-norm one).
  bool redundant() const { return redundant_; }
  /// Whether the last solve gave up because a floor row pushed (a body reached its pulley).
  bool floorHit() const { return floorHit_; }
  /// The Newton iterations the last solve ran, settled or not (the work it cost).
  int iterationsRun() const { return iterationsRun_; }

 private:
  std::span<const int> tautSteps_;  ///< setTautSteps()
  bool settledTaut(int cable) const;
  bool buildRows(std::span<const BodyState> bodies, std::span<Cable> cables,
                 std::span<const int> which, const Vec2& gravity, double h,
                 std::span<const Vec3> forces);
  void evaluate(std::span<const BodyState> bodies, std::span<const Cable> cables, double h);
  void buildIterationMatrix(std::span<const Cable> cables, double h);
  bool newtonStep(std::span<const BodyState> bodies, std::span<const Cable> cables, double h,
                  bool first);
  void settleRates(std::span<const BodyState> bodies, std::span<const Cable> cables);
  void finish(std::span<const BodyState> bodies, std::span<Cable> cables, double h,
              std::span<Vec3> forces, std::span<Vec3> kicks);
  bool redundantActiveRows(std::span<const Cable> cables);

  double share_ = 1;              // this step over the nominal sub-step
  std::vector<int> rows_;         // cable of each row
  std::vector<int> segment_;      // -1: the cable's length; i: a floor on its segment i
  std::vector<char> unresolved_;  // an elastic row whose axial mode h does not resolve
  std::vector<Vec2> normals_;     // a floor row's direction (floorNormal)
  std::vector<int> dofOfBody_;    // body -> first dof, -1: not moved
  std::vector<int> bodyOfDof_;    // dof / 3 -> body
  Eigen::VectorXd invM_, vStar_, vFree_, vb_, P_, phi0_, phi1_, b_;
  Eigen::VectorXd residual_, AinvR_, GAinvR_, dP_, dv_;
  Eigen::MatrixXd A_, Gt_, AinvGt_, K_;
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
  // A without a segment between two moving bodies is block-diagonal: inverted per body.
  bool blockDiagonal_ = false;
  BlockDiagonalInverse blockInverse_;
  // Redundant rows among those the first iteration's impulses pull on (redundantActiveRows).
  std::vector<int> active_;
  Eigen::MatrixXd activeK_;
  Eigen::LDLT<Eigen::MatrixXd> redundancy_;
  bool redundant_ = false, floorHit_ = false;
  int iterationsRun_ = 0;
  double lastMoved_ = 0, lastChanged_ = 0;  // the last iteration's h |dv| and |dP| (newtonStep)
  // The end rates of the pulling rigid rows (settleRates): their rows, J1 and M^-1 J1^T, the
  // LCP's K and b, the impulses mu, M^-1 J1^T mu and the end velocities v1.
  std::vector<int> settled_;
  Eigen::MatrixXd endJ_, endW_, rateK_;
  Eigen::VectorXd rateB_, mu_, endShift_, v1_;
  std::vector<BodyState> predicted_, midpoint_;  // q1 and the midpoint pose (q0 off the dofs)
  std::vector<WrapPoint> path_;
  // The rows' paths without circles, held over the iterations (step_chords.h): row r's index
  // there, -1 for a floor row or a path with circles (lengthDiscreteGradient on the path).
  StepChords chords_;
  std::vector<int> chordPath_;
  std::vector<StepChords::Point> midPoints_;  // a path with circles at the midpoint pose
  std::vector<BodyJacobian> gradient_;
  std::vector<std::vector<BodyJacobian>> gradients_;
  CableKinematics kin_;
  LcpWorkspace lcp_;
  LcpSolution solution_;
};

}  // namespace cablelab

// The sparse solve of one big island (docs/model.md, "Big islands").
//
// The dense path (cable_solver.cpp) holds W = M'^-1 J^T as an n x m matrix and J W as m x m,
// and its LCP factors dense active sets: an island of m rows costs O(m^2) to O(m^3) (a rope of
// 256 links took 0.3 s a step). Above sparseIslandThreshold() rows this path solves the same
// problem with sparse matrices: each Newton iteration on the end-of-step lengths is the KKT
// system
//     [ M'     J0_A^T ] [ v1  ]   [ M v*                 ]
//     [ J1_A  -C_A    ] [ P_A ] = [ J1_A v1_k - e_A      ]    (P = 0 off the active set A)
// (M' = M + h^2 T G the geometric stiffness, J0 the start-of-step Jacobian the impulses act
// along, J1 its linearisation at the predicted end-of-step state v1_k, C the elastic rows'
// compliance, e the length errors over h), which is the dense path's LCP K P = b with
// K = J1 M'^-1 J0^T + C on the active rows, without forming M'^-1. It is factored by
// Eigen::SparseLU (J1 != J0 makes it unsymmetric), once per active-set change. The active set
// is warm-started from the last sub-step's: the rows of a hanging rope stay taut, so a
// sub-step usually costs one factorisation per Newton iteration, linear in the cables.
//
// Same stages as the dense path: the same v*, M', length targets (length_targets.h), warm
// start, Newton iterations and tolerance, and the same forces. Joints among the island's bodies
// are equality rows C v1 + bias = 0 of the same system (reactions C^T lambda in the first block
// row): the velocities the dense path's projection gives. Islands it does not handle return false
// and take the dense path: cables split in spans by gripping wheels (capstans), segments short
// enough for a floor row (floors.h), and redundant rows (a singular [J0; C] M^-1 [J0; C]^T: the
// dense path's minimum-norm solve). Private to engine/dynamics.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/cable_solver.h"
#include "engine/dynamics/geometric_stiffness.h"
#include "engine/dynamics/joint_limits.h"
#include "engine/dynamics/joint_projection.h"
#include "engine/dynamics/step_pose.h"

namespace cablelab {

/// Islands with more rows than this take the sparse path (default 32: where BM_ChainPath
/// measured the two paths equally fast, docs/model.md).
int sparseIslandThreshold();
/// Test hook: -1 restores the default; 0 sends every island that qualifies to the sparse path,
/// a large value keeps every island dense.
void setSparseIslandThreshold(int rows);

class SparseIsland {
 public:
  /// Solves the island made of `islandCables` (its joints: `islandJoints`) as the dense path
  /// would: sets their tensions and adds the forces to `loads`. `predicted` holds every body at
  /// the end of the step as far as known (prescribed bodies moved); the island's are written.
  /// Returns false, having changed no cable and no load, if the island is not one for this
  /// path (small, or one of the cases the header lists).
  bool solve(const CableSolveInput& in, std::span<Cable> cables, std::span<const int> islandCables,
             std::span<const int> islandJoints, std::span<BodyState> predicted,
             std::span<Vec3> loads, StepStats& stats);

 private:
  using Sparse = Eigen::SparseMatrix<double>;
  using Triplet = Eigen::Triplet<double>;

  bool entered(int body, int c, double value);
  bool qualifies(const CableSolveInput& in, std::span<const Cable> cables,
                 std::span<const int> islandCables, std::span<const int> islandJoints) const;
  void buildDofs(const CableSolveInput& in, std::span<const Cable> cables,
                 std::span<const Vec3> loads);
  void buildStiffMass(double h, std::span<const Cable> cables);
  bool redundant();
  void lengthTargets(double h, double share, std::span<const Cable> cables);
  void warmStart(double h, std::span<const Cable> cables);
  void jointRows(const CableSolveInput& in, std::span<const int> islandJoints);
  void velocitiesAt(const Eigen::VectorXd& P);
  void linearise(const CableSolveInput& in, std::span<const Cable> cables,
                 std::span<BodyState> predicted, StepStats& stats);
  int solveLcp();
  void factorAndSolve();
  void assembleKkt();
  bool iterateNewton(const CableSolveInput& in, std::span<const Cable> cables,
                     std::span<BodyState> predicted, StepStats& stats);
  void applyForces(double h, std::span<Cable> cables, std::span<Vec3> loads);

  // The island: rows are its cables (one span each), dofs 3 per moving body.
  std::vector<int> rows_;
  std::vector<char> turns_;                 // per body: some cable has turned it (entered())
  std::vector<int> dofOfBody_, bodyOfDof_;  // body -> first dof (-1: not in this island)
  std::vector<StepMotion> motions_;         // per dof body: how Box2D moves it (step_pose.h)
  int n_ = 0, m_ = 0, q_ = 0;               // dofs, cable rows, joint rows
  std::vector<JointRow> joints_;            // C, as the dense path builds it (joint_projection.h)
  JointLimits limits_;                      // joints locked at a limit (joint_limits.h)
  const Eigen::VectorXd* fixed_ = nullptr;  // factorAndSolve(): P given, not solved for
  Eigen::VectorXd invM_, vRaw_, vFree_, momentum_;  // momentum_ = M v* (M v* = M' v*' if stiff)
  // Jacobians as (row, dof, value) lists: J0 at the start of the step, J1 at the prediction.
  std::vector<Triplet> j0_, j1_;
  std::vector<int> j0Start_, j1Start_;  // row r's entries: [start[r], start[r + 1])
  std::vector<double> j0Diagonal_;      // J0 M^-1 J0^T's diagonal (the guard's and the LCP's scale)
  std::vector<Triplet> stiffTriplets_;  // M' off the mass diagonal
  std::vector<StiffnessBlock> blocks_;
  std::vector<TautCable> taut_;  // geometric_stiffness.h
  bool stiff_ = false;
  Sparse mass_;  // M' (only when stiff_)
  Eigen::SimplicialLDLT<Sparse> massLdlt_, rankLdlt_;
  std::vector<int> massPattern_, rankPattern_;  // of the matrices they factor
  Eigen::VectorXd target_, compliance_, damped_, phi1_, e_, P_, v1_, v1k_, rhs_, sol_;
  std::vector<char> active_;
  bool failed_ = false;  // a KKT factorisation failed: the island goes to the dense path
  std::vector<WrapPoint> path_;
  CableKinematics kin_;
  std::vector<Triplet> kkt_;
  std::vector<std::pair<int, int>> kktKeys_;  // (row, col) of each entry of kkt_, as assembled
  std::vector<int> kktSlots_;                 // where each lands in kktMatrix_'s values
  Sparse kktMatrix_;
  Eigen::SparseLU<Sparse, Eigen::COLAMDOrdering<int>> lu_;
  // Per cable: the h and tension of this path's last solve (Newton's warm start) and whether
  // its row was active (the LCP's warm start).
  struct Warm {
    double h = 0, tension = 0;
    bool active = true;
  };
  std::vector<Warm> warm_;
};

}  // namespace cablelab

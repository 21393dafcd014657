// Stage 4 of the cable solver (cable_solver.h) for joints that form trees hanging from bodies
// that do not move (a hand's fingers: world - revolute - link - prismatic - slider - revolute -
// paddle): the same projection as the Schur complement's (joint_projection.h), in the joints'
// own coordinates. Each body's velocity is its root's prescribed motion plus S qdot, qdot one
// rate per revolute or prismatic joint between it and its root (welds add none). The projection
// onto what the joints allow is the M-orthogonal one onto that set,
//     qdot = (S^T M S)^-1 S^T M (v - r),   v <- r + S qdot,
// the velocity closest to v in kinetic energy that the joints allow: a k x k system per tree
// (k joints) where the Schur complement factors one of twice the size, and no joint rows at
// all. docs/model.md, "Islands", has the equations. Private to engine/dynamics.
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/joint_limits.h"
#include "engine/dynamics/joint_projection.h"

namespace cablelab {

/// Off: every cable island takes the Schur complement (tests and benchmarks compare the two).
void setJointTreeProjection(bool on);
bool jointTreeProjection();

class JointTree {
 public:
  /// Reads an island's joints (`island`: indices into `joints`) over its dofs (`dofOfBody`:
  /// body -> first dof, -1 if not a dof). False, leaving the Schur complement to project, unless
  /// every joint on a dof hangs it from a parent (a dof or a body that does not move) with no
  /// loop, and every jointed dof body moves in all three directions (invM > 0).
  bool build(std::span<const JointFrame> joints, std::span<const int> island,
             std::span<const BodyState> bodies, std::span<const int> dofOfBody,
             const Eigen::VectorXd& invM);

  /// W = M^-1 J^T and v* restricted to what the joints allow (M: build's diag(invM)^-1), a
  /// locked joint's coordinate held at its rate (`limits`, joint_limits.h).
  void project(Eigen::MatrixXd& W, Eigen::VectorXd& vStar, const JointLimits& limits) const;

  /// v projected onto what the joints allow at this pose, each tree keeping its kinetic energy
  /// relative to its root: after Box2D's step the joints have turned, and v, which they allowed
  /// at the step's start, has a part across them that Box2D's next solve would take out (about
  /// (h omega)^2 / 2 of the energy a step: a pendulum lost 17% of it in a minute at 60 Hz).
  void reproject(Eigen::VectorXd& v) const;

 private:
  // The trees' shape: which body hangs from which, through which joint. Kept while the island's
  // joints and dofs stay the same (every sub-step of a hand); only the values below change.
  // The work is the island's (`bodiesWithDofs` of them), not the world's.
  bool findTrees(std::span<const JointFrame> joints, std::span<const int> island,
                 std::span<const int> dofOfBody, int bodiesWithDofs);
  // The anchors, axes and root motions of this pose, S's entries, each body's mass.
  bool measure(std::span<const JointFrame> joints, std::span<const BodyState> bodies,
               const Eigen::VectorXd& invM);

  struct Tree;
  // One tree's projection of the columns_ (less the roots' motion); with `limits`, the last
  // column is v*, which takes the locked joints' rates.
  void projectColumns(const Tree& tree, const JointLimits* limits = nullptr) const;
  // The same with the tree's coordinates as the constant kN (0: any number, withFixedSize).
  template <int kN>
  void projectColumns(const Tree& tree, const JointLimits* limits) const;

  // A jointed dof body, listed parents first within its tree.
  struct Link {
    int body, dof;
    int parent;      // link index, -1: hangs from the root
    int joint;       // the joint it hangs by (index into the joints)
    int rootBody;    // the tree's root: a body that does not move, -1 the world
    int coordinate;  // its joint's rate within the tree, -1: a weld (none)
    double sign;     // the joint coordinate's rate per unit of that rate (-1: the body is side A)
    Vec3 mass;       // M's diagonal (m, m, I)
    Vec3 root;  // the root's prescribed motion at this body (v + omega perp(x - x_root), omega)
  };
  // Entries of S: the motion of a link's body (its first dof `dof`) per unit rate of one of its
  // tree's coordinates, that of `joint` (an ancestor's or its own); ms = M s, the link's mass
  // times s.
  struct Entry {
    int coordinate, joint, dof;
    Vec3 s, ms;
  };
  // Where S^T M S gets its terms: entry `at` (column-major, lower triangle) of the tree's k x k
  // array adds entries_[e].ms . entries_[f].s (e and f on one link), in the order of the sums.
  struct MassTerm {
    int e, f, at;
  };
  // A tree's links, entries and mass terms: links_[firstLink, firstLink + links) and so on.
  struct Tree {
    int firstLink, links, coordinates;
    int firstEntry = 0, entries = 0, firstTerm = 0, terms = 0;
  };
  std::vector<Link> links_;
  std::vector<Entry> entries_;  // link l's are entries_[entryStart_[l], entryStart_[l + 1])
  std::vector<int> entryStart_;
  std::vector<MassTerm> massTerms_;
  std::vector<Tree> trees_;
  bool found_ = false;                    // whether the joints last seen form trees
  std::vector<std::array<int, 3>> seen_;  // those joints (index, both sides' dofs)
  // findTrees' scratch: which joints are whose, per dof body.
  std::vector<int> linkOfBody_, jointsOfBody_, jointStart_;
  std::vector<char> jointUsed_;
  // Project's scratch: one tree's S^T M S and right-hand sides.
  mutable SmallLdlt ldlt_;
  mutable std::vector<double> mass_, rhs_;
  // [W | v*]'s columns that a tree's projection takes, each 0 on the tree's entries before `from`.
  struct Column {
    double* values;
    int from;
  };
  mutable std::vector<Column> columns_;
};

}  // namespace cablelab

// The joint projection in the joints' coordinates (joint_tree.h; docs/model.md, "Joints").
#include "engine/dynamics/joint_tree.h"

namespace cablelab {

namespace {
bool treeProjection = true;
}  // namespace

void setJointTreeProjection(bool on) {
  treeProjection = on;
}

bool JointTree::build(std::span<const JointFrame> joints, std::span<const int> island,
                      std::span<const BodyState> bodies, std::span<const int> dofOfBody,
                      const Eigen::VectorXd& invM) {
  links_.clear();
  trees_.clear();
  if (!treeProjection) return false;
  const int dofBodies = static_cast<int>(invM.size()) / 3;
  const int count = static_cast<int>(island.size());
  auto dofOf = [&](int body) { return body >= 0 ? dofOfBody[body] : -1; };
  // Each dof body's joints (positions in `island`), as lists one after the other.
  jointStart_.assign(dofBodies + 1, 0);
  for (int p = 0; p < count; ++p)
    for (int body : {joints[island[p]].bodyA, joints[island[p]].bodyB})
      if (const int d = dofOf(body); d >= 0) ++jointStart_[d / 3 + 1];
  for (int b = 0; b < dofBodies; ++b) jointStart_[b + 1] += jointStart_[b];
  jointsOfBody_.resize(jointStart_[dofBodies]);
  linkOfBody_.assign(jointStart_.begin(), jointStart_.end() - 1);  // as the fill positions
  for (int p = 0; p < count; ++p)
    for (int body : {joints[island[p]].bodyA, joints[island[p]].bodyB})
      if (const int d = dofOf(body); d >= 0) jointsOfBody_[linkOfBody_[d / 3]++] = p;
  linkOfBody_.assign(dofBodies, -1);
  jointUsed_.assign(count, 0);

  auto addLink = [&](int body, int parent, const JointFrame& joint, int rootBody, Tree& tree) {
    const int dof = dofOfBody[body];
    if (linkOfBody_[dof / 3] >= 0) return false;  // a second way to this body: a loop
    if (!(invM[dof] > 0 && invM[dof + 1] > 0 && invM[dof + 2] > 0)) return false;
    linkOfBody_[dof / 3] = static_cast<int>(links_.size());
    Vec3 root = Vec3::Zero();  // the world's prescribed motion: none
    if (rootBody >= 0) {
      const BodyState& r = bodies[rootBody];
      const Vec2 v =
          r.velocity + r.angularVelocity * perp(Vec2(bodies[body].position - r.position));
      root = Vec3(v.x(), v.y(), r.angularVelocity);
    }
    const bool rate = joint.kind != JointDef::Kind::Weld;
    links_.push_back({body, dof, parent, rate ? tree.coordinates++ : -1, joint.kind, joint.anchor,
                      joint.axis, root});
    ++tree.links;
    return true;
  };
  // Trees grow from the joints with one dof side (their roots), breadth first.
  for (int p = 0; p < count; ++p) {
    const JointFrame& rootJoint = joints[island[p]];
    const int da = dofOf(rootJoint.bodyA), db = dofOf(rootJoint.bodyB);
    if ((da >= 0) == (db >= 0)) continue;
    if (jointUsed_[p]) return false;  // reached from another root: a loop through the ground
    jointUsed_[p] = 1;
    const int rootBody = da >= 0 ? rootJoint.bodyB : rootJoint.bodyA;
    Tree tree{static_cast<int>(links_.size()), 0, 0};
    if (!addLink(da >= 0 ? rootJoint.bodyA : rootJoint.bodyB, -1, rootJoint, rootBody, tree))
      return false;
    for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
      const int d = links_[l].dof / 3;
      for (int q = jointStart_[d]; q < jointStart_[d + 1]; ++q) {
        const int j = jointsOfBody_[q];
        if (jointUsed_[j]) continue;
        jointUsed_[j] = 1;
        const JointFrame& joint = joints[island[j]];
        const int other = joint.bodyA == links_[l].body ? joint.bodyB : joint.bodyA;
        if (dofOf(other) < 0 || !addLink(other, l, joint, rootBody, tree)) return false;
      }
    }
    trees_.push_back(tree);
  }
  // Every joint on a dof belongs to a tree (else a jointed group floats free: the Schur path).
  for (int p = 0; p < count; ++p)
    if (!jointUsed_[p] &&
        (dofOf(joints[island[p]].bodyA) >= 0 || dofOf(joints[island[p]].bodyB) >= 0))
      return false;
  // S: a link's body moves with its own joint's rate and every ancestor's.
  entries_.clear();
  entryStart_.assign(1, 0);
  for (const Link& link : links_) {
    const Vec2 x = bodies[link.body].position;
    for (int a = static_cast<int>(&link - links_.data()); a >= 0; a = links_[a].parent) {
      const Link& joint = links_[a];
      if (joint.coordinate < 0) continue;
      const Vec3 s = joint.kind == JointDef::Kind::Prismatic
                         ? Vec3(joint.axis.x(), joint.axis.y(), 0)
                         : Vec3(-(x.y() - joint.anchor.y()), x.x() - joint.anchor.x(), 1);
      entries_.push_back({joint.coordinate, s});
    }
    entryStart_.push_back(static_cast<int>(entries_.size()));
  }
  return true;
}

void JointTree::project(const Eigen::VectorXd& invM, Eigen::MatrixXd& W, Eigen::VectorXd& vStar) {
  const int m = static_cast<int>(W.cols());
  const Eigen::Index n = W.rows();
  const int cols = m + 1;  // S^T M W, then S^T M (v* - root)
  for (const Tree& tree : trees_) {
    const int k = tree.coordinates;
    mass_.assign(static_cast<size_t>(k) * k, 0.0);
    rhs_.assign(static_cast<size_t>(k) * cols, 0.0);
    for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
      const Link& link = links_[l];
      const Vec3 mass(1 / invM[link.dof], 1 / invM[link.dof + 1], 1 / invM[link.dof + 2]);
      const Vec3 v = vStar.segment<3>(link.dof) - link.root;
      for (int e = entryStart_[l]; e < entryStart_[l + 1]; ++e) {
        const Vec3 ms = mass.cwiseProduct(entries_[e].s);
        const int ce = entries_[e].coordinate;
        for (int f = e; f < entryStart_[l + 1]; ++f) {  // S^T M S's lower triangle
          const int cf = entries_[f].coordinate;
          mass_[std::max(ce, cf) + std::min(ce, cf) * k] += ms.dot(entries_[f].s);
        }
        for (int s = 0; s < m; ++s)
          rhs_[ce + s * k] += ms.dot(Eigen::Map<const Vec3>(W.data() + s * n + link.dof));
        rhs_[ce + m * k] += ms.dot(v);
      }
    }
    for (int i = 0; i < k; ++i) mass_[i + i * k] += 1e-10 * (1 + mass_[i + i * k]);
    if (k > 0) {
      ldlt_.factor(mass_.data(), k);
      ldlt_.solveInPlace(mass_.data(), k, rhs_.data(), cols);
    }
    // W <- S qdot(W), v* <- root + S qdot(v*).
    for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
      const Link& link = links_[l];
      Vec3 v = link.root;
      for (int s = 0; s < m; ++s) W.block<3, 1>(link.dof, s).setZero();
      for (int e = entryStart_[l]; e < entryStart_[l + 1]; ++e) {
        const Entry& entry = entries_[e];
        for (int s = 0; s < m; ++s)
          W.block<3, 1>(link.dof, s) += entry.s * rhs_[entry.coordinate + s * k];
        v += entry.s * rhs_[entry.coordinate + m * k];
      }
      vStar.segment<3>(link.dof) = v;
    }
  }
}

}  // namespace cablelab

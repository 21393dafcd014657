// The joint projection in the joints' coordinates (joint_tree.h; docs/model.md, "Islands").
#include "engine/dynamics/joint_tree.h"

#include <algorithm>
#include <cmath>

namespace cablelab {

namespace {
bool treeProjection = true;
// reproject() restores at most this ratio of a tree's kinetic energy.
constexpr double kMaxReprojectionLoss = 1.05;
}  // namespace

void setJointTreeProjection(bool on) {
  treeProjection = on;
}

bool jointTreeProjection() {
  return treeProjection;
}

bool JointTree::build(std::span<const JointFrame> joints, std::span<const int> island,
                      std::span<const BodyState> bodies, std::span<const int> dofOfBody,
                      const Eigen::VectorXd& invM) {
  auto dofOf = [&](int body) { return body >= 0 ? dofOfBody[body] : -1; };
  key_.clear();
  for (int j : island) key_.push_back({j, dofOf(joints[j].bodyA), dofOf(joints[j].bodyB)});
  if (key_ != seen_) {
    seen_.swap(key_);
    found_ = findTrees(joints, island, dofOfBody, static_cast<int>(invM.size()) / 3);
  }
  return found_ && measure(joints, bodies, invM);
}

bool JointTree::findTrees(std::span<const JointFrame> joints, std::span<const int> island,
                          std::span<const int> dofOfBody, int bodiesWithDofs) {
  links_.clear();
  trees_.clear();
  const int count = static_cast<int>(island.size());
  auto dofOf = [&](int body) { return body >= 0 ? dofOfBody[body] : -1; };
  // Each dof body's joints (positions in `island`), as lists one after the other.
  jointStart_.assign(bodiesWithDofs + 1, 0);
  for (int p = 0; p < count; ++p)
    for (int body : {joints[island[p]].bodyA, joints[island[p]].bodyB})
      if (const int d = dofOf(body); d >= 0) ++jointStart_[d / 3 + 1];
  for (int b = 0; b < bodiesWithDofs; ++b) jointStart_[b + 1] += jointStart_[b];
  jointsOfBody_.resize(jointStart_[bodiesWithDofs]);
  linkOfBody_.assign(jointStart_.begin(), jointStart_.end() - 1);  // as the fill positions
  for (int p = 0; p < count; ++p)
    for (int body : {joints[island[p]].bodyA, joints[island[p]].bodyB})
      if (const int d = dofOf(body); d >= 0) jointsOfBody_[linkOfBody_[d / 3]++] = p;
  linkOfBody_.assign(bodiesWithDofs, -1);
  jointUsed_.assign(count, 0);

  auto addLink = [&](int body, int parent, int joint, int rootBody, Tree& tree) {
    const int dof = dofOfBody[body];
    if (linkOfBody_[dof / 3] >= 0) return false;  // a second way to this body: a loop
    linkOfBody_[dof / 3] = static_cast<int>(links_.size());
    const bool rate = joints[joint].kind != JointDef::Kind::Weld;
    links_.push_back({body, dof, parent, joint, rootBody, rate ? tree.coordinates++ : -1,
                      joints[joint].bodyB == body ? 1.0 : -1.0, Vec3::Zero(), Vec3::Zero()});
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
    if (!addLink(da >= 0 ? rootJoint.bodyA : rootJoint.bodyB, -1, island[p], rootBody, tree))
      return false;
    for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
      const int d = links_[l].dof / 3;
      for (int q = jointStart_[d]; q < jointStart_[d + 1]; ++q) {
        const int j = jointsOfBody_[q];
        if (jointUsed_[j]) continue;
        jointUsed_[j] = 1;
        const JointFrame& joint = joints[island[j]];
        const int other = joint.bodyA == links_[l].body ? joint.bodyB : joint.bodyA;
        if (dofOf(other) < 0 || !addLink(other, l, island[j], rootBody, tree)) return false;
      }
    }
    trees_.push_back(tree);
  }
  // Every joint on a dof belongs to a tree (else a jointed group floats free: the Schur path).
  for (int p = 0; p < count; ++p)
    if (!jointUsed_[p] &&
        (dofOf(joints[island[p]].bodyA) >= 0 || dofOf(joints[island[p]].bodyB) >= 0))
      return false;
  // S's shape: a link's body moves with its own joint's rate and every ancestor's.
  entries_.clear();
  entryStart_.assign(1, 0);
  for (size_t l = 0; l < links_.size(); ++l) {
    for (int a = static_cast<int>(l); a >= 0; a = links_[a].parent)
      if (links_[a].coordinate >= 0) entries_.push_back({links_[a].coordinate, a, Vec3::Zero()});
    entryStart_.push_back(static_cast<int>(entries_.size()));
  }
  return true;
}

bool JointTree::measure(std::span<const JointFrame> joints, std::span<const BodyState> bodies,
                        const Eigen::VectorXd& invM) {
  for (Link& link : links_) {
    const Vec3 inverse = invM.segment<3>(link.dof);
    if (!(inverse.minCoeff() > 0)) return false;  // cannot move one way: no finite M
    link.mass = inverse.cwiseInverse();
    link.root.setZero();  // the world's prescribed motion: none
    if (link.rootBody >= 0) {
      const BodyState& r = bodies[link.rootBody];
      const Vec2 offset = bodies[link.body].position - r.position;
      const Vec2 v = r.velocity + r.angularVelocity * perp(offset);
      link.root = Vec3(v.x(), v.y(), r.angularVelocity);
    }
  }
  for (size_t l = 0; l < links_.size(); ++l) {
    const Vec2 x = bodies[links_[l].body].position;
    for (int e = entryStart_[l]; e < entryStart_[l + 1]; ++e) {
      const JointFrame& joint = joints[links_[entries_[e].of].joint];
      const Vec2 arm = x - joint.anchor;
      entries_[e].s = joint.kind == JointDef::Kind::Prismatic
                          ? Vec3(joint.axis.x(), joint.axis.y(), 0)
                          : Vec3(-arm.y(), arm.x(), 1);  // (perp(x - anchor), 1)
    }
  }
  return true;
}

void JointTree::project(Eigen::MatrixXd& W, Eigen::VectorXd& vStar,
                        const JointLimits& limits) const {
  const int m = static_cast<int>(W.cols());
  const Eigen::Index n = W.rows();
  // v* less the roots' motion is projected like W's columns; the motion goes back on after.
  for (const Link& link : links_) vStar.segment<3>(link.dof) -= link.root;
  for (const Tree& tree : trees_) {
    // The columns to project: the cables that pull on this tree (a finger's own membrane, not
    // the other finger's), then v*.
    columns_.clear();
    for (int c = 0; c < m; ++c)
      for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
        double* x = W.data() + c * n + links_[l].dof;
        if (x[0] != 0 || x[1] != 0 || x[2] != 0) {
          columns_.push_back(W.data() + c * n);
          break;
        }
      }
    columns_.push_back(vStar.data());
    projectColumns(tree, &limits);
  }
  for (const Link& link : links_) vStar.segment<3>(link.dof) += link.root;
}

void JointTree::reproject(Eigen::VectorXd& v) const {
  for (const Link& link : links_) v.segment<3>(link.dof) -= link.root;
  for (const Tree& tree : trees_) {
    auto energy = [&] {
      double twice = 0;
      for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l)
        twice += links_[l].mass.dot(v.segment<3>(links_[l].dof).cwiseAbs2());
      return twice;
    };
    const double before = energy();
    columns_.assign(1, v.data());
    projectColumns(tree);
    const double after = energy();
    // The projection takes out (h omega)^2 / 2 or so of the energy; more is an impact or joints
    // Box2D left apart, whose loss stays.
    if (after > 0 && after < before && before < kMaxReprojectionLoss * after) {
      const double scale = std::sqrt(before / after);
      for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l)
        v.segment<3>(links_[l].dof) *= scale;
    }
  }
  for (const Link& link : links_) v.segment<3>(link.dof) += link.root;
}

// Plain loops over 3: Eigen's 3-vectors cost twice the arithmetic at these sizes.
void JointTree::projectColumns(const Tree& tree, const JointLimits* limits) const {
  const int k = tree.coordinates, cols = static_cast<int>(columns_.size());
  mass_.assign(static_cast<size_t>(k) * k, 0.0);
  rhs_.assign(static_cast<size_t>(k) * cols, 0.0);
  // S^T M S (lower triangle) and S^T M [W | v*].
  for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
    const Link& link = links_[l];
    for (int e = entryStart_[l]; e < entryStart_[l + 1]; ++e) {
      const double* s = entries_[e].s.data();
      const double ms[3] = {link.mass[0] * s[0], link.mass[1] * s[1], link.mass[2] * s[2]};
      const int ce = entries_[e].coordinate;
      for (int f = e; f < entryStart_[l + 1]; ++f) {
        const double* t = entries_[f].s.data();
        const int cf = entries_[f].coordinate;
        mass_[std::max(ce, cf) + std::min(ce, cf) * k] +=
            ms[0] * t[0] + ms[1] * t[1] + ms[2] * t[2];
      }
      for (int i = 0; i < cols; ++i) {
        const double* x = columns_[i] + link.dof;
        rhs_[ce + i * k] += ms[0] * x[0] + ms[1] * x[1] + ms[2] * x[2];
      }
    }
  }
  // A locked joint's rate by a penalty on its coordinate: held to 1e-12 of the locked rate, W's
  // columns (its rhs untouched) leave it still.
  if (limits)
    for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
      const Link& link = links_[l];
      const std::optional<double> rate = limits->lock(link.joint);
      if (link.coordinate < 0 || !rate) continue;
      const int c = link.coordinate;
      const double penalty = 1e12 * (1 + mass_[c + c * k]);
      mass_[c + c * k] += penalty;
      rhs_[c + (cols - 1) * k] += penalty * link.sign * *rate;
    }
  for (int i = 0; i < k; ++i) mass_[i + i * k] += 1e-10 * (1 + mass_[i + i * k]);
  if (k > 0) {
    ldlt_.factor(mass_.data(), k);
    ldlt_.solveInPlace(mass_.data(), k, rhs_.data(), cols);
  }
  // [W | v*] <- S qdot (a column left out stays 0 on the tree).
  for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l)
    for (int i = 0; i < cols; ++i) {
      double x0 = 0, x1 = 0, x2 = 0;
      for (int e = entryStart_[l]; e < entryStart_[l + 1]; ++e) {
        const double* s = entries_[e].s.data();
        const double q = rhs_[entries_[e].coordinate + i * k];
        x0 += s[0] * q, x1 += s[1] * q, x2 += s[2] * q;
      }
      double* x = columns_[i] + links_[l].dof;
      x[0] = x0, x[1] = x1, x[2] = x2;
    }
}

}  // namespace cablelab

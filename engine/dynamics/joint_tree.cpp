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
  auto key = [&](int j) { return std::array{j, dofOf(joints[j].bodyA), dofOf(joints[j].bodyB)}; };
  // Element by element, without building the new list: std::array's == is a memcmp call.
  bool same = seen_.size() == island.size();
  for (size_t p = 0; same && p < island.size(); ++p) {
    const std::array<int, 3> now = key(island[p]);
    same = seen_[p][0] == now[0] && seen_[p][1] == now[1] && seen_[p][2] == now[2];
  }
  if (!same) {
    seen_.clear();
    for (int j : island) seen_.push_back(key(j));
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
  // S's shape: a link's body moves with its own joint's rate and every ancestor's. S^T M S sums,
  // per entry, the products of each link's entries with those after them.
  entries_.clear();
  entryStart_.assign(1, 0);
  massTerms_.clear();
  for (Tree& tree : trees_) {
    tree.firstEntry = static_cast<int>(entries_.size());
    tree.firstTerm = static_cast<int>(massTerms_.size());
    for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
      for (int a = l; a >= 0; a = links_[a].parent)
        if (links_[a].coordinate >= 0)
          entries_.push_back(
              {links_[a].coordinate, links_[a].joint, links_[l].dof, Vec3::Zero(), Vec3::Zero()});
      const int end = static_cast<int>(entries_.size());
      for (int e = entryStart_[l]; e < end; ++e)
        for (int f = e; f < end; ++f) {
          const int ce = entries_[e].coordinate, cf = entries_[f].coordinate;
          massTerms_.push_back({e, f, std::max(ce, cf) + std::min(ce, cf) * tree.coordinates});
        }
      entryStart_.push_back(end);
    }
    tree.entries = static_cast<int>(entries_.size()) - tree.firstEntry;
    tree.terms = static_cast<int>(massTerms_.size()) - tree.firstTerm;
  }
  return true;
}

// Plain scalar code: through Eigen's 3-vectors it cost a tenth more.
bool JointTree::measure(std::span<const JointFrame> joints, std::span<const BodyState> bodies,
                        const Eigen::VectorXd& invM) {
  for (Link& link : links_) {
    const double* inverse = invM.data() + link.dof;
    // Cannot move one way: no finite M.
    if (!(std::min(std::min(inverse[0], inverse[1]), inverse[2]) > 0)) return false;
    link.mass = Vec3(1 / inverse[0], 1 / inverse[1], 1 / inverse[2]);
    if (link.rootBody >= 0) {  // (the world has none: project leaves it out)
      const BodyState& r = bodies[link.rootBody];
      const Vec2 v = pointVelocity(r, bodies[link.body].position);
      link.root = Vec3(v.x(), v.y(), r.angularVelocity);
    }
  }
  for (size_t l = 0; l < links_.size(); ++l) {
    const Vec2& x = bodies[links_[l].body].position;
    const double* mass = links_[l].mass.data();
    for (int e = entryStart_[l]; e < entryStart_[l + 1]; ++e) {
      const JointFrame& joint = joints[entries_[e].joint];
      double* s = entries_[e].s.data();
      if (joint.kind == JointDef::Kind::Prismatic) {
        s[0] = joint.axis.x(), s[1] = joint.axis.y(), s[2] = 0;
      } else {  // (perp(x - anchor), 1)
        s[0] = -(x.y() - joint.anchor.y()), s[1] = x.x() - joint.anchor.x(), s[2] = 1;
      }
      double* ms = entries_[e].ms.data();
      ms[0] = mass[0] * s[0], ms[1] = mass[1] * s[1], ms[2] = mass[2] * s[2];
    }
  }
  return true;
}

void JointTree::project(Eigen::MatrixXd& W, Eigen::VectorXd& vStar,
                        const JointLimits& limits) const {
  const int m = static_cast<int>(W.cols());
  const Eigen::Index n = W.rows();
  // v* less the roots' motion is projected like W's columns; the motion goes back on after. The
  // world's is none: x - 0 is x, and x + 0 too for the projection's x (its sums start at +0,
  // so they are never -0).
  for (const Link& link : links_)
    if (link.rootBody >= 0) vStar.segment<3>(link.dof) -= link.root;
  for (const Tree& tree : trees_) {
    // The columns to project: the cables that pull on this tree (a finger's own membrane, not
    // the other finger's), each from its first link not at 0, then v*.
    columns_.clear();
    for (int c = 0; c < m; ++c)
      for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
        double* x = W.data() + c * n + links_[l].dof;
        if (x[0] != 0 || x[1] != 0 || x[2] != 0) {
          columns_.push_back({W.data() + c * n, entryStart_[l] - tree.firstEntry});
          break;
        }
      }
    columns_.push_back({vStar.data(), 0});
    projectColumns(tree, &limits);
  }
  for (const Link& link : links_)
    if (link.rootBody >= 0) vStar.segment<3>(link.dof) += link.root;
}

void JointTree::reproject(Eigen::VectorXd& v) const {
  for (const Link& link : links_)  // (as in project)
    if (link.rootBody >= 0) v.segment<3>(link.dof) -= link.root;
  for (const Tree& tree : trees_) {
    auto energy = [&] {
      double twice = 0;
      for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l)
        twice += links_[l].mass.dot(v.segment<3>(links_[l].dof).cwiseAbs2());
      return twice;
    };
    const double before = energy();
    columns_.assign(1, {v.data(), 0});
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
  for (const Link& link : links_)
    if (link.rootBody >= 0) v.segment<3>(link.dof) += link.root;
}

void JointTree::projectColumns(const Tree& tree, const JointLimits* limits) const {
  withFixedSize(tree.coordinates, [&]<int kN>() { projectColumns<kN>(tree, limits); });
}

// Plain loops over 3: Eigen's 3-vectors cost twice the arithmetic at these sizes. Each sum adds
// its terms in link order, then entry order, whichever loop runs outside.
template <int kN>
void JointTree::projectColumns(const Tree& tree, const JointLimits* limits) const {
  const int k = kN > 0 ? kN : tree.coordinates, cols = static_cast<int>(columns_.size());
  if (static_cast<int>(mass_.size()) < k * k) mass_.resize(static_cast<size_t>(k) * k);
  if (static_cast<int>(rhs_.size()) < k * cols) rhs_.resize(static_cast<size_t>(k) * cols);
  double* const mass = mass_.data();
  double* const rhs = rhs_.data();
  std::fill_n(mass, k * k, 0.0);
  std::fill_n(rhs, k * cols, 0.0);
  const Entry* const entries = entries_.data() + tree.firstEntry;
  // S^T M S (lower triangle) and S^T M [W | v*].
  for (int t = tree.firstTerm; t < tree.firstTerm + tree.terms; ++t) {
    const MassTerm& term = massTerms_[t];
    const double* ms = entries_[term.e].ms.data();
    const double* s = entries_[term.f].s.data();
    mass[term.at] += ms[0] * s[0] + ms[1] * s[1] + ms[2] * s[2];
  }
  for (int i = 0; i < cols; ++i) {
    const double* column = columns_[i].values;
    double* columnRhs = rhs + i * k;
    // (The links before `from` add 0 products: sums that start at +0 stay as they are.)
    for (int e = columns_[i].from; e < tree.entries; ++e) {
      const double* ms = entries[e].ms.data();
      const double* x = column + entries[e].dof;
      columnRhs[entries[e].coordinate] += ms[0] * x[0] + ms[1] * x[1] + ms[2] * x[2];
    }
  }
  // A locked joint's rate by a penalty on its coordinate: held to 1e-12 of the locked rate, W's
  // columns (its rhs untouched) leave it still.
  if (limits && limits->anyLocked())
    for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
      const Link& link = links_[l];
      const std::optional<double> rate = limits->lock(link.joint);
      if (link.coordinate < 0 || !rate) continue;
      const int c = link.coordinate;
      const double penalty = 1e12 * (1 + mass[c + c * k]);
      mass[c + c * k] += penalty;
      rhs[c + (cols - 1) * k] += penalty * link.sign * *rate;
    }
  for (int i = 0; i < k; ++i) mass[i + i * k] += 1e-10 * (1 + mass[i + i * k]);
  if (k > 0) {
    ldlt_.factor(mass, k);
    ldlt_.solveInPlace(mass, k, rhs, cols);
  }
  // [W | v*] <- S qdot (a column left out stays 0 on the tree).
  for (int i = 0; i < cols; ++i) {
    const double* qdot = rhs + i * k;
    for (int l = tree.firstLink; l < tree.firstLink + tree.links; ++l) {
      double x0 = 0, x1 = 0, x2 = 0;
      for (int e = entryStart_[l]; e < entryStart_[l + 1]; ++e) {
        const double* s = entries_[e].s.data();
        const double q = qdot[entries_[e].coordinate];
        x0 += s[0] * q, x1 += s[1] * q, x2 += s[2] * q;
      }
      double* x = columns_[i].values + links_[l].dof;
      x[0] = x0, x[1] = x1, x[2] = x2;
    }
  }
}

}  // namespace cablelab

// Which taut cables' geometric stiffness a sub-step's M' = M + h^2 T G needs (stage 3 of the
// cable solver, cable_solver.h; the same test on the sparse path, sparse_island.h). A light body
// on a tight band turns the force direction faster than one step resolves: those cables add
// their length Hessian, scaled by h^2 T. Private to engine/dynamics.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab {

/// A taut cable's share of G: its tension and its Hessian blocks, blocks[begin, end).
struct TautCable {
  double tension = 0;
  size_t begin = 0, end = 0;
};

/// If `cable` is taut and its stiffness could matter at this h for the dofs of the island
/// (`dofOfBody`: body -> first dof, -1 if not a dof; `invM`: the dofs' inverse masses), appends
/// its Hessian blocks to `blocks`, its entry to `taut`, and sets `stiff` when a block is large
/// enough that M' must be factored (otherwise M' = M is used and the blocks go unused).
/// `tension`: what it pulls with (pullingTension); an elastic cable's stretch counts too.
void addGeometricStiffness(const Cable& cable, double tension, double h,
                           std::span<const int> dofOfBody, const Eigen::VectorXd& invM,
                           std::vector<StiffnessBlock>& blocks, std::vector<TautCable>& taut,
                           bool& stiff);

/// The tension a cable pulls with over a sub-step of h, from its last solve's `tension` over a
/// step of `lastH` (0: `tension` is already a force, World's average over a cut sub-step). A step
/// cut short at a wrap event ends on an impulse that takes out what is left of the cable's length
/// rate: as a tension, impulse / lastH, it says nothing of the force (309 N on an 11 N rope after a
/// cut of 6e-5 s, whose next step then damped a weight swinging on it of 14% of its energy through
/// a geometric stiffness 28 times too large); spread over h it does.
inline double pullingTension(double tension, double lastH, double h) {
  return lastH > 0 && lastH < h ? tension * lastH / h : tension;
}

}  // namespace cablelab

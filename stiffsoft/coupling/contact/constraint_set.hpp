#pragma once
/// @file The active contact set: primitive pairs closer than d̂, classified into IPC's
/// vertex–vertex / edge–vertex / edge–edge / face–vertex stencils. Candidates that classify
/// to the same stencil are merged and counted: the barrier is Σ over point–triangle and
/// edge–edge candidates (IPC, Li et al. 2020, eq. 4), so a merged stencil carries its
/// multiplicity as a weight. Dropping the count instead would make the energy jump whenever a
/// vertex crosses between Voronoi regions (the candidates of the faces around a corner
/// classify it as vertex–vertex or edge–vertex on either side), and Newton stalls there.

#include <Eigen/Core>
#include <array>
#include <vector>

#include <stiffsoft/coupling/contact/broad_phase.hpp>
#include <stiffsoft/coupling/contact/barrier_potential.hpp>
#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// One active contact: the stencil's kind, its global surface vertices (−1 where unused), its
/// multiplicity (how many candidates classified to it) and its distance where it was found.
struct ContactConstraint {
  contact::Stencil stencil;
  std::array<int, 4> vertices{-1, -1, -1, -1};
  double weight = 1;    ///< multiplicity, ≥ 1
  double distance = 0;  ///< d at the surface build_constraints found it at (m); 0 when unknown
};

/// Surface points stored point by point (|V|×3, row-major): a stencil's four points are four
/// contiguous triples instead of twelve scattered entries, for loops over many stencils.
using PointRows = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// The stencil's vertex positions packed [x_0; x_1; x_2; x_3] (unused entries zero), m, from
/// either storage of the surface points (Eigen::MatrixX3d or PointRows). Inline: it runs once
/// per stencil in every loop over the contacts.
template <class Points>
contact::Vector12d gather(const Points& x, const std::array<int, 4>& vertices) {
  contact::Vector12d out = contact::Vector12d::Zero();
  for (int i = 0; i < 4; ++i)
    if (vertices[i] >= 0) out.template segment<3>(3 * i) = x.row(vertices[i]).transpose();
  return out;
}

/// What build_constraints may sort out of its candidates on the way: with every surface
/// vertex v kept within `reach[v]` (m) of where it is now, the candidates that can come closer
/// than d̂ go into `near`, in their order; every other one stays at least d̂ apart there (no
/// point of a primitive moves farther than its farthest vertex), so `near` alone gives the
/// same contacts at any such configuration.
struct NearCandidates {
  const std::vector<double>& reach;  ///< per surface vertex, m
  Candidates& near;                  ///< filled (cleared first)
};

/// Contacts among the candidates whose distance at x is below d̂ (m). Nearly parallel edge
/// pairs (‖ea × eb‖² < ε_x) stay edge–edge with the mollifier and the true segment distance.
/// With `sort_out`, also the candidates that can come within d̂ in its reaches, from the same
/// bounds (NearCandidates).
std::vector<ContactConstraint> build_constraints(const Model& model, const Eigen::MatrixX3d& x,
                                                 const Candidates& candidates, double dhat,
                                                 const NearCandidates* sort_out = nullptr);

/// Smallest distance (m) between any two primitives of different bodies among the candidates,
/// or +∞ when there are none.
double smallest_distance(const Model& model, const Eigen::MatrixX3d& x, const Candidates& candidates);

}  // namespace stiffsoft

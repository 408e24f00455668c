#pragma once
/// @file The active contact set: primitive pairs closer than d̂, classified into IPC's
/// vertex–vertex / edge–vertex / edge–edge / face–vertex stencils and de-duplicated, so a
/// vertex pressing on an edge shared by two triangles feels one barrier, not two.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "coupling/broad_phase.hpp"
#include "coupling/contact/barrier_potential.hpp"
#include "coupling/model.hpp"

namespace stiffsoft {

/// One active contact: the stencil's kind and its global surface vertices (−1 where unused).
struct ContactConstraint {
  contact::Stencil stencil;
  std::array<int, 4> vertices{-1, -1, -1, -1};
};

/// The stencil's vertex positions packed [x_0; x_1; x_2; x_3] (unused entries zero), m.
contact::Vector12d gather(const Eigen::MatrixX3d& x, const std::array<int, 4>& vertices);

/// Contacts among the candidates whose distance at x is below d̂ (m). Nearly parallel edge
/// pairs (‖ea × eb‖² < ε_x) stay edge–edge with the mollifier and the true segment distance.
std::vector<ContactConstraint> build_constraints(const Model& model, const Eigen::MatrixX3d& x,
                                                 const Candidates& candidates, double dhat);

/// Smallest distance (m) between any two primitives of different bodies among the candidates,
/// or +∞ when there are none.
double smallest_distance(const Model& model, const Eigen::MatrixX3d& x, const Candidates& candidates);

}  // namespace stiffsoft

#pragma once
/// @file Lumped (diagonal) mass of a linear-tet mesh: each tet gives ρ V_e / 4 to each node.

#include <Eigen/Core>

namespace stiffsoft::fem {

/// Mass per node, |N| (kg), for rest positions X (|N|×3, m), tetrahedra T (|T|×4) and density
/// ρ (kg/m³). Sums to ρ × total volume. Throws std::invalid_argument for ρ ≤ 0, a bad index or a
/// degenerate tet.
Eigen::VectorXd lumped_mass(const Eigen::MatrixX3d& X, const Eigen::MatrixX4i& T, double density);

}  // namespace stiffsoft::fem

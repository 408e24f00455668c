#pragma once
/// @file Test helper: how far a triangulation inscribed in a curved surface can be off in volume.

#include <Eigen/Geometry>
#include <algorithm>

#include <stiffsoft/meshing/surface_mesh.hpp>

namespace stiffsoft {

/// Bound on |V_mesh − V_exact| when the vertices of the closed triangle surface `s` lie on a smooth
/// surface whose principal curvatures are at most κ (1/m). A point p = Σλ_i x_i of a flat triangle
/// is off the surface by at most ½ Σλ_i (x_i − p)ᵀH(x_i − p) ≤ κ/2 Σ_{i<j} λ_iλ_j |x_i − x_j|² ≤ κℓ²/6
/// (ℓ its longest edge; Σ_{i<j} λ_iλ_j ≤ 1/3), so the volume between the triangles and the surface
/// is at most Σ_f A_f κ ℓ_f² / 6 (to first order in κℓ).
inline double chord_volume_bound(const SurfaceMesh& s, double kappa) {
  double bound = 0.0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d x0 = s.V.row(s.F(f, 0)), x1 = s.V.row(s.F(f, 1)), x2 = s.V.row(s.F(f, 2));
    const double l = std::max({(x1 - x0).norm(), (x2 - x1).norm(), (x0 - x2).norm()});
    bound += 0.5 * (x1 - x0).cross(x2 - x0).norm() * kappa * l * l / 6.0;
  }
  return bound;
}

}  // namespace stiffsoft

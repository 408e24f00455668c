#pragma once
/// @file The solids a closed surface bounds: its shells, which are outer boundaries, which cavities.

#include <Eigen/Core>
#include <string>
#include <vector>

#include <stiffsoft/meshing/surface_mesh.hpp>

namespace stiffsoft {

/// One connected component of a closed surface.
struct SurfaceShell {
  /// indices of its faces in the surface, ascending
  std::vector<int> faces;
  /// signed volume it encloses (m³): > 0 for an outer boundary, < 0 for a cavity (faces inward)
  double volume = 0.0;
};

/// A solid: one outer shell and the cavities directly inside it.
struct SurfaceSolid {
  /// index of its outward shell in SurfaceSolids::shells
  int outer = 0;
  /// indices of its inward shells (holes) in SurfaceSolids::shells
  std::vector<int> cavities;
};

/// The shells of a surface and how they nest into solids.
struct SurfaceSolids {
  /// connected components (faces joined across edges), ordered by their smallest face index
  std::vector<SurfaceShell> shells;
  /// one per outward shell, in shell order
  std::vector<SurfaceSolid> solids;
};

/// Generalized winding number of the closed faces `faces` of `surface` around point p:
/// w = Σ_f Ω_f / 4π with the signed solid angle of each triangle (a, b, c seen from p)
/// tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|) (Van Oosterom & Strackee 1983);
/// 1 inside an outward shell, 0 outside, −1 inside an inward one. p must not lie on a face.
double winding_number(const SurfaceMesh& surface, const std::vector<int>& faces, const Eigen::Vector3d& p);

/// Splits a closed, manifold, non-self-intersecting surface (check_closed_manifold and
/// check_not_self_intersecting pass) into shells and solids. A point of every shell is classified
/// by the winding number w of all other shells: an outward shell must lie outside all material
/// (w = 0: in empty space or in a cavity), an inward one inside material (w = 1); a cavity belongs
/// to the smallest outward shell around it.
/// @throws std::runtime_error("<what>: shell k … ") naming the shell (its first face) when an
/// outward shell lies inside another solid's material (nested solids) or an inward shell lies in
/// no solid
SurfaceSolids surface_solids(const SurfaceMesh& surface, const std::string& what);

}  // namespace stiffsoft

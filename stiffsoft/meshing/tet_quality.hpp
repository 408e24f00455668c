#pragma once
/// @file Shape-quality statistics of a tetrahedral mesh, for the log.

#include <string>

#include <stiffsoft/meshing/tet_mesh.hpp>

namespace stiffsoft {

/// Quality of one tetrahedron.
struct TetShape {
  /// smallest of its six dihedral angles (degrees); a regular tetrahedron has acos(1/3) ≈ 70.53°
  double min_dihedral_angle_deg = 0.0;
  /// largest of its six dihedral angles (degrees)
  double max_dihedral_angle_deg = 0.0;
  /// radius ratio ρ = 3 r_in / r_circ ∈ [0, 1], 1 for a regular tetrahedron, 0 when flat;
  /// r_in = 3|V| / Σ face areas, r_circ = |‖a‖²(b×c) + ‖b‖²(c×a) + ‖c‖²(a×b)| / (12|V|),
  /// a, b, c the edges from node 0
  double radius_ratio = 0.0;
};

/// The shape measures of tetrahedron t (orientation does not matter). Indices must be in range.
TetShape tet_shape(const TetMesh& mesh, Eigen::Index t);

/// Mesh-wide statistics over all tetrahedra.
struct TetQuality {
  /// number of nodes |X|
  int num_nodes = 0;
  /// number of tetrahedra |T|
  int num_tets = 0;
  /// Σ V_t (m³)
  double volume = 0.0;
  /// smallest signed tetrahedron volume (m³)
  double min_tet_volume = 0.0;
  /// smallest dihedral angle over the mesh (degrees)
  double min_dihedral_angle_deg = 0.0;
  /// largest dihedral angle over the mesh (degrees)
  double max_dihedral_angle_deg = 0.0;
  /// worst (smallest) radius ratio 3 r_in / r_circ over the mesh, 1 for a regular tetrahedron
  double min_radius_ratio = 0.0;
  /// mean radius ratio over the mesh
  double mean_radius_ratio = 0.0;
  /// shortest edge length (m)
  double min_edge_length = 0.0;
  /// longest edge length (m)
  double max_edge_length = 0.0;
};

/// Statistics of `mesh` (all zero for a mesh without tetrahedra). Indices must be in range.
TetQuality tet_quality(const TetMesh& mesh);

/// A one-line summary for the log, e.g. "1234 nodes, 5678 tets, volume 0.5236 m³, dihedral angles
/// [12.3°, 151.2°], radius ratio min 0.21 mean 0.73, edges [0.02, 0.09] m".
std::string summary(const TetQuality& quality);

}  // namespace stiffsoft

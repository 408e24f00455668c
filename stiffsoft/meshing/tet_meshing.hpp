#pragma once
/// @file Making tetrahedral meshes with gmsh: of primitives, closed surfaces and CAD files.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include <stiffsoft/meshing/primitive.hpp>
#include <stiffsoft/meshing/surface_mesh.hpp>
#include <stiffsoft/meshing/tet_mesh.hpp>

namespace stiffsoft {

/// How gmsh meshes a volume.
struct TetMeshOptions {
  /// target element size h (m), gmsh's Mesh.MeshSizeMax; > 0 and finite. Edges come out near h,
  /// some longer (measured on primitives: longest boundary edge 1.1–1.9 h, longest tet edge up to
  /// 2.5 h). Not used when reading a .msh, nor with keep_surface.
  double h = 0.1;
  /// when > 0, also refine by curvature (gmsh's Mesh.MeshSizeFromCurvature): at least this many
  /// elements around a full circle of the local radius of curvature, finer than h where surfaces
  /// bend sharply (a thin torus tube, a small fillet); 0 uses h alone
  int elements_per_circle = 0;
  /// surface files only: keep the file's triangles as the boundary (no remeshing; the interior
  /// is graded from the surface's own edge lengths and h is not used). Otherwise the surface is
  /// split into patches at sharp edges (feature_angle_deg), reparametrized and remeshed with h.
  bool keep_surface = false;
  /// surface files only, when remeshing: an edge whose two triangles' normals differ by more than
  /// this angle (degrees) is a sharp feature that the new surface mesh keeps; in (0, 180]
  double feature_angle_deg = 40.0;
  /// print gmsh's messages to the terminal (otherwise gmsh prints nothing)
  bool verbose = false;
  /// CAD (.step, .stp, .brep) and .geo files only, when > 0: the most tetrahedra the mesh may be
  /// expected to have. Once the geometry is loaded and before gmsh meshes it, the count is
  /// estimated as V / (h³/(6√2)) (regular tetrahedra of edge h) from the solids' volume V
  /// (OpenCASCADE's for CAD; the solids' bounding boxes for .geo, an upper bound), and
  /// TetCountLimitError is thrown above it. Not part of the mesh cache's recipe: it decides
  /// whether to mesh, not how. 0: no limit. (Primitives and surfaces have a known volume: their
  /// callers check before meshing.)
  double max_tets = 0;
};

/// The expected number of tetrahedra of a solid of volume V (m³) meshed at edge length h (m):
/// V / (h³ / (6√2)), as if filled with regular tetrahedra of edge h. gmsh's meshes of box,
/// slab, sphere and torus come out at 0.55–0.7 of it (measured; docs/robustness.md), so it errs
/// high by a factor of about 1.7. A double: huge values do not overflow.
double expected_tet_count(double volume, double h);

/// Thrown by make_tet_mesh when a file's expected tet count is above TetMeshOptions::max_tets.
class TetCountLimitError : public std::runtime_error {
 public:
  /// what: the message; volume: the estimate's V (m³); expected: the estimated tet count
  TetCountLimitError(const std::string& what, double volume, double expected)
      : std::runtime_error(what), volume_(volume), expected_(expected) {}
  /// the volume the estimate used (m³)
  double volume() const { return volume_; }
  /// the estimated number of tetrahedra
  double expected() const { return expected_; }

 private:
  double volume_;
  double expected_;
};

/// Everything a tet mesh is made from: a primitive, or a file.
struct TetMeshRecipe {
  /// set for a primitive (file is then ignored)
  std::optional<PrimitiveShape> primitive;
  /// the file when there is no primitive: .stl/.obj (closed surface), .step/.stp/.brep (CAD),
  /// .geo (gmsh script) or .msh (a tet mesh, read as is); extension case-insensitive
  std::filesystem::path file;
  /// meshing settings
  TetMeshOptions options;
};

/// A tet mesh of a primitive, centred at the origin, in make_primitive()'s conventions (axis of
/// symmetry along y): box and plane: edge lengths `extents` (m); sphere: `radius`; cylinder:
/// `radius`, `height` along y; torus: major `radius`, tube `minor_radius`, around the y axis.
/// Built with gmsh's OpenCASCADE kernel (addBox, addSphere, addCylinder, addTorus), so boundary
/// nodes lie on the exact curved surface; `resolution` is not used.
/// @throws std::invalid_argument for a non-positive or non-finite size or h, or minor_radius ≥ radius
/// @throws std::runtime_error when gmsh fails
TetMesh make_tet_mesh(const PrimitiveShape& shape, const TetMeshOptions& options);

/// A tet mesh of the solid enclosed by `surface`, which is first checked closed, manifold,
/// outward-oriented (check_closed_manifold) and not self-intersecting (check_not_self_intersecting).
/// @param what the body or file the surface comes from, for messages
/// @throws std::runtime_error("<what>: …") when a check or gmsh fails
TetMesh make_tet_mesh(const SurfaceMesh& surface, const TetMeshOptions& options, const std::string& what);

/// A tet mesh from a file, chosen by extension (case-insensitive):
/// - `.stl`, `.obj`: read_surface_mesh(), then as make_tet_mesh(SurfaceMesh, …);
/// - `.step`, `.stp`, `.brep`: imported with OpenCASCADE, lengths converted to metres from the
///   file's declared unit (Geometry.OCCTargetUnit = "M": a STEP in mm is scaled by 1e-3); several
///   solids are fused into one conformal mesh (occ::removeAllDuplicates); a STEP file must start
///   with `ISO-10303-21;` (OpenCASCADE prints parse errors of a malformed body to stdout, whatever
///   `verbose` says);
/// - `.geo`: run by gmsh, then meshed in 3D with h (unless the script meshed itself): sizes given
///   at points (`Point(1) = {x, y, z, lc}`, `MeshSize{…}`) are ignored, size fields (`Field`,
///   `Background Field`) still refine, capped by h; these settings are made before the script
///   runs and again after it, so a script's own option lines only matter if it meshes itself;
/// - `.msh`: read_msh() (h unused).
/// Physical groups of .geo and .msh files become node sets (see tet_mesh_from_gmsh_model()).
/// @throws std::invalid_argument for an unknown extension or a bad h
/// @throws std::runtime_error naming the file for an unreadable file, a failed check or a gmsh error
TetMesh make_tet_mesh(const std::filesystem::path& file, const TetMeshOptions& options);

/// make_tet_mesh of the recipe's primitive, or else of its file.
TetMesh make_tet_mesh(const TetMeshRecipe& recipe);

}  // namespace stiffsoft

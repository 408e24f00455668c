#pragma once
/// @file A stiffsoft scene as every engine of the peer benchmark sees it: rigid bodies in
/// their centre-of-mass frames, with the mass properties, poses and velocities that
/// the scene builder (stiffsoft/scene) computed for stiffsoft, plus the stiffsoft Model and settings themselves.

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/scene/scene.hpp>

namespace stiffsoft::peers {

/// The faceted torus of stiffsoft/meshing/primitive.cpp: n rings of m vertices, vertex (j, k) at index j m + k.
struct TorusFacets {
  int n = 0;         ///< segments around the centre line (rings)
  int m = 0;         ///< segments around the tube (vertices per ring)
  double tube = 0;   ///< tube (minor) radius r (m), before the body's scale
};

/// One body, rigid, in the frame stiffsoft uses: x = R x̄ + c with x̄ centred at the centre of mass.
struct PeerBody {
  std::string name;                                   ///< the scene's body name
  bool fixed = false;                                 ///< static obstacle (stiffsoft `fixed`)
  double mass = 0;                                    ///< kg (of the solid at the scene's density; also set for fixed bodies)
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< inertia tensor about the centre of mass, body frame (kg·m²)
  Eigen::MatrixX3d x_bar;                             ///< surface vertices, body frame, centred at the centre of mass (m)
  Eigen::MatrixX3i F;                                 ///< triangles, indices into x_bar, outward
  Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();   ///< initial rotation
  Eigen::Vector3d c0 = Eigen::Vector3d::Zero();       ///< initial centre of mass, world (m)
  Eigen::Vector3d v0 = Eigen::Vector3d::Zero();       ///< initial centre-of-mass velocity, world (m/s)
  Eigen::Vector3d w0 = Eigen::Vector3d::Zero();       ///< initial angular velocity, world (rad/s)
  bool convex = false;                                ///< every vertex lies on or behind every face's plane
  std::optional<Eigen::Vector3d> box;                 ///< edge lengths (m) when the body is a `box`/`plane` primitive
  std::optional<TorusFacets> torus;                   ///< set when the body is a `torus` primitive
  double thickness = 0;  ///< smallest extent of the body-frame bounding box (m); a torus: its tube diameter
  int first_face = 0;    ///< the body's first triangle in the stiffsoft collision mesh
};

/// A scene ready for any engine: bodies, global settings, and what the tunnelling checks need.
struct PeerScene {
  std::string name;                              ///< scene file stem
  std::filesystem::path file;                    ///< the scene file
  double dt = 0;                                 ///< time step h (s), the benchmark's, not the file's
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< m/s²
  double mu = 0;                                 ///< Coulomb friction coefficient of every contact
  double dhat = 0;                               ///< stiffsoft's barrier distance d̂ (m), resolved
  std::vector<PeerBody> bodies;                  ///< every body, in scene order
  int ground = -1;  ///< the fixed body with the largest horizontal (x–z) footprint, −1 if none
  std::vector<std::pair<int, int>> linked_rings;  ///< torus pairs whose centre lines are linked at t = 0
  Model model;                                   ///< what stiffsoft simulates
  SimulationSettings settings;                   ///< stiffsoft's resolved settings at h = dt
  int triangles = 0;                             ///< triangles of all bodies
  /// Number of non-fixed bodies.
  int dynamic_bodies() const;
};

/// Loads `file` with prepare_scene() (the same path `stiffsoft run` takes),
/// sets the time step to `dt` and turns every body into a PeerBody. Throws std::runtime_error
/// for what the peers cannot represent: kinematic bodies, soft bodies.
PeerScene load_peer_scene(const std::filesystem::path& file, double dt);

/// Like load_peer_scene, from a scene already read (`file` names it in messages and resolves meshes).
PeerScene make_peer_scene(SceneDescription description, const std::filesystem::path& file, double dt);

/// True when every vertex of (V, F) lies on or behind the plane of every face, within
/// 1e-9 × the mesh's bounding-box diagonal.
bool is_convex(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

/// The vertices of slice j of a faceted torus body: rings j and j+1 (2m points, body frame).
/// Each slice is convex (checked by torus_slices_are_convex); together they are the torus.
Eigen::MatrixX3d torus_slice(const PeerBody& body, int j);

/// True when every slice's vertices lie behind the planes of the slice's own outer triangles:
/// the slices are convex, so their convex hulls tile the faceted torus exactly.
bool torus_slices_are_convex(const PeerBody& body);

/// The centre line of a faceted torus body: the centroid of each ring, n × 3, body frame (m).
Eigen::MatrixX3d torus_centre_line(const PeerBody& body);

}  // namespace stiffsoft::peers

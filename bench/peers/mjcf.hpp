#pragma once
/// @file The MJCF (MuJoCo XML) text of a peer scene.
///
/// Every body's geometry becomes convex mesh assets (MuJoCo collides the convex hull of a
/// mesh): a convex body is one mesh of its vertices; a faceted torus (a chain link, a ring)
/// is n meshes, one per slice between neighbouring rings of its tube, each the convex hull of
/// those two rings (2m vertices; peer_scene checks that each slice is convex, so the hulls
/// tile the torus exactly). A fixed body is geoms of the world body (a box primitive: a box
/// geom). The ground (the fixed box with the largest footprint, its y axis against gravity) is
/// a plane geom through its top face instead: MuJoCo 2.2 collides a mesh with a box by MPR
/// (libccd), which against a floor many times larger than the bodies finds its penetration
/// direction from the offset of the two centres, i.e. sideways: the piles exploded (bad qacc,
/// 0.2 m "depths") with a box floor, and a plane is MuJoCo's own way to model a ground (it
/// collides natively with meshes). A dynamic body is a body with a free joint at its centre of mass, with its exact
/// mass and full inertia tensor (explicit <inertial>, so MuJoCo does not infer it from the
/// hulls). Options: the scene's time step and gravity; friction μ on every geom (MuJoCo takes
/// the larger of the two geoms', so the contact gets μ); the rest is MuJoCo's default.

#include <string>

#include "peers/peer_scene.hpp"

namespace stiffsoft::peers {

/// Sizes of MuJoCo 2.2's preallocated contact and constraint buffers.
struct MjcfSizes {
  int nconmax = 0;  ///< contacts
  int njmax = 0;    ///< constraint rows
};

/// The MJCF text. Body i of the scene is MuJoCo body "b<i>" (dynamic bodies) and owns the
/// geoms "b<i>_<k>" (fixed bodies' geoms sit in the world body). Throws std::runtime_error for
/// a non-convex body that is not a torus primitive (no decomposition for it).
std::string make_mjcf(const PeerScene& scene, const MjcfSizes& sizes);

/// True when scene body `body` is the ground and becomes a plane geom (see above).
bool ground_is_plane(const PeerScene& scene, int body);

/// The scene body index encoded in a geom name "b<i>_<k>", or −1.
int body_of_geom_name(const char* name);

}  // namespace stiffsoft::peers

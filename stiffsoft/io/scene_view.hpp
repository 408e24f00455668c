#pragma once
/// @file Where to look at a run from: one camera rule for the ParaView script written beside
/// every run (io/paraview_script.hpp) and for `stiffsoft render`, so both show the same picture.
/// The camera looks along a fixed direction (from the front, a little from the side and from
/// above, against gravity) and is fitted to the framed box: every place the moving bodies reach
/// over the frames shown, with some room.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace stiffsoft {

/// One body's axis-aligned bounds in one frame.
struct BodyBounds {
  std::string model;        ///< "affine", "soft", "fixed" or "kinematic" (BodyFrame::model)
  Eigen::AlignedBox3d box;  ///< bounds of its points, m
};

/// How a run is looked at.
struct SceneView {
  Eigen::Vector3d up;         ///< unit up direction (against gravity)
  Eigen::Vector3d direction;  ///< unit direction from the looked-at point to the eye
  double view_angle_deg;      ///< vertical field of view, degrees
  double dolly;               ///< closer than fitting the framed box's sphere, factor > 1
  double room;                ///< room around the moving bodies, fraction of their extent on each side
  double arrow_fraction;      ///< the longest contact-force arrow, fraction of the framed box's diagonal
};

/// The view of a run under gravity `gravity` (m/s²; +y is up when it is zero).
SceneView scene_view(const Eigen::Vector3d& gravity);

/// The box the camera is fitted to: the union of `bounds` of the moving (affine and soft) bodies,
/// over as many frames as given, grown on each side by `view.room` times its largest extent; of
/// all bodies when none moves.
Eigen::AlignedBox3d framed_box(const std::vector<BodyBounds>& bounds, const SceneView& view);

/// Where the eye is: looking at the centre of `framed` along `view.direction`, at the distance
/// where the box's bounding sphere fills the field of view, divided by `view.dolly`.
Eigen::Vector3d eye_position(const Eigen::AlignedBox3d& framed, const SceneView& view);

/// Is a fixed or kinematic body a wall: at least twice as tall (along `up`, unit) as it is thick
/// (its smaller horizontal extent)? Walls are drawn translucent (kWallOpacity,
/// io/colour_maps.hpp), so that the bodies inside a container or behind a wall stay visible;
/// grounds, ramps and steps are not walls.
bool is_wall(const BodyBounds& body, const Eigen::Vector3d& up);

}  // namespace stiffsoft

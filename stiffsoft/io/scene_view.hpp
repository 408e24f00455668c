#pragma once
/// @file Where to look at a scene from: one camera for the ParaView script written beside every
/// run (io/paraview_script.hpp) and for `stiffsoft render`, so both show the same picture.

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

/// A camera looking at a scene.
struct SceneView {
  Eigen::Vector3d focal;     ///< point looked at, m
  Eigen::Vector3d position;  ///< eye, m
  Eigen::Vector3d up;        ///< unit up direction (against gravity)
  double view_angle_deg;     ///< vertical field of view, degrees
  double arrow_length;       ///< length of the longest contact-force arrow, m
};

/// The camera for a scene whose bodies have `bounds` (the first frame) under gravity `gravity`
/// (m/s²; +y is up when it is zero). It frames the bodies that move (affine and soft) with room
/// to fall and slide (15 % of their extent on every side), plus the parts of the fixed and kinematic
/// bodies inside that room (a large ground plane does not push the camera away), seen from the
/// front, a little from the side and from above.
SceneView scene_view(const std::vector<BodyBounds>& bounds, const Eigen::Vector3d& gravity);

}  // namespace stiffsoft

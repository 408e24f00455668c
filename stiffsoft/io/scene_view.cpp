#include "scene_view.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace stiffsoft {

namespace {

/// Vertical field of view of every rendering, degrees (ParaView's default).
constexpr double kViewAngleDeg = 30.0;
/// Closer than the framed box's bounding sphere: a wide picture has room left and right.
constexpr double kDolly = 1.3;
/// Room around the moving bodies, as a fraction of their extent on each side.
constexpr double kRoom = 0.1;
/// The longest contact-force arrow, as a fraction of the framed box's diagonal.
constexpr double kArrowFraction = 0.12;

bool is_scenery(const std::string& model) { return model == "fixed" || model == "kinematic"; }

}  // namespace

SceneView scene_view(const Eigen::Vector3d& gravity) {
  SceneView view;
  view.up = gravity.norm() > 0 ? Eigen::Vector3d(-gravity.normalized()) : Eigen::Vector3d::UnitY();
  // The front is +z unless up is (nearly) z; the eye sits in front, a little to the side and above.
  Eigen::Vector3d front = std::abs(view.up.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  front = (front - front.dot(view.up) * view.up).normalized();
  const Eigen::Vector3d side = view.up.cross(front);
  view.direction = (front + 0.45 * side + 0.6 * view.up).normalized();
  view.view_angle_deg = kViewAngleDeg;
  view.dolly = kDolly;
  view.room = kRoom;
  view.arrow_fraction = kArrowFraction;
  return view;
}

Eigen::AlignedBox3d framed_box(const std::vector<BodyBounds>& bounds, const SceneView& view) {
  Eigen::AlignedBox3d moving;
  for (const BodyBounds& b : bounds)
    if (!is_scenery(b.model)) moving.extend(b.box);
  if (moving.isEmpty())
    for (const BodyBounds& b : bounds) moving.extend(b.box);
  if (moving.isEmpty()) moving.extend(Eigen::Vector3d::Zero());
  const Eigen::Vector3d room = view.room * Eigen::Vector3d::Constant(moving.sizes().maxCoeff() + 1e-9);
  return {moving.min() - room, moving.max() + room};
}

Eigen::Vector3d eye_position(const Eigen::AlignedBox3d& framed, const SceneView& view) {
  const double radius = 0.5 * framed.diagonal().norm();
  const double distance = radius / std::sin(0.5 * view.view_angle_deg * M_PI / 180.0) / view.dolly;
  return framed.center() + distance * view.direction;
}

bool is_wall(const BodyBounds& body, const Eigen::Vector3d& up) {
  if (!is_scenery(body.model) || body.box.isEmpty()) return false;
  const Eigen::Vector3d sizes = body.box.sizes();
  const double height = sizes.dot(up.cwiseAbs());
  double thickness = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis)
    if (std::abs(up[axis]) < 0.5) thickness = std::min(thickness, sizes[axis]);
  return height >= 2.0 * thickness;
}

}  // namespace stiffsoft

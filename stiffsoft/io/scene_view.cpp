#include "scene_view.hpp"

#include <cmath>

namespace stiffsoft {

namespace {

/// Vertical field of view of every rendering, degrees (ParaView's default).
constexpr double kViewAngleDeg = 30.0;
/// Room around the moving bodies, as a fraction of their extent on each side.
constexpr double kRoom = 0.15;
/// The longest contact-force arrow, as a fraction of the framed box's diagonal.
constexpr double kArrowFraction = 0.12;

bool is_scenery(const std::string& model) { return model == "fixed" || model == "kinematic"; }

}  // namespace

SceneView scene_view(const std::vector<BodyBounds>& bounds, const Eigen::Vector3d& gravity) {
  Eigen::AlignedBox3d moving;
  for (const BodyBounds& b : bounds)
    if (!is_scenery(b.model)) moving.extend(b.box);
  if (moving.isEmpty())
    for (const BodyBounds& b : bounds) moving.extend(b.box);
  if (moving.isEmpty()) moving.extend(Eigen::Vector3d::Zero());
  const Eigen::Vector3d room = kRoom * moving.sizes().cwiseMax(1e-3 * moving.sizes().maxCoeff() + 1e-9);
  const Eigen::AlignedBox3d region(moving.min() - room, moving.max() + room);
  Eigen::AlignedBox3d framed = moving;
  for (const BodyBounds& b : bounds)
    if (is_scenery(b.model) && b.box.intersects(region)) framed.extend(b.box.intersection(region));

  SceneView view;
  view.up = gravity.norm() > 0 ? Eigen::Vector3d(-gravity.normalized()) : Eigen::Vector3d::UnitY();
  // The front is +z unless up is (nearly) z; the eye sits in front, a little to the side and above.
  Eigen::Vector3d front = std::abs(view.up.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  front = (front - front.dot(view.up) * view.up).normalized();
  const Eigen::Vector3d side = view.up.cross(front);
  const Eigen::Vector3d direction = (front + 0.45 * side + 0.5 * view.up).normalized();
  const double radius = 0.5 * framed.diagonal().norm();
  view.view_angle_deg = kViewAngleDeg;
  // The framed box's sphere fills the picture's height (a wide picture has room left and right).
  const double distance = radius / std::sin(0.5 * kViewAngleDeg * M_PI / 180.0);
  view.focal = framed.center();
  view.position = view.focal + 0.8 * distance * direction;
  view.arrow_length = kArrowFraction * framed.diagonal().norm();
  return view;
}

}  // namespace stiffsoft

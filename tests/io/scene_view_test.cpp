/// @file The camera of the ParaView script and `stiffsoft render` (stiffsoft/io/scene_view.hpp).

#include <gtest/gtest.h>

#include <stiffsoft/io/scene_view.hpp>

namespace stiffsoft {
namespace {

TEST(SceneView, FramesTheMovingBodiesNotTheWholeGroundAndLooksDownOnThem) {
  const std::vector<BodyBounds> bounds{
      {"fixed", Eigen::AlignedBox3d(Eigen::Vector3d(-50, -1, -50), Eigen::Vector3d(50, 0, 50))},
      {"affine", Eigen::AlignedBox3d(Eigen::Vector3d(-0.5, 0, -0.5), Eigen::Vector3d(0.5, 1, 0.5))}};
  const SceneView view = scene_view(bounds, Eigen::Vector3d(0, -9.81, 0));
  EXPECT_TRUE(view.up.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_LT((view.focal - Eigen::Vector3d(0, 0.5, 0)).norm(), 0.2);
  const double distance = (view.position - view.focal).norm();
  EXPECT_GT(distance, 1.0);
  EXPECT_LT(distance, 10.0) << "the 100 m ground must not push the camera away";
  EXPECT_GT(view.position.y(), view.focal.y()) << "seen from above";
  EXPECT_GT(view.arrow_length, 0.0);
  // Gravity along −z: z is up.
  EXPECT_TRUE(scene_view(bounds, Eigen::Vector3d(0, 0, -1)).up.isApprox(Eigen::Vector3d::UnitZ()));
}

}  // namespace
}  // namespace stiffsoft

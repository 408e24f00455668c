/// @file The camera rule of the ParaView script and `stiffsoft render` (stiffsoft/io/scene_view.hpp),
/// and which fixed bodies are walls.

#include <gtest/gtest.h>

#include <stiffsoft/io/scene_view.hpp>

namespace stiffsoft {
namespace {

TEST(SceneView, FramesWhereTheMovingBodiesGoNotTheWholeGroundAndLooksDownOnThem) {
  const SceneView view = scene_view(Eigen::Vector3d(0, -9.81, 0));
  EXPECT_TRUE(view.up.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(view.direction.norm(), 1.0, 1e-12);
  EXPECT_GT(view.direction.y(), 0.3) << "seen from above";
  // A body falls from y = 1 to y = 0 over two frames, on a 100 m ground.
  const std::vector<BodyBounds> bounds{
      {"fixed", Eigen::AlignedBox3d(Eigen::Vector3d(-50, -1, -50), Eigen::Vector3d(50, 0, 50))},
      {"affine", Eigen::AlignedBox3d(Eigen::Vector3d(-0.5, 1, -0.5), Eigen::Vector3d(0.5, 2, 0.5))},
      {"affine", Eigen::AlignedBox3d(Eigen::Vector3d(-0.5, 0, -0.5), Eigen::Vector3d(0.5, 1, 0.5))}};
  const Eigen::AlignedBox3d framed = framed_box(bounds, view);
  EXPECT_TRUE(framed.contains(Eigen::AlignedBox3d(Eigen::Vector3d(-0.5, 0, -0.5), Eigen::Vector3d(0.5, 2, 0.5))));
  EXPECT_LT(framed.sizes().maxCoeff(), 3.0) << "the 100 m ground must not push the camera away";
  const Eigen::Vector3d eye = eye_position(framed, view);
  EXPECT_GT((eye - framed.center()).norm(), 1.0);
  EXPECT_LT((eye - framed.center()).norm(), 10.0);
  EXPECT_TRUE((eye - framed.center()).normalized().isApprox(view.direction));
  // Gravity along −z: z is up; without gravity, y.
  EXPECT_TRUE(scene_view(Eigen::Vector3d(0, 0, -1)).up.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(scene_view(Eigen::Vector3d::Zero()).up.isApprox(Eigen::Vector3d::UnitY()));
}

TEST(SceneView, TallThinFixedBodiesAreWallsGroundsAndRampsAreNot) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const auto box = [](const std::string& model, Eigen::Vector3d size) {
    return BodyBounds{model, Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), size)};
  };
  EXPECT_TRUE(is_wall(box("fixed", {0.05, 0.5, 0.9}), up));
  EXPECT_TRUE(is_wall(box("kinematic", {0.9, 0.5, 0.05}), up));
  EXPECT_FALSE(is_wall(box("fixed", {3.0, 0.05, 3.0}), up)) << "a ground";
  EXPECT_FALSE(is_wall(box("fixed", {1.1, 0.58, 0.5}), up)) << "a tilted ramp's bounds";
  EXPECT_FALSE(is_wall(box("affine", {0.05, 0.5, 0.9}), up)) << "only fixed and kinematic bodies";
  EXPECT_FALSE(is_wall(box("fixed", {3.0, 3.0, 0.05}), Eigen::Vector3d::UnitZ())) << "a ground, z up";
  EXPECT_TRUE(is_wall(box("fixed", {0.9, 0.05, 0.5}), Eigen::Vector3d::UnitZ())) << "a wall, z up";
}

}  // namespace
}  // namespace stiffsoft

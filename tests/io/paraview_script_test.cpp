/// @file The ParaView script's text (stiffsoft/io/paraview_script.hpp): bodies sorted by model
/// into Python lists, the view of scene_view(), the colour maps of colour_maps.hpp. That it
/// runs in ParaView is tested with pvbatch in tests/apps/paraview_script_test.cpp.

#include <gtest/gtest.h>

#include <stiffsoft/io/paraview_script.hpp>

namespace stiffsoft {
namespace {

BodyFrame body(const std::string& name, const std::string& model, double x, double y, double size) {
  BodyFrame b;
  b.name = name;
  b.model = model;
  b.x.resize(2, 3);
  b.x << x - size, y - size, -size, x + size, y + size, size;
  return b;
}

TEST(ParaViewScript, SortsBodiesByModelAndFindsThePvdBesideItself) {
  const std::vector<BodyFrame> bodies{body("ground", "fixed", 0, -0.05, 10), body("box \"a\"", "affine", 0, 1, 0.1),
                                      body("ball", "soft", 1, 1, 0.1), body("piston", "kinematic", 0, 2, 0.1)};
  const ParaViewScene scene = paraview_scene("run", bodies, Eigen::Vector3d(0, -9.81, 0));
  EXPECT_EQ(scene.pvd_name, "run.pvd");
  EXPECT_EQ(scene.soft, std::vector<std::string>{"ball"});
  EXPECT_EQ(scene.affine, std::vector<std::string>{"box \"a\""});
  EXPECT_EQ(scene.scenery, (std::vector<std::string>{"ground", "piston"}));
  EXPECT_TRUE(scene.walls.empty());
  const std::string text = paraview_script(scene);
  EXPECT_NE(text.find("PVD = os.path.join(HERE, \"run.pvd\")"), std::string::npos);
  EXPECT_NE(text.find("SOFT = [\"ball\"]"), std::string::npos);
  EXPECT_NE(text.find("AFFINE = [\"box \\\"a\\\"\"]"), std::string::npos);  // quotes escaped
  EXPECT_NE(text.find("SCENERY = [\"ground\",\"piston\"]"), std::string::npos);
  EXPECT_EQ(text.find('@'), std::string::npos) << "a field was left unfilled";
  EXPECT_EQ(paraview_script_path("out", "run"), std::filesystem::path("out/run.paraview.py"));
}

}  // namespace
}  // namespace stiffsoft

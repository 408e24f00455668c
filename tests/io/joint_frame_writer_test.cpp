/// @file The joints' ParaView frames: written atomically, listed in their .pvd, read back
/// through VTK with the values given.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include <stiffsoft/io/joint_frame_reader.hpp>
#include <stiffsoft/io/joint_frame_writer.hpp>

using namespace stiffsoft;

TEST(JointFrameWriter, WritesReadableFramesListedInThePvd) {
  std::random_device rd;
  const auto out = std::filesystem::temp_directory_path() / ("stiffsoft_joint_frames_" + std::to_string(rd()));
  std::filesystem::remove_all(out);
  {
    JointFrameWriter writer(out, "scene");
    EXPECT_EQ(writer.pvd_path(), out / "scene_joints.pvd");
    EXPECT_TRUE(std::filesystem::exists(writer.pvd_path()));
    const std::vector<JointFrameEntry> joints{
        {"pivot", 0, {0, 1, 0}, {0, 1, 0}, {0.5, 9.81, -0.25}, std::nan("")},
        {"rope", 4, {1, 2, 3}, {1, 2.5, 3}, {0, -2, 0}, 0.125}};
    writer.write(0.0, joints);
    writer.write(0.5, joints);
    EXPECT_EQ(writer.frame_count(), 2);
  }
  std::ifstream in(out / "scene_joints.pvd");
  std::stringstream pvd;
  pvd << in.rdbuf();
  EXPECT_NE(pvd.str().find("timestep=\"0.5\" part=\"0\" file=\"frames/scene_joints_000001.vtp\""), std::string::npos)
      << pvd.str();
  const JointFrameRead frame = read_joint_frame(out / "frames" / "scene_joints_000001.vtp");
  EXPECT_EQ(frame.time, 0.5);
  ASSERT_EQ(frame.joints.size(), 2u);
  EXPECT_EQ(frame.joints[0].name, "pivot");
  EXPECT_EQ(frame.joints[1].kind, 4);
  EXPECT_EQ(frame.joints[1].x_b, Eigen::Vector3d(1, 2.5, 3));
  EXPECT_EQ(frame.joints[0].force, Eigen::Vector3d(0.5, 9.81, -0.25));
  EXPECT_TRUE(std::isnan(frame.joints[0].gap));
  EXPECT_EQ(frame.joints[1].gap, 0.125);
  EXPECT_THROW(read_joint_frame(out / "frames" / "missing.vtp"), std::runtime_error);
  std::filesystem::remove_all(out);
}

#include <stiffsoft/meshing/tet_msh_io.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <stiffsoft/meshing/tet_meshing.hpp>

namespace stiffsoft {
namespace {

const std::filesystem::path data = std::filesystem::path(STIFFSOFT_SOURCE_DIR) / "tests" / "meshing" / "data";

class TetMshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("stiffsoft_tet_msh_io_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path write(const std::string& name, const std::string& content) {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }
  static std::string error_of(const std::filesystem::path& path) {
    try {
      read_msh(path);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "no exception";
  }
  std::filesystem::path dir_;
};

TEST_F(TetMshIo, HandWrittenMsh2IsReorientedAndGroupsBecomeNodeSets) {
  // Two tets, the second written with negative orientation; node 6 is used by no tet; a named
  // triangle group, a named volume group and an unnamed point group.
  const TetMesh m = read_msh(data / "tet_two_tets.msh");
  ASSERT_EQ(m.X.rows(), 5);
  EXPECT_EQ(m.X.row(4), Eigen::RowVector3d(1, 1, 1));
  ASSERT_EQ(m.T.rows(), 2);
  EXPECT_EQ(m.T.row(0), Eigen::RowVector4i(0, 1, 2, 3));
  EXPECT_EQ(m.T.row(1), Eigen::RowVector4i(2, 3, 1, 4));  // was (2, 1, 3, 4): nodes 1 and 2 swapped
  EXPECT_DOUBLE_EQ(tet_mesh_volume(m), 0.5);
  EXPECT_EQ(m.node_sets.size(), 3u);
  EXPECT_EQ(m.node_sets.at("bottom"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(m.node_sets.at("body"), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(m.node_sets.at("physical_0_7"), (std::vector<int>{0}));
}

TEST_F(TetMshIo, WriteThenReadGivesTheSameMeshAndNodeSets) {
  PrimitiveShape s;
  s.type = PrimitiveShape::Type::Sphere;
  s.radius = 0.3;
  TetMeshOptions o;
  o.h = 0.15;
  TetMesh m = make_tet_mesh(s, o);
  for (Eigen::Index i = 0; i < m.X.rows(); ++i) {
    if (m.X(i, 1) < -0.2) m.node_sets["south"].push_back(static_cast<int>(i));
    if (m.X(i, 0) > 0.1) m.node_sets["east"].push_back(static_cast<int>(i));  // overlaps "south"
  }
  m.node_sets["one"] = {3};
  ASSERT_GT(m.node_sets.at("south").size(), 3u);

  const auto file = dir_ / "sphere.msh";
  write_msh(file, m);
  const TetMesh back = read_msh(file);
  ASSERT_EQ(back.X.rows(), m.X.rows());
  EXPECT_LT((back.X - m.X).cwiseAbs().maxCoeff(), 1e-15 * 0.3 * 10);  // 16 significant digits
  EXPECT_EQ(back.T, m.T);
  EXPECT_EQ(back.node_sets, m.node_sets);
  // No temporary left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1);
}

TEST_F(TetMshIo, GarbageAndMissingFilesNameTheFile) {
  const auto missing = dir_ / "missing.msh";
  EXPECT_EQ(error_of(missing), missing.string() + ": cannot open file");

  const auto text = write("text.msh", "hello world\n");
  EXPECT_EQ(error_of(text),
            text.string() + ": not a gmsh .msh file (expected '$MeshFormat' on the first line)");

  const auto truncated =
      write("truncated.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n");
  const std::string e = error_of(truncated);
  EXPECT_EQ(e.rfind(truncated.string() + ": ", 0), 0u) << e;
  EXPECT_NE(e, "no exception");

  const auto empty = write("empty.msh", "");
  EXPECT_EQ(error_of(empty).rfind(empty.string() + ": not a gmsh .msh file", 0), 0u) << error_of(empty);
}

TEST_F(TetMshIo, SurfaceOnlyMshHasNoTetrahedra) {
  const auto file =
      write("triangle.msh",
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
            "$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n");
  const std::string e = error_of(file);
  EXPECT_EQ(e.rfind(file.string() + ": contains no tetrahedra", 0), 0u) << e;
}

TEST_F(TetMshIo, SecondOrderTetsAreRejected) {
  // One 10-node tetrahedron (gmsh type 11).
  const auto file =
      write("tet10.msh",
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n"
            "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0.5 0 0\n6 0.5 0.5 0\n7 0 0.5 0\n8 0 0 0.5\n"
            "9 0 0.5 0.5\n10 0.5 0 0.5\n$EndNodes\n$Elements\n1\n1 11 2 1 1 1 2 3 4 5 6 7 8 9 10\n"
            "$EndElements\n");
  const std::string e = error_of(file);
  EXPECT_EQ(e.rfind(file.string() + ": has volume elements of gmsh type 11", 0), 0u) << e;
}

TEST_F(TetMshIo, InvalidMeshIsNotWritten) {
  TetMesh bad;
  bad.X.resize(4, 3);
  bad.X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;  // flat
  bad.T.resize(1, 4);
  bad.T << 0, 1, 2, 3;
  const auto file = dir_ / "bad.msh";
  EXPECT_THROW(write_msh(file, bad), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(file));
}

}  // namespace
}  // namespace stiffsoft

#include <stiffsoft/meshing/read_surface_mesh.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <stiffsoft/meshing/mass_moments.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>
#include <stiffsoft/meshing/primitive.hpp>

namespace stiffsoft {
namespace {

class ReadSurfaceMesh : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("stiffsoft_read_surface_mesh_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
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
      read_surface_mesh(path);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "no exception";
  }
  std::filesystem::path dir_;
};

SurfaceMesh unit_box() {
  PrimitiveShape s;
  s.extents = {1.0, 2.0, 0.5};
  return make_primitive(s);
}

TEST_F(ReadSurfaceMesh, ObjWithQuadsSlashesAndNegativeIndicesIsAClosedBox) {
  // A unit cube, quads counter-clockwise from outside, written with every index form.
  const std::string obj =
      "# cube\no cube\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "vn 0 0 1\nvt 0 0\n"
      "f 1/1/1 4/1/1 3/1/1 2/1/1\n"
      "f 5//1 6//1 7//1 8//1\n"
      "f -8/1 -7/1 -3/1 -4/1\n"  // 1 2 6 5
      "f 2 3 7 6\n"
      "f 3 4 8 7\n"
      "usemtl x\ns off\n"
      "f 4 1 5 8\n";
  const SurfaceMesh m = read_surface_mesh(write("cube.obj", obj));
  EXPECT_EQ(m.V.rows(), 8);
  EXPECT_EQ(m.F.rows(), 12);
  EXPECT_FALSE(closed_manifold_problem(m).has_value()) << *closed_manifold_problem(m);
  EXPECT_NEAR(mass_moments(m).volume, 1.0, 1e-15);
}

TEST_F(ReadSurfaceMesh, ObjRoundTripKeepsVerticesAndFaces) {
  const SurfaceMesh box = unit_box();
  std::ostringstream out;
  out.precision(17);
  for (Eigen::Index i = 0; i < box.V.rows(); ++i) out << "v " << box.V(i, 0) << ' ' << box.V(i, 1) << ' ' << box.V(i, 2) << '\n';
  for (Eigen::Index f = 0; f < box.F.rows(); ++f)
    out << "f " << box.F(f, 0) + 1 << ' ' << box.F(f, 1) + 1 << ' ' << box.F(f, 2) + 1 << '\n';
  const SurfaceMesh m = read_surface_mesh(write("box.OBJ", out.str()));
  EXPECT_EQ(m.V, box.V);
  EXPECT_EQ(m.F, box.F);
}

std::string ascii_stl(const SurfaceMesh& m) {
  std::ostringstream out;
  out.precision(17);
  out << "solid box\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k)
      out << "      vertex " << m.V(m.F(f, k), 0) << ' ' << m.V(m.F(f, k), 1) << ' ' << m.V(m.F(f, k), 2) << '\n';
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid box\n";
  return out.str();
}

std::string binary_stl(const SurfaceMesh& m) {
  std::string bytes(80, ' ');
  bytes.replace(0, 11, "solid fake!");  // binary files may start with "solid" too
  const std::uint32_t count = static_cast<std::uint32_t>(m.F.rows());
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    float record[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) record[3 + 3 * k + d] = static_cast<float>(m.V(m.F(f, k), d));
    bytes.append(reinterpret_cast<const char*>(record), 48);
    bytes.append(2, '\0');
  }
  return bytes;
}

TEST_F(ReadSurfaceMesh, AsciiStlMergesDuplicateVertices) {
  const SurfaceMesh box = unit_box();
  const SurfaceMesh m = read_surface_mesh(write("box.stl", ascii_stl(box)));
  EXPECT_EQ(m.V.rows(), 8);
  EXPECT_EQ(m.F.rows(), 12);
  EXPECT_FALSE(closed_manifold_problem(m).has_value()) << *closed_manifold_problem(m);
  EXPECT_NEAR(mass_moments(m).volume, 1.0, 1e-15);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m.V.row(m.F(f, k)), box.V.row(box.F(f, k)));
}

TEST_F(ReadSurfaceMesh, BinaryStlMergesDuplicateVertices) {
  const SurfaceMesh box = unit_box();  // coordinates are exact in float
  const SurfaceMesh m = read_surface_mesh(write("box.stl", binary_stl(box)));
  EXPECT_EQ(m.V.rows(), 8);
  EXPECT_EQ(m.F.rows(), 12);
  EXPECT_FALSE(closed_manifold_problem(m).has_value()) << *closed_manifold_problem(m);
  EXPECT_NEAR(mass_moments(m).volume, 1.0, 1e-15);
}

TEST_F(ReadSurfaceMesh, ErrorsNameTheFileTheLineAndWhatWasExpected) {
  const auto bad_index = write("bad_index.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  std::string e = error_of(bad_index);
  EXPECT_NE(e.find(bad_index.string() + ":3:"), std::string::npos) << e;
  EXPECT_NE(e.find("out of range"), std::string::npos) << e;

  e = error_of(write("bad_vertex.obj", "v 0 0 0\nv 1 zero 0\n"));
  EXPECT_NE(e.find("bad_vertex.obj:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("v x y z"), std::string::npos) << e;

  e = error_of(write("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"));
  EXPECT_NE(e.find("two.obj:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 3"), std::string::npos) << e;

  e = error_of(write("negative.obj", "v 0 0 0\nf -1 -2 -3\n"));
  EXPECT_NE(e.find("negative.obj:2:"), std::string::npos) << e;

  e = error_of(write("empty.obj", "v 0 0 0\n"));
  EXPECT_NE(e.find("no faces"), std::string::npos) << e;

  e = error_of(write("quad.stl", "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
                                 "vertex 0 1 0\nendloop\nendfacet\nendsolid q\n"));
  EXPECT_NE(e.find("quad.stl:8:"), std::string::npos) << e;
  EXPECT_NE(e.find("expected 3 vertices"), std::string::npos) << e;

  e = error_of(write("garbage.stl", "hello"));
  EXPECT_NE(e.find("garbage.stl"), std::string::npos) << e;
  EXPECT_NE(e.find("neither a binary STL"), std::string::npos) << e;

  e = error_of(write("mesh.ply", "ply\n"));
  EXPECT_NE(e.find("expected .obj or .stl"), std::string::npos) << e;

  e = error_of(dir_ / "missing.obj");
  EXPECT_NE(e.find("missing.obj: cannot open"), std::string::npos) << e;
}

}  // namespace
}  // namespace stiffsoft

#include <stiffsoft/meshing/tet_meshing.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>

#include <stiffsoft/meshing/gmsh_session.hpp>
#include <stiffsoft/meshing/mass_moments.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>
#include <stiffsoft/meshing/tet_boundary.hpp>
#include <stiffsoft/meshing/tet_quality.hpp>
#include "tet_chord_bound.hpp"

namespace stiffsoft {
namespace {

const std::filesystem::path data = std::filesystem::path(STIFFSOFT_SOURCE_DIR) / "tests" / "meshing" / "data";

PrimitiveShape shape(PrimitiveShape::Type type) {
  PrimitiveShape s;
  s.type = type;
  return s;
}

TetMeshOptions with_h(double h) {
  TetMeshOptions o;
  o.h = h;
  return o;
}

/// What every mesh we make must satisfy: passes check_tet_mesh (positive volumes, no unreferenced
/// node); its boundary is closed, manifold, outward and not self-intersecting, and encloses exactly
/// the tets' volume (divergence theorem, so equal up to rounding); the quality is that of a
/// usable Delaunay mesh (gmsh's optimizer leaves no dihedral angle below ~5° in these shapes).
TetBoundary expect_good_mesh(const TetMesh& m) {
  EXPECT_FALSE(tet_mesh_problem(m).has_value()) << *tet_mesh_problem(m);
  const TetBoundary b = boundary_surface(m);
  const auto problem = closed_manifold_problem(b.surface);
  EXPECT_FALSE(problem.has_value()) << *problem;
  const auto crossing = find_self_intersection(b.surface);
  EXPECT_FALSE(crossing.has_value()) << "faces " << crossing->first << " and " << crossing->second;
  const double V = tet_mesh_volume(m);
  EXPECT_NEAR(mass_moments(b.surface).volume, V, 1e-13 * V);
  const TetQuality q = tet_quality(m);
  EXPECT_GT(q.min_dihedral_angle_deg, 5.0) << summary(q);
  EXPECT_LT(q.max_dihedral_angle_deg, 175.0) << summary(q);
  EXPECT_GT(q.min_radius_ratio, 0.05) << summary(q);
  EXPECT_LE(q.min_radius_ratio, q.mean_radius_ratio);
  EXPECT_LE(q.mean_radius_ratio, 1.0);
  return b;
}

TEST(TetMeshing, BoxIsExactAndCentred) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Box);
  s.extents = {1.0, 0.5, 0.6};
  const TetMesh m = make_tet_mesh(s, with_h(0.25));
  expect_good_mesh(m);
  EXPECT_NEAR(tet_mesh_volume(m), 0.3, 1e-14);  // planar faces: exact up to rounding
  EXPECT_NEAR(m.X.col(0).maxCoeff(), 0.5, 1e-15);
  EXPECT_NEAR(m.X.col(1).minCoeff(), -0.25, 1e-15);
  EXPECT_NEAR(m.X.col(2).maxCoeff(), 0.3, 1e-15);
  EXPECT_LT(m.T.rows(), 400);
  EXPECT_TRUE(m.node_sets.empty());
}

TEST(TetMeshing, PlaneIsAThinBox) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Plane);
  s.extents = {1.0, 0.05, 1.0};
  const TetMesh m = make_tet_mesh(s, with_h(0.25));
  expect_good_mesh(m);
  EXPECT_NEAR(tet_mesh_volume(m), 0.05, 1e-15);
  EXPECT_NEAR(m.X.col(1).maxCoeff(), 0.025, 1e-16);
}

TEST(TetMeshing, SphereIsInscribedWithinTheChordBound) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Sphere);
  s.radius = 0.5;
  const TetMesh m = make_tet_mesh(s, with_h(0.2));
  const TetBoundary b = expect_good_mesh(m);
  for (Eigen::Index i = 0; i < b.surface.V.rows(); ++i)
    EXPECT_NEAR(b.surface.V.row(i).norm(), 0.5, 1e-12) << i;
  const double exact = 4.0 / 3.0 * std::numbers::pi * 0.125;
  // All nodes in the ball and the ball convex: the tets fill less than the ball.
  EXPECT_LT(tet_mesh_volume(m), exact);
  EXPECT_GT(tet_mesh_volume(m), exact - chord_volume_bound(b.surface, 1.0 / 0.5));
  EXPECT_LT(m.T.rows(), 600);
}

TEST(TetMeshing, CylinderAxisIsY) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Cylinder);
  s.radius = 0.3;
  s.height = 0.8;
  const TetMesh m = make_tet_mesh(s, with_h(0.2));
  const TetBoundary b = expect_good_mesh(m);
  EXPECT_NEAR(m.X.col(1).minCoeff(), -0.4, 1e-15);
  EXPECT_NEAR(m.X.col(1).maxCoeff(), 0.4, 1e-15);
  const Eigen::VectorXd radial = (m.X.col(0).array().square() + m.X.col(2).array().square()).sqrt();
  EXPECT_NEAR(radial.maxCoeff(), 0.3, 1e-12);
  const double exact = std::numbers::pi * 0.09 * 0.8;
  EXPECT_LT(tet_mesh_volume(m), exact);
  EXPECT_GT(tet_mesh_volume(m), exact - chord_volume_bound(b.surface, 1.0 / 0.3));
  EXPECT_LT(m.T.rows(), 600);
}

TEST(TetMeshing, TorusTurnsAroundY) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Torus);
  s.radius = 0.5;
  s.minor_radius = 0.2;
  const TetMesh m = make_tet_mesh(s, with_h(0.15));
  const TetBoundary b = expect_good_mesh(m);
  for (Eigen::Index i = 0; i < b.surface.V.rows(); ++i) {
    const Eigen::Vector3d x = b.surface.V.row(i);
    EXPECT_NEAR(std::hypot(std::hypot(x.x(), x.z()) - 0.5, x.y()), 0.2, 1e-9) << i;
  }
  // The surface is not convex (saddle-shaped inside), so the error has either sign. Curvatures:
  // 1/r around the tube, |cos ψ / (R + r cos ψ)| ≤ 1/(R − r) along it.
  const double exact = 2.0 * std::numbers::pi * std::numbers::pi * 0.5 * 0.2 * 0.2;
  EXPECT_NEAR(tet_mesh_volume(m), exact, chord_volume_bound(b.surface, std::max(1.0 / 0.2, 1.0 / 0.3)));
  EXPECT_LT(m.T.rows(), 900);
}

TEST(TetMeshing, SmallerHGivesMoreTetsAndCurvatureRefines) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Sphere);
  s.radius = 0.5;
  const TetMesh coarse = make_tet_mesh(s, with_h(0.4));
  const TetMesh fine = make_tet_mesh(s, with_h(0.2));
  EXPECT_GT(fine.T.rows(), 4 * coarse.T.rows());  // ~8× for half the size in 3D
  TetMeshOptions curved = with_h(0.4);
  curved.elements_per_circle = 16;  // 2π r / 16 ≈ 0.2 m on this sphere
  EXPECT_GT(make_tet_mesh(s, curved).T.rows(), 4 * coarse.T.rows());
}

TEST(TetMeshing, SameRecipeGivesBitIdenticalMesh) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Torus);
  s.radius = 0.5;
  s.minor_radius = 0.2;
  const TetMesh a = make_tet_mesh(s, with_h(0.2));
  const TetMesh b = make_tet_mesh(s, with_h(0.2));
  EXPECT_EQ(a.X, b.X);
  EXPECT_EQ(a.T, b.T);
}

TEST(TetMeshing, ConcurrentCallsTakeTurnsAndAgree) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Cylinder);
  s.radius = 0.2;
  s.height = 0.5;
  const TetMesh serial = make_tet_mesh(s, with_h(0.15));
  TetMesh a, b;
  std::thread ta([&] { a = make_tet_mesh(s, with_h(0.15)); });
  std::thread tb([&] { b = make_tet_mesh(s, with_h(0.15)); });
  ta.join();
  tb.join();
  EXPECT_EQ(a.T, serial.T);
  EXPECT_EQ(b.T, serial.T);
  EXPECT_EQ(a.X, serial.X);
  EXPECT_EQ(b.X, serial.X);
}

TEST(TetMeshing, GmshSessionsDoNotNest) {
  EXPECT_THROW(run_gmsh("outer", false, [] { run_gmsh("inner", false, [] {}); }), std::logic_error);
  // The lock was released: the next session runs.
  EXPECT_NO_THROW(run_gmsh("next", false, [] {}));
}

TEST(TetMeshing, GmshPrintsNothingUnlessVerbose) {
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  make_tet_mesh(shape(PrimitiveShape::Type::Box), with_h(0.5));
  make_tet_mesh(data / "tet_box_100x200x300mm.step", with_h(0.2));
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
  // The capture does see gmsh when it is asked to talk.
  TetMeshOptions verbose = with_h(0.5);
  verbose.verbose = true;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  make_tet_mesh(shape(PrimitiveShape::Type::Box), verbose);
  const std::string talk = testing::internal::GetCapturedStdout() + testing::internal::GetCapturedStderr();
  EXPECT_NE(talk.find("Meshing 3D"), std::string::npos) << talk;
}

TEST(TetMeshing, BadPrimitiveParametersAreRejected) {
  EXPECT_THROW(make_tet_mesh(shape(PrimitiveShape::Type::Box), with_h(0.0)), std::invalid_argument);
  EXPECT_THROW(make_tet_mesh(shape(PrimitiveShape::Type::Box), with_h(std::nan(""))), std::invalid_argument);
  PrimitiveShape torus = shape(PrimitiveShape::Type::Torus);
  torus.radius = 0.2;
  torus.minor_radius = 0.3;
  try {
    make_tet_mesh(torus, with_h(0.1));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("primitive torus: minor_radius"), std::string::npos) << e.what();
  }
  PrimitiveShape box = shape(PrimitiveShape::Type::Box);
  box.extents.y() = -1.0;
  EXPECT_THROW(make_tet_mesh(box, with_h(0.1)), std::invalid_argument);
}

TEST(TetMeshing, StlCubeIsRemeshedWithH) {
  const TetMesh m = make_tet_mesh(data / "tet_cube_half_metre.stl", with_h(0.2));
  const TetBoundary b = expect_good_mesh(m);
  EXPECT_NEAR(tet_mesh_volume(m), 0.125, 1e-14);
  EXPECT_GT(b.surface.F.rows(), 12);  // the 12 input triangles were remeshed
  EXPECT_NEAR(m.X.minCoeff(), 0.0, 1e-15);
  EXPECT_NEAR(m.X.maxCoeff(), 0.5, 1e-15);
}

TEST(TetMeshing, StlCubeKeepsItsTrianglesWhenAsked) {
  TetMeshOptions o = with_h(0.2);
  o.keep_surface = true;
  const TetMesh m = make_tet_mesh(data / "tet_cube_half_metre.stl", o);
  const TetBoundary b = expect_good_mesh(m);
  EXPECT_EQ(b.surface.F.rows(), 12);
  EXPECT_EQ(b.surface.V.rows(), 8);
  EXPECT_NEAR(tet_mesh_volume(m), 0.125, 1e-15);
}

TEST(TetMeshing, ObjTorusSurfaceOfGenusOneIsMeshed) {
  PrimitiveShape s = shape(PrimitiveShape::Type::Torus);
  s.radius = 0.5;
  s.minor_radius = 0.2;
  s.resolution = 24;
  const SurfaceMesh surface = make_primitive(s);
  const auto file = std::filesystem::temp_directory_path() /
                    ("stiffsoft_tet_meshing_torus_" + std::to_string(::getpid()) + ".obj");
  {
    std::ofstream out(file);
    out.precision(17);
    for (Eigen::Index i = 0; i < surface.V.rows(); ++i)
      out << "v " << surface.V(i, 0) << " " << surface.V(i, 1) << " " << surface.V(i, 2) << "\n";
    for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
      out << "f " << surface.F(f, 0) + 1 << " " << surface.F(f, 1) + 1 << " " << surface.F(f, 2) + 1 << "\n";
  }
  const TetMesh m = make_tet_mesh(file, with_h(0.15));
  std::filesystem::remove(file);
  const TetBoundary b = expect_good_mesh(m);
  // The input polyhedron's nodes lie on the torus, so it is within its chord bound B_in of the
  // torus, and its points are off the torus by at most κℓ²/6, which moves the remeshed nodes (they
  // lie on the input) by as much: another B_in at most. Then the remeshed triangles' own chords.
  const double kappa = std::max(1.0 / 0.2, 1.0 / 0.3);
  const double exact = 2.0 * std::numbers::pi * std::numbers::pi * 0.5 * 0.2 * 0.2;
  EXPECT_NEAR(tet_mesh_volume(m), exact,
              chord_volume_bound(b.surface, kappa) + 2.0 * chord_volume_bound(surface, kappa));
}

TEST(TetMeshing, OpenSurfaceIsRejectedNamingTheFile) {
  const auto file = data / "tet_open_box.obj";
  try {
    make_tet_mesh(file, with_h(0.2));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ": edge", 0), 0u) << message;
    EXPECT_NE(message.find("not closed"), std::string::npos) << message;
  }
}

TEST(TetMeshing, SelfIntersectingSurfaceIsRejectedNamingTheFile) {
  const auto file = data / "tet_two_crossing_tets.obj";
  try {
    make_tet_mesh(file, with_h(0.2));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ": the surface intersects itself: face", 0), 0u) << message;
  }
}

TEST(TetMeshing, StepInMillimetresBecomesMetres) {
  const TetMesh m = make_tet_mesh(data / "tet_box_100x200x300mm.step", with_h(0.1));
  expect_good_mesh(m);
  EXPECT_NEAR(tet_mesh_volume(m), 0.1 * 0.2 * 0.3, 1e-15);
  EXPECT_NEAR(m.X.col(0).minCoeff(), 0.0, 1e-15);
  EXPECT_NEAR(m.X.col(0).maxCoeff(), 0.1, 1e-15);
  EXPECT_NEAR(m.X.col(1).maxCoeff(), 0.2, 1e-15);
  EXPECT_NEAR(m.X.col(2).maxCoeff(), 0.3, 1e-15);
}

TEST(TetMeshing, CadAndGeoFilesAboveMaxTetsAreRefusedBeforeMeshing) {
  // h = 10 µm would mean about 5e13 tetrahedra: refused once the geometry is loaded.
  TetMeshOptions options = with_h(1e-5);
  options.max_tets = 1e6;
  try {
    make_tet_mesh(data / "tet_box_100x200x300mm.step", options);
    FAIL() << "meshed";
  } catch (const TetCountLimitError& e) {
    EXPECT_NEAR(e.volume(), 0.1 * 0.2 * 0.3, 1e-12);  // OpenCASCADE's volume
    EXPECT_DOUBLE_EQ(e.expected(), expected_tet_count(0.006, 1e-5));
  }
  try {
    make_tet_mesh(data / "tet_box_with_groups.geo", options);
    FAIL() << "meshed";
  } catch (const TetCountLimitError& e) {
    EXPECT_NEAR(e.volume(), 0.2 * 0.1 * 0.1, 1e-7);  // the bounding box's volume (gmsh pads boxes by 1e-7 m)
  }
}

TEST(TetMeshing, ExpectedTetCountIsTheVolumeOverARegularTetrahedron) {
  EXPECT_DOUBLE_EQ(expected_tet_count(1.0, 1.0), 6.0 * std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(expected_tet_count(0.008, 0.1), 0.008 * 6.0 * std::sqrt(2.0) / 1e-3);
}

TEST(TetMeshing, GeoPhysicalGroupsBecomeNodeSets) {
  const TetMesh m = make_tet_mesh(data / "tet_box_with_groups.geo", with_h(0.05));
  expect_good_mesh(m);
  EXPECT_NEAR(tet_mesh_volume(m), 0.2 * 0.1 * 0.1, 1e-16);
  ASSERT_EQ(m.node_sets.size(), 2u);
  EXPECT_EQ(m.node_sets.at("body").size(), static_cast<size_t>(m.X.rows()));
  const auto& left = m.node_sets.at("left");
  EXPECT_GE(left.size(), 4u);
  int on_left_face = 0;
  for (Eigen::Index i = 0; i < m.X.rows(); ++i) on_left_face += std::abs(m.X(i, 0)) < 1e-12;
  EXPECT_EQ(static_cast<int>(left.size()), on_left_face);
  for (int i : left) EXPECT_LT(std::abs(m.X(i, 0)), 1e-12) << i;
}

TEST(TetMeshing, UnreadableFilesNameTheFile) {
  for (const char* name : {"missing.stl", "missing.step", "missing.geo", "missing.msh"}) {
    const auto file = data / name;
    try {
      make_tet_mesh(file, with_h(0.2));
      ADD_FAILURE() << name << ": no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(file.string() + ":", 0), 0u) << e.what();
    }
  }
  const auto garbage = std::filesystem::temp_directory_path() /
                       ("stiffsoft_tet_meshing_garbage_" + std::to_string(::getpid()) + ".step");
  std::ofstream(garbage) << "this is not a STEP file\n";
  try {
    make_tet_mesh(garbage, with_h(0.2));
    ADD_FAILURE() << "garbage step: no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), garbage.string() + ": not a STEP file (expected 'ISO-10303-21;' first)");
  }
  std::filesystem::remove(garbage);
  EXPECT_THROW(make_tet_mesh(data / "mesh.vtk", with_h(0.2)), std::invalid_argument);
}

}  // namespace
}  // namespace stiffsoft

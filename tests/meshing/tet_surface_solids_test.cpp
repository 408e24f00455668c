#include <stiffsoft/meshing/tet_surface_solids.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <stiffsoft/meshing/mass_moments.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>
#include <stiffsoft/meshing/primitive.hpp>
#include <stiffsoft/meshing/tet_boundary.hpp>
#include <stiffsoft/meshing/tet_meshing.hpp>
#include "tet_chord_bound.hpp"

namespace stiffsoft {
namespace {

SurfaceMesh sphere(double r) {
  PrimitiveShape s;
  s.type = PrimitiveShape::Type::Sphere;
  s.radius = r;
  s.resolution = 16;
  return make_primitive(s);
}

SurfaceMesh cube(double edge) {
  PrimitiveShape s;
  s.extents = Eigen::Vector3d::Constant(edge);
  return make_primitive(s);
}

/// a ∪ b as one surface, b moved by `shift` and turned inside out when `flip_b`
SurfaceMesh join(const SurfaceMesh& a, const SurfaceMesh& b, const Eigen::Vector3d& shift, bool flip_b) {
  SurfaceMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V.rowwise() + shift.transpose();
  Eigen::MatrixX3i Fb = b.F.array() + static_cast<int>(a.V.rows());
  if (flip_b) Fb.col(1).swap(Fb.col(2));
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, Fb;
  return m;
}

std::string error_of(const SurfaceMesh& m) {
  try {
    surface_solids(m, "body 'shells'");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no exception";
}

TEST(WindingNumber, IsOneInsideZeroOutsideMinusOneInsideOut) {
  const SurfaceMesh s = sphere(0.5);
  std::vector<int> all(static_cast<size_t>(s.F.rows()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  EXPECT_NEAR(winding_number(s, all, Eigen::Vector3d(0.1, -0.2, 0.05)), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(s, all, Eigen::Vector3d(0.7, 0.0, 0.0)), 0.0, 1e-12);
  const SurfaceMesh inside_out =
      join(SurfaceMesh{Eigen::MatrixX3d(0, 3), Eigen::MatrixX3i(0, 3)}, s, Eigen::Vector3d::Zero(), true);
  EXPECT_NEAR(winding_number(inside_out, all, Eigen::Vector3d::Zero()), -1.0, 1e-12);
}

TEST(SurfaceSolids, OneShellIsOneSolid) {
  const SurfaceSolids s = surface_solids(cube(1.0), "cube");
  ASSERT_EQ(s.shells.size(), 1u);
  EXPECT_EQ(s.shells[0].faces.size(), 12u);
  EXPECT_NEAR(s.shells[0].volume, 1.0, 1e-15);
  ASSERT_EQ(s.solids.size(), 1u);
  EXPECT_TRUE(s.solids[0].cavities.empty());
}

TEST(SurfaceSolids, HollowSphereWithABallInsideItsCavity) {
  // outer sphere r 1, cavity r 0.6, and a free ball r 0.3 inside the cavity: two solids.
  const SurfaceMesh m = join(join(sphere(1.0), sphere(0.6), Eigen::Vector3d::Zero(), true), sphere(0.3),
                             Eigen::Vector3d::Zero(), false);
  const SurfaceSolids s = surface_solids(m, "nested");
  ASSERT_EQ(s.shells.size(), 3u);
  EXPECT_GT(s.shells[0].volume, 0.0);
  EXPECT_LT(s.shells[1].volume, 0.0);
  EXPECT_GT(s.shells[2].volume, 0.0);
  ASSERT_EQ(s.solids.size(), 2u);
  EXPECT_EQ(s.solids[0].outer, 0);
  EXPECT_EQ(s.solids[0].cavities, std::vector<int>{1});
  EXPECT_EQ(s.solids[1].outer, 2);
  EXPECT_TRUE(s.solids[1].cavities.empty());
}

TEST(SurfaceSolids, NestedSolidsAndStrayCavitiesAreRejected) {
  const std::string nested = error_of(join(cube(1.0), cube(0.5), Eigen::Vector3d::Zero(), false));
  EXPECT_EQ(nested.rfind("body 'shells': shell 1 (from face 12", 0), 0u) << nested;
  EXPECT_NE(nested.find("lies inside the material of another shell"), std::string::npos) << nested;

  const std::string stray = error_of(join(cube(1.0), cube(0.5), Eigen::Vector3d(3, 0, 0), true));
  EXPECT_EQ(stray.rfind("body 'shells': shell 1 (from face 12", 0), 0u) << stray;
  EXPECT_NE(stray.find("faces inward (a cavity) but lies in no solid"), std::string::npos) << stray;
}

TEST(SurfaceSolids, HollowAndTwoPieceSurfacesMeshWithTheirCavities) {
  const double outer = 0.5, inner = 0.25;
  const SurfaceMesh hollow = join(sphere(outer), sphere(inner), Eigen::Vector3d::Zero(), true);
  ASSERT_FALSE(closed_manifold_problem(hollow).has_value());
  TetMeshOptions keep;
  keep.h = 0.15;
  keep.keep_surface = true;
  const TetMesh kept = make_tet_mesh(hollow, keep, "hollow");
  EXPECT_FALSE(tet_mesh_problem(kept).has_value());
  // The cavity stays empty: the tets fill exactly the input's enclosed volume.
  EXPECT_NEAR(tet_mesh_volume(kept), mass_moments(hollow).volume, 1e-14);
  EXPECT_EQ(boundary_surface(kept).surface.F.rows(), hollow.F.rows());

  TetMeshOptions remesh = keep;
  remesh.keep_surface = false;
  const TetMesh remeshed = make_tet_mesh(hollow, remesh, "hollow");
  EXPECT_FALSE(tet_mesh_problem(remeshed).has_value());
  const TetBoundary b = boundary_surface(remeshed);
  EXPECT_FALSE(closed_manifold_problem(b.surface).has_value());
  EXPECT_NEAR(mass_moments(b.surface).volume, tet_mesh_volume(remeshed), 1e-13);
  // The cavity's wall is boundary: a second shell, inward, around the cavity of the one solid.
  const SurfaceSolids parts = surface_solids(b.surface, "boundary");
  ASSERT_EQ(parts.shells.size(), 2u);
  ASSERT_EQ(parts.solids.size(), 1u);
  ASSERT_EQ(parts.solids[0].cavities.size(), 1u);
  const SurfaceShell& wall = parts.shells[static_cast<size_t>(parts.solids[0].cavities[0])];
  SurfaceMesh wall_mesh{b.surface.V, Eigen::MatrixX3i(static_cast<Eigen::Index>(wall.faces.size()), 3)};
  for (size_t i = 0; i < wall.faces.size(); ++i)
    wall_mesh.F.row(static_cast<Eigen::Index>(i)) = b.surface.F.row(wall.faces[i]);
  // Its volume against the exact cavity: as for the torus in tet_meshing_test, the input sphere's
  // chords count twice (its own deviation, and the remeshed nodes lying on it), the new ones once.
  const double exact_cavity = 4.0 / 3.0 * std::numbers::pi * inner * inner * inner;
  const double tolerance =
      chord_volume_bound(wall_mesh, 1.0 / inner) + 2.0 * chord_volume_bound(sphere(inner), 1.0 / inner);
  EXPECT_NEAR(-wall.volume, exact_cavity, tolerance);
  EXPECT_LT(tolerance, 0.5 * exact_cavity);

  const SurfaceMesh two = join(cube(0.3), cube(0.3), Eigen::Vector3d(1.0, 0.0, 0.0), false);
  for (bool keep_surface : {true, false}) {
    TetMeshOptions o = keep;
    o.keep_surface = keep_surface;
    const TetMesh m = make_tet_mesh(two, o, "two cubes");
    EXPECT_FALSE(tet_mesh_problem(m).has_value());
    EXPECT_NEAR(tet_mesh_volume(m), 2 * 0.027, 1e-15) << keep_surface;
  }
}

}  // namespace
}  // namespace stiffsoft

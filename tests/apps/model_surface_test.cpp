/// @file The surface points of affine bodies: Model::surface and Model::surface_step give, to the
/// bit, the numbers of Eigen's product of the rest positions by Aᵀ plus the translation, which they
/// compute without its temporary; fixed bodies' steps are zero.

#include <gtest/gtest.h>

#include <random>
#include <stiffsoft/libabd/affine_body.hpp>
#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

namespace stiffsoft {
namespace {

/// Turned boxes and a sphere over a fixed floor.
constexpr const char* kBodies = R"({
  "description": "surface test bodies",
  "time": {"dt": 0.01, "duration": 0.01},
  "contact": {"check_start_gaps": false},
  "bodies": [
    {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [2.0, 0.1, 2.0]}, "position": [0.0, -0.05, 0.0]},
    {"name": "a", "mesh": {"primitive": "box", "size": [0.3, 0.2, 0.4]}, "density": 1000.0,
     "position": [0.0, 0.3, 0.0], "rotation_deg": [0.0, 10.0, 0.0]},
    {"name": "b", "mesh": {"primitive": "sphere", "radius": 0.1, "resolution": 8}, "density": 1000.0,
     "position": [0.5, 0.5, 0.1]}
  ]
})";

/// Rows of body `body` as Eigen's expression gives them: (x̄ Aᵀ).rowwise() + pᵀ of q's block.
Eigen::MatrixX3d eigen_rows(const Model& model, const BodyModel& body, const abd::Vector12d& qb) {
  const int n = body.vertex_end - body.vertex_begin;
  return (model.mesh.x_bar.middleRows(body.vertex_begin, n) * abd::affine_matrix(qb).transpose()).rowwise() +
         abd::translation(qb).transpose();
}

TEST(ModelSurface, AffineBodiesPointsAreEigensProductsBitForBit) {
  const PreparedScene p = prepare_scene(
      load_scene_from_string(kBodies, STIFFSOFT_SOURCE_DIR, "bodies.json", "bodies"), "bodies.json");
  const Model& model = p.model;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd q = model.initial_q(), dq(q.size());
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    q(i) += 0.1 * unit(random);  // an affine map away from a rotation, with rounding in every entry
    dq(i) = 1e-3 * unit(random);
  }
  const Eigen::MatrixX3d x = model.surface(q), dx = model.surface_step(dq);
  int affine = 0;
  for (const BodyModel& body : model.bodies) {
    const int n = body.vertex_end - body.vertex_begin;
    if (body.dof < 0) {
      EXPECT_TRUE((dx.middleRows(body.vertex_begin, n).array() == 0.0).all()) << body.name;
      continue;
    }
    ++affine;
    EXPECT_TRUE((x.middleRows(body.vertex_begin, n).array() ==
                 eigen_rows(model, body, q.segment<12>(body.dof)).array())
                    .all())
        << body.name;
    EXPECT_TRUE((dx.middleRows(body.vertex_begin, n).array() ==
                 eigen_rows(model, body, dq.segment<12>(body.dof)).array())
                    .all())
        << body.name;
  }
  EXPECT_EQ(affine, 2);
}

}  // namespace
}  // namespace stiffsoft

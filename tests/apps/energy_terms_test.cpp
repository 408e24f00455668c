/// @file Whole-term derivative checks: every energy term Newton sees (inertia, orthogonality,
/// elasticity, contact barrier, friction, joint limits, damping), and their sum, on one small
/// mixed model with active contacts, built as Simulation::step builds them at a step's start.
/// For each: the value is finite, the gradient matches central differences of the value, the
/// exact (un-projected) Hessian matches central differences of the gradient, add_hessian is the
/// documented element-wise PSD projection of that exact Hessian, and the assembled sparse
/// matrix is symmetric PSD. The CCD-bounded max_step of the barrier and of the joint limits
/// never lets a step reach an intersection or cross a limit.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <type_traits>
#include <string>
#include <vector>

#include <stiffsoft/coupling/contact/constraint_set.hpp>
#include <stiffsoft/coupling/contact/friction.hpp>
#include <stiffsoft/coupling/joints/joint_measures.hpp>
#include <stiffsoft/coupling/model/block_islands.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>
#include <stiffsoft/coupling/solver/integrator.hpp>
#include <stiffsoft/coupling/terms/barrier_term.hpp>
#include <stiffsoft/coupling/terms/damping_term.hpp>
#include <stiffsoft/coupling/terms/elasticity_term.hpp>
#include <stiffsoft/coupling/terms/friction_term.hpp>
#include <stiffsoft/coupling/terms/inertia_term.hpp>
#include <stiffsoft/coupling/terms/joint_term.hpp>
#include <stiffsoft/coupling/terms/orthogonality_term.hpp>
#include <stiffsoft/libabd/orthogonality_potential.hpp>
#include <stiffsoft/libfem/elastic_energy.hpp>
#include <stiffsoft/libfem/make_material.hpp>
#include <stiffsoft/libfem/tet_element.hpp>
#include <stiffsoft/meshing/intersection.hpp>
#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

#include "finite_differences.hpp"

using namespace stiffsoft;
using stiffsoft::testing::fd_gradient;
using stiffsoft::testing::fd_jacobian;
using stiffsoft::testing::min_eigenvalue;
using stiffsoft::testing::relative_error;

namespace {

/// d̂ of the scene (m). The bodies start 2 d̂ apart (the loader wants more than d̂) and the
/// test moves them to 0.5 d̂ (contact_q), well inside the barrier's active range.
constexpr double kDhat = 0.01;

/// A fixed ground, a soft pad (coarse tets) lying on it and an affine block lying on the pad,
/// hinged to the world about the vertical through its centre with a rotation range whose upper
/// limit (0.03 rad) is closer than the limit's activation (0.05 rad), so the limit barrier is
/// active at the initial angle 0. Friction, contact damping and hinge damping are on. The
/// bodies are turned about y by different angles so that no edges are parallel and no vertex
/// sits on a Voronoi boundary of the primitive it faces (the Hessians jump there).
const char* kScene = R"({
  "description": "Energy-term test model: fixed ground, soft pad, affine block hinged to the world.",
  "time": {"dt": 0.01},
  "contact": {"dhat": 0.01, "mu": 0.4, "eps_v": 0.01, "damping": 0.05},
  "solver": {"linear": "cholmod"},
  "bodies": [
    {"name": "ground", "kind": "fixed", "mesh": {"primitive": "box", "size": [3.0, 0.2, 3.0]},
     "position": [0.0, -0.1, 0.0], "rotation_deg": [0.0, 7.0, 0.0]},
    {"name": "pad", "model": "soft", "mesh": {"primitive": "box", "size": [1.0, 0.4, 1.0]}, "mesh_size": 0.6,
     "material": {"young": 100000.0, "poisson": 0.3}, "density": 500.0,
     "position": [0.13, 0.22, -0.07], "rotation_deg": [0.0, 20.0, 0.0]},
    {"name": "block", "mesh": {"primitive": "box", "size": [0.6, 0.3, 0.6]}, "density": 1000.0,
     "position": [0.17, 0.59, -0.05], "rotation_deg": [0.0, 50.0, 0.0]}
  ],
  "joints": [
    {"name": "hinge", "kind": "hinge", "body_a": "block", "anchor": [0.17, 0.59, -0.05], "axis": [0.0, 1.0, 0.0],
     "lower": -0.5, "upper": 0.03, "damping": 2.0}
  ]
})";

/// The prepared scene, built once: meshing the pad is the slow part, and the terms only hold a
/// reference to the model.
const PreparedScene& prepared() {
  static const PreparedScene p =
      prepare_scene(load_scene_from_string(kScene, STIFFSOFT_SOURCE_DIR, "terms.json", "terms"), "terms.json");
  return p;
}

int body_index(const Model& model, const std::string& name) {
  for (int b = 0; b < int(model.bodies.size()); ++b)
    if (model.bodies[b].name == name) return b;
  throw std::runtime_error("no body " + name);
}

/// The DOFs with the contacts active: the pad lowered by 1.5 d̂ (0.5 d̂ above the ground), the
/// block by 3 d̂ (0.5 d̂ above the pad). This leaves the hinge's anchor equality (eliminated by
/// the reduced basis, not a term) but none of the terms checked here.
Eigen::VectorXd contact_q(const Model& model) {
  Eigen::VectorXd q = model.initial_q();
  const BodyModel& pad = model.bodies[body_index(model, "pad")];
  for (int i = pad.node_begin; i < pad.node_end; ++i)
    if (model.nodes.dof[i] >= 0) q[model.nodes.dof[i] + 1] -= 1.5 * kDhat;
  q[model.bodies[body_index(model, "block")].dof + 1] -= 3.0 * kDhat;
  return q;
}

/// q_n plus a random perturbation of 1e-4 (m, and dimensionless for A) in every DOF, plus a
/// slide of the block by (2, 0, 1)·1e-4 m: some friction stencils slide (‖u‖ > ε_v h = 1e-4 m),
/// others stick, and nothing sits at a symmetric point. All gaps stay near 0.5 d̂ = 5e-3 m.
Eigen::VectorXd perturbed(const Model& model, const Eigen::VectorXd& q_n) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q = q_n;
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] += 1e-4 * u(rng);
  q.segment<3>(model.bodies[body_index(model, "block")].dof) += Eigen::Vector3d(2e-4, 0.0, 1e-4);
  return q;
}

/// V max(Λ, 0) Vᵀ of the symmetric part of A: the test's own PSD projection.
Eigen::MatrixXd clamp_psd(const Eigen::MatrixXd& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()));
  return es.eigenvectors() * es.eigenvalues().cwiseMax(0.0).asDiagonal() * es.eigenvectors().transpose();
}

/// The full symmetric dense matrix of a BlockHessian, from its sparse upper triangle (the
/// matrix the linear solver gets).
Eigen::MatrixXd dense(const BlockHessian& H) {
  const Eigen::SparseMatrix<double> upper = H.upper();
  const Eigen::SparseMatrix<double> full = upper.selfadjointView<Eigen::Upper>();
  return Eigen::MatrixXd(full);
}

/// The dense matrix of BlockHessian::multiply (column i = H e_i), which reads the stored
/// blocks as they are, not through a compressed copy.
Eigen::MatrixXd dense_by_products(const BlockHessian& H, int n) {
  Eigen::MatrixXd M(n, n);
  for (int i = 0; i < n; ++i) M.col(i) = H.multiply(Eigen::VectorXd::Unit(n, i));
  return M;
}

/// The terms of one step, built at q_n exactly as Simulation does at the start of a step
/// (constructors as in Simulation's, then step(): q̃, barrier update, κ balancing, friction lag,
/// damping lag).
struct StepTerms {
  const Model& model;
  const SimulationSettings& s;
  const double beta = integrator_beta(s.integrator);
  const double beta_h2 = beta * s.h * s.h;
  InertiaTerm inertia{model, s.kinematic_weight};
  OrthogonalityTerm orthogonality{model, beta_h2};
  ElasticityTerm elasticity{model, beta_h2};
  BarrierTerm barrier;
  std::optional<FrictionTerm> friction;
  JointTerm joints{model, beta_h2};
  DampingTerm damping{model};
  Eigen::VectorXd q_n;
  Eigen::MatrixX3d x_n;
  std::vector<ContactConstraint> lagged;  ///< the barrier's contacts at q_n (friction's stencils)
  double kappa_lagged = 0;                ///< κ when friction was lagged

  StepTerms(const Model& m, const SimulationSettings& settings, const Eigen::VectorXd& q)
      : model(m), s(settings), barrier(m, barrier_settings(m, settings), nullptr), q_n(q), x_n(m.surface(q)) {
    if (s.mu > 0) friction.emplace(model, s.mu, s.eps_v * s.h);
    // q̃ of backward Euler from rest: qⁿ + h² g on the dynamic DOFs.
    Eigen::VectorXd gravity_q = Eigen::VectorXd::Zero(model.num_dofs);
    for (const BodyModel& body : model.bodies)
      if (body.dof >= 0 && body.motion == Motion::Dynamic) gravity_q.segment<3>(body.dof) = s.gravity;
    for (int i = 0; i < model.nodes.size(); ++i)
      if (model.nodes.motion[i] == Motion::Dynamic) gravity_q.segment<3>(model.nodes.dof[i]) = s.gravity;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.num_dofs);
    inertia.set_target(predicted_q(s.integrator, s.h, q_n, zero, q_n, zero, gravity_q));
    const Configuration c_n{q_n, x_n};
    barrier.update(c_n);
    Eigen::VectorXd grad_other = Eigen::VectorXd::Zero(model.num_dofs);
    inertia.add_gradient(c_n, grad_other);
    orthogonality.add_gradient(c_n, grad_other);
    elasticity.add_gradient(c_n, grad_other);
    barrier.initialize_stiffness(c_n, grad_other);
    if (friction) friction->lag(c_n, barrier);
    damping.start_step(q_n, beta * s.h);
    damping.lag_contact(c_n, barrier, s.contact_damping, s.contact_pair_damping, beta_h2);
    damping.lag_joints();
    lagged = barrier.constraints();
    kappa_lagged = barrier.kappa();
  }

  /// The term called `name`, or all of them for "sum".
  std::vector<EnergyTerm*> terms(const std::string& name) {
    std::map<std::string, EnergyTerm*> by_name{{"inertia", &inertia},   {"orthogonality", &orthogonality},
                                               {"elasticity", &elasticity}, {"barrier", &barrier},
                                               {"friction", &*friction}, {"joints", &joints},
                                               {"damping", &damping}};
    if (name != "sum") return {by_name.at(name)};
    std::vector<EnergyTerm*> all;
    for (const auto& [n, t] : by_name) all.push_back(t);
    return all;
  }

  /// Σ value after update() at q, as Newton evaluates a trial point.
  double value(const std::vector<EnergyTerm*>& ts, const Eigen::VectorXd& q) const {
    const Eigen::MatrixX3d x = model.surface(q);
    double e = 0;
    for (EnergyTerm* t : ts) t->update({q, x});
    for (EnergyTerm* t : ts) e += t->value({q, x});
    return e;
  }

  /// Σ gradient after update() at q.
  Eigen::VectorXd gradient(const std::vector<EnergyTerm*>& ts, const Eigen::VectorXd& q) const {
    const Eigen::MatrixX3d x = model.surface(q);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
    for (EnergyTerm* t : ts) t->update({q, x});
    for (EnergyTerm* t : ts) t->add_gradient({q, x}, g);
    return g;
  }

  /// Σ add_hessian after update() at q, as the BlockHessian Newton assembles.
  BlockHessian hessian(const std::vector<EnergyTerm*>& ts, const Eigen::VectorXd& q) const {
    const Eigen::MatrixX3d x = model.surface(q);
    BlockHessian H(model.blocks);
    for (EnergyTerm* t : ts) t->update({q, x});
    for (EnergyTerm* t : ts) t->add_hessian({q, x}, H);
    return H;
  }

  /// The exact Hessian of a term and its element-wise PSD projection, assembled by the test
  /// from the library's un-projected element Hessians, each projected where the term documents
  /// it projects: the 12×12 stencil (barrier, friction, orthogonality), the joint potential's
  /// y-space Hessian (joints), ∂P/∂F (elasticity). Inertia and damping are quadratics with
  /// constant PSD Hessians: their add_hessian is both.
  struct Reference {
    Eigen::MatrixXd exact, projected;
  };
  Reference reference(const std::string& name, const Eigen::VectorXd& q) {
    if (name == "sum") {
      Reference sum{Eigen::MatrixXd::Zero(q.size(), q.size()), Eigen::MatrixXd::Zero(q.size(), q.size())};
      for (const char* n : {"inertia", "orthogonality", "elasticity", "barrier", "friction", "joints", "damping"}) {
        const Reference r = reference(n, q);
        sum.exact += r.exact;
        sum.projected += r.projected;
      }
      return sum;
    }
    const Eigen::MatrixX3d x = model.surface(q);
    const Configuration c{q, x};
    for (EnergyTerm* t : terms(name)) t->update(c);
    BlockHessian exact(model.blocks), projected(model.blocks);
    if (name == "inertia" || name == "damping") {
      for (EnergyTerm* t : terms(name)) t->add_hessian(c, exact);
      return {dense(exact), dense(exact)};
    }
    if (name == "orthogonality") {
      for (const BodyModel& body : model.bodies) {
        if (body.representation != Representation::Affine || body.motion != Motion::Dynamic) continue;
        const abd::Matrix12d H = abd::orthogonality_potential_hessian(q.segment<12>(body.dof),
                                                                      beta_h2 * body.kappa * body.volume, 1.0, false);
        exact.add(body.block, body.block, H);
        projected.add(body.block, body.block, clamp_psd(H));
      }
    } else if (name == "barrier") {
      for (const ContactConstraint& k : barrier.constraints()) {
        const contact::Matrix12d H = barrier.kappa() * k.weight *
                                     contact::barrier_potential_hessian(k.stencil, gather(x, k.vertices), s.dhat, false);
        const StencilJacobian J(model, k.vertices);
        J.scatter_hessian(H, exact);
        J.scatter_hessian(contact::Matrix12d(clamp_psd(H)), projected);
      }
    } else if (name == "friction") {
      for (const ContactConstraint& k : lagged) {
        const contact::FrictionStencil f =
            contact::make_friction_stencil(k.stencil, gather(x_n, k.vertices), s.dhat, kappa_lagged * k.weight);
        const contact::Vector12d dx = gather(x, k.vertices) - gather(x_n, k.vertices);
        const contact::Matrix12d H = contact::friction_potential_hessian(f, dx, s.mu, s.eps_v * s.h, false);
        const StencilJacobian J(model, k.vertices);
        J.scatter_hessian(H, exact);
        J.scatter_hessian(contact::Matrix12d(clamp_psd(H)), projected);
      }
    } else if (name == "joints") {
      for (const auto& [p, v] : joints.potentials()) {
        const Eigen::VectorXd y = v.gather(q);
        if (p.inactive(measure(p.measure, y))) continue;
        const MeasureValue m = measure_derivatives(p.measure, y);
        const Eigen::MatrixXd H_y = p.second_derivative(m.s) * m.grad * m.grad.transpose() + p.first_derivative(m.s) * m.hess;
        v.scatter_hessian(beta_h2 * H_y, exact);
        v.scatter_hessian(beta_h2 * clamp_psd(H_y), projected);
      }
    } else if (name == "elasticity") {
      for (const BodyModel& body : model.bodies) {
        if (body.representation != Representation::Soft) continue;
        const int n = body.node_end - body.node_begin;
        const Eigen::MatrixX4i T =
            model.nodes.T.middleRows(body.tet_begin, body.tet_end - body.tet_begin).array() - body.node_begin;
        const fem::ElasticEnergy energy(model.nodes.X.middleRows(body.node_begin, n), T,
                                        fem::make_material(body.material.model, body.material.young,
                                                           body.material.poisson));
        Eigen::VectorXd xb(3 * n);
        for (int i = 0; i < n; ++i) {
          const int node = body.node_begin + i;
          xb.segment<3>(3 * i) = model.nodes.dof[node] < 0 ? Eigen::Vector3d(model.nodes.X.row(node).transpose())
                                                           : Eigen::Vector3d(q.segment<3>(model.nodes.dof[node]));
        }
        for (int e = 0; e < energy.num_elements(); ++e) {
          const fem::TetElement& te = energy.element(e);
          const fem::Matrix9x12d dFdx = fem::deformation_gradient_jacobian(te);
          const fem::Matrix9d dPdF = energy.material().dPdF(fem::deformation_gradient(te, energy.element_positions(e, xb)));
          const fem::Matrix12d H = beta_h2 * te.volume * dFdx.transpose() * dPdF * dFdx;
          const fem::Matrix12d H_proj = beta_h2 * te.volume * dFdx.transpose() * clamp_psd(dPdF) * dFdx;
          for (int a = 0; a < 4; ++a) {
            const int block_a = model.nodes.block[body.node_begin + energy.tets()(e, a)];
            if (block_a < 0) continue;
            for (int b = 0; b < 4; ++b) {
              const int block_b = model.nodes.block[body.node_begin + energy.tets()(e, b)];
              if (block_b < block_a) continue;  // each unordered pair once (add() keeps the upper triangle)
              exact.add(block_a, block_b, H.block<3, 3>(3 * a, 3 * b));
              projected.add(block_a, block_b, H_proj.block<3, 3>(3 * a, 3 * b));
            }
          }
        }
      }
    }
    return {dense(exact), dense(projected)};
  }
};

/// The model, the contact configuration q_n the terms are lagged at, and the perturbed q the
/// derivatives are checked at.
struct Fixture {
  /// The scene's settings with Newton's barrier Hessian made by `method` (the checks above
  /// are of the projected form; GaussNewtonBarrier checks the other).
  explicit Fixture(contact::BarrierHessian method = contact::BarrierHessian::Projected)
      : settings(with_barrier_hessian(method)) {}
  /// The prepared scene's settings with `method` (set before `step` is built from them).
  static SimulationSettings with_barrier_hessian(contact::BarrierHessian method) {
    SimulationSettings s = prepared().settings;
    s.barrier_hessian = method;
    return s;
  }
  const Model& model = prepared().model;
  SimulationSettings settings;
  Eigen::VectorXd q_n = contact_q(model);
  Eigen::VectorXd q = perturbed(model, q_n);
  StepTerms step{model, settings, q_n};
};

// Central differences: with step δ the truncation error is O((δ/ℓ)²) relative, ℓ the shortest
// length over which a term's derivatives change, and the round-off O(ε_mach E/(δ ‖∇E‖)).
// ℓ is the 5e-3 m contact gap for the barrier and ≥ 0.1 m for the bodies' own terms: δ = 1e-6
// (m for positions and translations, dimensionless for A). Friction changes over
// ε_v h = 1e-4 m (its smoothing of static friction): its error is (δ/3e-4)², measured, so it
// takes δ = 1e-8. The sum holds both: δ = 3e-8, where friction's truncation and the
// elasticity's round-off are both ≈ 1e-9.
double fd_step(const std::string& term) {
  if (term == "friction") return 1e-8;
  if (term == "sum") return 3e-8;
  return 1e-6;
}
// Gradients and Hessians against differences: the largest relative error observed with these
// steps is 1.6e-8 (elasticity's gradient; every Hessian ≤ 1.1e-8), so 1e-6 leaves a margin of
// 60 or more, while a wrong sign, a missing factor or a dropped element changes the relative
// error by the share of the wrong piece: even the exact Hessian's PSD projection, which changes
// it by 2e-5 (orthogonality) to 1e-2 (joints) here, would fail.
constexpr double kGradientTolerance = 1e-6;
constexpr double kHessianTolerance = 1e-6;
// Identities that hold up to round-off only (the same element matrices summed in another order,
// another eigen-solver): observed ≤ 1e-15 relative; 1e-10 leaves room for other compilers.
constexpr double kRoundOff = 1e-10;

const std::vector<std::string> kTerms{"inertia", "orthogonality", "elasticity", "barrier", "friction",
                                      "joints",  "damping",       "sum"};

class WholeTerm : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST(EnergyTermsModel, HasEveryTermActiveAnAffineSoftContactAndBothFrictionRegimes) {
  Fixture f;
  const Model& model = f.model;
  const int ground = body_index(model, "ground"), pad = body_index(model, "pad"), block = body_index(model, "block");
  EXPECT_EQ(model.bodies[pad].representation, Representation::Soft);
  EXPECT_EQ(model.bodies[block].representation, Representation::Affine);
  EXPECT_EQ(model.bodies[ground].motion, Motion::Fixed);
  EXPECT_FALSE(f.step.orthogonality.empty());
  EXPECT_FALSE(f.step.elasticity.empty());
  EXPECT_FALSE(f.step.joints.empty());
  EXPECT_FALSE(f.step.damping.empty());
  ASSERT_TRUE(f.step.friction);
  EXPECT_GT(f.step.friction->size(), 0u);
  // Contacts of every pair of bodies that touch: block–pad (the stencil Jacobian mixes 12-wide
  // affine and 3-wide node blocks) and pad–ground (a fixed body's vertices drop out).
  bool block_pad = false, pad_ground = false;
  for (const ContactConstraint& k : f.step.lagged) {
    std::vector<int> bodies;
    for (const int v : k.vertices)
      if (v >= 0) bodies.push_back(model.mesh.vertex_body[v]);
    const auto has = [&](int b) { return std::find(bodies.begin(), bodies.end(), b) != bodies.end(); };
    block_pad |= has(block) && has(pad);
    pad_ground |= has(pad) && has(ground);
  }
  EXPECT_TRUE(block_pad);
  EXPECT_TRUE(pad_ground);
  // The hinge's upper limit barrier is active (gap 0.03 rad < activation 0.05 rad).
  bool limit_active = false;
  for (const auto& [p, v] : f.step.joints.potentials()) limit_active |= !p.inactive(measure(p.measure, v.gather(f.q)));
  EXPECT_TRUE(limit_active);
  const Eigen::MatrixX3d x = model.surface(f.q);
  // Friction in both regimes: some stencils slide (‖u‖ ≥ ε_v h), some stick.
  int sliding = 0, sticking = 0;
  for (const ContactConstraint& k : f.step.lagged) {
    const contact::FrictionStencil s = contact::make_friction_stencil(k.stencil, gather(f.step.x_n, k.vertices), kDhat,
                                                                      f.step.kappa_lagged * k.weight);
    if (s.normal_force <= 0) continue;
    const double u = (contact::tangent_operator(s) * (gather(x, k.vertices) - gather(f.step.x_n, k.vertices))).norm();
    (u >= f.settings.eps_v * f.settings.h ? sliding : sticking) += 1;
  }
  EXPECT_GT(sliding, 0);
  EXPECT_GT(sticking, 0);
  std::cout << f.step.lagged.size() << " contacts, " << sliding << " sliding, " << sticking << " sticking, "
            << model.num_dofs << " DOFs\n";
  f.step.barrier.update({f.q, x});
  EXPECT_LT(f.step.barrier.min_active_distance({f.q, x}), 0.6 * kDhat);
  EXPECT_GT(f.step.barrier.min_active_distance({f.q, x}), 0.4 * kDhat);
}

TEST_P(WholeTerm, ValueAndGradientAreFiniteAndTheGradientMatchesFiniteDifferences) {
  Fixture f;
  const std::vector<EnergyTerm*> terms = f.step.terms(GetParam());
  const double e = f.step.value(terms, f.q);
  const Eigen::VectorXd g = f.step.gradient(terms, f.q);
  ASSERT_TRUE(std::isfinite(e));
  ASSERT_TRUE(g.allFinite());
  ASSERT_GT(g.norm(), 0.0) << "a zero gradient would make the check vacuous";
  const Eigen::VectorXd g_fd = fd_gradient([&](const Eigen::VectorXd& y) { return f.step.value(terms, y); }, f.q, fd_step(GetParam()));
  EXPECT_LT(relative_error(g, g_fd), kGradientTolerance) << "‖g‖ = " << g.norm();
}

TEST_P(WholeTerm, ExactHessianMatchesFiniteDifferencesOfTheGradient) {
  Fixture f;
  const std::vector<EnergyTerm*> terms = f.step.terms(GetParam());
  const Eigen::MatrixXd H = f.step.reference(GetParam(), f.q).exact;
  ASSERT_TRUE(H.allFinite());
  ASSERT_GT(H.norm(), 0.0);
  const Eigen::MatrixXd H_fd =
      fd_jacobian([&](const Eigen::VectorXd& y) { return f.step.gradient(terms, y); }, f.q, fd_step(GetParam()));
  EXPECT_LT(relative_error(H, H_fd), kHessianTolerance) << "‖H‖ = " << H.norm();
}

TEST_P(WholeTerm, HessianIsTheElementwisePsdProjectionOfTheExactHessian) {
  Fixture f;
  const std::vector<EnergyTerm*> terms = f.step.terms(GetParam());
  const StepTerms::Reference r = f.step.reference(GetParam(), f.q);
  const Eigen::MatrixXd H = dense(f.step.hessian(terms, f.q));
  EXPECT_LT(relative_error(H, r.projected), kRoundOff);
  // Projecting an element only adds curvature: H − H_exact = Σ Gᵀ (P(A) − A) G ⪰ 0.
  const Eigen::MatrixXd added = H - r.exact;
  EXPECT_GE(min_eigenvalue(added), -kRoundOff * H.norm());
  // Convex terms (quadratics with PSD matrices; friction, whose 2×2 core is PSD for every
  // tangential displacement) are not changed by the projection: there add_hessian is the
  // exact Hessian, and so matches the differences directly.
  if (GetParam() == "inertia" || GetParam() == "damping" || GetParam() == "friction")
    EXPECT_LT(relative_error(H, r.exact), kRoundOff);
  std::cout << "[ " << GetParam() << " ] projection changed the Hessian by ‖H − H_exact‖/‖H_exact‖ = "
            << relative_error(H, r.exact) << "\n";
}

TEST(GaussNewtonBarrier, HessianIsTheSumOfTheStencilFormsAndPsd) {
  // solver.barrier_hessian = gauss_newton: each stencil's κ w c(d²) ∇d² ∇d²ᵀ (mollified
  // stencils projected as before), mapped to q; the value and gradient are unchanged.
  Fixture f(contact::BarrierHessian::GaussNewton);
  Fixture projected;
  const std::vector<EnergyTerm*> terms = f.step.terms("barrier");
  const Eigen::MatrixX3d x = f.model.surface(f.q);
  BlockHessian expected(f.model.blocks);
  int gauss_newton_stencils = 0;
  for (const ContactConstraint& k : f.step.barrier.constraints()) {
    const contact::Vector12d xs = gather(x, k.vertices);
    const bool gauss_newton = !contact::mollifier_active(k.stencil, xs);
    const contact::Matrix12d H = gauss_newton ? contact::barrier_gauss_newton_hessian(k.stencil, xs, f.settings.dhat)
                                              : contact::barrier_potential_hessian(k.stencil, xs, f.settings.dhat, true);
    gauss_newton_stencils += gauss_newton;
    StencilJacobian(f.model, k.vertices).scatter_hessian(contact::Matrix12d(f.step.barrier.kappa() * k.weight * H), expected);
  }
  const int stencils = int(f.step.barrier.constraints().size());
  std::cout << "[ barrier ] " << stencils << " stencils, " << stencils - gauss_newton_stencils << " mollified, "
            << gauss_newton_stencils << " in the Gauss–Newton form\n";
  ASSERT_GT(gauss_newton_stencils, 0) << "the check would not see the Gauss–Newton form";
  const Eigen::MatrixXd H = dense(f.step.hessian(terms, f.q));
  ASSERT_GT(H.norm(), 0.0);
  EXPECT_LT(relative_error(H, dense(expected)), kRoundOff);
  EXPECT_LT(relative_error(H, H.transpose()), kRoundOff);
  EXPECT_GE(min_eigenvalue(H), -kRoundOff * H.norm());
  EXPECT_GT(relative_error(H, dense(projected.step.hessian(projected.step.terms("barrier"), projected.q))), 1e-3)
      << "the Gauss–Newton form should differ from the projected one";
  EXPECT_EQ(f.step.value(terms, f.q), projected.step.value(projected.step.terms("barrier"), projected.q));
  EXPECT_EQ(f.step.gradient(terms, f.q), projected.step.gradient(projected.step.terms("barrier"), projected.q));
}

TEST(StencilJacobian, LowRankBlocksEqualTheBlocksOfTheFormedHessian) {
  // The rank-R path, (B J)ᵀ C (B J) (friction's R = 2, the barrier's projection up to 5),
  // against Jᵀ (Bᵀ C B) J on every lagged stencil of the model (affine–soft, soft–fixed and
  // affine-only slots), with random B and symmetric C.
  Fixture f;
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  int stencils = 0;
  const auto check = [&](auto rank, const ContactConstraint& k) {
    constexpr int R = decltype(rank)::value;
    Eigen::Matrix<double, R, 12> B;
    for (Eigen::Index i = 0; i < B.size(); ++i) B.data()[i] = normal(rng);
    Eigen::Matrix<double, R, R> C;
    for (Eigen::Index i = 0; i < C.size(); ++i) C.data()[i] = normal(rng);
    C = (C + C.transpose()).eval();
    const StencilJacobian J(f.model, k.vertices);
    StencilHessian low_rank, formed;
    J.low_rank_block_hessians(B, C, low_rank);
    J.block_hessians(contact::Matrix12d(B.transpose() * C * B), formed);
    ASSERT_EQ(low_rank.count, formed.count);
    for (int b = 0; b < formed.count; ++b) {
      EXPECT_EQ(low_rank.row[b], formed.row[b]);
      EXPECT_EQ(low_rank.column[b], formed.column[b]);
      const int rows = f.model.blocks[formed.row[b]].size, columns = f.model.blocks[formed.column[b]].size;
      const Eigen::Map<const Eigen::MatrixXd> a(low_rank.values.data() + low_rank.at[b], rows, columns),
          e(formed.values.data() + formed.at[b], rows, columns);
      // A diagonal block counts by its upper triangle: its other entries are not read (nor set).
      Eigen::MatrixXd difference = Eigen::MatrixXd::Zero(rows, columns), expected = difference;
      if (formed.row[b] == formed.column[b]) {
        difference.triangularView<Eigen::Upper>() = a - e;
        expected.triangularView<Eigen::Upper>() = e;
      } else {
        difference = a - e;
        expected = e;
      }
      EXPECT_LT(difference.norm(), 1e-12 * std::max(1.0, expected.norm()))
          << "rank " << R << ", stencil " << stencils << ", block " << b;
    }
  };
  for (const ContactConstraint& k : f.step.lagged) {
    check(std::integral_constant<int, 1>{}, k);
    check(std::integral_constant<int, 2>{}, k);
    check(std::integral_constant<int, 3>{}, k);
    check(std::integral_constant<int, 5>{}, k);
    ++stencils;
  }
  EXPECT_GT(stencils, 0);
}

TEST_P(WholeTerm, AssembledHessianIsSymmetricPositiveSemiDefinite) {
  Fixture f;
  const std::vector<EnergyTerm*> terms = f.step.terms(GetParam());
  const BlockHessian H = f.step.hessian(terms, f.q);
  const Eigen::MatrixXd full = dense(H);
  const Eigen::MatrixXd products = dense_by_products(H, f.model.num_dofs);
  ASSERT_TRUE(full.allFinite());
  // H e_i reproduces the matrix the solver gets from the compressed upper triangle.
  EXPECT_LT(relative_error(products, full), kRoundOff);
  EXPECT_LT((products - products.transpose()).norm(), kRoundOff * products.norm());
  // PSD up to the eigen-solver's backward error (n ε ‖H‖ ≈ 1e-13 ‖H‖ here).
  EXPECT_GE(min_eigenvalue(full), -kRoundOff * full.norm());
}

TEST(EnergyTermsFriction, ReversedSlidesGetTheMajorizerInTheRevisedHessian) {
  Fixture f;
  const FrictionTerm& friction = *f.step.friction;
  const Eigen::VectorXd& q = f.q;
  const Eigen::MatrixX3d x = f.model.surface(q);
  const Configuration c{q, x};
  f.step.friction->update(c);
  BlockHessian H(f.model.blocks);
  friction.add_hessian(c, H);
  const Eigen::MatrixXd exact = dense(H);
  // A step onward reverses no slide and leaves H alone; one that carries q back past q_n
  // reverses every slide, and the sliding stencils gain the majorizer's curvature (only).
  const Eigen::VectorXd onward = 0.5 * (q - f.step.q_n), back = -2.0 * (q - f.step.q_n);
  EXPECT_FALSE(friction.revise_hessian(c, onward, f.model.surface_step(onward), H));
  EXPECT_LT(relative_error(dense(H), exact), kRoundOff);
  ASSERT_TRUE(friction.revise_hessian(c, back, f.model.surface_step(back), H));
  const Eigen::MatrixXd revised = dense(H);
  EXPECT_GT(relative_error(revised, exact), 1e-3);
  EXPECT_GE(min_eigenvalue(Eigen::MatrixXd(revised - exact)), -kRoundOff * revised.norm());
}

// solver.release_hessian: a direction that takes an active contact 35–65 % of the rest of its
// way out of d̂ (Newton on the barrier's cubic tail takes an unloaded one half-way) releases it,
// and the revised H holds release_hessian (0.6) of that contact's Hessian. Every gap is near
// 0.5 d̂: lifting the block by a quarter of d̂ takes the block–pad contacts half of their way out;
// lifting pad and block together the pad–ground ones. The two revisions together take
// 1 − release_hessian of the whole barrier Hessian off.
TEST(EnergyTermsBarrier, ReleasedContactsKeepReleaseHessianOfTheirHessian) {
  Fixture f;
  const BarrierTerm& barrier = f.step.barrier;
  const Eigen::MatrixX3d x = f.model.surface(f.q);
  const Configuration c{f.q, x};
  f.step.barrier.update(c);
  const auto assembled = [&] {
    BlockHessian H(f.model.blocks);
    barrier.add_hessian(c, H);
    return H;
  };
  const Eigen::MatrixXd exact = dense(assembled());
  // dq lifting the named bodies by δ (m).
  const auto lift = [&](const std::vector<std::string>& names, double delta) {
    Eigen::VectorXd dq = Eigen::VectorXd::Zero(f.model.num_dofs);
    for (const std::string& name : names) {
      const BodyModel& body = f.model.bodies[body_index(f.model, name)];
      if (body.dof >= 0) dq[body.dof + 1] = delta;
      for (int i = body.node_begin; i < body.node_end; ++i)
        if (f.model.nodes.dof[i] >= 0) dq[f.model.nodes.dof[i] + 1] = delta;
    }
    return dq;
  };
  // The change the revision makes to H along dq, or nothing if it releases no contact.
  const auto revision = [&](const Eigen::VectorXd& dq) -> std::optional<Eigen::MatrixXd> {
    BlockHessian H = assembled();
    if (!barrier.revise_hessian(c, dq, f.model.surface_step(dq), H)) return std::nullopt;
    return dense(H) - exact;
  };
  const double half_way = 0.25 * kDhat;
  EXPECT_FALSE(revision(lift({"block"}, 0.2 * half_way)));  // a tenth of the way out
  EXPECT_FALSE(revision(lift({"block"}, 2.5 * half_way)));  // past d̂
  const std::optional<Eigen::MatrixXd> block = revision(lift({"block"}, half_way));
  const std::optional<Eigen::MatrixXd> both = revision(lift({"pad", "block"}, half_way));
  ASSERT_TRUE(block && both);
  EXPECT_GT(block->norm(), 0.05 * exact.norm());
  EXPECT_GT(both->norm(), 0.05 * exact.norm());
  EXPECT_LT(relative_error(Eigen::MatrixXd(*block + *both), (f.settings.release_hessian - 1) * exact), kRoundOff);
  // With release_hessian 1 nothing is revised.
  SimulationSettings off = f.settings;
  off.release_hessian = 1;
  BarrierTerm unreleased(f.model, barrier_settings(f.model, off), nullptr);
  unreleased.update(c);
  BlockHessian H(f.model.blocks);
  const Eigen::VectorXd dq = lift({"block"}, half_way);
  EXPECT_FALSE(unreleased.revise_hessian(c, dq, f.model.surface_step(dq), H));
}

// value() and add_gradient() at the contacts' own surface take each stencil's d² from the
// build's squared_distances(), which revise_hessian() and the stopping rule also fill: they must
// be the energy and gradient of the surface asked for, whichever build the term returns to.
TEST(EnergyTermsBarrier, ValueAndGradientAreTheStencilSumsAfterEveryBuild) {
  Fixture f;
  BarrierTerm& barrier = f.step.barrier;
  const auto check = [&](const Configuration& c) {
    barrier.update(c);
    double sum = 0;
    Eigen::VectorXd sum_gradient = Eigen::VectorXd::Zero(f.model.num_dofs);
    for (const ContactConstraint& k : barrier.constraints()) {
      const contact::Vector12d x = gather(c.x, k.vertices);
      sum += barrier.kappa() * k.weight * contact::barrier_potential(k.stencil, x, barrier.dhat());
      StencilJacobian(f.model, k.vertices)
          .scatter_gradient(barrier.kappa() * k.weight * contact::barrier_potential_gradient(k.stencil, x, barrier.dhat()),
                            sum_gradient);
    }
    ASSERT_GT(sum, 0);
    EXPECT_NEAR(barrier.value(c), sum, kRoundOff * sum);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(f.model.num_dofs);
    barrier.add_gradient(c, g);
    EXPECT_LT(relative_error(g, sum_gradient), kRoundOff);
  };
  const Configuration c{f.q, f.model.surface(f.q)};
  const Eigen::VectorXd dq = 0.1 * (f.q - f.q_n);
  const Eigen::VectorXd q_moved = f.q + dq;
  const Configuration moved{q_moved, f.model.surface(q_moved)};
  check(c);
  // The distances at c and at its move, as a revision and the stopping rule ask for them.
  BlockHessian H(f.model.blocks);
  barrier.add_hessian(c, H);
  barrier.revise_hessian(c, dq, f.model.surface_step(dq), H);
  check(moved);  // a new build
  check(c);      // c's build again, kept
  check(moved);
}

// A stencil once revised keeps its majorizer until friction is lagged again: the next Hessian
// assembled is the revised one, and the same step's reversal revises nothing more.
TEST(EnergyTermsFriction, RevisedStencilsKeepTheMajorizerUntilTheNextLag) {
  Fixture f;
  FrictionTerm& friction = *f.step.friction;
  const Eigen::VectorXd& q = f.q;
  const Eigen::MatrixX3d x = f.model.surface(q);
  const Configuration c{q, x};
  friction.update(c);
  const auto assembled = [&] {
    BlockHessian H(f.model.blocks);
    friction.add_hessian(c, H);
    return H;
  };
  BlockHessian H = assembled();
  const Eigen::MatrixXd exact = dense(H);
  const Eigen::VectorXd back = -2.0 * (q - f.step.q_n);
  ASSERT_TRUE(friction.revise_hessian(c, back, f.model.surface_step(back), H));
  const Eigen::MatrixXd revised = dense(H);
  BlockHessian again = assembled();
  EXPECT_LT(relative_error(dense(again), revised), kRoundOff);
  EXPECT_FALSE(friction.revise_hessian(c, back, f.model.surface_step(back), again));
  // Lagged again (here at the step's start, so the same stencils): every stencil exact again.
  friction.relag({f.step.q_n, f.step.x_n}, f.step.barrier);
  EXPECT_LT(relative_error(dense(assembled()), exact), kRoundOff);
  EXPECT_GT(relative_error(revised, exact), 1e-3);
}

// The normal forces friction_lag_error asks for at a step's result keep their stencils for the
// next step's lag there: that lag must equal a fresh one, and a lag elsewhere or with another κ
// must not take them.
TEST(EnergyTermsFriction, LagAfterTheNormalForcesAtTheSamePointEqualsAFreshLag) {
  Fixture f;
  BarrierTerm& barrier = f.step.barrier;
  const double epsv_h = f.settings.eps_v * f.settings.h;
  const Eigen::MatrixX3d x = f.model.surface(f.q);
  const Configuration c{f.q, x}, c_n{f.step.q_n, f.step.x_n};
  // Friction's value and gradient at a third point, after a lag at `at` (the barrier there).
  const auto lagged = [&](FrictionTerm& friction, const Configuration& at) {
    barrier.update(at);
    friction.lag(at, barrier);
    const Eigen::VectorXd q2 = f.q + 0.5 * (f.q - f.step.q_n);
    const Eigen::MatrixX3d x2 = f.model.surface(q2);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(q2.size());
    friction.add_gradient({q2, x2}, g);
    return std::make_pair(friction.value({q2, x2}), g);
  };
  const auto forces_at = [&](FrictionTerm& friction, const Configuration& at) {
    barrier.update(at);
    return friction.normal_force_per_body(at, barrier);
  };
  FrictionTerm fresh(f.model, f.settings.mu, epsv_h), made(f.model, f.settings.mu, epsv_h);
  const auto fresh_lag = lagged(fresh, c);
  EXPECT_EQ(forces_at(made, c), fresh.normal_force_per_body());
  const auto made_lag = lagged(made, c);
  EXPECT_EQ(made_lag.first, fresh_lag.first);
  EXPECT_EQ(made_lag.second, fresh_lag.second);
  EXPECT_GT(fresh_lag.first, 0.0);
  // Made at c, lagged at the step's start: the stencils of c_n.
  FrictionTerm elsewhere(f.model, f.settings.mu, epsv_h), fresh_n(f.model, f.settings.mu, epsv_h);
  forces_at(elsewhere, c);
  EXPECT_EQ(lagged(elsewhere, c_n), lagged(fresh_n, c_n));
  EXPECT_NE(lagged(fresh_n, c_n).first, fresh_lag.first);
  // Made with κ, lagged with 2 κ at the same point: the normal forces of 2 κ.
  FrictionTerm stiffer(f.model, f.settings.mu, epsv_h), fresh_stiffer(f.model, f.settings.mu, epsv_h);
  forces_at(stiffer, c);
  barrier.restore_stiffness(2 * barrier.kappa(), barrier.kappa_balanced());
  const auto stiffer_lag = lagged(stiffer, c);
  EXPECT_EQ(stiffer_lag, lagged(fresh_stiffer, c));
  EXPECT_NE(stiffer_lag.first, fresh_lag.first);
}

// At the step's start every friction stencil sticks (u = 0): sliding the block along x by δ
// moves the block–pad stencils by δ across their (horizontal) contact planes and the pad–ground
// ones not at all, so the stick-zone step is δ / (ε_v h). Once the block has slid 3 ε_v h, its
// stencils are out of the stick zone and the same move counts for nothing.
TEST(EnergyTermsFriction, StickZoneStepIsTheLargestMoveOfAStickingStencilOverEpsvH) {
  Fixture f;
  const FrictionTerm& friction = *f.step.friction;
  const double epsv_h = f.settings.eps_v * f.settings.h;
  const BodyModel& block = f.model.bodies[body_index(f.model, "block")];
  const auto slide = [&](double delta) {
    Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(f.step.x_n.rows(), 3);
    dx.middleRows(block.vertex_begin, block.vertex_end - block.vertex_begin).col(0).array() = delta;
    return dx;
  };
  const Configuration start{f.step.q_n, f.step.x_n};
  EXPECT_NEAR(friction.stick_zone_step(start, slide(0.3 * epsv_h)), 0.3, 1e-12);
  EXPECT_EQ(friction.stick_zone_step(start, Eigen::MatrixX3d::Zero(f.step.x_n.rows(), 3)), 0.0);
  Eigen::VectorXd q_slid = f.step.q_n;
  q_slid[block.dof] += 3 * epsv_h;
  const Eigen::MatrixX3d x_slid = f.model.surface(q_slid);
  EXPECT_EQ(friction.stick_zone_step({q_slid, x_slid}, slide(0.3 * epsv_h)), 0.0);
}

INSTANTIATE_TEST_SUITE_P(EnergyTerms, WholeTerm, ::testing::ValuesIn(kTerms),
                         [](const auto& info) { return info.param; });

namespace {

/// The bodies' surfaces at x, one SurfaceMesh per body, for the exact intersection test.
std::vector<SurfaceMesh> body_surfaces(const Model& model, const Eigen::MatrixX3d& x) {
  std::vector<SurfaceMesh> out;
  for (const BodyModel& body : model.bodies) {
    SurfaceMesh s;
    s.V = x.middleRows(body.vertex_begin, body.vertex_end - body.vertex_begin);
    s.F = model.mesh.F.middleRows(body.face_begin, body.face_end - body.face_begin).array() - body.vertex_begin;
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

TEST(EnergyTermsMaxStep, BarrierStepNeverReachesAnIntersection) {
  Fixture f;
  const Model& model = f.model;
  const Eigen::MatrixX3d x = model.surface(f.q);
  const Configuration c{f.q, x};
  f.step.barrier.update(c);
  ASSERT_FALSE(find_intersection(body_surfaces(model, x)).has_value());
  // Push the block 2 cm down and the pad 1 cm down (gaps are ≈ 5 mm): the full step goes
  // through the pad and the ground.
  Eigen::VectorXd dq = Eigen::VectorXd::Zero(f.q.size());
  dq[model.bodies[body_index(model, "block")].dof + 1] = -0.02;
  const BodyModel& pad = model.bodies[body_index(model, "pad")];
  for (int i = pad.node_begin; i < pad.node_end; ++i) dq[model.nodes.dof[i] + 1] = -0.01;
  const Eigen::MatrixX3d dx = model.surface_step(dq);
  ASSERT_TRUE(find_intersection(body_surfaces(model, x + dx)).has_value()) << "the test direction must cross a surface";
  const double alpha = f.step.barrier.max_step(c, dq, dx);
  EXPECT_GT(alpha, 0.0);
  EXPECT_LT(alpha, 1.0);
  for (const double t : {0.25, 0.5, 0.9, 0.99, 1.0}) {
    const Eigen::VectorXd q_t = f.q + t * alpha * dq;
    const Eigen::MatrixX3d x_t = model.surface(q_t);
    EXPECT_FALSE(find_intersection(body_surfaces(model, x_t)).has_value()) << "t = " << t;
    f.step.barrier.update({q_t, x_t});
    const double e = f.step.barrier.value({q_t, x_t});
    EXPECT_TRUE(std::isfinite(e)) << "t = " << t;
    EXPECT_GT(f.step.barrier.min_active_distance({q_t, x_t}), 0.0) << "t = " << t;
  }
  // Away from every contact nothing bounds the step.
  Eigen::VectorXd up = Eigen::VectorXd::Zero(f.q.size());
  up[model.bodies[body_index(model, "block")].dof + 1] = 0.01;
  f.step.barrier.update(c);
  EXPECT_EQ(f.step.barrier.max_step(c, up, model.surface_step(up)), 1.0);
  // The other terms never bound a step.
  for (EnergyTerm* t : std::vector<EnergyTerm*>{&f.step.inertia, &f.step.orthogonality, &f.step.elasticity,
                                                &*f.step.friction, &f.step.damping})
    EXPECT_EQ(t->max_step(c, dq, dx), 1.0) << t->name();
}

TEST(EnergyTermsMaxStep, BarrierKeepingItsCandidatesBoundsAndFindsContactsAsAFreshTerm) {
  // A run of moves from the contact state: tiny random ones (1e-6 in every DOF, far too little
  // to close the 5 mm gaps, which the barrier serves from the candidates of an earlier move)
  // and, every fourth, the block 2 cm down through the pad (a new broad phase and CCD). After
  // each, the kept term and a term built afresh at the same state give the same CCD bound, the
  // same bound per island and the same contacts at the new state.
  Fixture f;
  const Model& model = f.model;
  BarrierTerm& kept = f.step.barrier;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q = f.q_n;
  int tiny = 0;
  for (int move = 0; move < 12; ++move) {
    Eigen::VectorXd dq = Eigen::VectorXd::Zero(q.size());
    if (move % 4 == 3) {
      dq[model.bodies[body_index(model, "block")].dof + 1] = -0.02;
    } else {
      for (Eigen::Index i = 0; i < q.size(); ++i) dq[i] = 1e-6 * u(rng);
      ++tiny;
    }
    const Configuration c{q, model.surface(q)};
    const Eigen::MatrixX3d dx = model.surface_step(dq);
    kept.update(c);
    BarrierTerm fresh(model, barrier_settings(model, f.settings), nullptr);
    fresh.update(c);
    const double alpha = kept.max_step(c, dq, dx);
    EXPECT_EQ(alpha, fresh.max_step(c, dq, dx)) << "move " << move;
    if (move % 4 == 3) EXPECT_LT(alpha, 1.0);
    const auto island_bounds = [&](const BarrierTerm& term) {
      BlockIslands islands(int(model.blocks.size()));
      term.join_coupled_blocks(c, dx, islands);
      islands.number();
      std::vector<double> bound(std::size_t(islands.count()), 1.0);
      term.max_step_per_island(c, dq, dx, islands, bound);
      std::vector<double> per_block;
      for (int b = 0; b < int(model.blocks.size()); ++b) per_block.push_back(bound[std::size_t(islands.island(b))]);
      return per_block;
    };
    EXPECT_EQ(island_bounds(kept), island_bounds(fresh)) << "move " << move;
    q += 0.9 * alpha * dq;
    const Configuration next{q, model.surface(q)};
    kept.update(next);
    fresh.update(next);
    ASSERT_EQ(kept.constraints().size(), fresh.constraints().size()) << "move " << move;
    for (std::size_t k = 0; k < kept.constraints().size(); ++k) {
      const ContactConstraint &a = kept.constraints()[k], &b = fresh.constraints()[k];
      EXPECT_TRUE(a.vertices == b.vertices && a.weight == b.weight && a.distance == b.distance)
          << "move " << move << ", contact " << k;
    }
  }
  // Each tiny move is asked twice (max_step, then join_coupled_blocks); the first after a
  // deep move has no candidates of its own segment to start from.
  EXPECT_GT(kept.kept_moves(), std::size_t(tiny));
  EXPECT_LE(kept.kept_moves(), std::size_t(2 * tiny));
  // Pushed twice all the way to its CCD bound, the block ends a fraction of a millimetre above
  // the pad; 50 μm more down lies inside the candidates' boxes (they swept the whole 2 cm) but
  // could close that gap: not kept, and bounded as afresh.
  Eigen::VectorXd down = Eigen::VectorXd::Zero(q.size());
  down[model.bodies[body_index(model, "block")].dof + 1] = -0.02;
  for (int push = 0; push < 2; ++push) {
    const Configuration c{q, model.surface(q)};
    kept.update(c);
    q += kept.max_step(c, down, model.surface_step(down)) * down;
  }
  const Configuration close{q, model.surface(q)};
  kept.update(close);
  EXPECT_LT(kept.min_active_distance(close), 0.1 * kDhat);
  const std::size_t before = kept.kept_moves();
  const Eigen::VectorXd nudge = 0.0025 * down;
  const Eigen::MatrixX3d nudge_x = model.surface_step(nudge);
  BarrierTerm fresh(model, barrier_settings(model, f.settings), nullptr);
  fresh.update(close);
  const double alpha = kept.max_step(close, nudge, nudge_x);
  EXPECT_EQ(kept.kept_moves(), before);
  EXPECT_EQ(alpha, fresh.max_step(close, nudge, nudge_x));
  EXPECT_LT(alpha, 1.0);
  // 10 μm up from there: that move's candidates span 10 μm, so their reaches are about the
  // slack (0.1 d̂) and a move inside their boxes checks their near pairs alone. From half-way
  // up, 10 nm sideways is kept; a move down by 0.095 d̂, past the gap and still inside the
  // boxes, is not, and is bounded as afresh.
  ASSERT_LT(kept.min_active_distance(close), 0.01 * kDhat);
  const Eigen::VectorXd up = -5e-4 * down;  // 10 μm
  EXPECT_EQ(kept.max_step(close, up, model.surface_step(up)), 1.0);
  const Eigen::VectorXd q_half = close.q + 0.5 * up;
  const Configuration half{q_half, model.surface(q_half)};
  kept.update(half);  // sorts out the near candidates
  Eigen::VectorXd sideways = Eigen::VectorXd::Zero(q.size());
  sideways[model.bodies[body_index(model, "block")].dof] = 1e-8;
  const std::size_t kept_before = kept.kept_moves();
  EXPECT_EQ(kept.max_step(half, sideways, model.surface_step(sideways)), 1.0);
  EXPECT_EQ(kept.kept_moves(), kept_before + 1);
  const Eigen::VectorXd closing = (0.095 * kDhat / 0.02) * down;
  const Eigen::MatrixX3d closing_x = model.surface_step(closing);
  BarrierTerm fresh_half(model, barrier_settings(model, f.settings), nullptr);
  fresh_half.update(half);
  const double closing_alpha = kept.max_step(half, closing, closing_x);
  EXPECT_EQ(kept.kept_moves(), kept_before + 1);
  EXPECT_EQ(closing_alpha, fresh_half.max_step(half, closing, closing_x));
  EXPECT_LT(closing_alpha, 1.0);
}

TEST(EnergyTermsMaxStep, JointStepNeverCrossesTheHingeLimit) {
  Fixture f;
  const Model& model = f.model;
  const BodyModel& block = model.bodies[body_index(model, "block")];
  const Eigen::MatrixX3d x = model.surface(f.q);
  const Configuration c{f.q, x};
  // Turn the block by 0.1 rad about the hinge axis, past its upper limit (gap ≈ 0.03 rad).
  const abd::Vector12d qb = f.q.segment<12>(block.dof);
  Eigen::VectorXd dq = Eigen::VectorXd::Zero(f.q.size());
  dq.segment<12>(block.dof) = abd::rigid_motion(qb, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 1, 0), 0.1) - qb;
  const auto smallest_gap = [&](const Eigen::VectorXd& q) {
    double gap = std::numeric_limits<double>::infinity();
    for (const auto& [p, v] : f.step.joints.potentials()) gap = std::min(gap, p.gap(measure(p.measure, v.gather(q))));
    return gap;
  };
  ASSERT_GT(smallest_gap(f.q), 0.0);
  ASSERT_LT(smallest_gap(f.q + dq), 0.0) << "the test direction must cross the limit";
  const double alpha = f.step.joints.max_step(c, dq, model.surface_step(dq));
  EXPECT_GT(alpha, 0.0);
  EXPECT_LT(alpha, 1.0);
  for (const double t : {0.5, 0.9, 1.0}) {
    const Eigen::VectorXd q_t = f.q + t * alpha * dq;
    const Eigen::MatrixX3d x_t = model.surface(q_t);
    EXPECT_GT(smallest_gap(q_t), 0.0) << "t = " << t;
    EXPECT_TRUE(std::isfinite(f.step.joints.value({q_t, x_t}))) << "t = " << t;
  }
}

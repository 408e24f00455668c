/// @file newton_minimize on energies with known minimisers, over a one-body model (one affine
/// body, 12 DOFs): a convex quadratic is minimised by the first Newton step, and a strictly
/// convex non-quadratic energy converges to its minimiser with the energy decreasing at every
/// accepted iteration, and the line search counts its halvings.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>
#include <stiffsoft/coupling/solver/newton.hpp>
#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

using namespace stiffsoft;

namespace {

/// One dynamic affine box: the model only supplies the DOF layout (one 12-wide block) and a
/// surface for Newton's step-size stopping rule.
const Model& one_body_model() {
  static const PreparedScene p = prepare_scene(
      load_scene_from_string(R"({"description": "Newton test: one affine box.",
                                  "bodies": [{"name": "box", "mesh": {"primitive": "box", "size": [0.5, 0.5, 0.5]}}]})",
                             STIFFSOFT_SOURCE_DIR, "newton.json", "newton"),
      "newton.json");
  return p.model;
}

/// A random symmetric positive definite 12×12 matrix BᵀB + I (condition number ≈ 50).
Eigen::MatrixXd random_spd(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd B(12, 12);
  for (Eigen::Index i = 0; i < B.size(); ++i) B.data()[i] = u(rng);
  return B.transpose() * B + Eigen::MatrixXd::Identity(12, 12);
}

/// A random 12-vector with entries in [−scale, scale].
Eigen::VectorXd random_vector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(12);
  for (Eigen::Index i = 0; i < 12; ++i) v[i] = u(rng);
  return v;
}

/// E(q) = ½ qᵀ A q − bᵀ q on the body's block; A symmetric positive definite.
class QuadraticTerm final : public EnergyTerm {
 public:
  /// The quadratic on DOF block `block`.
  QuadraticTerm(Eigen::MatrixXd A, Eigen::VectorXd b, int block) : m_A(std::move(A)), m_b(std::move(b)), m_block(block) {}
  /// See EnergyTerm::name.
  const char* name() const override { return "quadratic"; }
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override { return 0.5 * c.q.dot(m_A * c.q) - m_b.dot(c.q); }
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override { g += m_A * c.q - m_b; }
  /// See EnergyTerm::add_hessian.
  void add_hessian(const Configuration&, BlockHessian& H) const override { H.add(m_block, m_block, m_A); }

 private:
  Eigen::MatrixXd m_A;
  Eigen::VectorXd m_b;
  int m_block;
};

/// E(q) = Σ_i w_i cosh(q_i − c_i) + ½ (q − c)ᵀ B (q − c) with w_i > 0 and B PSD: strictly
/// convex (∇²E = diag(w_i cosh(q_i − c_i)) + B ≻ 0), not quadratic, minimised at q = c with
/// E(c) = Σ w_i. Records E at every accepted Newton iterate (end_iteration).
class CoshTerm final : public EnergyTerm {
 public:
  /// The term on DOF block `block`.
  CoshTerm(Eigen::VectorXd w, Eigen::MatrixXd B, Eigen::VectorXd c, int block)
      : m_w(std::move(w)), m_B(std::move(B)), m_c(std::move(c)), m_block(block) {}
  /// See EnergyTerm::name.
  const char* name() const override { return "cosh"; }
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override {
    const Eigen::VectorXd d = c.q - m_c;
    return m_w.dot(d.array().cosh().matrix()) + 0.5 * d.dot(m_B * d);
  }
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override {
    const Eigen::VectorXd d = c.q - m_c;
    g += (m_w.array() * d.array().sinh()).matrix() + m_B * d;
  }
  /// See EnergyTerm::add_hessian.
  void add_hessian(const Configuration& c, BlockHessian& H) const override {
    const Eigen::VectorXd d = c.q - m_c;
    const Eigen::MatrixXd Hq = Eigen::MatrixXd((m_w.array() * d.array().cosh()).matrix().asDiagonal()) + m_B;
    H.add(m_block, m_block, Hq);
  }
  /// Records E at the accepted iterate.
  bool end_iteration(const Configuration& c) override {
    energies.push_back(value(c));
    return false;
  }
  /// E after each accepted iteration, in order.
  std::vector<double> energies;

 private:
  Eigen::VectorXd m_w;
  Eigen::MatrixXd m_B;
  Eigen::VectorXd m_c;
  int m_block;
};

/// E(q) = Σ_i √(1 + (q_i − c_i)²): strictly convex, minimised at q = c, and Newton's full step
/// −d (1 + d²) from an offset d overshoots the minimiser in every coordinate.
class PseudoHuberTerm final : public EnergyTerm {
 public:
  /// The term on DOF block `block`.
  PseudoHuberTerm(Eigen::VectorXd c, int block) : m_c(std::move(c)), m_block(block) {}
  /// See EnergyTerm::name.
  const char* name() const override { return "pseudo-Huber"; }
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override { return (1 + (c.q - m_c).array().square()).sqrt().sum(); }
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override {
    const Eigen::ArrayXd d = (c.q - m_c).array();
    g += (d / (1 + d.square()).sqrt()).matrix();
  }
  /// See EnergyTerm::add_hessian.
  void add_hessian(const Configuration& c, BlockHessian& H) const override {
    const Eigen::ArrayXd d = (c.q - m_c).array();
    H.add(m_block, m_block, Eigen::MatrixXd((1 + d.square()).pow(-1.5).matrix().asDiagonal()));
  }

 private:
  Eigen::VectorXd m_c;
  int m_block;
};

}  // namespace

TEST(NewtonMinimize, QuadraticIsMinimisedByTheFirstNewtonStep) {
  const Model& model = one_body_model();
  ASSERT_EQ(model.num_dofs, 12);
  std::mt19937 rng(11);
  const Eigen::MatrixXd A = random_spd(rng);
  const Eigen::VectorXd b = random_vector(rng, 1.0);
  const Eigen::VectorXd q_star = A.ldlt().solve(b);
  QuadraticTerm term(A, b, model.bodies[0].block);
  const std::vector<EnergyTerm*> terms{&term};
  const std::unique_ptr<LinearSolver> solver = make_linear_solver("cholmod");
  PhaseTimes times;

  // One iteration: the full Newton step (α = 1, one energy evaluation) lands on A⁻¹b, to the
  // round-off of a Cholesky solve with condition ≈ 50 (≈ 1e-14 relative; 1e-10 is the margin).
  // Trials on the straight line q + α p: a geodesic trial turns the box off the line along which
  // a quadratic in q is minimised (TrialPath).
  NewtonSettings straight;
  straight.geodesic_line_search = false;
  NewtonSettings one = straight;
  one.max_iterations = 1;
  Eigen::VectorXd q = model.initial_q();
  const NewtonReport first = newton_minimize(model, terms, q, *solver, one, times);
  EXPECT_EQ(first.iterations, 1);
  EXPECT_EQ(first.line_search_steps, 1);
  EXPECT_EQ(first.smallest_ccd_step, 1.0);
  EXPECT_EQ(first.ccd_limited_iterations, 0);
  EXPECT_LT((q - q_star).norm(), 1e-10 * q_star.norm());

  // Unbounded: the step to A⁻¹b, then a zero step that meets the stopping rule.
  q = model.initial_q();
  const NewtonReport report = newton_minimize(model, terms, q, *solver, straight, times);
  EXPECT_TRUE(report.converged) << report.failure;
  EXPECT_EQ(report.iterations, 2);
  EXPECT_LT((q - q_star).norm(), 1e-10 * q_star.norm());
  EXPECT_NEAR(report.energy, -0.5 * b.dot(q_star), 1e-10 * std::abs(b.dot(q_star)));
}

/// Adds nothing to E; its step bound is `first` on the first direction and 1 afterwards, as
/// CCD bounds a step that would reach a contact once.
class StepBoundTerm final : public EnergyTerm {
 public:
  explicit StepBoundTerm(double first) : m_first(first) {}
  const char* name() const override { return "step bound"; }
  double value(const Configuration&) const override { return 0; }
  void add_gradient(const Configuration&, Eigen::VectorXd&) const override {}
  void add_hessian(const Configuration&, BlockHessian&) const override {}
  double max_step(const Configuration&, const Eigen::VectorXd&, const Eigen::MatrixX3d&) const override {
    return m_calls++ == 0 ? m_first : 1.0;
  }

 private:
  double m_first;
  mutable int m_calls = 0;
};

TEST(NewtonMinimize, ReportsTheIterationsWhoseStepCcdBounded) {
  const Model& model = one_body_model();
  std::mt19937 rng(12);
  const Eigen::MatrixXd A = random_spd(rng);
  const Eigen::VectorXd b = random_vector(rng, 1.0);
  QuadraticTerm term(A, b, model.bodies[0].block);
  StepBoundTerm bound(0.25);
  const std::vector<EnergyTerm*> terms{&term, &bound};
  const std::unique_ptr<LinearSolver> solver = make_linear_solver("cholmod");
  PhaseTimes times;
  Eigen::VectorXd q = model.initial_q();
  NewtonSettings straight;  // as in QuadraticIsMinimisedByTheFirstNewtonStep
  straight.geodesic_line_search = false;
  const NewtonReport report = newton_minimize(model, terms, q, *solver, straight, times);
  EXPECT_TRUE(report.converged) << report.failure;
  // A quarter of the way, then the rest of the (same) Newton step, then a zero step.
  EXPECT_EQ(report.iterations, 3);
  EXPECT_EQ(report.ccd_limited_iterations, 1);
  EXPECT_EQ(report.smallest_ccd_step, 0.25);
  EXPECT_LT((q - A.ldlt().solve(b)).norm(), 1e-10 * b.norm());
}

TEST(NewtonMinimize, StrictlyConvexEnergyConvergesMonotonicallyToItsMinimiser) {
  const Model& model = one_body_model();
  std::mt19937 rng(5);
  const Eigen::VectorXd w = (random_vector(rng, 1.0).cwiseAbs().array() + 0.5).matrix();
  const Eigen::MatrixXd B = 0.1 * (random_spd(rng) - Eigen::MatrixXd::Identity(12, 12));
  const Eigen::VectorXd c = model.initial_q() + random_vector(rng, 0.3);
  CoshTerm term(w, B, c, model.bodies[0].block);
  const std::vector<EnergyTerm*> terms{&term};
  const std::unique_ptr<LinearSolver> solver = make_linear_solver("cholmod");
  PhaseTimes times;
  // Start 3 units away in every coordinate, where cosh is far from its quadratic model.
  Eigen::VectorXd q = c + 3.0 * random_vector(rng, 1.0).cwiseSign();
  const Eigen::MatrixX3d x0 = model.surface(q);
  const double E0 = term.value({q, x0});
  NewtonSettings settings;
  settings.tolerance = 1e-6;  // m/s: stop when the surface moves < 1e-8 m in a step (h = 1e-2 s)
  const NewtonReport report = newton_minimize(model, terms, q, *solver, settings, times);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_LT(report.iterations, 30);
  // Quadratic convergence: the last step was < 1e-8, so the error after it is far smaller.
  EXPECT_LT((q - c).lpNorm<Eigen::Infinity>(), 1e-8);
  EXPECT_NEAR(report.energy, w.sum(), 1e-12 * w.sum());
  // The line search accepts no rise beyond round-off (the converged direction's step, below
  // ε_d, is taken without the test); before the minimum is reached (gap to E(c) above
  // round-off) every accepted iterate lowers E strictly.
  ASSERT_FALSE(term.energies.empty());
  double previous = E0;
  for (size_t k = 0; k < term.energies.size(); ++k) {
    EXPECT_LE(term.energies[k], previous) << "iteration " << k + 1;
    if (previous - w.sum() > 1e-10) EXPECT_LT(term.energies[k], previous) << "iteration " << k + 1;
    previous = term.energies[k];
  }
}

TEST(NewtonMinimize, TakesTheConvergedStepAsItsFirstTrial) {
  // The light pile's first steps are free fall: the initial guess is within ε_d of the minimiser,
  // so the one direction meets the stopping rule. Its step is taken as the first trial, without
  // the energy test: the energy it changes is round-off, on which the test used to spend 3–12
  // trials per step here (docs/newton.md, session 40).
  SceneSimulation run = make_simulation(STIFFSOFT_SOURCE_DIR "/scenes/light.json");
  for (int k = 0; k < 5; ++k) {
    const StepStats s = run.simulation.step();
    ASSERT_EQ(s.contacts, 0) << "step " << s.step;
    EXPECT_TRUE(s.newton.converged) << s.newton.failure;
    EXPECT_EQ(s.newton.iterations, 1) << "step " << s.step;
    EXPECT_EQ(s.newton.line_search_steps, 1) << "step " << s.step;
  }
}

TEST(NewtonMinimize, CountsTheLineSearchHalvings) {
  // On the straight line every trial after an iteration's first halves its step: trials =
  // iterations + halvings. The pseudo-Huber energy's full Newton steps overshoot, so there are
  // halvings to count.
  const Model& model = one_body_model();
  std::mt19937 rng(5);
  const Eigen::VectorXd c = model.initial_q();
  PseudoHuberTerm term(c, model.bodies[0].block);
  const std::vector<EnergyTerm*> terms{&term};
  const std::unique_ptr<LinearSolver> solver = make_linear_solver("cholmod");
  PhaseTimes times;
  Eigen::VectorXd q = c + 2.0 * random_vector(rng, 1.0);
  NewtonSettings settings;
  settings.geodesic_line_search = false;
  settings.tolerance = 1e-6;
  const NewtonReport report = newton_minimize(model, terms, q, *solver, settings, times);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_LT((q - c).lpNorm<Eigen::Infinity>(), 1e-8);
  EXPECT_GT(report.line_search_halvings, 0);
  EXPECT_EQ(report.line_search_steps, report.iterations + report.line_search_halvings);
}

TEST(NewtonMinimize, IslandsMoveByTheirOwnBoundsOnlyWhereThatDescends) {
  // Island 0 is cut at a quarter, island 1 not at all.
  const std::vector<double> bound{0.25, 1.0};
  // Both parts of p descend: each island by its own bound, or α where that is smaller.
  EXPECT_EQ(island_multiples(bound, 1.0, {-3.0, -1.0}), (std::vector<double>{0.25, 1.0}));
  EXPECT_EQ(island_multiples(bound, 0.5, {-3.0, -1.0}), (std::vector<double>{0.25, 0.5}));
  // An inexact direction: island 1's part ascends, the whole of p descends (−3 + 1 < 0). Cut
  // to its own bound, island 0 no longer outweighs it (0.25 · −3 + 1 > 0): every island moves
  // by the smallest multiple, along p itself, which descends.
  EXPECT_EQ(island_multiples(bound, 1.0, {-3.0, 1.0}), (std::vector<double>{0.25, 0.25}));
  // Where the islands' own multiples still descend (0.25 · −3 + 0.5 < 0), they stay.
  EXPECT_EQ(island_multiples(bound, 1.0, {-3.0, 0.5}), (std::vector<double>{0.25, 1.0}));
  // One island: its multiple, whatever the slope.
  EXPECT_EQ(island_multiples({0.5}, 1.0, {2.0}), (std::vector<double>{0.5}));
}

#include <stiffsoft/libfem/solve_static.hpp>

#include <tbb/parallel_for.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <stdexcept>
#include <string>

namespace stiffsoft::fem {

namespace {

/// Π(x) = elastic energy − fᵀx, and a scale for its round-off (|elastic| + |fᵀx|).
struct Potential {
  double value;
  double scale;
};

Potential potential(const ElasticEnergy& energy, const Eigen::VectorXd& f, const Eigen::VectorXd& x) {
  const double elastic = energy.value(x), work = f.dot(x);
  return {elastic - work, std::abs(elastic) + std::abs(work)};
}

/// ∂Π/∂x restricted to the free DOFs.
Eigen::VectorXd free_gradient(const ElasticEnergy& energy, const Eigen::VectorXd& f, const Eigen::VectorXd& x,
                              const std::vector<int>& dof_of) {
  const Eigen::VectorXd g = energy.gradient(x) - f;
  Eigen::VectorXd gf(g.size());
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < g.size(); ++i)
    if (dof_of[i] >= 0) gf[n++] = g[i];
  return gf.head(n);
}

/// The Hessian of Π over the free DOFs (lower triangle is what the LDLᵀ reads; both are stored).
Eigen::SparseMatrix<double> free_hessian(const ElasticEnergy& energy, const Eigen::VectorXd& x,
                                         const std::vector<int>& dof_of, int num_free, bool project) {
  const int num_elements = energy.num_elements();
  std::vector<ElementHessian> local(num_elements);
  tbb::parallel_for(tbb::blocked_range<int>(0, num_elements, 256), [&](const tbb::blocked_range<int>& r) {
    for (int e = r.begin(); e != r.end(); ++e) local[e] = energy.element_hessian(e, x, project);
  });
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(144 * std::size_t(num_elements));
  for (const ElementHessian& h : local)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int r = dof_of[3 * h.nodes[a] + i], c = dof_of[3 * h.nodes[b] + j];
            if (r >= 0 && c >= 0) triplets.emplace_back(r, c, h.H(3 * a + i, 3 * b + j));
          }
  Eigen::SparseMatrix<double> H(num_free, num_free);
  H.setFromTriplets(triplets.begin(), triplets.end());
  return H;
}

}  // namespace

StaticResult solve_static(const ElasticEnergy& energy, const Eigen::VectorXd& f,
                          const std::vector<bool>& fixed, const Eigen::VectorXd& x0,
                          const StaticSettings& settings) {
  const int N = energy.num_nodes();
  if (f.size() != 3 * N || x0.size() != 3 * N || int(fixed.size()) != N)
    throw std::invalid_argument("libfem: solve_static: f has " + std::to_string(f.size()) + ", x0 " +
                                std::to_string(x0.size()) + " entries and fixed " +
                                std::to_string(fixed.size()) +
                                " flags; expected 3N, 3N and N for N = " + std::to_string(N) + " nodes");
  // dof_of[3i + k]: the free DOF of coordinate k of node i, −1 when node i is fixed.
  std::vector<int> dof_of(3 * N, -1);
  int num_free = 0;
  for (int i = 0; i < N; ++i)
    if (!fixed[i])
      for (int k = 0; k < 3; ++k) dof_of[3 * i + k] = num_free++;

  StaticResult result;
  result.x = x0;
  Eigen::VectorXd g = free_gradient(energy, f, result.x, dof_of);
  result.initial_gradient_norm = result.gradient_norm = g.norm();
  const double tolerance =
      std::max(settings.relative_tolerance * result.initial_gradient_norm, settings.absolute_tolerance);
  Potential pi = potential(energy, f, result.x);

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  bool analysed = false;
  while (true) {
    if (result.gradient_norm <= tolerance) {
      result.converged = true;
      break;
    }
    if (result.iterations >= settings.max_iterations) break;

    const Eigen::SparseMatrix<double> H =
        free_hessian(energy, result.x, dof_of, num_free, settings.project_psd);
    // The sparsity pattern depends only on the mesh and the fixed set: analyse it once.
    if (!analysed) {
      ldlt.analyzePattern(H);
      analysed = true;
    }
    ldlt.factorize(H);
    // A (numerically) zero pivot means a rigid or otherwise free motion no fixed node removes.
    const double largest_pivot = ldlt.vectorD().cwiseAbs().maxCoeff();
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().cwiseAbs().minCoeff() > 1e-14 * largest_pivot))
      throw std::runtime_error(
          "libfem: solve_static: the Hessian over the free DOFs is singular (smallest LDL^T pivot below "
          "1e-14 of the largest); fix enough nodes to remove rigid motions");
    Eigen::VectorXd p = ldlt.solve(-g);
    // Without projection H may be indefinite; fall back to steepest descent when p goes uphill.
    const bool newton = g.dot(p) < 0;
    if (!newton) p = -g;

    Eigen::VectorXd step = Eigen::VectorXd::Zero(3 * N);
    for (int i = 0; i < 3 * N; ++i)
      if (dof_of[i] >= 0) step[i] = p[dof_of[i]];
    const double slope = g.dot(p);  // directional derivative gᵀp < 0
    if (newton &&
        p.cwiseAbs().maxCoeff() <= settings.relative_step_tolerance * result.x.cwiseAbs().maxCoeff()) {
      result.converged = result.at_roundoff = true;
      break;
    }

    double alpha = 1;
    bool accepted = false;
    while (alpha >= settings.min_step) {
      const Eigen::VectorXd x_trial = result.x + alpha * step;
      const Potential pi_trial = potential(energy, f, x_trial);
      if (pi_trial.value <= pi.value + settings.armijo * alpha * slope) {
        accepted = true;
      } else if (alpha == 1 &&
                 std::abs(pi_trial.value - pi.value) <= 1e-12 * std::max(pi.scale, pi_trial.scale)) {
        // Round-off regime: Π cannot resolve the decrease; trust the gradient norm instead.
        const Eigen::VectorXd g_trial = free_gradient(energy, f, x_trial, dof_of);
        accepted = g_trial.norm() < result.gradient_norm;
      }
      if (accepted) {
        result.x = x_trial;
        pi = pi_trial;
        break;
      }
      alpha /= 2;
      ++result.line_search_halvings;
    }
    if (!accepted) break;
    ++result.iterations;
    g = free_gradient(energy, f, result.x, dof_of);
    result.gradient_norm = g.norm();
  }
  result.energy = pi.value;
  return result;
}

}  // namespace stiffsoft::fem

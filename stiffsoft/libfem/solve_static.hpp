#pragma once
/// @file Static equilibrium of one elastic mesh under nodal forces and Dirichlet nodes:
/// x* = argmin Π(x), Π(x) = Σ_e V_e ψ(F_e(x)) − fᵀx, by projected Newton with a backtracking line
/// search on Π and a sparse LDLᵀ (Eigen::SimplicialLDLT) on the free DOFs.

#include <Eigen/Core>
#include <vector>

#include <stiffsoft/libfem/elastic_energy.hpp>

namespace stiffsoft::fem {

/// Settings of solve_static.
struct StaticSettings {
  int max_iterations = 100;          ///< Newton iteration cap
  double relative_tolerance = 1e-8;  ///< converged when ‖g_free‖ ≤ this × ‖g_free(x₀)‖
  double absolute_tolerance = 0;     ///< … or when ‖g_free‖ ≤ this (N)
  /// … or when the Newton step is negligible: ‖p‖∞ ≤ this × ‖x‖∞. This catches the round-off
  /// floor of ‖g‖ (≈ 1e-16 × stiffness × |x|, set by absolute positions), which a gradient test
  /// relative to ‖g(x₀)‖ cannot see; 1e-12 of the coordinates is ~5000 ulps.
  double relative_step_tolerance = 1e-12;
  bool project_psd = true;  ///< project each element Hessian to PSD (projected Newton)
  double armijo = 1e-4;     ///< sufficient-decrease constant c: Π(x + αp) ≤ Π(x) + c α gᵀp
  double min_step = 1e-10;  ///< give up when the line search halves α below this
};

/// What solve_static did.
struct StaticResult {
  Eigen::VectorXd x;                 ///< final positions, 3N node-major (m)
  int iterations = 0;                ///< Newton steps taken
  int line_search_halvings = 0;      ///< total step halvings over all iterations
  double gradient_norm = 0;          ///< ‖∂Π/∂x‖ over the free DOFs at x (N)
  double initial_gradient_norm = 0;  ///< the same at x₀ (N)
  double energy = 0;                 ///< Π(x) (J)
  bool converged = false;            ///< a tolerance was met (false: iteration cap or line search failed)
  bool at_roundoff = false;          ///< converged by the step test (round-off floor), not the gradient test
};

/// Minimises Π(x) = energy.value(x) − fᵀx over the DOFs of the nodes with fixed[i] == false; a
/// fixed node keeps its position from x0 (its prescribed, Dirichlet position). f: nodal forces,
/// 3N (N); fixed: |N| flags; x0: start, 3N (m).
/// Near convergence Π stops changing in floating point; there a full step that lowers ‖g_free‖
/// and changes Π by less than 1e-12 of its scale is accepted.
/// With project_psd = false and an indefinite Hessian, a Newton direction that goes uphill is
/// replaced by −g for that iteration.
/// Throws std::invalid_argument for mismatched sizes, std::runtime_error when the free-DOF Hessian
/// is singular (smallest LDLᵀ pivot ≤ 1e-14 × largest; e.g. too few fixed nodes to remove rigid
/// motions).
StaticResult solve_static(const ElasticEnergy& energy, const Eigen::VectorXd& f,
                          const std::vector<bool>& fixed, const Eigen::VectorXd& x0,
                          const StaticSettings& settings = {});

}  // namespace stiffsoft::fem

#pragma once
/// @file β h² Σ_b V⊥(q_b): the orthogonality potentials of the dynamic affine bodies.

#include <vector>

#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/terms/energy_term.hpp>

namespace stiffsoft {

/// β h² Σ_b κ_b ν_b ‖A_b A_bᵀ − I‖²_F over dynamic bodies (Lan et al. 2022, eq. 6).
class OrthogonalityTerm final : public EnergyTerm {
 public:
  /// `scale` is β h² (s²).
  OrthogonalityTerm(const Model& model, double scale);
  /// See EnergyTerm::name.
  const char* name() const override { return "orthogonality"; }
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override;
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override;
  /// See EnergyTerm::add_hessian.
  void add_hessian(const Configuration& c, BlockHessian& H) const override;
  /// Couples no two blocks: see EnergyTerm::join_coupled_blocks.
  void join_coupled_blocks(const Configuration&, const Eigen::MatrixX3d&, BlockIslands&) const override {}
  /// True when no dynamic affine body exists (the term can be left out).
  bool empty() const { return m_bodies.empty(); }

 private:
  struct Body {
    int block;
    int dof;
    double kappa_volume;  // β h² κ ν
  };
  std::vector<Body> m_bodies;
};

}  // namespace stiffsoft

#pragma once
/// @file A hyperelastic material at a point: energy density ψ(F), first Piola–Kirchhoff stress
/// P = ∂ψ/∂F and its derivative ∂P/∂F, and nothing else (Drake's constitutive-model split).

#include <Eigen/Core>

#include <stiffsoft/libfem/lame_parameters.hpp>
#include <stiffsoft/libfem/types.hpp>

namespace stiffsoft::fem {

/// An isotropic hyperelastic material given by Young's modulus and Poisson ratio.
/// Units: F is dimensionless, ψ in J/m³ (= Pa), P in Pa, ∂P/∂F in Pa.
/// Derivatives use column-major vec(F): (∂P/∂F)(i + 3j, k + 3l) = ∂P_ij / ∂F_kl.
class Material {
 public:
  /// A material with Young's modulus E (Pa) and Poisson ratio ν.
  /// @pre E > 0 and −1 < ν < 0.5; otherwise throws std::invalid_argument.
  Material(double youngs_modulus, double poisson_ratio);
  /// Materials are used through pointers to this base.
  virtual ~Material() = default;

  /// The model's name as make_material accepts it ("linear", "fixed_corotated", …).
  virtual const char* name() const = 0;
  /// Strain-energy density ψ(F) (J/m³); zero at F = I.
  virtual double psi(const Eigen::Matrix3d& F) const = 0;
  /// First Piola–Kirchhoff stress P(F) = ∂ψ/∂F (Pa).
  virtual Eigen::Matrix3d P(const Eigen::Matrix3d& F) const = 0;
  /// ∂vec(P)/∂vec(F) = ∂²ψ/∂F², 9×9 symmetric (Pa); may be indefinite.
  virtual Matrix9d dPdF(const Eigen::Matrix3d& F) const = 0;
  /// ∂P/∂F projected onto the positive semi-definite cone (negative eigenvalues of the 9×9 set to
  /// zero), for projected Newton. Valid for every F, inverted included.
  virtual Matrix9d dPdF_projected(const Eigen::Matrix3d& F) const;

  /// ∂P/∂F, projected (dPdF_projected) or not (dPdF).
  Matrix9d dPdF(const Eigen::Matrix3d& F, bool project_psd) const {
    return project_psd ? dPdF_projected(F) : dPdF(F);
  }
  /// Von Mises equivalent stress √(3/2 s:s) of the Cauchy stress σ = P Fᵀ / det F,
  /// s = σ − tr(σ)/3 I (Pa). For det F ≤ 0 (inverted) it uses |det F|; +∞ when det F = 0.
  double von_mises(const Eigen::Matrix3d& F) const;

  /// Young's modulus E (Pa).
  double youngs_modulus() const { return m_E; }
  /// Poisson ratio ν.
  double poisson_ratio() const { return m_nu; }
  /// Lamé parameters of small-strain elasticity with the same E and ν (Pa). A model may use
  /// re-parameterised values internally (stable neo-Hookean does) so that it linearises to these.
  const LameParameters& lame() const { return m_lame; }

 private:
  double m_E;
  double m_nu;
  LameParameters m_lame;
};

}  // namespace stiffsoft::fem

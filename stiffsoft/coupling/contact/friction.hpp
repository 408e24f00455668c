#pragma once
/// @file Lagged, smoothed friction of one contact stencil (IPC, Li et al. 2020, §5, eqs. 14–18).
/// D(dx) = μ λ f₀(‖u‖), u = Pᵀ Γ dx: λ (normal force), P (tangent basis) and Γ (closest-point
/// operator) are frozen at the lagged configuration; dx = x − xⁿ is the step's displacement.

#include <Eigen/Core>

#include <stiffsoft/coupling/contact/barrier.hpp>
#include <stiffsoft/coupling/contact/barrier_potential.hpp>
#include <stiffsoft/coupling/contact/primitive_pair.hpp>

namespace stiffsoft::contact {

/// Friction data of one stencil, built once per lag by make_friction_stencil.
struct FrictionStencil {
  /// primitive pair of the stencil it was built from
  PrimitivePair kind = PrimitivePair::VertexVertex;
  /// lagged normal force magnitude λ ≥ 0, N
  double normal_force = 0;
  /// orthonormal tangent basis, 3×2, of the plane orthogonal to the contact normal
  Eigen::Matrix<double, 3, 2> P = Eigen::Matrix<double, 3, 2>::Zero();
  /// relative closest-point displacement operator, 3×12: u₃ = Γ dx = Σ c_i dx_i
  Eigen::Matrix<double, 3, 12> Gamma = Eigen::Matrix<double, 3, 12>::Zero();
  /// Pᵀ Γ, 2×12, formed once by make_friction_stencil (a stencil assembled by hand must set it
  /// too): every evaluation of the lagged friction reads it
  Eigen::Matrix<double, 2, 12> T = Eigen::Matrix<double, 2, 12>::Zero();
};

/// Tangential operator T = Pᵀ Γ, 2×12: u = T dx.
inline const Eigen::Matrix<double, 2, 12>& tangent_operator(const FrictionStencil& f) { return f.T; }

/// An orthonormal basis (3×2) of the plane orthogonal to the unit vector n.
Eigen::Matrix<double, 3, 2> orthonormal_complement(const Eigen::Vector3d& n);

/// Builds the lagged friction data from x_lag (IPC §5):
/// λ = κ m(x_lag) (−b'(d²)) 2d — the normal force κ |∂(m b)/∂d| with the mollifier value m
/// kept as a factor (m ≡ 1 unless the stencil is mollified), 0 when d ≥ d̂, +∞ when d = 0;
/// Γ = c(y*) ⊗ I₃ from the stencil's closest points (classified for segment-distance stencils);
/// P spans the plane orthogonal to the normal n = r/‖r‖ (r joins the closest points; for a
/// touching stencil, d = 0, the face normal or ea × eb is used, else an arbitrary axis).
/// Friction is isotropic, so any orthonormal P of that plane gives the same D.
/// dhat: d̂, m; kappa: barrier stiffness κ, N/m³.
FrictionStencil make_friction_stencil(const Stencil& s, const Vector12d& x_lag, double dhat,
                                      double kappa);

/// Smoothed friction magnitude f₀(y) = −y³/(3ε²) + y²/ε + ε/3 for y < ε, y otherwise
/// (IPC eq. 15 integrated; C² at ε). y = ‖u‖, m; eps = ε_v h, m.
double friction_f0(double y, double eps);

/// f₁(y) = f₀'(y) = 2y/ε − y²/ε² for y < ε, 1 otherwise; dimensionless.
double friction_f1(double y, double eps);

/// f₁(y)/y = 2/ε − y/ε² for y < ε, 1/y otherwise (finite at y = 0), 1/m.
double friction_f1_over_y(double y, double eps);

/// Friction potential D = μ λ f₀(‖u‖), u = Pᵀ Γ dx; J. dx: step displacement of the stencil,
/// 12-vector, m; mu: friction coefficient; epsv_h: ε = ε_v h, m.
double friction_potential(const FrictionStencil& f, const Vector12d& dx, double mu, double epsv_h);

/// ∇D = μ λ (f₁(y)/y) Tᵀ u, T = PᵀΓ; 12-vector, N. Its magnitude is μλ‖Tᵀû‖ when sliding.
Vector12d friction_potential_gradient(const FrictionStencil& f, const Vector12d& dx, double mu,
                                      double epsv_h);

/// ∇²D = μ λ Tᵀ M T with the 2×2 core (y = ‖u‖, û = u/y)
///   y ≥ ε:     M = (I − û ûᵀ)/y,
///   0 < y < ε: M = (f₁/y) I + (f₁' y − f₁)/y³ u uᵀ = (2/ε − y/ε²) I − (y/ε²) û ûᵀ,
///   y = 0:     M = (2/ε) I;
/// N/m. project_psd projects the 2×2 core (as ipc-toolkit does), which keeps Tᵀ M T PSD: its
/// eigenvalues are f₁/y across û and 0 (y ≥ ε) or 2 (ε − y)/ε² (y < ε) along û, so the exact
/// core is PSD already and the projection, the second clamped at zero, only guards round-off.
Matrix12d friction_potential_hessian(const FrictionStencil& f, const Vector12d& dx, double mu,
                                     double epsv_h, bool project_psd);

/// friction_potential_hessian() as its factors: ∇²D = Tᵀ C T with T the tangent operator and
/// C = μ λ M (projected as asked), so that a caller can map T through its own Jacobian before
/// forming any 12×12 product (rank ≤ 2). C is zero when μ λ = 0.
struct FrictionHessianFactors {
  Eigen::Matrix<double, 2, 12> T;  ///< tangent_operator(f)
  Eigen::Matrix2d C;               ///< μ λ M, N/m
};

/// The factors of friction_potential_hessian(f, dx, mu, epsv_h, project_psd).
FrictionHessianFactors friction_hessian_factors(const FrictionStencil& f, const Vector12d& dx, double mu,
                                                double epsv_h, bool project_psd);

/// The isotropic majorizer of D's Hessian: μ λ Tᵀ (f₁(y)/y) I T, N/m. Its quadratic model lies
/// above D in every direction (f₀(‖v‖) is concave in ‖v‖², so the quadratic in v that touches
/// it at u with slope f₁(y)/y bounds it from above), and it exceeds the exact Hessian by
/// μ λ Tᵀ (f₁/y − f₁') û ûᵀ T ⪰ 0. Where the exact Hessian has no curvature along the slide
/// (y ≥ ε), a Newton step sized by the other terms can run u through the stick zone and out the
/// other side, where D has risen linearly; a step on this model stops short of reversing it.
Matrix12d friction_majorizer_hessian(const FrictionStencil& f, const Vector12d& dx, double mu,
                                     double epsv_h);

/// friction_majorizer_hessian() as its factors: T and C = μ λ (f₁(y)/y) I₂.
FrictionHessianFactors friction_majorizer_factors(const FrictionStencil& f, const Vector12d& dx, double mu,
                                                  double epsv_h);

/// Whether the step dx_step reverses the slide of a stencil displaced by dx: it slides
/// (‖u‖ ≥ ε) and the full step ends on the far side, u·(u + T dx_step) < 0.
bool step_reverses_slide(const FrictionStencil& f, const Vector12d& dx, const Vector12d& dx_step,
                         double epsv_h);

}  // namespace stiffsoft::contact

#pragma once
/// @file Kinematics of one affine body (Lan et al. 2022, "Affine Body Dynamics", §3).
///
/// The 12 DOFs are q = (p, a₁, a₂, a₃) with p the translation and a_i the rows of the affine
/// matrix A, so a material point with body-frame position x̄ sits at x = A x̄ + p = J(x̄) q,
/// J(x̄) = [I₃, I₃ ⊗ x̄ᵀ] (3×12), constant in time.

#include <Eigen/Core>

namespace stiffsoft::abd {

/// 12-vector of an affine body's DOFs, (p, a₁, a₂, a₃): metres and dimensionless.
using Vector12d = Eigen::Matrix<double, 12, 1>;
/// 12×12 matrix over one affine body's DOFs.
using Matrix12d = Eigen::Matrix<double, 12, 12>;
/// J(x̄), 3×12.
using Jacobian = Eigen::Matrix<double, 3, 12>;

/// J(x̄) = [I₃, I₃ ⊗ x̄ᵀ]: x = J(x̄) q.
Jacobian jacobian(const Eigen::Vector3d& x_bar);

/// The translation p of q (m).
inline Eigen::Vector3d translation(const Vector12d& q) { return q.head<3>(); }

/// The affine matrix A of q, whose rows are a₁, a₂, a₃.
Eigen::Matrix3d affine_matrix(const Vector12d& q);

/// q from a translation p (m) and an affine matrix A.
Vector12d make_q(const Eigen::Vector3d& p, const Eigen::Matrix3d& A);

/// World position x = A x̄ + p of the body-frame point x̄ (m).
inline Eigen::Vector3d world_point(const Vector12d& q, const Eigen::Vector3d& x_bar) {
  return q.head<3>() + Eigen::Vector3d(q.segment<3>(3).dot(x_bar), q.segment<3>(6).dot(x_bar),
                                       q.segment<3>(9).dot(x_bar));
}

/// q̇ of a rigid motion: centre-of-mass velocity v (m/s) and world angular velocity ω (rad/s)
/// of a body whose configuration is q: ṗ = v, Ȧ = [ω]× A.
Vector12d rigid_velocity(const Vector12d& q, const Eigen::Vector3d& v, const Eigen::Vector3d& omega);

/// The world angular velocity ω of the rigid part of q̇ at q: the axial vector of the skew part
/// of Ȧ A⁻¹ (the inverse of rigid_velocity for rigid motions), rad/s.
Eigen::Vector3d angular_velocity(const Vector12d& q, const Vector12d& qdot);

/// The configuration reached from q after time t of the rigid motion (v, ω): p + v t and
/// exp([ω]× t) A (exact rotation, Rodrigues).
Vector12d rigid_motion(const Vector12d& q, const Eigen::Vector3d& v, const Eigen::Vector3d& omega,
                       double t);

/// The rotation closest to A (polar decomposition), for reporting orientations.
Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& A);

}  // namespace stiffsoft::abd

#pragma once
/// @file Fixed-size Eigen types of the tetrahedral FEM: vec(F) is column-major (index i + 3j for
/// F_ij), element DOFs are node-major (x₀, y₀, z₀, x₁, …, z₃).

#include <Eigen/Core>

namespace stiffsoft::fem {

/// vec(F), column-major: entry i + 3j is F_ij.
using Vector9d = Eigen::Matrix<double, 9, 1>;
/// A 9×9 matrix over vec(F) (e.g. ∂P/∂F).
using Matrix9d = Eigen::Matrix<double, 9, 9>;
/// The 12 DOFs of one tetrahedron, node-major.
using Vector12d = Eigen::Matrix<double, 12, 1>;
/// A 12×12 matrix over the DOFs of one tetrahedron.
using Matrix12d = Eigen::Matrix<double, 12, 12>;
/// ∂vec(F)/∂x for one tetrahedron.
using Matrix9x12d = Eigen::Matrix<double, 9, 12>;

/// vec(F) (column-major) of a 3×3 matrix.
inline Vector9d vec(const Eigen::Matrix3d& F) { return Eigen::Map<const Vector9d>(F.data()); }

/// The 3×3 matrix whose column-major vec is v (inverse of vec).
inline Eigen::Matrix3d unvec(const Vector9d& v) { return Eigen::Map<const Eigen::Matrix3d>(v.data()); }

}  // namespace stiffsoft::fem

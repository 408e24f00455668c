#pragma once
/// @file The elastic energy of one tetrahedral mesh, Σ_e V_e ψ(F_e(x)), over the positions of all
/// its nodes: x ∈ ℝ^{3N}, node-major (x₀, y₀, z₀, x₁, …), metres.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <memory>
#include <vector>

#include <stiffsoft/libfem/material.hpp>
#include <stiffsoft/libfem/tet_element.hpp>
#include <stiffsoft/libfem/types.hpp>

namespace stiffsoft::fem {

/// One element's Hessian and the mesh nodes its four 3×3 block rows/columns belong to.
struct ElementHessian {
  Matrix12d H;               ///< ∂²(V_e ψ)/∂x_e², 12×12 node-major (N/m)
  std::array<int, 4> nodes;  ///< global node of block row/column a = 0..3 (row a of T)
};

/// Σ_e V_e ψ(F_e) over a linear-tet mesh with one material. Immutable after construction; every
/// method is const and thread-safe. Value and gradient loop over elements in parallel (TBB) and
/// reduce in element order, so results do not depend on the thread count.
class ElasticEnergy {
 public:
  /// Rest positions X (|N|×3, m), tetrahedra T (|T|×4, zero-based node indices; either
  /// orientation), material. Throws std::invalid_argument for an index out of range, a repeated
  /// node in a tet, a null material, or a degenerate tet (naming the element).
  ElasticEnergy(Eigen::MatrixX3d X, Eigen::MatrixX4i T, std::unique_ptr<const Material> material);

  /// Number of nodes N.
  int num_nodes() const { return int(m_X.rows()); }
  /// Number of tetrahedra.
  int num_elements() const { return int(m_T.rows()); }
  /// Rest positions, |N|×3 (m).
  const Eigen::MatrixX3d& rest_positions() const { return m_X; }
  /// Rest positions flattened node-major, 3N (m): the x at which the energy is zero.
  Eigen::VectorXd rest_state() const;
  /// Tetrahedra, |T|×4.
  const Eigen::MatrixX4i& tets() const { return m_T; }
  /// The material.
  const Material& material() const { return *m_material; }
  /// Rest data of element e.
  const TetElement& element(int e) const { return m_elements[e]; }
  /// Rest volume V_e per element, |T| (m³).
  const Eigen::VectorXd& rest_volumes() const { return m_volumes; }

  /// The 12 positions of element e gathered from x (3N, m).
  Vector12d element_positions(int e, const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// F_e(x) of element e.
  Eigen::Matrix3d deformation_gradient(int e, const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// Σ_e V_e ψ(F_e(x)) (J); x has 3N entries.
  double value(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// V_e ψ(F_e(x)) per element, |T| (J).
  Eigen::VectorXd element_values(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// g += ∂value/∂x (N); g has 3N entries (pass a segment of a longer vector to embed).
  void add_gradient(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> g) const;
  /// ∂value/∂x (N), 3N.
  Eigen::VectorXd gradient(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// Element e's 12×12 Hessian, projected to PSD when `project_psd`, with its nodes: block (a, b)
  /// = H.block<3,3>(3a, 3b) goes to global nodes (nodes[a], nodes[b]). Throws
  /// std::invalid_argument for e out of range or x of the wrong size.
  ElementHessian element_hessian(int e, const Eigen::Ref<const Eigen::VectorXd>& x, bool project_psd) const;
  /// element_hessian(e, x, project_psd) weighted by `weight` (an incremental potential's β h²),
  /// formed in place in `out`: what a coupled solver's parallel assembly calls per element.
  void element_hessian(int e, const Eigen::Ref<const Eigen::VectorXd>& x, bool project_psd, double weight,
                       ElementHessian& out) const;
  /// The global Hessian, 3N × 3N, both triangles stored (N/m). A convenience for small problems
  /// and tests; a coupled solver scatters element_hessian blocks itself.
  Eigen::SparseMatrix<double> hessian(const Eigen::Ref<const Eigen::VectorXd>& x, bool project_psd) const;

  /// Von Mises stress of every element's Cauchy stress, |T| (Pa); see Material::von_mises.
  Eigen::VectorXd von_mises(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// Per element: true when det F_e ≤ 0 (inverted or flat), |T|.
  std::vector<bool> inverted(const Eigen::Ref<const Eigen::VectorXd>& x) const;

 private:
  void check_size(const Eigen::Ref<const Eigen::VectorXd>& x, const char* what) const;

  Eigen::MatrixX3d m_X;
  Eigen::MatrixX4i m_T;
  std::unique_ptr<const Material> m_material;
  std::vector<TetElement> m_elements;
  Eigen::VectorXd m_volumes;
};

}  // namespace stiffsoft::fem

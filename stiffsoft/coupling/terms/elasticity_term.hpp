#pragma once
/// @file β h² Σ_e V_e ψ(F_e): the elastic energy of the soft bodies' tetrahedra (libfem).

#include <array>
#include <memory>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/terms/energy_term.hpp>
#include <stiffsoft/libfem/elastic_energy.hpp>

namespace stiffsoft {

/// The elastic energies of all soft bodies, scaled by β h²; fixed nodes enter at their rest
/// positions and receive no gradient. Hessians are projected to PSD per element.
class ElasticityTerm final : public EnergyTerm {
 public:
  /// One libfem::ElasticEnergy per soft body; `scale` is β h² (s²).
  ElasticityTerm(const Model& model, double scale);
  /// See EnergyTerm::name.
  const char* name() const override { return "elasticity"; }
  /// See EnergyTerm::value.
  double value(const Configuration& c) const override;
  /// See EnergyTerm::add_gradient.
  void add_gradient(const Configuration& c, Eigen::VectorXd& g) const override;
  /// See EnergyTerm::add_hessian.
  void add_hessian(const Configuration& c, BlockHessian& H) const override;
  /// Joins the nodes of every element: see EnergyTerm::join_coupled_blocks.
  void join_coupled_blocks(const Configuration& c, const Eigen::MatrixX3d& dx, BlockIslands& islands) const override;
  /// True when the model has no soft body (the term can be left out).
  bool empty() const { return m_bodies.empty(); }
  /// Von Mises stress of every tetrahedron of the model, in Model::nodes.T order (Pa).
  Eigen::VectorXd von_mises(const Eigen::VectorXd& q) const;
  /// Number of inverted tetrahedra (det F ≤ 0) of each body at q, indexed like Model::bodies (0 for affine ones).
  std::vector<int> inverted_per_body(const Eigen::VectorXd& q) const;

 private:
  /// Where an element's 3×3 blocks go: a body's Hessian has a fixed pattern (its mesh's node
  /// pairs), so each element block has a place in the body's own sum, found once; the sums then
  /// enter the global Hessian once per node pair instead of once per element touching it.
  struct ElementSlots {
    /// Per local pair k of kLocalPairs: its node pair's place in SoftBody::sums, −1 where a node
    /// has no DOFs.
    std::array<int, 10> pair;
    /// Whether pair k goes in transposed (its first local node has the higher DOF block).
    std::array<bool, 10> transposed;
  };
  struct SoftBody {
    int index;  // in Model::bodies
    int node_begin;
    std::unique_ptr<fem::ElasticEnergy> energy;
    std::vector<ElementSlots> slots;             // per element
    std::vector<std::array<int, 2>> pair_blocks;  // DOF blocks (row ≤ column) of each node pair
    mutable std::vector<double> sums;            // 9 per node pair: Σ of its element blocks (scratch)
  };
  /// Finds every element block's node pair and the body's pattern (constructor).
  void index_pairs(SoftBody& body) const;
  /// The body's node positions from q, flattened node-major (3N).
  Eigen::VectorXd body_positions(const SoftBody& body, const Eigen::VectorXd& q) const;

  const Model& m_model;
  double m_scale;
  std::vector<SoftBody> m_bodies;
};

}  // namespace stiffsoft

#include <stiffsoft/coupling/terms/elasticity_term.hpp>

#include <algorithm>
#include <map>

#include <stiffsoft/coupling/terms/chunked_assembly.hpp>
#include <stiffsoft/libfem/make_material.hpp>

namespace stiffsoft {

ElasticityTerm::ElasticityTerm(const Model& model, double scale) : m_model(model), m_scale(scale) {
  for (int b = 0; b < int(model.bodies.size()); ++b) {
    const BodyModel& body = model.bodies[b];
    if (body.representation != Representation::Soft) continue;
    const int n = body.node_end - body.node_begin;
    const Eigen::MatrixX4i T =
        model.nodes.T.middleRows(body.tet_begin, body.tet_end - body.tet_begin).array() - body.node_begin;
    m_bodies.push_back({b, body.node_begin, std::make_unique<fem::ElasticEnergy>(
                                             model.nodes.X.middleRows(body.node_begin, n), T,
                                             fem::make_material(body.material.model, body.material.young,
                                                                body.material.poisson)),
                         {}, {}, {}});
    index_pairs(m_bodies.back());
  }
}

namespace {
/// The local node pairs (a, b), a ≤ b, of a tetrahedron's Hessian.
constexpr int kLocalPairs[10][2] = {{0, 0}, {0, 1}, {0, 2}, {0, 3}, {1, 1}, {1, 2}, {1, 3}, {2, 2}, {2, 3}, {3, 3}};
}  // namespace

void ElasticityTerm::index_pairs(SoftBody& body) const {
  const Eigen::MatrixX4i& T = body.energy->tets();
  std::map<std::array<int, 2>, int> place;  // (row block, column block) → node pair
  body.slots.resize(std::size_t(T.rows()));
  for (Eigen::Index e = 0; e < T.rows(); ++e) {
    for (int k = 0; k < 10; ++k) {
      const int block_a = m_model.nodes.block[body.node_begin + T(e, kLocalPairs[k][0])];
      const int block_b = m_model.nodes.block[body.node_begin + T(e, kLocalPairs[k][1])];
      body.slots[e].transposed[k] = block_a > block_b;
      if (block_a < 0 || block_b < 0) {
        body.slots[e].pair[k] = -1;
        continue;
      }
      const std::array<int, 2> key{std::min(block_a, block_b), std::max(block_a, block_b)};
      const auto [it, added] = place.emplace(key, int(body.pair_blocks.size()));
      if (added) body.pair_blocks.push_back(key);
      body.slots[e].pair[k] = it->second;
    }
  }
  body.sums.assign(9 * body.pair_blocks.size(), 0.0);
}

Eigen::VectorXd ElasticityTerm::body_positions(const SoftBody& body, const Eigen::VectorXd& q) const {
  const SoftNodes& nodes = m_model.nodes;
  const int n = body.energy->num_nodes();
  Eigen::VectorXd x(3 * n);
  for (int i = 0; i < n; ++i) {
    const int node = body.node_begin + i;
    x.segment<3>(3 * i) = nodes.dof[node] < 0 ? Eigen::Vector3d(nodes.X.row(node).transpose())
                                              : Eigen::Vector3d(q.segment<3>(nodes.dof[node]));
  }
  return x;
}

double ElasticityTerm::value(const Configuration& c) const {
  double e = 0;
  for (const SoftBody& body : m_bodies) e += body.energy->value(body_positions(body, c.q));
  return m_scale * e;
}

void ElasticityTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  const SoftNodes& nodes = m_model.nodes;
  for (const SoftBody& body : m_bodies) {
    const Eigen::VectorXd gb = body.energy->gradient(body_positions(body, c.q));
    for (int i = 0; i < body.energy->num_nodes(); ++i) {
      const int dof = nodes.dof[body.node_begin + i];
      if (dof >= 0) g.segment<3>(dof) += m_scale * gb.segment<3>(3 * i);
    }
  }
}

void ElasticityTerm::add_hessian(const Configuration& c, BlockHessian& H) const {
  for (const SoftBody& body : m_bodies) {
    const Eigen::VectorXd x = body_positions(body, c.q);
    std::fill(body.sums.begin(), body.sums.end(), 0.0);
    assemble_in_chunks<fem::ElementHessian>(
        std::size_t(body.energy->num_elements()),
        [&](std::size_t e, fem::ElementHessian& out) { body.energy->element_hessian(int(e), x, true, m_scale, out); },
        [&](std::size_t e, const fem::ElementHessian& eh) {
          const ElementSlots& slots = body.slots[e];
          for (int k = 0; k < 10; ++k) {
            if (slots.pair[k] < 0) continue;
            // The block whose row node has the lower DOF block: the pair's upper block.
            const int a = kLocalPairs[k][slots.transposed[k] ? 1 : 0], b = kLocalPairs[k][slots.transposed[k] ? 0 : 1];
            Eigen::Map<Eigen::Matrix3d>(body.sums.data() + 9 * slots.pair[k]) += eh.H.block<3, 3>(3 * a, 3 * b);
          }
        });
    for (std::size_t p = 0; p < body.pair_blocks.size(); ++p)
      H.add(body.pair_blocks[p][0], body.pair_blocks[p][1], Eigen::Map<const Eigen::Matrix3d>(body.sums.data() + 9 * p));
  }
}

Eigen::VectorXd ElasticityTerm::von_mises(const Eigen::VectorXd& q) const {
  Eigen::VectorXd out(m_model.nodes.T.rows());
  Eigen::Index at = 0;
  for (const SoftBody& body : m_bodies) {
    const Eigen::VectorXd s = body.energy->von_mises(body_positions(body, q));
    out.segment(at, s.size()) = s;
    at += s.size();
  }
  return out;
}

std::vector<int> ElasticityTerm::inverted_per_body(const Eigen::VectorXd& q) const {
  std::vector<int> counts(m_model.bodies.size(), 0);
  for (const SoftBody& body : m_bodies)
    for (const bool inverted : body.energy->inverted(body_positions(body, q))) counts[body.index] += inverted;
  return counts;
}

void ElasticityTerm::join_coupled_blocks(const Configuration&, const Eigen::MatrixX3d&, BlockIslands& islands) const {
  for (const SoftBody& body : m_bodies)
    for (const auto& [a, b] : body.pair_blocks) islands.join(a, b);
}

}  // namespace stiffsoft

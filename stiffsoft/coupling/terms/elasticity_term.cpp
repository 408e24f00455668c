#include <stiffsoft/coupling/terms/elasticity_term.hpp>

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
                                                                body.material.poisson))});
  }
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
  const SoftNodes& nodes = m_model.nodes;
  for (const SoftBody& body : m_bodies) {
    const Eigen::VectorXd x = body_positions(body, c.q);
    assemble_in_chunks<fem::ElementHessian>(
        std::size_t(body.energy->num_elements()),
        [&](std::size_t e, fem::ElementHessian& out) { body.energy->element_hessian(int(e), x, true, m_scale, out); },
        [&](std::size_t, const fem::ElementHessian& eh) {
          std::array<int, 4> block;
          for (int a = 0; a < 4; ++a) block[a] = nodes.block[body.node_begin + eh.nodes[a]];
          for (int a = 0; a < 4; ++a) {
            if (block[a] < 0) continue;
            for (int b = 0; b < 4; ++b) {
              if (block[b] < block[a]) continue;  // each unordered pair once; add() keeps the upper triangle
              H.add(block[a], block[b], eh.H.block<3, 3>(3 * a, 3 * b));
            }
          }
        });
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

}  // namespace stiffsoft

#include <stiffsoft/coupling/terms/orthogonality_term.hpp>

#include <tbb/parallel_for.h>

#include <vector>

#include <stiffsoft/libabd/orthogonality_potential.hpp>

namespace stiffsoft {

OrthogonalityTerm::OrthogonalityTerm(const Model& model, double scale) {
  for (const BodyModel& body : model.bodies)
    if (body.representation == Representation::Affine && body.motion == Motion::Dynamic)
      m_bodies.push_back({body.block, body.dof, scale * body.kappa * body.volume});
}

double OrthogonalityTerm::value(const Configuration& c) const {
  double e = 0;
  for (const Body& b : m_bodies)
    e += abd::orthogonality_potential(c.q.segment<12>(b.dof), b.kappa_volume, 1.0);
  return e;
}

void OrthogonalityTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  for (const Body& b : m_bodies)
    g.segment<12>(b.dof) +=
        abd::orthogonality_potential_gradient(c.q.segment<12>(b.dof), b.kappa_volume, 1.0);
}

void OrthogonalityTerm::add_hessian(const Configuration& c, BlockHessian& H) const {
  // Each body's block in parallel; the blocks are disjoint, added serially.
  std::vector<abd::Matrix12d> local(m_bodies.size());
  tbb::parallel_for(size_t(0), m_bodies.size(), [&](size_t k) {
    local[k] = abd::orthogonality_potential_hessian(c.q.segment<12>(m_bodies[k].dof), m_bodies[k].kappa_volume, 1.0, true);
  });
  for (size_t k = 0; k < m_bodies.size(); ++k) H.add(m_bodies[k].block, m_bodies[k].block, local[k]);
}

}  // namespace stiffsoft

#include <stiffsoft/coupling/terms/orthogonality_term.hpp>

#include <stiffsoft/coupling/for_each_item.hpp>
#include <stiffsoft/coupling/terms/ordered_sum.hpp>
#include <stiffsoft/libabd/orthogonality_potential.hpp>

namespace stiffsoft {

OrthogonalityTerm::OrthogonalityTerm(const Model& model, double scale) {
  for (const BodyModel& body : model.bodies)
    if (body.representation == Representation::Affine && body.motion == Motion::Dynamic)
      m_bodies.push_back({body.block, body.dof, scale * body.kappa * body.volume});
}

// Bodies in parallel: the energy summed in their order, each gradient into its own segment.
namespace {
constexpr std::size_t kBodyGrain = 32;
}  // namespace

double OrthogonalityTerm::value(const Configuration& c) const {
  return ordered_sum(0.0, m_bodies.size(), kBodyGrain, [&](std::size_t k) {
    return abd::orthogonality_potential(c.q.segment<12>(m_bodies[k].dof), m_bodies[k].kappa_volume, 1.0);
  });
}

void OrthogonalityTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  for_each_item(m_bodies.size(), kBodyGrain, [&](std::size_t k) {
    const Body& b = m_bodies[k];
    g.segment<12>(b.dof) += abd::orthogonality_potential_gradient(c.q.segment<12>(b.dof), b.kappa_volume, 1.0);
  });
}

void OrthogonalityTerm::add_hessian(const Configuration& c, BlockHessian& H) const {
  // Each body its own diagonal block: threads add different ones at once.
  for_each_item(m_bodies.size(), kBodyGrain, [&](std::size_t k) {
    const Body& b = m_bodies[k];
    H.add(b.block, b.block,
          abd::orthogonality_potential_hessian(c.q.segment<12>(b.dof), b.kappa_volume, 1.0, true));
  });
}

}  // namespace stiffsoft

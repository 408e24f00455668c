#include <stiffsoft/coupling/terms/friction_term.hpp>

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <stiffsoft/coupling/for_each_item.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>
#include <stiffsoft/coupling/terms/owned_assembly.hpp>
#include <stiffsoft/coupling/terms/ordered_sum.hpp>

namespace stiffsoft {

namespace {
/// Stencils per task when friction is lagged: a friction stencil costs about 1,000
/// instructions, a task's hand-out a few µs.
constexpr std::size_t kRelagGrain = 64;
}  // namespace

FrictionTerm::FrictionTerm(const Model& model, double mu, double epsv_h)
    : m_model(model), m_mu(mu), m_epsv_h(epsv_h) {}

void FrictionTerm::lag(const Configuration& c, const BarrierTerm& barrier) {
  m_x_lag = c.x;
  m_flips = 0;
  relag(c, barrier);
}

void FrictionTerm::relag(const Configuration& c, const BarrierTerm& barrier) {
  const std::vector<ContactConstraint>& constraints = barrier.constraints();
  const std::size_t n = constraints.size();
  m_stencils.resize(n);
  m_vertices.resize(n);
  m_lagged.resize(n);
  m_majorized.assign(n, 0);
  m_slip.assign(n, Slip::None);
  m_jacobians.resize(n, StencilJacobian(m_model, {-1, -1, -1, -1}));  // every one set below
  m_block_rank = barrier.block_rank();  // ranked where the barrier built these contacts
  // What normal_force_per_body made for the barrier's contacts at c (update() at c), with this κ.
  const bool made = m_made.barrier == &barrier && m_made.build == barrier.build() && m_made.build != 0 &&
                    m_made.kappa == barrier.kappa();
  if (made) m_stencils.swap(m_made.stencils);
  m_made.build = 0;  // used up (the buffers kept for the next step's)
  for_each_item(n, kRelagGrain, [&](std::size_t k) {
    const ContactConstraint& constraint = constraints[k];
    if (!made)
      m_stencils[k] = contact::make_friction_stencil(constraint.stencil, gather(c.x, constraint.vertices),
                                                     barrier.dhat(), barrier.kappa() * constraint.weight);
    m_vertices[k] = constraint.vertices;
    m_lagged[k] = gather(m_x_lag, constraint.vertices);
    m_jacobians[k] = StencilJacobian(m_model, constraint.vertices);
  });
}

namespace {
/// Adds λ to each body the stencil's vertices belong to, once per body.
void add_per_body(const Model& model, const std::array<int, 4>& vertices, double lambda, std::vector<double>& sums) {
  int counted[4] = {-1, -1, -1, -1};
  for (int i = 0; i < 4; ++i) {
    if (vertices[i] < 0) continue;
    const int b = model.mesh.vertex_body[vertices[i]];
    if (std::find(counted, counted + i, b) != counted + i) continue;
    counted[i] = b;
    sums[b] += lambda;
  }
}
}  // namespace

std::vector<double> FrictionTerm::normal_force_per_body() const {
  std::vector<double> sums(m_model.bodies.size(), 0.0);
  for (size_t k = 0; k < m_stencils.size(); ++k) add_per_body(m_model, m_vertices[k], m_stencils[k].normal_force, sums);
  return sums;
}

std::vector<double> FrictionTerm::normal_force_per_body(const Configuration& c, const BarrierTerm& barrier) {
  const std::vector<ContactConstraint>& constraints = barrier.constraints();
  m_made.stencils.resize(constraints.size());
  for_each_item(constraints.size(), kRelagGrain, [&](std::size_t k) {
    const ContactConstraint& constraint = constraints[k];
    m_made.stencils[k] = contact::make_friction_stencil(constraint.stencil, gather(c.x, constraint.vertices),
                                                        barrier.dhat(), barrier.kappa() * constraint.weight);
  });
  m_made.barrier = &barrier;
  m_made.build = barrier.build();
  m_made.kappa = barrier.kappa();
  std::vector<double> sums(m_model.bodies.size(), 0.0);  // summed in the constraints' order, as before
  for (std::size_t k = 0; k < constraints.size(); ++k)
    add_per_body(m_model, constraints[k].vertices, m_made.stencils[k].normal_force, sums);
  return sums;
}

contact::Vector12d FrictionTerm::displacement(const Configuration& c, size_t k) const {
  return gather(c.x, m_vertices[k]) - m_lagged[k];
}

double FrictionTerm::stick_zone_step(const Configuration& c, const Eigen::MatrixX3d& dx) const {
  // max is exact in any order: the same result whatever the thread count.
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, m_stencils.size(), 256), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double worst) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
          const contact::FrictionStencil& f = m_stencils[k];
          if (!(f.normal_force > 0) || (f.T * displacement(c, k)).norm() >= m_epsv_h) continue;
          worst = std::max(worst, (f.T * gather(dx, m_vertices[k])).norm() / m_epsv_h);
        }
        return worst;
      },
      [](double a, double b) { return std::max(a, b); });
}

FrictionTerm::Slip FrictionTerm::slip(const Configuration& c, size_t k) const {
  const contact::FrictionStencil& f = m_stencils[k];
  if (!(f.normal_force > 0)) return Slip::None;
  return (f.T * displacement(c, k)).norm() < m_epsv_h ? Slip::Sticking : Slip::Sliding;
}

FrictionTerm::StickSlip FrictionTerm::stick_slip(const Configuration& c) const {
  // Sums of integers: the same whatever the thread count.
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, m_stencils.size(), 256), StickSlip{},
      [&](const tbb::blocked_range<size_t>& r, StickSlip counts) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
          const Slip state = slip(c, k);
          counts.sticking += state == Slip::Sticking;
          counts.sliding += state == Slip::Sliding;
        }
        return counts;
      },
      [](StickSlip a, const StickSlip& b) {
        a.sticking += b.sticking;
        a.sliding += b.sliding;
        return a;
      });
}

bool FrictionTerm::end_iteration(const Configuration& c) {
  // Each stencil's state is its own, and the count a sum of integers.
  m_flips += tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, m_stencils.size(), 256), 0,
      [&](const tbb::blocked_range<size_t>& r, int flips) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
          const Slip state = slip(c, k);
          flips += m_slip[k] != Slip::None && state != Slip::None && state != m_slip[k];
          m_slip[k] = state;
        }
        return flips;
      },
      [](int a, int b) { return a + b; });
  return false;
}

double FrictionTerm::value(const Configuration& c) const {
  // The stencils' energies in parallel, summed in their order.
  return ordered_sum(0.0, m_stencils.size(), 64, [&](std::size_t k) {
    return contact::friction_potential(m_stencils[k], displacement(c, k), m_mu, m_epsv_h);
  });
}

void FrictionTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  assemble_gradient_by_owner<contact::Vector12d>(
      int(m_model.blocks.size()), m_block_rank, m_stencils.size(),
      [&](size_t k) { return m_jacobians[k].block; },
      [&](size_t k, contact::Vector12d& out) {
        out = contact::friction_potential_gradient(m_stencils[k], displacement(c, k), m_mu, m_epsv_h);
      },
      [&](size_t k, const contact::Vector12d& out, const BlockOwner& owner) {
        m_jacobians[k].scatter_gradient(out, g, owner);
      });
}

void FrictionTerm::add_hessian(const Configuration& c, BlockHessian& H) const {
  assemble_hessian_by_owner(
      H, int(m_model.blocks.size()), m_block_rank, m_stencils.size(),
      [&](size_t k) { return m_jacobians[k].block; },
      [&](size_t k, StencilHessian& out) {
        // Rank ≤ 2: T is mapped through J before any 12×12 product is formed.
        const contact::Vector12d u = displacement(c, k);
        const contact::FrictionHessianFactors h =
            m_majorized[k] ? contact::friction_majorizer_factors(m_stencils[k], u, m_mu, m_epsv_h)
                           : contact::friction_hessian_factors(m_stencils[k], u, m_mu, m_epsv_h, true);
        m_jacobians[k].low_rank_block_hessians(h.T, h.C, out);
      });
}

bool FrictionTerm::revise_hessian(const Configuration& c, const Eigen::VectorXd&, const Eigen::MatrixX3d& dx,
                                  BlockHessian& H) const {
  // The stencils whose slide the step reverses switch to their majorizer (each flag its own:
  // the same flags whatever the thread count).
  const std::vector<std::size_t> reversed = selected_items(m_stencils.size(), [&](std::size_t k) {
    if (m_majorized[k] ||
        !contact::step_reverses_slide(m_stencils[k], displacement(c, k), gather(dx, m_vertices[k]), m_epsv_h))
      return false;
    m_majorized[k] = 1;
    return true;
  });
  // Both models are Tᵀ C T with the same T: the change is Tᵀ (C_majorizer − C) T, rank ≤ 2.
  assemble_hessian_by_owner(
      H, int(m_model.blocks.size()), m_block_rank, reversed.size(),
      [&](size_t i) { return m_jacobians[reversed[i]].block; },
      [&](size_t i, StencilHessian& out) {
        const size_t k = reversed[i];
        const contact::Vector12d u = displacement(c, k);
        const contact::FrictionHessianFactors majorizer =
            contact::friction_majorizer_factors(m_stencils[k], u, m_mu, m_epsv_h);
        const contact::FrictionHessianFactors exact =
            contact::friction_hessian_factors(m_stencils[k], u, m_mu, m_epsv_h, true);
        m_jacobians[k].low_rank_block_hessians(exact.T, Eigen::Matrix2d(majorizer.C - exact.C), out);
      });
  const bool revised = !reversed.empty();
  return revised;
}

Eigen::MatrixX3d FrictionTerm::vertex_forces(const Configuration& c) const {
  Eigen::MatrixX3d f = Eigen::MatrixX3d::Zero(c.x.rows(), 3);
  for (size_t k = 0; k < m_stencils.size(); ++k) {
    const contact::Vector12d g =
        contact::friction_potential_gradient(m_stencils[k], displacement(c, k), m_mu, m_epsv_h);
    for (int i = 0; i < 4; ++i)
      if (m_vertices[k][i] >= 0) f.row(m_vertices[k][i]) -= g.segment<3>(3 * i).transpose();
  }
  return f;
}

void FrictionTerm::join_coupled_blocks(const Configuration&, const Eigen::MatrixX3d&, BlockIslands& islands) const {
  for (const StencilJacobian& J : m_jacobians) islands.join_blocks(J.block);
}

}  // namespace stiffsoft

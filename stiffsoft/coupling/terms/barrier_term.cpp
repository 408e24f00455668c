#include <stiffsoft/coupling/terms/barrier_term.hpp>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

#include <stiffsoft/coupling/ccd/ccd.hpp>
#include <stiffsoft/coupling/contact/clear_motion.hpp>
#include <stiffsoft/coupling/contact/distance_classification.hpp>
#include <stiffsoft/coupling/contact/ordered_chunks.hpp>
#include <stiffsoft/coupling/contact/squared_distance.hpp>
#include <stiffsoft/coupling/contact/projected_barrier_hessian.hpp>
#include <stiffsoft/coupling/for_each_item.hpp>
#include <stiffsoft/coupling/model/stencil_jacobian.hpp>
#include <stiffsoft/coupling/terms/block_order.hpp>
#include <stiffsoft/coupling/terms/owned_assembly.hpp>

namespace stiffsoft {

namespace {

/// Jᵀ (Gᵀ diag(λ) G) J by pairs of DOF blocks, through the rank of the projected Hessian
/// (3 for most contacts) instead of its 12×12 form: the same blocks to round-off.
void add_low_rank_blocks(const StencilJacobian& J, const contact::LowRankHessian& H, StencilHessian& out) {
  const auto blocks = [&](auto rank) {
    constexpr int R = decltype(rank)::value;
    J.low_rank_block_hessians<R>(H.G.topRows<R>(), H.lambda.head<R>().asDiagonal(), out);
  };
  switch (H.rank) {
    case 0: J.block_hessians(contact::Matrix12d::Zero(), out); break;  // the pattern as before
    case 1: blocks(std::integral_constant<int, 1>{}); break;
    case 2: blocks(std::integral_constant<int, 2>{}); break;
    case 3: blocks(std::integral_constant<int, 3>{}); break;
    case 4: blocks(std::integral_constant<int, 4>{}); break;
    default: blocks(std::integral_constant<int, 5>{}); break;
  }
}
/// Slack of a direction's swept candidates (SweptCandidates), in d̂: a resting pile's bodies
/// breathe by about 10 µm per 1 ms step, and with a tenth of d̂ (0.1 mm on the seed's piles) the
/// same candidates serve several steps' moves, each trial looking only at their near ones
/// (docs/benchmarks.md, session 48).
constexpr double kSweptSlack = 0.1;
/// A move's islands are joined by its candidate pairs whose swept boxes, grown by d̂/2 plus
/// this, in d̂, meet (SweptCandidates::tight; the slack the candidates had before session 48,
/// so the same islands).
constexpr double kIslandSlack = 0.01;
/// Candidate pairs per chunk when a move's islands are joined: a pair's blocks cost a few ns to
/// look up, a chunk's hand-out a few µs.
constexpr std::size_t kJoinGrain = 4096;
/// Whether a step from distance d0 to d1 (both in m, d0 < d̂) releases a contact: leaves it
/// 35–65 % of its way out of d̂, as Newton on the barrier's cubic tail does (half of it).
bool releases(double d0, double d1, double dhat) {
  const double rest = (dhat - d1) / (dhat - d0);
  return rest >= 0.35 && rest <= 0.65;
}
/// κ_min of IPC (ipc-toolkit, initial_barrier_stiffness): the stiffness at which the barrier's
/// curvature at d = 1e-8 × diagonal balances 1e11 × the average mass.
double kappa_min(const BarrierSettings& s) {
  const double d0 = std::pow(1e-8 * s.bbox_diagonal, 2);
  const double curvature = 4 * d0 * contact::barrier_second_derivative(d0, s.dhat);
  return 1e11 * s.average_mass / curvature;
}
}  // namespace

BarrierTerm::BarrierTerm(const Model& model, const BarrierSettings& settings, PhaseTimes* times)
    : m_model(model), m_settings(settings), m_times(times),
      // A body's pairs are found again once it moves d̂ out of its last boxes (on medium,
      // margins of 0.5, 1, 2 and 4 d̂ cost the same within this machine's noise).
      m_vertex_block(vertex_blocks(model)),
      m_broad_phase(settings.dhat) {
  m_kappa = settings.kappa ? *settings.kappa : kappa_min(settings);
  m_kappa_max = settings.kappa ? *settings.kappa : 100 * m_kappa;
}

void BarrierTerm::update(const Configuration& c) {
  // The contacts depend on c.x alone (whichever candidate set finds them, the pairs closer
  // than d̂ and their multiplicities are the same).
  if (built_at(c.x)) return;
  // The last kKeptBuilds builds, most recent first, rotated through m_constraints: a surface
  // among them takes its contacts back.
  for (std::size_t k = 0; k < kKeptBuilds; ++k) {
    m_constraints.swap(m_previous[k]);
    m_constraints_at.swap(m_previous_at[k]);
    std::swap(m_build, m_previous_build[k]);
    if (built_at(c.x)) return;
  }
  double dummy = 0;
  ScopedTimer timer(m_times ? m_times->broad_phase : dummy);
  if (m_swept && m_swept->covers(c.x)) {
    m_constraints = covered_constraints(c.x);
  } else {
    const Candidates candidates = m_broad_phase.find(m_model, c.x, c.x, 0.5 * m_settings.dhat);
    m_constraints = build_constraints(m_model, c.x, candidates, m_settings.dhat);
  }
  if (!m_still_body.empty()) {
    const std::vector<int>& body = m_model.mesh.vertex_body;
    std::erase_if(m_constraints, [&](const ContactConstraint& k) {
      return std::all_of(k.vertices.begin(), k.vertices.end(), [&](int v) { return v < 0 || m_still_body[body[v]]; });
    });
  }
  m_constraints_at = c.x;
  m_build = ++m_builds;
  if (available_threads() > 1) m_block_rank = blocks_along_widest_axis(m_model, c.q);  // one thread: no parts
}

void BarrierTerm::hold_still(const std::vector<char>& still) {
  const bool any = std::find(still.begin(), still.end(), 1) != still.end();
  std::vector<char> marks = any ? still : std::vector<char>{};
  if (marks == m_still_body) return;
  m_still_body = std::move(marks);
  m_constraints_at.resize(0, 3);  // no build is at any surface now
  for (Eigen::MatrixX3d& at : m_previous_at) at.resize(0, 3);
}

void BarrierTerm::sweep(const Configuration& c, const Eigen::MatrixX3d& x1) const {
  if (m_swept && m_swept->advance(m_model, c.x, x1)) return;
  m_swept.emplace(m_model, c.x, x1, 0.5 * m_settings.dhat, kSweptSlack * m_settings.dhat, kIslandSlack * m_settings.dhat,
                  m_broad_phase);
}

std::vector<ContactConstraint> BarrierTerm::covered_constraints(const Eigen::MatrixX3d& x) const {
  // The first configuration the candidates serve sorts out those that can come within d̂
  // anywhere they serve; later ones (the line search's trials, the next step's start at rest)
  // look at those alone. After advance() only the moved bodies' new pairs are sorted out.
  if (const Candidates* pending = m_swept->pending()) {
    const std::vector<double> reach = m_swept->reach_from(x);
    Candidates near;
    const NearCandidates sort_out{reach, near};
    build_constraints(m_model, x, *pending, m_settings.dhat, &sort_out);
    m_swept->add_near(m_model, near, reach);
  }
  if (const Candidates* near = m_swept->near()) return build_constraints(m_model, x, *near, m_settings.dhat);
  const std::vector<double> reach = m_swept->reach_from(x);
  Candidates near;
  const NearCandidates sort_out{reach, near};
  std::vector<ContactConstraint> out = build_constraints(m_model, x, m_swept->all(), m_settings.dhat, &sort_out);
  m_swept->keep_near(m_model, std::move(near), reach);
  return out;
}

double BarrierTerm::value(const Configuration& c) const {
  // Deterministic: the same run gives the same energies, bit for bit, whatever the schedule.
  // Ranges of 64 stencils or fewer are summed in a loop (the split is fixed by the range
  // alone); split down to single stencils, the reduction's tasks cost as much as the barrier.
  // At the contacts' own surface (every trial's) the distances are the build's.
  const std::vector<double>* d2 = built_at(c.x) ? &squared_distances(c) : nullptr;
  const double sum = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<size_t>(0, m_constraints.size(), 64), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double acc) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
          const ContactConstraint& s = m_constraints[k];
          const contact::Vector12d x = gather(c.x, s.vertices);
          acc += s.weight * (d2 ? contact::barrier_potential(s.stencil, x, (*d2)[k], m_settings.dhat)
                                : contact::barrier_potential(s.stencil, x, m_settings.dhat));
        }
        return acc;
      },
      std::plus<>());
  return m_kappa * sum;
}

std::array<int, 4> BarrierTerm::stencil_blocks(size_t k) const {
  std::array<int, 4> b;
  for (std::size_t i = 0; i < 4; ++i) {
    const int v = m_constraints[k].vertices[i];
    b[i] = v < 0 ? -1 : m_vertex_block[std::size_t(v)];
  }
  return b;
}

void BarrierTerm::add_gradient(const Configuration& c, Eigen::VectorXd& g) const {
  const std::vector<double>* d2 = built_at(c.x) ? &squared_distances(c) : nullptr;  // as in value()
  assemble_gradient_by_owner<contact::Vector12d>(
      int(m_model.blocks.size()), m_block_rank, m_constraints.size(),
      [&](size_t k) { return stencil_blocks(k); },
      [&](size_t k, contact::Vector12d& out) {
        const ContactConstraint& s = m_constraints[k];
        const contact::Vector12d x = gather(c.x, s.vertices);
        out = m_kappa * s.weight *
              (d2 ? contact::barrier_potential_gradient(s.stencil, x, (*d2)[k], m_settings.dhat)
                  : contact::barrier_potential_gradient(s.stencil, x, m_settings.dhat));
      },
      [&](size_t k, const contact::Vector12d& out, const BlockOwner& owner) {
        StencilJacobian(m_model, m_constraints[k].vertices).scatter_gradient(out, g, owner);
      });
}

void BarrierTerm::stencil_hessian(const Configuration& c, size_t k, double scale, StencilHessian& out) const {
  const ContactConstraint& s = m_constraints[k];
  const contact::Vector12d x = gather(c.x, s.vertices);
  const StencilJacobian J(m_model, s.vertices);
  if (m_settings.hessian == contact::BarrierHessian::Projected && !contact::mollifier_active(s.stencil, x)) {
    contact::LowRankHessian H_x = contact::projected_barrier_factors(s.stencil, x, m_settings.dhat);
    H_x.lambda *= scale * m_kappa * s.weight;
    add_low_rank_blocks(J, H_x, out);
    return;
  }
  J.block_hessians(scale * m_kappa * s.weight * contact::barrier_newton_hessian(s.stencil, x, m_settings.dhat, m_settings.hessian),
                   out);
}

void BarrierTerm::add_hessian(const Configuration& c, BlockHessian& H) const {
  assemble_hessian_by_owner(H, int(m_model.blocks.size()), m_block_rank, m_constraints.size(),
                            [&](size_t k) { return stencil_blocks(k); },
                            [&](size_t k, StencilHessian& out) { stencil_hessian(c, k, 1.0, out); });
}

bool BarrierTerm::revise_hessian(const Configuration& c, const Eigen::VectorXd&, const Eigen::MatrixX3d& dx,
                                 BlockHessian& H) const {
  const double fraction = m_settings.release_hessian;
  if (fraction == 1.0) return false;
  const double dhat = m_settings.dhat;
  const std::vector<double>& d2_0 = squared_distances(c);
  const std::vector<double>& d2_1 = squared_distances(c, &dx);
  const std::vector<std::size_t> released = selected_items(m_constraints.size(), [&](std::size_t k) {
    return releases(std::sqrt(d2_0[k]), std::sqrt(d2_1[k]), dhat);
  });
  // H holds each stencil's whole Hessian: adding fraction − 1 of it leaves fraction.
  assemble_hessian_by_owner(
      H, int(m_model.blocks.size()), m_block_rank, released.size(),
      [&](size_t i) { return stencil_blocks(released[i]); },
      [&](size_t i, StencilHessian& out) { stencil_hessian(c, released[i], fraction - 1.0, out); });
  const bool revised = !released.empty();
  return revised;
}

double BarrierTerm::max_step(const Configuration& c, const Eigen::VectorXd&, const Eigen::MatrixX3d& dx) const {
  double dummy = 0;
  ScopedTimer timer(m_times ? m_times->ccd : dummy);
  const Eigen::MatrixX3d x1 = c.x + dx;
  m_cut.clear();
  if (keeps_clear(c, x1)) return 1.0;
  // One broad phase for the CCD and every line-search trial of this direction (update()).
  sweep(c, x1);
  std::vector<double> bound{1.0};
  ccd_bounds(c.x, x1, nullptr, bound);
  return bound[0];
}

void BarrierTerm::join_coupled_blocks(const Configuration& c, const Eigen::MatrixX3d& dx, BlockIslands& islands) const {
  double dummy = 0;
  ScopedTimer timer(m_times ? m_times->ccd : dummy);
  const Eigen::MatrixX3d x1 = c.x + dx;
  m_cut.clear();
  m_move_clear = keeps_clear(c, x1);
  const CollisionMesh& mesh = m_model.mesh;
  const std::vector<int>& block = m_vertex_block;
  // Joins the blocks of every pair. The pairs come body pair by body pair, so a pair's blocks
  // are mostly the last pair's: chunks of pairs list their blocks in parallel without those
  // repeats, and the few lists left are joined in turn (the islands do not depend on the order
  // of the joins: each is numbered from its smallest block).
  using Joins = std::vector<std::array<int, 4>>;
  const auto add = [](Joins& part, const std::array<int, 4>& b) {
    if (part.empty()) return part.push_back(b);
    const std::array<int, 4>& last = part.back();
    if (last[0] != b[0] || last[1] != b[1] || last[2] != b[2] || last[3] != b[3]) part.push_back(b);
  };
  const auto join_all = [&](const Joins& part) {
    for (const std::array<int, 4>& blocks : part) islands.join_blocks(blocks);
  };
  const auto join_pairs = [&](const Candidates& pairs) {
    in_ordered_chunks<Joins>(pairs.vertex_face.size(), kJoinGrain, [&](std::size_t k, Joins& part) {
      const auto& [v, f] = pairs.vertex_face[k];
      add(part, {block[v], block[mesh.F(f, 0)], block[mesh.F(f, 1)], block[mesh.F(f, 2)]});
    }, join_all);
    in_ordered_chunks<Joins>(pairs.edge_edge.size(), kJoinGrain, [&](std::size_t k, Joins& part) {
      const auto& [ea, eb] = pairs.edge_edge[k];
      add(part, {block[mesh.E(ea, 0)], block[mesh.E(ea, 1)], block[mesh.E(eb, 0)], block[mesh.E(eb, 1)]});
    }, join_all);
  };
  if (m_move_clear) {
    // Every CCD bound of a kept move is 1, so its islands step alike; they are joined by the
    // pairs that can come within d̂ on it (all covered), few at rest.
    if (!m_swept->near()) covered_constraints(c.x);
    join_pairs(*m_swept->near());
    return;
  }
  sweep(c, x1);
  join_pairs(m_swept->tight());
}

void BarrierTerm::max_step_per_island(const Configuration& c, const Eigen::VectorXd&, const Eigen::MatrixX3d& dx,
                                      const BlockIslands& islands, std::vector<double>& bound) const {
  double dummy = 0;
  ScopedTimer timer(m_times ? m_times->ccd : dummy);
  if (m_move_clear) return;
  ccd_bounds(c.x, c.x + dx, islands.count() == 1 ? nullptr : &islands, bound);
}

void BarrierTerm::entering_pairs(const Configuration& c, std::vector<EnteringPair>& out) const {
  const double dhat2 = m_settings.dhat * m_settings.dhat;
  for (const CutPair& cut : m_cut) {
    const std::array<int, 4>& v = cut.vertices;
    const auto soft = [&](int u) { return m_model.mesh.vertex_node[std::size_t(u)] >= 0; };
    if (std::any_of(v.begin(), v.end(), soft)) continue;  // affine and fixed bodies only (see the header)
    const auto row = [&](int i) -> Eigen::Vector3d { return c.x.row(v[std::size_t(i)]).transpose(); };
    const contact::Classified k = cut.vertex_face ? contact::classify_point_triangle(row(0), row(1), row(2), row(3))
                                                  : contact::classify_edge_edge(row(0), row(1), row(2), row(3));
    const contact::Vector12d sub = contact::gather_classified(k, gather(c.x, v));
    const double d2 = contact::squared_distance(k.kind, sub);
    if (d2 < dhat2) continue;  // an active contact: the barrier's model has it
    const double d = std::sqrt(d2);
    const contact::Vector12d normal = contact::scatter_classified(k, contact::squared_distance_gradient(k.kind, sub)) / (2 * d);
    out.push_back({v, cut.vertex_face, normal, d - kEnteringGap * m_settings.dhat});
  }
}

bool BarrierTerm::keeps_clear(const Configuration& c, const Eigen::MatrixX3d& x1) const {
  if (!m_swept) return false;
  const std::optional<std::vector<int>> moved = m_swept->extension(m_model, c.x, x1);
  if (!moved || !built_at(c.x)) return false;
  // The move's own broad phase would find a subset of these pairs (the moved bodies have none).
  const ccd::CcdSettings ccd_settings{};  // the queries' own
  const ClearMotion clear(m_constraints, c.x, x1, m_settings.dhat, ccd_settings);
  // Where no body left its boxes, a pair that is not near stays at least d̂ apart on the move,
  // and its gap d changes by at most 4 R, R the larger reach of its two bodies (body_reach).
  // ACCD returns less than t_max only once d − ξ falls below s (d₀ − ξ), which needs d₀ − ξ >
  // (d̂ − ξ) / s and then a change of more than (1 − s)(d̂ − ξ) / s (9 d̂ with the defaults): with
  // R well below that, such pairs would return t_max and need no test. So the near pairs are
  // tested, and of the others only those of a body that reaches farther.
  const double no_cut = (1 - ccd_settings.tolerance) * (m_settings.dhat - ccd_settings.min_distance) / ccd_settings.tolerance;
  const CollisionMesh& mesh = m_model.mesh;
  const auto vertex_face_clear = [&](const std::array<int, 2>& k) {
    return clear.is_clear({k[0], mesh.F(k[1], 0), mesh.F(k[1], 1), mesh.F(k[1], 2)});
  };
  const auto edge_edge_clear = [&](const std::array<int, 2>& k) {
    return clear.is_clear({mesh.E(k[0], 0), mesh.E(k[0], 1), mesh.E(k[1], 0), mesh.E(k[1], 1)});
  };
  const auto all_clear = [&](const Candidates& pairs) {
    return std::all_of(pairs.vertex_face.begin(), pairs.vertex_face.end(), vertex_face_clear) &&
           std::all_of(pairs.edge_edge.begin(), pairs.edge_edge.end(), edge_edge_clear);
  };
  const Candidates* near = moved->empty() ? m_swept->near() : nullptr;
  if (!near) {
    if (!all_clear(m_swept->all())) return false;
  } else {
    if (!all_clear(*near)) return false;
    const std::vector<double>& reach = m_swept->body_reach();
    const auto far = [&](double r) { return 8 * r > no_cut; };
    if (std::any_of(reach.begin(), reach.end(), far)) {
      const auto body_far = [&](const std::vector<int>& body_of, int primitive) {
        return far(reach[std::size_t(body_of[std::size_t(primitive)])]);
      };
      const Candidates& all = m_swept->all();
      for (const auto& k : all.vertex_face)
        if ((body_far(mesh.vertex_body, k[0]) || body_far(mesh.face_body, k[1])) && !vertex_face_clear(k)) return false;
      for (const auto& k : all.edge_edge)
        if ((body_far(mesh.edge_body, k[0]) || body_far(mesh.edge_body, k[1])) && !edge_edge_clear(k)) return false;
    }
  }
  m_swept->extend(m_model, c.x, x1, *moved);
  ++m_kept_moves;
  return true;
}

void BarrierTerm::ccd_bounds(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, const BlockIslands* islands,
                             std::vector<double>& bound) const {
  const Candidates& candidates = m_swept->for_ccd();
  const CollisionMesh& mesh = m_model.mesh;
  const PointRows x0_rows = x0, x1_rows = x1;  // each query reads its points from 8 places, not 24
  const auto row = [](const PointRows& m, int i) -> Eigen::Vector3d { return m.row(i).transpose(); };
  const auto vertex_face_vertices = [&](std::size_t k) {
    const auto [v, f] = candidates.vertex_face[k];
    return std::array<int, 4>{v, mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
  };
  const auto edge_edge_vertices = [&](std::size_t k) {
    const auto [ea, eb] = candidates.edge_edge[k];
    return std::array<int, 4>{mesh.E(ea, 0), mesh.E(ea, 1), mesh.E(eb, 0), mesh.E(eb, 1)};
  };
  // With the active set built at x0, the pairs whose vertices move too little to close their
  // clearance need no query (a resting pile's almost all): skipping them gives the same times.
  std::optional<ClearMotion> clear;
  if (built_at(x0))
    clear.emplace(m_constraints, x0, x1, m_settings.dhat, ccd::CcdSettings{});
  const auto vertex_face_time = [&](const std::array<int, 4>& v, const ccd::CcdSettings& s) {
    if (clear && clear->is_clear(v)) return s.t_max;
    return ccd::point_triangle_toi(row(x0_rows, v[0]), row(x0_rows, v[1]), row(x0_rows, v[2]), row(x0_rows, v[3]),
                                   row(x1_rows, v[0]), row(x1_rows, v[1]), row(x1_rows, v[2]), row(x1_rows, v[3]), s);
  };
  const auto edge_edge_time = [&](const std::array<int, 4>& v, const ccd::CcdSettings& s) {
    if (clear && clear->is_clear(v)) return s.t_max;
    return ccd::edge_edge_toi(row(x0_rows, v[0]), row(x0_rows, v[1]), row(x0_rows, v[2]), row(x0_rows, v[3]),
                              row(x1_rows, v[0]), row(x1_rows, v[1]), row(x1_rows, v[2]), row(x1_rows, v[3]), s);
  };
  // Per island (one without `islands`): its point–triangle pairs with t_max = 1, then its
  // edge–edge pairs with t_max = their minimum, never a time another query found (the time
  // ACCD returns depends on its bound). Every query of a pass looks up to the bound the pass
  // started with, and the times are reduced after it by minima (exact in any order), so the
  // bounds do not depend on the thread count and the split of the work.
  const auto island_of = [&](const std::array<int, 4>& vertices) {
    for (int v : vertices) {
      const int b = v < 0 ? -1 : m_vertex_block[std::size_t(v)];
      if (b >= 0) return islands ? islands->island(b) : 0;
    }
    return -1;  // no vertex moves: nothing to bound
  };
  std::vector<double> t_max(bound.size(), 1.0);
  m_cut.clear();
  // The pairs whose query stopped before the bound it looked up to: cut, and their times lower
  // their island's bound once every query of the pass is done.
  struct Stop {
    CutPair pair;
    int island;
    double time;
  };
  const auto lower = [&](std::size_t count, const auto& vertices_of, const auto& time_of, bool vertex_face) {
    tbb::enumerable_thread_specific<std::vector<Stop>> stops;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<Stop>& local = stops.local();
      ccd::CcdSettings s;
      for (std::size_t k = r.begin(); k < r.end(); ++k) {
        const std::array<int, 4> vertices = vertices_of(k);
        const int island = island_of(vertices);
        if (island < 0) continue;
        s.t_max = t_max[std::size_t(island)];
        const double time = s.t_max > 0 ? time_of(vertices, s) : 0.0;
        if (time < s.t_max) local.push_back({{vertices, vertex_face}, island, time});
      }
    });
    // In the threads' order, which neither the minima nor the sorted cut pairs depend on.
    for (const std::vector<Stop>& local : stops)
      for (const Stop& stop : local) {
        m_cut.push_back(stop.pair);
        t_max[std::size_t(stop.island)] = std::min(t_max[std::size_t(stop.island)], stop.time);
      }
  };
  lower(candidates.vertex_face.size(), vertex_face_vertices, vertex_face_time, true);
  lower(candidates.edge_edge.size(), edge_edge_vertices, edge_edge_time, false);
  // In an order of their own: the candidates' order depends on the broad phase's memory (the
  // calls before, its slack), and the springs on these pairs are summed in this order.
  std::sort(m_cut.begin(), m_cut.end(), [](const CutPair& a, const CutPair& b) {
    return std::make_pair(a.vertex_face, a.vertices) < std::make_pair(b.vertex_face, b.vertices);
  });
  for (std::size_t i = 0; i < bound.size(); ++i) bound[i] = std::min(bound[i], t_max[i]);
}

const std::vector<double>& BarrierTerm::squared_distances(const Configuration& c, const Eigen::MatrixX3d* dx) const {
  SquaredDistances& kept = m_squared[dx ? 1 : 0];
  if (kept.build == m_build && (!dx || (kept.dx.rows() == dx->rows() && kept.dx == *dx))) return kept.d2;
  kept.d2.resize(m_constraints.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, m_constraints.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const ContactConstraint& k = m_constraints[i];
      contact::Vector12d x = gather(c.x, k.vertices);
      if (dx) x += gather(*dx, k.vertices);
      kept.d2[i] = contact::stencil_squared_distance(k.stencil, x);
    }
  });
  kept.build = m_build;
  if (dx) kept.dx = *dx;
  return kept.d2;
}

double BarrierTerm::relative_gap_change(const Configuration& c, const Eigen::MatrixX3d& dx) const {
  const std::vector<double>& d2_0 = squared_distances(c);
  const std::vector<double>& d2_1 = squared_distances(c, &dx);
  double worst = 0;  // max is exact in any order
  for (size_t i = 0; i < d2_0.size(); ++i) {
    const double d0 = std::sqrt(d2_0[i]);
    worst = std::max(worst, std::abs(std::sqrt(d2_1[i]) - d0) / d0);
  }
  return worst;
}

double BarrierTerm::min_active_distance(const Configuration& c) const {
  double smallest = std::numeric_limits<double>::infinity();
  if (built_at(c.x)) {
    for (double d2 : squared_distances(c)) smallest = std::min(smallest, d2);
  } else {  // elsewhere (a result projected onto joints' equalities after the last build)
    for (const ContactConstraint& k : m_constraints)
      smallest = std::min(smallest, contact::stencil_squared_distance(k.stencil, gather(c.x, k.vertices)));
  }
  return std::sqrt(smallest);
}

bool BarrierTerm::end_iteration(const Configuration& c) {
  if (m_settings.kappa) return false;
  const double d = min_active_distance(c);
  const double eps = 1e-9 * m_settings.bbox_diagonal;
  const double before = m_kappa;
  if (m_prev_min_distance >= 0 && m_prev_min_distance < eps && d < eps && d < m_prev_min_distance)
    m_kappa = std::min(m_kappa_max, 2 * m_kappa);
  m_prev_min_distance = d;
  return m_kappa != before;
}

void BarrierTerm::initialize_stiffness(const Configuration& c, const Eigen::VectorXd& grad_other) {
  m_prev_min_distance = -1;
  // Balance once, when contact first appears; re-balancing every step would change the force
  // at a given distance from one step to the next (and with it the lagged friction).
  if (m_settings.kappa || !m_settings.balance || m_constraints.empty() || m_balanced) return;
  m_balanced = true;
  const double saved = m_kappa;
  m_kappa = 1.0;
  Eigen::VectorXd grad_barrier = Eigen::VectorXd::Zero(grad_other.size());
  add_gradient(c, grad_barrier);
  const double k_min = m_kappa_max / 100;
  m_kappa = saved;
  if (grad_barrier.squaredNorm() <= 0) return;
  const double balanced = -grad_barrier.dot(grad_other) / grad_barrier.squaredNorm();
  m_kappa = std::clamp(balanced, k_min, m_kappa_max);
}

Eigen::MatrixX3d BarrierTerm::vertex_forces(const Configuration& c) const {
  Eigen::MatrixX3d f = Eigen::MatrixX3d::Zero(c.x.rows(), 3);
  for (const ContactConstraint& k : m_constraints) {
    const contact::Vector12d gx = m_kappa * k.weight *
                                  contact::barrier_potential_gradient(k.stencil, gather(c.x, k.vertices), m_settings.dhat);
    for (int i = 0; i < 4; ++i)
      if (k.vertices[i] >= 0) f.row(k.vertices[i]) -= gx.segment<3>(3 * i).transpose();
  }
  return f;
}

}  // namespace stiffsoft

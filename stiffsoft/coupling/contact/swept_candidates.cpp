#include <stiffsoft/coupling/contact/swept_candidates.hpp>

#include <stiffsoft/coupling/contact/ordered_chunks.hpp>

namespace stiffsoft {

SweptCandidates::SweptCandidates(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                                 double proximity, double slack, BroadPhase& finder)
    : m_lo(x0.array().min(x1.array())),
      m_hi(x0.array().max(x1.array())),
      m_slack(slack),
      m_all(finder.find(model, x0, x1, proximity + slack)) {}

bool SweptCandidates::covers(const Eigen::MatrixX3d& x) const {
  if (x.rows() != m_lo.rows()) return false;
  return ((x.array() >= m_lo - m_slack).all() && (x.array() <= m_hi + m_slack).all());
}

Candidates SweptCandidates::for_ccd(const Model& model) const {
  const CollisionMesh& mesh = model.mesh;
  // Box of a primitive (no growth) from its vertices' swept boxes; two primitives are kept
  // when those boxes overlap, as broad_phase(x0, x1, 0) decides.
  const auto overlap = [&](auto&& va, int na, auto&& vb, int nb) {
    Eigen::Array3d alo = m_lo.row(va(0)).transpose(), ahi = m_hi.row(va(0)).transpose();
    for (int i = 1; i < na; ++i) {
      alo = alo.min(m_lo.row(va(i)).transpose());
      ahi = ahi.max(m_hi.row(va(i)).transpose());
    }
    Eigen::Array3d blo = m_lo.row(vb(0)).transpose(), bhi = m_hi.row(vb(0)).transpose();
    for (int i = 1; i < nb; ++i) {
      blo = blo.min(m_lo.row(vb(i)).transpose());
      bhi = bhi.max(m_hi.row(vb(i)).transpose());
    }
    return (alo <= bhi).all() && (blo <= ahi).all();
  };
  using Pairs = std::vector<std::array<int, 2>>;
  // The pairs of `from` that pass, in their order.
  const auto kept = [](const Pairs& from, const auto& passes) {
    Pairs to;
    in_ordered_chunks<Pairs>(
        from.size(), 1024, [&](std::size_t k, Pairs& part) { if (passes(from[k])) part.push_back(from[k]); },
        [&](const Pairs& part) { to.insert(to.end(), part.begin(), part.end()); });
    return to;
  };
  Candidates out;
  out.vertex_face = kept(m_all.vertex_face, [&](const std::array<int, 2>& vf) {
    return overlap([v = vf[0]](int) { return v; }, 1, [&, f = vf[1]](int i) { return mesh.F(f, i); }, 3);
  });
  out.edge_edge = kept(m_all.edge_edge, [&](const std::array<int, 2>& ee) {
    return overlap([&, a = ee[0]](int i) { return mesh.E(a, i); }, 2, [&, b = ee[1]](int i) { return mesh.E(b, i); }, 2);
  });
  return out;
}

}  // namespace stiffsoft

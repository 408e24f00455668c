#include <stiffsoft/coupling/model/block_islands.hpp>

#include <stiffsoft/coupling/model/model.hpp>

#include <algorithm>

namespace stiffsoft {

BlockIslands::BlockIslands(int blocks) : m_parent(std::size_t(blocks)) {
  for (int b = 0; b < blocks; ++b) m_parent[std::size_t(b)] = b;
}

int BlockIslands::root(int b) {
  while (m_parent[std::size_t(b)] != b) {
    m_parent[std::size_t(b)] = m_parent[std::size_t(m_parent[std::size_t(b)])];  // path halving
    b = m_parent[std::size_t(b)];
  }
  return b;
}

void BlockIslands::join(int a, int b) {
  if (a < 0 || b < 0 || m_all) return;
  const int ra = root(a), rb = root(b);
  if (ra != rb) m_parent[std::size_t(std::max(ra, rb))] = std::min(ra, rb);
}

void BlockIslands::join_blocks(const std::array<int, 4>& blocks) {
  int first = -1;
  for (int b : blocks) {
    if (b < 0) continue;
    if (first < 0)
      first = b;
    else if (b != first)
      join(first, b);
  }
}

void BlockIslands::join_all() { m_all = true; }

void BlockIslands::number() {
  const std::size_t n = m_parent.size();
  m_island.assign(n, 0);
  m_count = 1;  // also without blocks: one (empty) island, so that there is always a bound
  if (m_all || n == 0) return;
  std::vector<int> of_root(n, -1);
  m_count = 0;
  for (std::size_t b = 0; b < n; ++b) {
    int& id = of_root[std::size_t(root(int(b)))];
    if (id < 0) id = m_count++;
    m_island[b] = id;
  }
}

Eigen::VectorXd BlockIslands::scaled(const Model& model, const Eigen::VectorXd& dq, const std::vector<double>& scale) const {
  Eigen::VectorXd out = dq;
  for (std::size_t b = 0; b < model.blocks.size(); ++b)
    out.segment(model.blocks[b].offset, model.blocks[b].size) *= scale[std::size_t(m_island[b])];
  return out;
}

int vertex_block(const Model& model, int v) {
  const int node = model.mesh.vertex_node[std::size_t(v)];
  return node < 0 ? model.bodies[std::size_t(model.mesh.vertex_body[std::size_t(v)])].block
                  : model.nodes.block[std::size_t(node)];
}

std::vector<int> vertex_blocks(const Model& model) {
  std::vector<int> out(model.mesh.vertex_body.size());
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = vertex_block(model, int(v));
  return out;
}

}  // namespace stiffsoft

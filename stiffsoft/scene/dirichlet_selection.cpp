#include <stiffsoft/scene/dirichlet_selection.hpp>

#include <sstream>

#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

std::vector<int> dirichlet_nodes(const TetMesh& mesh, const DirichletDescription& condition) {
  using Select = DirichletDescription::Select;
  if (condition.select == Select::NodeSet) {
    const auto it = mesh.node_sets.find(condition.node_set);
    return it == mesh.node_sets.end() ? std::vector<int>{} : it->second;
  }
  std::vector<int> nodes;
  for (int i = 0; i < int(mesh.X.rows()); ++i) {
    const Eigen::Vector3d x = mesh.X.row(i).transpose();
    const bool selected = condition.select == Select::Box
                              ? (x.array() >= condition.min.array()).all() && (x.array() <= condition.max.array()).all()
                              : (x - condition.point).dot(condition.normal) >= 0;
    if (selected) nodes.push_back(i);
  }
  return nodes;
}

void apply_dirichlet(const TetMesh& mesh, const std::vector<DirichletDescription>& conditions,
                     const std::string& body_name, const std::string& file, const std::string& path,
                     std::vector<Motion>& motion, Eigen::MatrixX3d& velocity) {
  for (size_t j = 0; j < conditions.size(); ++j) {
    const DirichletDescription& c = conditions[j];
    const std::vector<int> nodes = dirichlet_nodes(mesh, c);
    if (nodes.empty()) {
      std::ostringstream what;
      what << "selects no node of body '" << body_name << "'";
      if (c.select == DirichletDescription::Select::NodeSet) {
        what << ": no node set named '" << c.node_set << "' (the mesh has:";
        for (const auto& [name, set] : mesh.node_sets) what << " '" << name << "'";
        what << (mesh.node_sets.empty() ? " none)" : ")");
      } else {
        const Eigen::RowVector3d lo = mesh.X.colwise().minCoeff(), hi = mesh.X.colwise().maxCoeff();
        what << " (its nodes span [" << lo << "] to [" << hi << "] m in the world frame)";
      }
      throw SceneError(file, path + ".dirichlet[" + std::to_string(j) + "]", what.str());
    }
    const bool fixed = c.velocity.isZero(0);
    for (const int i : nodes) {
      motion[i] = fixed ? Motion::Fixed : Motion::Kinematic;
      velocity.row(i) = c.velocity.transpose();
    }
  }
}

}  // namespace stiffsoft

#include <stiffsoft/libfem/elastic_energy.hpp>

#include <tbb/parallel_for.h>

#include <Eigen/LU>
#include <stdexcept>
#include <string>

namespace stiffsoft::fem {

namespace {
/// Runs body(e) for every element in parallel; each e writes only its own output slot.
template <typename Body>
void for_each_element(int num_elements, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, num_elements, 256), [&](const tbb::blocked_range<int>& r) {
    for (int e = r.begin(); e != r.end(); ++e) body(e);
  });
}
}  // namespace

ElasticEnergy::ElasticEnergy(Eigen::MatrixX3d X, Eigen::MatrixX4i T, std::unique_ptr<const Material> material)
    : m_X(std::move(X)), m_T(std::move(T)), m_material(std::move(material)) {
  if (!m_material) throw std::invalid_argument("libfem: ElasticEnergy needs a material, got null");
  const int n = num_nodes();
  m_elements.reserve(m_T.rows());
  m_volumes.resize(m_T.rows());
  for (int e = 0; e < num_elements(); ++e) {
    for (int a = 0; a < 4; ++a) {
      const int v = m_T(e, a);
      if (v < 0 || v >= n)
        throw std::invalid_argument("libfem: tetrahedron " + std::to_string(e) + " has node index " +
                                    std::to_string(v) + "; expected 0 <= index < " + std::to_string(n));
      for (int b = 0; b < a; ++b)
        if (m_T(e, b) == v)
          throw std::invalid_argument("libfem: tetrahedron " + std::to_string(e) + " repeats node " +
                                      std::to_string(v));
    }
    Vector12d Xe;
    for (int a = 0; a < 4; ++a) Xe.segment<3>(3 * a) = m_X.row(m_T(e, a)).transpose();
    m_elements.push_back(make_tet_element(Xe, e));
    m_volumes[e] = m_elements.back().volume;
  }
}

Eigen::VectorXd ElasticEnergy::rest_state() const {
  Eigen::VectorXd x(3 * num_nodes());
  for (int i = 0; i < num_nodes(); ++i) x.segment<3>(3 * i) = m_X.row(i).transpose();
  return x;
}

void ElasticEnergy::check_size(const Eigen::Ref<const Eigen::VectorXd>& x, const char* what) const {
  if (x.size() != 3 * num_nodes())
    throw std::invalid_argument(std::string("libfem: ElasticEnergy: ") + what + " has " +
                                std::to_string(x.size()) + " entries; expected 3 * " +
                                std::to_string(num_nodes()) + " nodes");
}

Vector12d ElasticEnergy::element_positions(int e, const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Vector12d xe;
  for (int a = 0; a < 4; ++a) xe.segment<3>(3 * a) = x.segment<3>(3 * m_T(e, a));
  return xe;
}

Eigen::Matrix3d ElasticEnergy::deformation_gradient(int e, const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return fem::deformation_gradient(m_elements[e], element_positions(e, x));
}

Eigen::VectorXd ElasticEnergy::element_values(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  check_size(x, "x");
  Eigen::VectorXd values(num_elements());
  for_each_element(num_elements(), [&](int e) {
    values[e] = tet_energy(m_elements[e], *m_material, element_positions(e, x));
  });
  return values;
}

double ElasticEnergy::value(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const Eigen::VectorXd values = element_values(x);
  double sum = 0;
  for (Eigen::Index e = 0; e < values.size(); ++e) sum += values[e];  // fixed order: deterministic
  return sum;
}

void ElasticEnergy::add_gradient(const Eigen::Ref<const Eigen::VectorXd>& x,
                                 Eigen::Ref<Eigen::VectorXd> g) const {
  check_size(x, "x");
  check_size(g, "g");
  std::vector<Vector12d> local(num_elements());
  for_each_element(num_elements(), [&](int e) {
    local[e] = tet_gradient(m_elements[e], *m_material, element_positions(e, x));
  });
  // Scatter in element order so the sums are bitwise reproducible.
  for (int e = 0; e < num_elements(); ++e)
    for (int a = 0; a < 4; ++a) g.segment<3>(3 * m_T(e, a)) += local[e].segment<3>(3 * a);
}

Eigen::VectorXd ElasticEnergy::gradient(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * num_nodes());
  add_gradient(x, g);
  return g;
}

ElementHessian ElasticEnergy::element_hessian(int e, const Eigen::Ref<const Eigen::VectorXd>& x,
                                              bool project_psd) const {
  ElementHessian out;
  element_hessian(e, x, project_psd, 1.0, out);
  return out;
}

void ElasticEnergy::element_hessian(int e, const Eigen::Ref<const Eigen::VectorXd>& x, bool project_psd,
                                    double weight, ElementHessian& out) const {
  if (e < 0 || e >= num_elements())
    throw std::invalid_argument("libfem: element_hessian: element " + std::to_string(e) +
                                " out of range; expected 0 <= e < " + std::to_string(num_elements()));
  check_size(x, "x");
  tet_hessian(m_elements[e], *m_material, element_positions(e, x), project_psd, weight, out.H);
  out.nodes = {m_T(e, 0), m_T(e, 1), m_T(e, 2), m_T(e, 3)};
}

Eigen::SparseMatrix<double> ElasticEnergy::hessian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                   bool project_psd) const {
  check_size(x, "x");
  std::vector<Matrix12d> local(num_elements());
  for_each_element(num_elements(), [&](int e) {
    local[e] = tet_hessian(m_elements[e], *m_material, element_positions(e, x), project_psd);
  });
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(144 * std::size_t(num_elements()));
  for (int e = 0; e < num_elements(); ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            triplets.emplace_back(3 * m_T(e, a) + i, 3 * m_T(e, b) + j, local[e](3 * a + i, 3 * b + j));
  Eigen::SparseMatrix<double> H(3 * num_nodes(), 3 * num_nodes());
  H.setFromTriplets(triplets.begin(), triplets.end());
  return H;
}

Eigen::VectorXd ElasticEnergy::von_mises(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  check_size(x, "x");
  Eigen::VectorXd s(num_elements());
  for_each_element(num_elements(), [&](int e) { s[e] = m_material->von_mises(deformation_gradient(e, x)); });
  return s;
}

std::vector<bool> ElasticEnergy::inverted(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  check_size(x, "x");
  std::vector<bool> out(num_elements());
  for (int e = 0; e < num_elements(); ++e) out[e] = deformation_gradient(e, x).determinant() <= 0;
  return out;
}

}  // namespace stiffsoft::fem

#include <stiffsoft/coupling/contact/barrier_potential.hpp>

#include <stiffsoft/coupling/contact/projected_barrier_hessian.hpp>

namespace stiffsoft::contact {

Classified classify_edge_edge_stencil(const Vector12d& x) {
  return classify_edge_edge(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9));
}

double stencil_squared_distance(const Stencil& s, const Vector12d& x) {
  if (!uses_segment_distance(s)) return squared_distance(s.kind, x);
  const Classified c = classify_edge_edge_stencil(x);
  return squared_distance(c.kind, gather_classified(c, x));
}

Vector12d stencil_squared_distance_gradient(const Stencil& s, const Vector12d& x) {
  if (!uses_segment_distance(s)) return squared_distance_gradient(s.kind, x);
  const Classified c = classify_edge_edge_stencil(x);
  return scatter_classified(c, squared_distance_gradient(c.kind, gather_classified(c, x)));
}

Matrix12d stencil_squared_distance_hessian(const Stencil& s, const Vector12d& x) {
  if (!uses_segment_distance(s)) return squared_distance_hessian(s.kind, x);
  const Classified c = classify_edge_edge_stencil(x);
  return scatter_classified(c, squared_distance_hessian(c.kind, gather_classified(c, x)));
}

ClosestPoints stencil_closest_points(const Stencil& s, const Vector12d& x) {
  if (!uses_segment_distance(s)) return closest_points(s.kind, x);
  const Classified c = classify_edge_edge_stencil(x);
  ClosestPoints sub = closest_points(c.kind, gather_classified(c, x));
  ClosestPoints out = sub;
  out.weights.setZero();
  for (int i = 0; i < vertex_count(c.kind); ++i) out.weights[c.local[i]] += sub.weights[i];
  return out;
}

double barrier_potential(const Stencil& s, const Vector12d& x, double dhat) {
  return barrier_potential(s, x, stencil_squared_distance(s, x), dhat);
}

double barrier_potential(const Stencil& s, const Vector12d& x, double d2, double dhat) {
  if (d2 >= dhat * dhat) return 0.0;
  const double b = barrier(d2, dhat);
  return is_mollified(s) ? edge_edge_mollifier(x, s.eps_x) * b : b;
}

bool mollifier_active(const Stencil& s, const Vector12d& x) {
  return is_mollified(s) && edge_edge_cross_squared_norm(x) < s.eps_x;
}

Vector12d barrier_potential_gradient(const Stencil& s, const Vector12d& x, double dhat) {
  return barrier_potential_gradient(s, x, stencil_squared_distance(s, x), dhat);
}

Vector12d barrier_potential_gradient(const Stencil& s, const Vector12d& x, double d2, double dhat) {
  if (d2 >= dhat * dhat) return Vector12d::Zero();
  const Vector12d grad_d2 = stencil_squared_distance_gradient(s, x);
  const double db = barrier_first_derivative(d2, dhat);
  if (!is_mollified(s)) return db * grad_d2;
  return edge_edge_mollifier(x, s.eps_x) * db * grad_d2 +
         barrier(d2, dhat) * edge_edge_mollifier_gradient(x, s.eps_x);
}

Matrix12d barrier_potential_hessian(const Stencil& s, const Vector12d& x, double dhat,
                                    bool project_psd) {
  // Where the mollifier is 1 its terms vanish and the Hessian is the unmollified one, which
  // projects in ≤ 5 dimensions instead of 9.
  if (project_psd && !mollifier_active(s, x)) return projected_barrier_hessian(s, x, dhat);
  const double d2 = stencil_squared_distance(s, x);
  if (d2 >= dhat * dhat) return Matrix12d::Zero();
  const Vector12d grad_d2 = stencil_squared_distance_gradient(s, x);
  const double db = barrier_first_derivative(d2, dhat);
  const double ddb = barrier_second_derivative(d2, dhat);
  Matrix12d H = ddb * grad_d2 * grad_d2.transpose() + db * stencil_squared_distance_hessian(s, x);
  if (is_mollified(s)) {
    const double m = edge_edge_mollifier(x, s.eps_x);
    const Vector12d grad_m = edge_edge_mollifier_gradient(x, s.eps_x);
    H = m * H + db * (grad_m * grad_d2.transpose() + grad_d2 * grad_m.transpose()) +
        barrier(d2, dhat) * edge_edge_mollifier_hessian(x, s.eps_x);
  }
  if (project_psd) project_translation_invariant_to_psd(H, vertex_count(s.kind));
  return H;
}

Matrix12d barrier_gauss_newton_hessian(const Stencil& s, const Vector12d& x, double dhat) {
  const double d2 = stencil_squared_distance(s, x);
  if (d2 >= dhat * dhat) return Matrix12d::Zero();
  const Vector12d grad_d2 = stencil_squared_distance_gradient(s, x);
  return barrier_gauss_newton_coefficient(d2, dhat) * grad_d2 * grad_d2.transpose();
}

Matrix12d barrier_newton_hessian(const Stencil& s, const Vector12d& x, double dhat, BarrierHessian method) {
  if (method == BarrierHessian::GaussNewton && !mollifier_active(s, x)) return barrier_gauss_newton_hessian(s, x, dhat);
  return barrier_potential_hessian(s, x, dhat, true);
}
}  // namespace stiffsoft::contact

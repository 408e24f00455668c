#include <stiffsoft/meshing/tet_quality.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace stiffsoft {

TetShape tet_shape(const TetMesh& mesh, Eigen::Index t) {
  Eigen::Vector3d x[4];
  for (int k = 0; k < 4; ++k) x[k] = mesh.X.row(mesh.T(t, k));

  TetShape shape;
  shape.min_dihedral_angle_deg = std::numeric_limits<double>::infinity();
  shape.max_dihedral_angle_deg = -std::numeric_limits<double>::infinity();
  // The dihedral angle at edge (i, j) is the angle between the other two nodes k, l seen along the
  // edge: the angle between their offsets projected onto the plane normal to the edge.
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      int other[2], n = 0;
      for (int k = 0; k < 4; ++k)
        if (k != i && k != j) other[n++] = k;
      const Eigen::Vector3d e = (x[j] - x[i]).normalized();
      Eigen::Vector3d u = x[other[0]] - x[i], w = x[other[1]] - x[i];
      u -= u.dot(e) * e;
      w -= w.dot(e) * e;
      // atan2 keeps full precision near 0° and 180°, where acos of a dot product does not.
      const double angle = std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi;
      shape.min_dihedral_angle_deg = std::min(shape.min_dihedral_angle_deg, angle);
      shape.max_dihedral_angle_deg = std::max(shape.max_dihedral_angle_deg, angle);
    }

  const Eigen::Vector3d a = x[1] - x[0], b = x[2] - x[0], c = x[3] - x[0];
  const double six_volume = std::abs(a.cross(b).dot(c));
  const double area = 0.5 * (a.cross(b).norm() + b.cross(c).norm() + c.cross(a).norm() +
                             (x[2] - x[1]).cross(x[3] - x[1]).norm());
  const Eigen::Vector3d circumcentre_times_2det =
      a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b);
  // r_in = 3V / A = six_volume / (2A); r_circ = |…| / (2 · six_volume)  ⇒  3 r_in / r_circ:
  const double numerator = 3.0 * six_volume * six_volume;
  const double denominator = area * circumcentre_times_2det.norm();
  shape.radius_ratio = denominator > 0.0 ? numerator / denominator : 0.0;
  return shape;
}

TetQuality tet_quality(const TetMesh& mesh) {
  TetQuality q;
  q.num_nodes = static_cast<int>(mesh.X.rows());
  q.num_tets = static_cast<int>(mesh.T.rows());
  if (mesh.T.rows() == 0) return q;
  constexpr double inf = std::numeric_limits<double>::infinity();
  q.min_tet_volume = inf;
  q.min_dihedral_angle_deg = inf;
  q.max_dihedral_angle_deg = -inf;
  q.min_radius_ratio = inf;
  q.min_edge_length = inf;
  q.max_edge_length = 0.0;
  double ratio_sum = 0.0;
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    const double V = tet_signed_volume(mesh, t);
    q.volume += V;
    q.min_tet_volume = std::min(q.min_tet_volume, V);
    const TetShape s = tet_shape(mesh, t);
    q.min_dihedral_angle_deg = std::min(q.min_dihedral_angle_deg, s.min_dihedral_angle_deg);
    q.max_dihedral_angle_deg = std::max(q.max_dihedral_angle_deg, s.max_dihedral_angle_deg);
    q.min_radius_ratio = std::min(q.min_radius_ratio, s.radius_ratio);
    ratio_sum += s.radius_ratio;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const double l = (mesh.X.row(mesh.T(t, b)) - mesh.X.row(mesh.T(t, a))).norm();
        q.min_edge_length = std::min(q.min_edge_length, l);
        q.max_edge_length = std::max(q.max_edge_length, l);
      }
  }
  q.mean_radius_ratio = ratio_sum / static_cast<double>(mesh.T.rows());
  return q;
}

std::string summary(const TetQuality& q) {
  char line[320];
  std::snprintf(
      line, sizeof line,
      "%d nodes, %d tets, volume %.6g m³, dihedral angles [%.3g°, %.4g°], radius ratio min %.3g mean "
      "%.3g, edges [%.3g, %.3g] m",
      q.num_nodes, q.num_tets, q.volume, q.min_dihedral_angle_deg, q.max_dihedral_angle_deg,
      q.min_radius_ratio, q.mean_radius_ratio, q.min_edge_length, q.max_edge_length);
  return line;
}

}  // namespace stiffsoft

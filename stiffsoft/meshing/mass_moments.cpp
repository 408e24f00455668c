#include <stiffsoft/meshing/mass_moments.hpp>

#include <Eigen/Geometry>

namespace stiffsoft {

MassMoments mass_moments(const SurfaceMesh& mesh) {
  MassMoments m;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose();
    const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose();
    const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose();
    const double V = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d s = a + b + c;
    m.volume += V;
    m.first += (V / 4.0) * s;
    m.second += (V / 20.0) * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  return m;
}

}  // namespace stiffsoft

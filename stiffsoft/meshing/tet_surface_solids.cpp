#include <stiffsoft/meshing/tet_surface_solids.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include <stiffsoft/meshing/mass_moments.hpp>

namespace stiffsoft {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<size_t>(i)] != i)
    i = parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
  return i;
}

std::string shell_text(const SurfaceSolids& s, int k) {
  return "shell " + std::to_string(k) + " (from face " +
         std::to_string(s.shells[static_cast<size_t>(k)].faces.front()) + ", volume " +
         std::to_string(s.shells[static_cast<size_t>(k)].volume) + " m³)";
}

}  // namespace

double winding_number(const SurfaceMesh& surface, const std::vector<int>& faces, const Eigen::Vector3d& p) {
  double sum = 0.0;
  for (int f : faces) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0)).transpose() - p;
    const Eigen::Vector3d b = surface.V.row(surface.F(f, 1)).transpose() - p;
    const Eigen::Vector3d c = surface.V.row(surface.F(f, 2)).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4.0 * std::numbers::pi);
}

SurfaceSolids surface_solids(const SurfaceMesh& surface, const std::string& what) {
  // Components: faces joined through shared vertices (a closed manifold shares edges along them).
  const auto n = static_cast<int>(surface.V.rows());
  std::vector<int> parent(static_cast<size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, surface.F(f, 0)), b = find_root(parent, surface.F(f, k));
      if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
    }
  SurfaceSolids s;
  std::vector<int> shell_of_root(static_cast<size_t>(n), -1);
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    int& shell = shell_of_root[static_cast<size_t>(find_root(parent, surface.F(f, 0)))];
    if (shell < 0) {
      shell = static_cast<int>(s.shells.size());
      s.shells.emplace_back();
    }
    s.shells[static_cast<size_t>(shell)].faces.push_back(static_cast<int>(f));
  }
  for (auto& shell : s.shells) {
    SurfaceMesh part;
    part.V = surface.V;
    part.F.resize(static_cast<Eigen::Index>(shell.faces.size()), 3);
    for (size_t i = 0; i < shell.faces.size(); ++i)
      part.F.row(static_cast<Eigen::Index>(i)) = surface.F.row(shell.faces[i]);
    shell.volume = mass_moments(part).volume;
  }

  const auto count = static_cast<int>(s.shells.size());
  std::vector<int> solid_of_shell(static_cast<size_t>(count), -1);
  for (int k = 0; k < count; ++k)
    if (s.shells[static_cast<size_t>(k)].volume > 0.0) {
      solid_of_shell[static_cast<size_t>(k)] = static_cast<int>(s.solids.size());
      s.solids.push_back({k, {}});
    }
  if (count == 1) return s;

  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d p = surface.V.row(surface.F(s.shells[static_cast<size_t>(k)].faces.front(), 0));
    double total = 0.0;  // winding number of all other shells: how deep in material p is
    int smallest_around = -1;
    for (int j = 0; j < count; ++j) {
      if (j == k) continue;
      const double w = winding_number(surface, s.shells[static_cast<size_t>(j)].faces, p);
      total += w;
      if (s.shells[static_cast<size_t>(j)].volume > 0.0 && w > 0.5 &&
          (smallest_around < 0 ||
           s.shells[static_cast<size_t>(j)].volume < s.shells[static_cast<size_t>(smallest_around)].volume))
        smallest_around = j;
    }
    const long depth = std::lround(total);
    if (s.shells[static_cast<size_t>(k)].volume > 0.0) {
      if (depth != 0)
        throw std::runtime_error(what + ": " + shell_text(s, k) +
                                 " lies inside the material of another shell (nested solids overlap)");
    } else {
      if (depth != 1 || smallest_around < 0)
        throw std::runtime_error(what + ": " + shell_text(s, k) +
                                 " faces inward (a cavity) but lies in no solid's material");
      s.solids[static_cast<size_t>(solid_of_shell[static_cast<size_t>(smallest_around)])].cavities.push_back(
          k);
    }
  }
  return s;
}

}  // namespace stiffsoft

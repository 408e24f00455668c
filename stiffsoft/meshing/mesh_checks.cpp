#include <stiffsoft/meshing/mesh_checks.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <stiffsoft/meshing/mass_moments.hpp>

namespace stiffsoft {
namespace {

std::string face_text(const SurfaceMesh& mesh, Eigen::Index f) {
  std::ostringstream s;
  s << "face " << f << " (" << mesh.F(f, 0) << ", " << mesh.F(f, 1) << ", " << mesh.F(f, 2) << ")";
  return s.str();
}

/// one use of an undirected edge by a face
struct EdgeUse {
  std::uint64_t key;  // min(a,b) · |V| + max(a,b)
  bool forward;       // traversed min → max
  int face;
  bool operator<(const EdgeUse& o) const { return key != o.key ? key < o.key : face < o.face; }
};

}  // namespace

std::optional<std::string> closed_manifold_problem(const SurfaceMesh& mesh) {
  const auto& V = mesh.V;
  const auto& F = mesh.F;
  const std::uint64_t n = static_cast<std::uint64_t>(V.rows());
  if (F.rows() == 0) return "has no faces";

  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= V.rows())
        return face_text(mesh, f) + " has vertex index " + std::to_string(F(f, k)) + " out of range [0, " +
               std::to_string(V.rows()) + ")";

  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    if (a == b || b == c || c == a) return face_text(mesh, f) + " repeats a vertex (degenerate)";
    const Eigen::Vector3d pa = V.row(a), pb = V.row(b), pc = V.row(c);
    const double longest2 = std::max({(pb - pa).squaredNorm(), (pc - pb).squaredNorm(), (pa - pc).squaredNorm()});
    if ((pb - pa).cross(pc - pa).norm() <= degenerate_area_tolerance * longest2)
      return face_text(mesh, f) + " has (numerically) zero area (degenerate)";
  }

  std::vector<EdgeUse> uses;
  uses.reserve(3 * static_cast<size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = static_cast<std::uint64_t>(F(f, k)), b = static_cast<std::uint64_t>(F(f, (k + 1) % 3));
      uses.push_back({std::min(a, b) * n + std::max(a, b), a < b, static_cast<int>(f)});
    }
  std::sort(uses.begin(), uses.end());
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    const std::string edge =
        "edge (" + std::to_string(uses[i].key / n) + ", " + std::to_string(uses[i].key % n) + ")";
    if (j - i == 1)
      return edge + " has only one face, " + face_text(mesh, uses[i].face) + ": the surface is not closed";
    if (j - i > 2) {
      std::string faces;
      for (size_t k = i; k < j; ++k) faces += (k > i ? ", " : "") + std::to_string(uses[k].face);
      return edge + " has " + std::to_string(j - i) + " faces (" + faces + "): the surface is not manifold";
    }
    if (uses[i].forward == uses[i + 1].forward)
      return edge + " is traversed in the same direction by faces " + std::to_string(uses[i].face) + " and " +
             std::to_string(uses[i + 1].face) + ": the faces are not consistently oriented";
    i = j;
  }

  // Every edge is now shared by exactly two opposite faces; a vertex can still join two cones at
  // their tips. Walk the fan around each vertex across edges and compare with its face count.
  std::vector<std::pair<std::uint64_t, int>> face_of_directed;  // (a·n + b, face) for a → b
  face_of_directed.reserve(uses.size());
  std::vector<int> incident_count(static_cast<size_t>(n), 0), first_face(static_cast<size_t>(n), -1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint64_t>(F(f, k)), b = static_cast<std::uint64_t>(F(f, (k + 1) % 3));
      face_of_directed.emplace_back(a * n + b, static_cast<int>(f));
      ++incident_count[a];
      if (first_face[a] < 0) first_face[a] = static_cast<int>(f);
    }
  std::sort(face_of_directed.begin(), face_of_directed.end());
  const auto face_with = [&](std::uint64_t a, std::uint64_t b) {
    return std::lower_bound(face_of_directed.begin(), face_of_directed.end(), std::make_pair(a * n + b, -1))->second;
  };
  for (std::uint64_t v = 0; v < n; ++v) {
    if (first_face[v] < 0) continue;
    int f = first_face[v], steps = 0;
    do {
      const int k = F(f, 0) == static_cast<int>(v) ? 0 : F(f, 1) == static_cast<int>(v) ? 1 : 2;
      const auto next = static_cast<std::uint64_t>(F(f, (k + 1) % 3));
      f = face_with(next, v);  // the neighbour across edge v–next holds next → v
      ++steps;
    } while (f != first_face[v] && steps <= incident_count[v]);
    if (steps != incident_count[v])
      return "vertex " + std::to_string(v) + " is not manifold: its " + std::to_string(incident_count[v]) +
             " faces form more than one fan (surfaces touching at a point)";
  }

  const double volume = mass_moments(mesh).volume;
  if (!(volume > 0.0))
    return "encloses a non-positive volume (" + std::to_string(volume) + " m³): the faces are oriented inward";
  return std::nullopt;
}

void check_closed_manifold(const SurfaceMesh& mesh, const std::string& what) {
  if (const auto problem = closed_manifold_problem(mesh)) throw std::runtime_error(what + ": " + *problem);
}

}  // namespace stiffsoft

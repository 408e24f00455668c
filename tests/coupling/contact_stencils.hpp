#pragma once
/// @file Random contact stencils with known distance, shared by the contact conformance tests.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <random>

#include <stiffsoft/coupling/contact/primitive_pair.hpp>

namespace stiffsoft::contact::test_stencils {

using Eigen::Vector3d;

inline Vector3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Vector3d(n(rng), n(rng), n(rng)).normalized();
}

/// Stencil of the kind with interior closest points at distance d (as in the barrier tests).
inline Vector12d stencil_at_distance(PrimitivePair kind, double d, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.2, 0.8);
  const Vector3d n = random_unit(rng);
  Vector3d t = random_unit(rng);
  t = (t - t.dot(n) * n).normalized();
  const Vector3d b = n.cross(t);
  const Vector3d c(u(rng), u(rng), u(rng));
  Vector12d x = Vector12d::Zero();
  switch (kind) {
    case PrimitivePair::VertexVertex: x << c + d * n, c, Eigen::Matrix<double, 6, 1>::Zero(); break;
    case PrimitivePair::EdgeVertex: {
      const double s = w(rng);
      x << c + d * n, c - s * t, c + (1 - s) * t, Vector3d::Zero();
      break;
    }
    case PrimitivePair::FaceVertex:
      x << c + d * n, c - 0.5 * t - 0.4 * b, c + 0.6 * t - 0.3 * b, c + 0.1 * t + 0.7 * b;
      break;
    case PrimitivePair::EdgeEdge: {
      const Vector3d db = (t + b).normalized();
      const double sa = w(rng), sb = w(rng);
      x << c + d * n - sa * t, c + d * n + (1 - sa) * t, c - sb * db, c + (1 - sb) * db;
      break;
    }
  }
  return x;
}

}  // namespace stiffsoft::contact::test_stencils

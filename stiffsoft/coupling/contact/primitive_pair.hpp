#pragma once
/// @file Primitive pairs of an IPC contact stencil and the packing of their vertices.

#include <Eigen/Core>
#include <cstdint>

namespace stiffsoft::contact {

/// Positions of the (up to) four vertices of a contact stencil, packed [x_0; x_1; x_2; x_3], metres.
using Vector12d = Eigen::Matrix<double, 12, 1>;
/// Second derivatives with respect to a packed stencil, 12×12.
using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// Primitive pair of a contact stencil after IPC's classification (Li et al. 2020, §4.3).
/// Vertex order inside the packed stencil: VertexVertex {v0, v1}; EdgeVertex {v, e0, e1};
/// EdgeEdge {ea0, ea1, eb0, eb1}; FaceVertex {v, f0, f1, f2}.
enum class PrimitivePair : std::uint8_t { VertexVertex, EdgeVertex, EdgeEdge, FaceVertex };

/// Number of stencil vertices a pair uses: 2, 3, 4, 4 for VV, EV, EE, FV.
inline constexpr int vertex_count(PrimitivePair kind) {
  switch (kind) {
    case PrimitivePair::VertexVertex: return 2;
    case PrimitivePair::EdgeVertex: return 3;
    case PrimitivePair::EdgeEdge: return 4;
    case PrimitivePair::FaceVertex: return 4;
  }
  return 4;
}

/// Vertex i (0..3) of a packed stencil, 3-vector, metres.
inline Eigen::Vector3d stencil_vertex(const Vector12d& x, int i) { return x.segment<3>(3 * i); }

/// Packs four points into a stencil vector [a; b; c; d].
inline Vector12d pack_stencil(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  Vector12d x;
  x << a, b, c, d;
  return x;
}

}  // namespace stiffsoft::contact

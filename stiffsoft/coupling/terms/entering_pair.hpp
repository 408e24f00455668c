#pragma once
/// @file A contact pair outside the barrier's reach that a Newton move would bring into it:
/// its gap linearised at the iterate, for the direction's one-sided spring
/// (solver/entering_springs.hpp, docs/newton.md, "Springs on the pairs CCD finds entering").

#include <array>

#include <stiffsoft/coupling/contact/primitive_pair.hpp>

namespace stiffsoft {

/// One pair at distance d ≥ d̂ whose CCD time on the move is below 1.
struct EnteringPair {
  std::array<int, 4> vertices{-1, -1, -1, -1};  ///< stencil vertices, packed as the barrier's
  bool vertex_face = true;  ///< point–triangle (vertices: the point, then the triangle's) or edge–edge (edge a's, edge b's)
  contact::Vector12d normal = contact::Vector12d::Zero();  ///< ∇_x d at the iterate (dimensionless)
  double slack = 0;  ///< how far the gap may close before the spring acts, d − the target gap (m), > 0
};

}  // namespace stiffsoft

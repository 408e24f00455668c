#pragma once
/// @file What a Simulation looks like now, as the frames the writers take: one BodyFrame per
/// body (frame_writer.hpp) and one JointFrameEntry per joint (joint_frame_writer.hpp).

#include <vector>

#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/io/frame_writer.hpp>
#include <stiffsoft/io/joint_frame_writer.hpp>

namespace stiffsoft {

/// Every body of `sim` now, in Model::bodies order. Affine, fixed and kinematic bodies: their
/// surface, displacement from `x0` (the surface at t = 0, |V|×3, m). Soft bodies: all their
/// nodes as points, tetrahedra then surface triangles as cells (triangles carry their
/// tetrahedron's von Mises stress), displacement from the rest positions; contact and
/// friction forces land on the surface nodes.
std::vector<BodyFrame> body_frames(const Simulation& sim, const Eigen::MatrixX3d& x0);

/// Every joint of `sim` now, in Model::joints order: both ends, its force on body a and its gap
/// to a limit.
std::vector<JointFrameEntry> joint_frame_entries(const Simulation& sim);

}  // namespace stiffsoft

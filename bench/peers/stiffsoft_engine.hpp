#pragma once
/// @file stiffsoft (coupling::Simulation) behind the peer benchmark's Engine interface.

#include <optional>

#include "coupling/simulation.hpp"
#include "peers/engine.hpp"
#include "peers/peer_scene.hpp"

namespace stiffsoft::peers {

/// Runs the scene's stiffsoft Model with its resolved settings (affine bodies, IPC barrier,
/// lagged friction, backward Euler unless the scene says BDF-2).
class StiffsoftEngine final : public Engine {
 public:
  /// Copies the scene's model and settings into a Simulation at t = 0.
  explicit StiffsoftEngine(const PeerScene& scene);
  std::string name() const override { return "stiffsoft"; }
  std::string settings() const override;
  void step() override;
  /// stiffsoft never reports penetrations: its contacts keep a positive distance.
  std::vector<Penetration> penetrations() override { return {}; }
  void finish_probe() override {}
  Pose pose(int b) const override;
  Twist twist(int b) const override;
  Eigen::MatrixX3d collision_vertices(int b) const override;
  StepDetails details() const override { return m_details; }
  /// The world surface of all bodies, |V|×3 (m), as stiffsoft's own check sees it.
  Eigen::MatrixX3d surface() const { return m_simulation.surface(); }

 private:
  Simulation m_simulation;
  StepDetails m_details;
};

}  // namespace stiffsoft::peers

#pragma once
/// @file stiffsoft (coupling::Simulation) behind the peer benchmark's Engine interface.

#include <optional>

#include <stiffsoft/coupling/solver/simulation.hpp>
#include "peers/engine.hpp"
#include "peers/peer_scene.hpp"

namespace stiffsoft::peers {

/// The scene's settings with libuipc's default friction smoothing and Newton tolerance (its
/// eps_velocity 0.01 m/s and velocity_tol 0.05 m/s for metre-sized scenes), relative to the
/// scene's size like stiffsoft's own defaults: ε_v = 1e-2 L and ε_d = 5e-2 L (L the bounding-box
/// diagonal), where the scene's values are smaller. stiffsoft's defaults are 1e-3 L and 1e-2 L.
SimulationSettings coarse_settings(const PeerScene& scene);

/// Runs the scene's stiffsoft Model (affine bodies, IPC barrier, lagged friction, backward Euler
/// unless the scene says BDF-2) with the given settings.
class StiffsoftEngine final : public Engine {
 public:
  /// Copies the scene's model and `settings` into a Simulation at t = 0; `name` labels the runs.
  StiffsoftEngine(const PeerScene& scene, const SimulationSettings& settings, std::string name);
  std::string name() const override { return m_name; }
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
  std::string m_name;
  StepDetails m_details;
};

}  // namespace stiffsoft::peers

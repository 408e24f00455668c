#pragma once
/// @file Which engines this build has, and making one for a scene.

#include <memory>
#include <string>
#include <vector>

#include "peers/engine.hpp"
#include "peers/peer_scene.hpp"

namespace stiffsoft::peers {

/// Engine settings the benchmark may change from their defaults.
struct EngineOptions {
  double bullet_margin = 0;  ///< Bullet collision margin of hulls and meshes (m); ≤ 0: half the scene's d̂
  int mujoco_nconmax = 0;    ///< MuJoCo contact buffer; ≤ 0: 4 per dynamic geom + 200
  int mujoco_njmax = 0;      ///< MuJoCo constraint rows; ≤ 0: 4 per contact (pyramidal cone, condim 3)
  double sleep_time = 2.0;   ///< stiffsoft-sleep's solver.sleep_time (s): Bullet's own deactivation time
};

/// "stiffsoft" (the scene's settings), "stiffsoft-coarse" (coarse_settings: libuipc's friction
/// smoothing and Newton tolerance), "stiffsoft-sleep" (the scene's settings with bodies at rest
/// put to sleep after EngineOptions::sleep_time, as Bullet does) and the peers compiled in ("bullet_mesh":
/// Bullet with every dynamic body a triangle mesh, "bullet_mesh-awake": the same with Bullet's sleeping off,
/// "bullet": Bullet with convex hulls, "mujoco": MuJoCo's default settings, "mujoco-cg": the same with its CG
/// solver), in that order.
std::vector<std::string> available_engines();

/// available_engines() joined by ", " (for messages and --help).
std::string available_engine_list();

/// A fresh engine of that name on the scene at t = 0; throws std::invalid_argument for a name
/// that is not available.
std::unique_ptr<Engine> make_engine(const std::string& name, const PeerScene& scene, const EngineOptions& options);

}  // namespace stiffsoft::peers

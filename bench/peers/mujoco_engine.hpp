#pragma once
/// @file MuJoCo (mjModel from generated MJCF, mj_step) behind the peer benchmark's Engine interface.
///
/// The model is peers/mjcf.hpp's text, compiled from memory. Solver settings are MuJoCo's
/// defaults (semi-implicit Euler, Newton solver, 100 iterations, tolerance 1e-8, pyramidal
/// cone, no noslip, soft contacts with solref (0.02, 1)), the constraint solver optionally
/// another; settings() prints what is in force.
/// MuJoCo 2.2 preallocates its contact and constraint buffers: their sizes are arguments, and a
/// run that overflows them says so in warnings(). After mj_step, MuJoCo's body poses (xpos,
/// xmat) still describe the state before the step's integration; pose() recomputes them
/// (mj_kinematics, outside the timed step) so that every engine is judged on its current state.

#include <string>
#include <vector>

#include "peers/engine.hpp"
#include "peers/mjcf.hpp"
#include "peers/peer_scene.hpp"

struct mjModel_;
struct mjData_;

namespace stiffsoft::peers {

/// MuJoCo's model and data for one scene.
class MujocoEngine final : public Engine {
 public:
  /// Compiles the scene's MJCF and sets the initial velocities; `solver` ("PGS", "CG" or
  /// "Newton"; empty: MuJoCo's default) replaces the model's constraint solver, and the engine
  /// reports itself as `name`. Throws std::runtime_error with MuJoCo's message when the model
  /// does not compile, and std::invalid_argument for another solver name.
  MujocoEngine(const PeerScene& scene, const MjcfSizes& sizes, std::string name = "mujoco",
               const std::string& solver = "");
  ~MujocoEngine() override;
  std::string name() const override { return m_name; }
  std::string settings() const override;
  void step() override;
  std::vector<Penetration> penetrations() override;
  void finish_probe() override;
  Pose pose(int b) const override;
  Twist twist(int b) const override;
  Eigen::MatrixX3d collision_vertices(int b) const override;
  bool whole_surface(int b) const override { return b != m_plane; }
  std::string warnings() const override;
  /// Largest number of contacts and of constraint rows seen after any step, and the buffer sizes.
  std::string statistics() const override;

 private:
  std::string m_name;
  mjModel_* m_model = nullptr;
  mjData_* m_data = nullptr;
  MjcfSizes m_sizes;
  std::vector<int> m_body;        ///< scene body → MuJoCo body id (0 for fixed bodies)
  std::vector<int> m_geom_owner;  ///< MuJoCo geom → scene body
  std::vector<Pose> m_fixed;      ///< poses of fixed bodies (index = scene body)
  int m_plane = -1;               ///< the scene body that is a ground plane, −1 if none
  int m_peak_contacts = 0, m_peak_rows = 0;
  /// mj_step leaves xpos/xmat at the state before its integration; true until mj_kinematics
  /// has brought them to the current qpos.
  mutable bool m_stale = false;
  /// Runs mj_kinematics when the poses are stale (not timed: only pose queries call it).
  void refresh() const;
};

}  // namespace stiffsoft::peers

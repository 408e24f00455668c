#pragma once
/// @file What the peer benchmark asks of each engine (stiffsoft, Bullet, MuJoCo).

#include <Eigen/Core>
#include <string>
#include <vector>

namespace stiffsoft::peers {

/// Where a body is: x = A x̄ + p for its body-frame (centre-of-mass centred) vertices x̄.
/// A is a rotation for the rigid peers, stiffsoft's affine matrix for stiffsoft.
struct Pose {
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();  ///< linear part
  Eigen::Vector3d p = Eigen::Vector3d::Zero();      ///< centre of mass (m)
};

/// How a body moves: centre-of-mass velocity and angular velocity, both world frame.
struct Twist {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();  ///< m/s
  Eigen::Vector3d w = Eigen::Vector3d::Zero();  ///< rad/s
};

/// One contact the engine reports with overlap.
struct Penetration {
  int body_a = -1;       ///< scene index of one body
  int body_b = -1;       ///< scene index of the other
  double engine = 0;     ///< depth the engine reports (m, > 0): −distance of its contact
  double surface = 0;    ///< depth of the bodies' actual surfaces (m): engine depth minus the
                         ///< collision margins the engine adds around its shapes
};

/// What an engine did in its last step beyond moving the bodies (stiffsoft only).
struct StepDetails {
  int newton_iterations = -1;   ///< −1 for engines without Newton iterations
  bool converged = true;        ///< Newton met its tolerance
  double smallest_distance = 0; ///< stiffsoft: smallest active contact distance (m), +∞ without contact
  double broad_phase_s = 0;     ///< stiffsoft phase times of the step (s)
  double ccd_s = 0;             ///< time of the continuous collision detection (s)
  double assembly_s = 0;        ///< time of the gradient and Hessian assembly (s)
  double solve_s = 0;           ///< time of the linear solves (s)
};

/// One engine running one scene.
class Engine {
 public:
  virtual ~Engine() = default;
  /// "stiffsoft", "stiffsoft-coarse", "bullet_mesh", "bullet" or "mujoco".
  virtual std::string name() const = 0;
  /// One line naming the solver settings in force (reported with the results).
  virtual std::string settings() const = 0;
  /// Advances by the scene's time step h. This call, and only this, is timed.
  virtual void step() = 0;
  /// The contacts with overlap that the engine's own collision detection saw in its last step
  /// (peers: at the start of the step; after finish_probe(): in the current state). Empty for stiffsoft.
  virtual std::vector<Penetration> penetrations() = 0;
  /// Runs the engine's collision detection on the current state so that penetrations()
  /// describes it (called once after the last step; not timed).
  virtual void finish_probe() = 0;
  /// Pose of body b now.
  virtual Pose pose(int b) const = 0;
  /// Velocity of body b now (stiffsoft: the rigid part of its affine velocity).
  virtual Twist twist(int b) const = 0;
  /// World positions of the vertices of the engine's collision shapes of body b (the
  /// hull points, box corners, mesh vertices): for checking that the engine holds the same
  /// geometry in the same place as stiffsoft.
  virtual Eigen::MatrixX3d collision_vertices(int b) const = 0;
  /// False when the engine holds only part of body b's surface (MuJoCo's ground plane: the top
  /// face), so that collision_vertices(b) covers only some of its vertices.
  virtual bool whole_surface(int b) const { return b >= 0; }
  /// Details of the last step.
  virtual StepDetails details() const { return {}; }
  /// Problems the engine flagged during the run (overflowing contact buffers, resets); empty if none.
  virtual std::string warnings() const { return ""; }
  /// Counters of the run worth recording (MuJoCo: peak contacts and constraint rows); may be empty.
  virtual std::string statistics() const { return ""; }
};

}  // namespace stiffsoft::peers

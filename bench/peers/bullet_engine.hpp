#pragma once
/// @file Bullet (btDiscreteDynamicsWorld) behind the peer benchmark's Engine interface.
///
/// Shapes (BulletShapes): with `hulls` ("bullet"), a dynamic convex body is a
/// btConvexHullShape of its vertices and a dynamic non-convex body (a torus, a ring) a
/// btGImpactMeshShape of its triangles; with `meshes` ("bullet_mesh", the representation the
/// ABD and Rigid-IPC papers compared against), every dynamic body is a btGImpactMeshShape of
/// its triangles. A fixed box is a btBoxShape; any other fixed body is a btConvexHullShape
/// (convex, `hulls` only) or a btBvhTriangleMeshShape. Every hull, GImpact and triangle-mesh
/// shape gets the collision margin `margin` (Bullet adds it around those shapes, its default
/// is 0.04 m, as large as the bodies); a btBoxShape keeps its margin inside its extents.
/// Bodies sit in their principal-axes frames (Bullet takes a diagonal inertia); friction is
/// √μ per body because Bullet multiplies the two bodies' coefficients; restitution 0
/// (default). Everything else is Bullet's default: btSequentialImpulseConstraintSolver, 10
/// iterations, ERP 0.2, split impulse, no CCD, deactivation (sleeping) on unless
/// BulletSettings::sleeping is false ("bullet_mesh-awake"), single precision.

#include <LinearMath/btScalar.h>

#include <memory>
#include <vector>

#include "peers/engine.hpp"
#include "peers/peer_scene.hpp"

class btDefaultCollisionConfiguration;
class btCollisionDispatcher;
class btBroadphaseInterface;
class btSequentialImpulseConstraintSolver;
class btDiscreteDynamicsWorld;
class btCollisionShape;
class btRigidBody;
class btStridingMeshInterface;

namespace stiffsoft::peers {

/// Which Bullet shapes the bodies that are not fixed boxes get.
enum class BulletShapes {
  hulls,   ///< "bullet": convex bodies as btConvexHullShape, non-convex ones as triangle meshes
  meshes,  ///< "bullet_mesh": every body as a triangle mesh (btGImpactMeshShape, fixed: BVH)
};

/// How BulletEngine builds its world.
struct BulletSettings {
  double margin = 0.04;                       ///< margin of hull and mesh shapes (m); Bullet's default
  BulletShapes shapes = BulletShapes::hulls;  ///< shape of each body
  /// Bullet's deactivation: an island below its thresholds for 2 s sleeps (Bullet's default);
  /// false: every body stays awake (DISABLE_DEACTIVATION), as stiffsoft's bodies by default.
  bool sleeping = true;
};

/// Bullet's world for one scene.
class BulletEngine final : public Engine {
 public:
  /// Builds the world.
  BulletEngine(const PeerScene& scene, const BulletSettings& settings);
  ~BulletEngine() override;
  /// "bullet" (hulls) or "bullet_mesh" (meshes), "-awake" appended without sleeping.
  std::string name() const override;
  std::string settings() const override;
  void step() override;
  std::vector<Penetration> penetrations() override;
  void finish_probe() override;
  Pose pose(int b) const override;
  Twist twist(int b) const override;
  Eigen::MatrixX3d collision_vertices(int b) const override;

 private:
  double m_h;
  BulletSettings m_settings;
  std::unique_ptr<btDefaultCollisionConfiguration> m_configuration;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  std::unique_ptr<btBroadphaseInterface> m_broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
  std::unique_ptr<btDiscreteDynamicsWorld> m_world;
  std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
  std::vector<std::unique_ptr<btStridingMeshInterface>> m_meshes;
  std::vector<std::vector<btScalar>> m_vertex_storage;
  std::vector<std::vector<int>> m_index_storage;
  std::vector<std::unique_ptr<btRigidBody>> m_bodies;     ///< one per scene body
  std::vector<Eigen::Matrix3d> m_principal;               ///< Q: x̄ = Q x_principal
  std::vector<double> m_inflation;                        ///< margin each shape adds outside the body's surface (m)
  int m_gimpact = 0, m_hulls = 0, m_boxes = 0, m_trimeshes = 0;
};

}  // namespace stiffsoft::peers

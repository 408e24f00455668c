#include "peers/bullet_engine.hpp"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletDynamicsCommon.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace stiffsoft::peers {

namespace {

btVector3 bt(const Eigen::Vector3d& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }

btMatrix3x3 bt(const Eigen::Matrix3d& m) {
  return btMatrix3x3(btScalar(m(0, 0)), btScalar(m(0, 1)), btScalar(m(0, 2)), btScalar(m(1, 0)), btScalar(m(1, 1)),
                     btScalar(m(1, 2)), btScalar(m(2, 0)), btScalar(m(2, 1)), btScalar(m(2, 2)));
}

/// Principal axes Q (a rotation, columns = axes) and moments of a symmetric inertia tensor.
std::pair<Eigen::Matrix3d, Eigen::Vector3d> principal_axes(const Eigen::Matrix3d& inertia) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia);
  Eigen::Matrix3d Q = eigen.eigenvectors();
  if (Q.determinant() < 0) Q.col(2) = -Q.col(2);
  return {Q, eigen.eigenvalues()};
}

/// A key that identifies a shape by its kind and exact vertex coordinates, so bodies of the
/// same shape share one btCollisionShape.
std::string shape_key(char kind, const Eigen::MatrixX3d& V) {
  std::string key(1, kind);
  key.append(reinterpret_cast<const char*>(V.data()), sizeof(double) * size_t(V.size()));
  return key;
}

}  // namespace

BulletEngine::BulletEngine(const PeerScene& scene, const BulletSettings& settings)
    : m_h(scene.dt), m_settings(settings) {
  const double margin = settings.margin;
  m_configuration = std::make_unique<btDefaultCollisionConfiguration>();
  m_dispatcher = std::make_unique<btCollisionDispatcher>(m_configuration.get());
  btGImpactCollisionAlgorithm::registerAlgorithm(m_dispatcher.get());
  m_broadphase = std::make_unique<btDbvtBroadphase>();
  m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
  m_world = std::make_unique<btDiscreteDynamicsWorld>(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
                                                      m_configuration.get());
  m_world->setGravity(bt(scene.gravity));

  std::map<std::string, std::pair<btCollisionShape*, double>> shared;  // key → (shape, inflation)
  const btScalar friction = btScalar(std::sqrt(scene.mu));
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const PeerBody& body = scene.bodies[i];
    // Dynamic bodies live in their principal frame (x̄ = Q x'), fixed ones in the x̄ frame.
    Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();
    Eigen::Vector3d moments = Eigen::Vector3d::Zero();
    if (!body.fixed) std::tie(Q, moments) = principal_axes(body.inertia);
    const Eigen::MatrixX3d V = body.x_bar * Q;  // rows x'ᵀ = x̄ᵀ Q

    const bool hull = body.convex && settings.shapes == BulletShapes::hulls;
    const char kind = body.fixed && body.box ? 'b' : hull ? 'h' : body.fixed ? 't' : 'g';
    const std::string key = shape_key(kind, V);
    auto it = shared.find(key);
    if (it == shared.end()) {
      btCollisionShape* shape = nullptr;
      double inflation = margin;
      if (kind == 'b') {
        shape = new btBoxShape(bt(Eigen::Vector3d(0.5 * *body.box)));  // margin inside the extents
        inflation = 0;
        ++m_boxes;
      } else if (kind == 'h') {
        auto* hull = new btConvexHullShape();
        for (Eigen::Index v = 0; v < V.rows(); ++v) hull->addPoint(bt(Eigen::Vector3d(V.row(v))), false);
        hull->recalcLocalAabb();
        hull->setMargin(btScalar(margin));
        shape = hull;
        ++m_hulls;
      } else {
        std::vector<btScalar>& vertices = m_vertex_storage.emplace_back();
        std::vector<int>& indices = m_index_storage.emplace_back();
        for (Eigen::Index v = 0; v < V.rows(); ++v)
          for (int d = 0; d < 3; ++d) vertices.push_back(btScalar(V(v, d)));
        for (Eigen::Index f = 0; f < body.F.rows(); ++f)
          for (int d = 0; d < 3; ++d) indices.push_back(body.F(f, d));
        auto* mesh = new btTriangleIndexVertexArray(int(body.F.rows()), indices.data(), 3 * int(sizeof(int)),
                                                    int(V.rows()), vertices.data(), 3 * int(sizeof(btScalar)));
        m_meshes.emplace_back(mesh);
        if (kind == 'g') {
          auto* gimpact = new btGImpactMeshShape(mesh);
          gimpact->setMargin(btScalar(margin));
          gimpact->updateBound();
          shape = gimpact;
          ++m_gimpact;
        } else {
          auto* trimesh = new btBvhTriangleMeshShape(mesh, true);
          trimesh->setMargin(btScalar(margin));
          shape = trimesh;
          ++m_trimeshes;
        }
      }
      m_shapes.emplace_back(shape);
      it = shared.emplace(key, std::make_pair(shape, inflation)).first;
    }

    btRigidBody::btRigidBodyConstructionInfo info(body.fixed ? btScalar(0) : btScalar(body.mass), nullptr,
                                                  it->second.first, bt(moments));
    info.m_startWorldTransform = btTransform(bt(Eigen::Matrix3d(body.R0 * Q)), bt(body.c0));
    info.m_friction = friction;
    auto rigid = std::make_unique<btRigidBody>(info);
    rigid->setUserIndex(int(i));
    if (!body.fixed) {
      rigid->setLinearVelocity(bt(body.v0));
      rigid->setAngularVelocity(bt(body.w0));
      if (!settings.sleeping) rigid->setActivationState(DISABLE_DEACTIVATION);
    }
    m_world->addRigidBody(rigid.get());
    m_bodies.push_back(std::move(rigid));
    m_principal.push_back(Q);
    m_inflation.push_back(it->second.second);
  }
}

BulletEngine::~BulletEngine() {
  for (auto& body : m_bodies) m_world->removeRigidBody(body.get());
}

std::string BulletEngine::name() const {
  return std::string(m_settings.shapes == BulletShapes::meshes ? "bullet_mesh" : "bullet") +
         (m_settings.sleeping ? "" : "-awake");
}

std::string BulletEngine::settings() const {
  const btContactSolverInfo& s = m_world->getSolverInfo();
  char line[640];
  std::snprintf(line, sizeof line,
                "Bullet %d (%s precision), btDiscreteDynamicsWorld + btSequentialImpulseConstraintSolver, "
                "%d iterations, ERP %.2g (contacts %.2g), CFM %.2g, split impulse %s (below %.3g m), "
                "warm start %.2g, CCD off, sleeping %s; shapes: %d hull, %d GImpact, %d box, %d BVH trimesh; "
                "margin %.3g m on hulls/meshes",
                btGetVersion(), sizeof(btScalar) == 8 ? "double" : "single", s.m_numIterations, double(s.m_erp),
                double(s.m_erp2), double(s.m_globalCfm), s.m_splitImpulse ? "on" : "off",
                double(s.m_splitImpulsePenetrationThreshold), double(s.m_warmstartingFactor),
                m_settings.sleeping ? "on" : "off", m_hulls, m_gimpact,
                m_boxes, m_trimeshes, m_settings.margin);
  return line;
}

void BulletEngine::step() { m_world->stepSimulation(btScalar(m_h), 0); }

std::vector<Penetration> BulletEngine::penetrations() {
  std::vector<Penetration> out;
  const int manifolds = m_dispatcher->getNumManifolds();
  for (int i = 0; i < manifolds; ++i) {
    const btPersistentManifold* manifold = m_dispatcher->getManifoldByIndexInternal(i);
    const int a = manifold->getBody0()->getUserIndex(), b = manifold->getBody1()->getUserIndex();
    for (int k = 0; k < manifold->getNumContacts(); ++k) {
      const double distance = double(manifold->getContactPoint(k).getDistance());
      if (distance < 0) out.push_back({a, b, -distance, -distance - m_inflation[a] - m_inflation[b]});
    }
  }
  return out;
}

void BulletEngine::finish_probe() { m_world->performDiscreteCollisionDetection(); }

Pose BulletEngine::pose(int b) const {
  const btTransform& t = m_bodies[b]->getWorldTransform();
  Eigen::Matrix3d B;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) B(r, c) = double(t.getBasis()[r][c]);
  const btVector3& o = t.getOrigin();
  return {B * m_principal[b].transpose(), Eigen::Vector3d(double(o.x()), double(o.y()), double(o.z()))};
}

Eigen::MatrixX3d BulletEngine::collision_vertices(int b) const {
  const btCollisionShape* shape = m_bodies[b]->getCollisionShape();
  std::vector<btVector3> local;
  if (const auto* hull = dynamic_cast<const btConvexHullShape*>(shape)) {
    for (int i = 0; i < hull->getNumPoints(); ++i) local.push_back(hull->getUnscaledPoints()[i]);
  } else if (const auto* box = dynamic_cast<const btBoxShape*>(shape)) {
    for (int i = 0; i < 8; ++i) {
      btVector3 corner;
      box->getVertex(i, corner);  // corners of the extents including the (inner) margin
      local.push_back(corner);
    }
  } else {
    const btStridingMeshInterface* mesh = nullptr;
    if (const auto* gimpact = dynamic_cast<const btGImpactMeshShape*>(shape)) mesh = gimpact->getMeshInterface();
    if (const auto* trimesh = dynamic_cast<const btBvhTriangleMeshShape*>(shape)) mesh = trimesh->getMeshInterface();
    if (!mesh) throw std::logic_error("BulletEngine::collision_vertices: unexpected shape type");
    const auto* array = static_cast<const btTriangleIndexVertexArray*>(mesh);
    const btIndexedMesh& part = array->getIndexedMeshArray()[0];
    const auto* v = reinterpret_cast<const btScalar*>(part.m_vertexBase);
    for (int i = 0; i < part.m_numVertices; ++i) local.emplace_back(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  }
  const btTransform& t = m_bodies[b]->getWorldTransform();
  Eigen::MatrixX3d world(Eigen::Index(local.size()), 3);
  for (size_t i = 0; i < local.size(); ++i) {
    const btVector3 x = t * local[i];
    world.row(Eigen::Index(i)) << double(x.x()), double(x.y()), double(x.z());
  }
  return world;
}

Twist BulletEngine::twist(int b) const {
  const btVector3 &v = m_bodies[b]->getLinearVelocity(), &w = m_bodies[b]->getAngularVelocity();
  return {Eigen::Vector3d(double(v.x()), double(v.y()), double(v.z())),
          Eigen::Vector3d(double(w.x()), double(w.y()), double(w.z()))};
}

}  // namespace stiffsoft::peers

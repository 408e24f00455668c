#include "peers/verify.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include <stiffsoft/scene/scene_loader.hpp>

namespace stiffsoft::peers {

namespace {

/// Largest distance from a row of X to its nearest row of Y (m).
double farthest_nearest(const Eigen::MatrixX3d& X, const Eigen::MatrixX3d& Y) {
  double worst = 0;
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    worst = std::max(worst, std::sqrt((Y.rowwise() - X.row(i)).rowwise().squaredNorm().minCoeff()));
  return worst;
}

int report(bool ok, const std::string& engine, const std::string& what) {
  std::printf("%s  %-11s %s\n", ok ? "PASS" : "FAIL", engine.c_str(), what.c_str());
  std::fflush(stdout);
  return ok ? 0 : 1;
}

PeerScene scene_from_text(const std::string& text, const std::string& name, double dt) {
  const std::filesystem::path folder = std::filesystem::current_path();
  return make_peer_scene(load_scene_from_string(text, folder, "<" + name + ">", name), folder / (name + ".json"), dt);
}

const char* kFreeFlight = R"({
  "description": "peer_bench --verify: free flight of a tumbling box and torus under gravity.",
  "bodies": [
    {"name": "box", "mesh": {"primitive": "box", "size": [0.3, 0.2, 0.1]}, "density": 700,
     "position": [0, 0, 0], "rotation_deg": [30, 50, 70], "velocity": [1, 2, 0.5], "angular_velocity": [3, -4, 5]},
    {"name": "torus", "mesh": {"primitive": "torus", "radius": 0.1, "minor_radius": 0.03, "resolution": 16},
     "density": 2000, "position": [2, 0, 0], "rotation_deg": [10, 20, 30], "velocity": [0, 1, 0],
     "angular_velocity": [-2, 6, 1]}
  ]
})";

const char* kCollision = R"({
  "description": "peer_bench --verify: two boxes of different densities collide off-centre in zero gravity.",
  "gravity": [0, 0, 0],
  "contact": {"mu": 0.3},
  "bodies": [
    {"name": "light", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "density": 1000,
     "position": [-0.3, 0, 0], "velocity": [2, 0, 0]},
    {"name": "heavy", "mesh": {"primitive": "box", "size": [0.1, 0.3, 0.2]}, "density": 3000,
     "position": [0.3, 0.08, 0.05], "rotation_deg": [0, 0, 30], "velocity": [-1, 0, 0]}
  ]
})";

/// Angular momentum about the origin and linear momentum of all dynamic bodies.
std::pair<Eigen::Vector3d, Eigen::Vector3d> momenta(const Engine& engine, const PeerScene& scene) {
  Eigen::Vector3d P = Eigen::Vector3d::Zero(), L = Eigen::Vector3d::Zero();
  for (size_t b = 0; b < scene.bodies.size(); ++b) {
    const PeerBody& body = scene.bodies[b];
    if (body.fixed) continue;
    const Pose pose = engine.pose(int(b));
    const Twist twist = engine.twist(int(b));
    const Eigen::Matrix3d R = pose.A;
    P += body.mass * twist.v;
    L += pose.p.cross(body.mass * twist.v) + R * body.inertia * R.transpose() * twist.w;
  }
  return {P, L};
}

}  // namespace

int verify_engines(const std::vector<std::string>& engines, const std::vector<std::filesystem::path>& scenes,
                   const EngineOptions& options) {
  int failures = 0;
  char line[512];
  // 1. Geometry in place.
  for (const auto& file : scenes) {
    const PeerScene scene = load_peer_scene(file, 1.0 / 240);
    for (const std::string& name : engines) {
      const auto engine = make_engine(name, scene, options);
      double worst = 0;
      std::string where;
      for (size_t b = 0; b < scene.bodies.size(); ++b) {
        const PeerBody& body = scene.bodies[b];
        const Eigen::MatrixX3d ours = (body.x_bar * body.R0.transpose()).rowwise() + body.c0.transpose();
        const Eigen::MatrixX3d theirs = engine->collision_vertices(int(b));
        const double d = !theirs.rows()                  ? 1e9
                         : engine->whole_surface(int(b)) ? std::max(farthest_nearest(theirs, ours), farthest_nearest(ours, theirs))
                                                         : farthest_nearest(theirs, ours);
        if (d > worst) {
          worst = d;
          where = body.name;
        }
      }
      std::snprintf(line, sizeof line, "%s: collision vertices vs stiffsoft surface, worst %.3g m (%s)",
                    scene.name.c_str(), worst, where.c_str());
      failures += report(worst < 1e-5, name, line);
    }
  }

  // 2. Free flight.
  {
    const double h = 1e-3;
    const int steps = 300;
    const PeerScene scene = scene_from_text(kFreeFlight, "free_flight", h);
    for (const std::string& name : engines) {
      const auto engine = make_engine(name, scene, options);
      for (int k = 0; k < steps; ++k) engine->step();
      const double t = steps * h;
      for (size_t b = 0; b < scene.bodies.size(); ++b) {
        const PeerBody& body = scene.bodies[b];
        // Semi-implicit (Bullet, MuJoCo) and backward (stiffsoft) Euler both reach
        // c0 + v0 t + g (t² + h t) / 2 after t/h steps of constant acceleration g.
        const Eigen::Vector3d expected = body.c0 + body.v0 * t + 0.5 * scene.gravity * (t * t + h * t);
        const Pose pose = engine->pose(int(b));
        const double error = (pose.p - expected).norm(), allowed = 1e-5;
        std::snprintf(line, sizeof line,
                      "free flight, %s: centre of mass %.3g m from the Euler parabola (allowed %.3g m; %.3g m from the exact one)",
                      body.name.c_str(), error, allowed,
                      (pose.p - body.c0 - body.v0 * t - 0.5 * scene.gravity * t * t).norm());
        failures += report(error < allowed, name, line);
        const Eigen::Vector3d L0 = body.R0 * body.inertia * body.R0.transpose() * body.w0;
        const Eigen::Vector3d L = pose.A * body.inertia * pose.A.transpose() * engine->twist(int(b)).w;
        const double relative = (L - L0).norm() / L0.norm();
        std::snprintf(line, sizeof line, "free flight, %s: angular momentum changed by %.3g %% (allowed 2 %%)",
                      body.name.c_str(), 100 * relative);
        failures += report(relative < 0.02, name, line);
      }
    }
  }

  // 3. Momentum balance in a collision.
  {
    const double h = 1e-3;
    const int steps = 400;
    const PeerScene scene = scene_from_text(kCollision, "collision", h);
    for (const std::string& name : engines) {
      const auto engine = make_engine(name, scene, options);
      const auto [P0, L0] = momenta(*engine, scene);
      for (int k = 0; k < steps; ++k) engine->step();
      const auto [P, L] = momenta(*engine, scene);
      const double dv = (engine->twist(0).v - scene.bodies[0].v0).norm() / scene.bodies[0].v0.norm();
      std::snprintf(line, sizeof line, "collision: light box's velocity changed by %.3g %% (must exceed 10 %%)", 100 * dv);
      failures += report(dv > 0.1, name, line);
      const double dP = (P - P0).norm() / P0.norm();
      const double scale = L0.norm() + 0.3 * P0.norm();  // |L| about the origin, plus |P| × the scene's size
      const double dL = (L - L0).norm() / scale;
      std::snprintf(line, sizeof line, "collision: momentum changed by %.3g %%, angular momentum by %.3g %% (allowed 1 %%)",
                    100 * dP, 100 * dL);
      failures += report(dP < 0.01 && dL < 0.01, name, line);
    }
  }
  return failures;
}

}  // namespace stiffsoft::peers

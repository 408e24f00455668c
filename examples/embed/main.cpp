/// @file Embedding stiffsoft: a hybrid scene built in code (no scene file): a soft rubber ball
/// dropped onto an affine box resting on a fixed ground. Steps it for 1.5 s, prints the ball's
/// centre every 0.1 s and writes frames for ParaView into the folder given as argument
/// (default `out`): open `out/ball_on_box.pvd`.

#include <stiffsoft/stiffsoft.hpp>

#include <cstdio>
#include <exception>

namespace {

/// A body whose mesh is a primitive shape.
stiffsoft::BodyDescription primitive_body(const char* name, stiffsoft::PrimitiveShape shape,
                                          const Eigen::Vector3d& position) {
  stiffsoft::BodyDescription body;
  body.name = name;
  body.mesh.primitive = shape;
  body.position = position;
  return body;
}

/// The scene: ground (fixed), box (affine, 40 × 20 × 40 cm), ball (soft, radius 10 cm, 30 cm above).
stiffsoft::SceneDescription ball_on_box() {
  stiffsoft::SceneDescription scene;
  scene.name = "ball_on_box";
  scene.description = "A soft ball dropped on an affine box on a fixed ground (examples/embed).";
  scene.time.dt = 0.01;
  scene.time.duration = 1.5;
  scene.contact.mu = 0.3;
  scene.contact.dhat = 0.0005;  // m: bodies must start more than d̂ apart (the box starts 1 mm above the ground)

  stiffsoft::PrimitiveShape slab;
  slab.type = stiffsoft::PrimitiveShape::Type::Box;
  slab.extents = {2.0, 0.1, 2.0};
  stiffsoft::BodyDescription ground = primitive_body("ground", slab, {0, -0.05, 0});
  ground.kind = stiffsoft::Motion::Fixed;

  stiffsoft::PrimitiveShape block;
  block.extents = {0.4, 0.2, 0.4};
  stiffsoft::BodyDescription box = primitive_body("box", block, {0, 0.101, 0});
  box.density = 800;

  stiffsoft::PrimitiveShape sphere;
  sphere.type = stiffsoft::PrimitiveShape::Type::Sphere;
  sphere.radius = 0.1;
  stiffsoft::BodyDescription ball = primitive_body("ball", sphere, {0.02, 0.5, 0});
  ball.model = stiffsoft::ModelChoice::Soft;
  ball.mesh_size = 0.04;
  ball.density = 1100;
  ball.material.young = 2e5;  // rubber, Pa
  ball.material.poisson = 0.45;

  scene.bodies = {ground, box, ball};
  return scene;
}

/// Mean of the ball's node positions and velocities (m, m/s).
std::pair<Eigen::Vector3d, Eigen::Vector3d> centre_and_velocity(const stiffsoft::Simulation& sim, int body) {
  const stiffsoft::BodyModel& b = sim.model().bodies[body];
  const int n = b.node_end - b.node_begin;
  return {sim.node_positions().middleRows(b.node_begin, n).colwise().mean().transpose(),
          sim.node_velocities().middleRows(b.node_begin, n).colwise().mean().transpose()};
}

}  // namespace

int main(int argc, char** argv) {
  try {
    stiffsoft::SceneSimulation run = stiffsoft::make_simulation(ball_on_box());
    stiffsoft::Simulation& sim = run.simulation;
    stiffsoft::Recorder recorder(argc > 1 ? argv[1] : "out", run.scene, sim);
    const int steps = int(run.scene.time.duration / run.scene.time.dt + 0.5);
    for (int k = 1; k <= steps; ++k) {
      const stiffsoft::StepStats s = sim.step();
      recorder.record(s, k == steps);
      if (k % 10 == 0 || k == steps) {
        const auto [c, v] = centre_and_velocity(sim, 2);
        std::printf(
            "t = %.2f s  ball centre = (%.4f, %.4f, %.4f) m  speed = %.4f m/s  vertical = %.4f m/s  Newton iterations = %d\n",
            sim.time(), c.x(), c.y(), c.z(), v.norm(), v.y(), s.newton.iterations);
      }
    }
    recorder.finish();
    std::printf("wrote %d frames to %s\n", recorder.frame_count(), recorder.pvd_path().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "embed: %s\n", e.what());
    return 1;
  }
  return 0;
}

#include "run_command.hpp"

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>

#include "coupling/linear_solver/petsc_session.hpp"
#include "io/atomic_file.hpp"
#include "io/body_state_writer.hpp"
#include "io/frame_writer.hpp"
#include "io/joint_frame_writer.hpp"
#include "io/scene_builder.hpp"
#include "io/scene_loader.hpp"
#include "io/stats_writer.hpp"
#include "progress.hpp"

namespace stiffsoft {

namespace {

const std::vector<std::string> kStatsColumns{
    "step", "time", "newton_iterations", "linear_iterations", "line_search_steps", "smallest_ccd_step", "converged",
    "contacts", "smallest_distance", "kinetic_energy", "potential_energy", "momentum_x", "momentum_y",
    "momentum_z", "orthogonality_error", "elastic_energy", "inverted_tets", "kappa", "joint_error", "joint_force", "seconds_broad_phase", "seconds_ccd",
    "seconds_assembly", "seconds_solve", "seconds_step"};

/// joints.csv: per written frame, each joint's anchor on body a and its force on body a
/// (Simulation::joint_forces()); `joint` is the index in the scene's `joints` list.
const std::vector<std::string> kJointColumns{"step", "time", "joint", "x", "y", "z", "force_x", "force_y", "force_z", "force"};

void add_joint_rows(StatsWriter& out, const Simulation& sim, int step) {
  const std::vector<Eigen::Vector3d> x = sim.joint_positions();
  const std::vector<Eigen::Vector3d>& f = sim.joint_forces();
  for (std::size_t j = 0; j < x.size(); ++j) {
    const Eigen::Vector3d force = j < f.size() ? f[j] : Eigen::Vector3d::Zero();
    out.add_row({double(step), sim.time(), double(j), x[j].x(), x[j].y(), x[j].z(), force.x(), force.y(), force.z(),
                 force.norm()});
  }
}

/// The joints of the current state, for the joints' .vtp frames.
std::vector<JointFrameEntry> joint_frame(const Simulation& sim) {
  const std::vector<Eigen::Vector3d> x_a = sim.joint_positions(), x_b = sim.joint_positions_b();
  const std::vector<Eigen::Vector3d>& f = sim.joint_forces();
  const std::vector<double> gaps = sim.joint_gaps();
  std::vector<JointFrameEntry> out;
  for (std::size_t j = 0; j < x_a.size(); ++j) {
    const JointModel& joint = sim.model().joints[j];
    out.push_back({joint.name, int(joint.kind), x_a[j], x_b[j], j < f.size() ? f[j] : Eigen::Vector3d::Zero(), gaps[j]});
  }
  return out;
}

std::vector<double> stats_row(const StepStats& s) {
  return {double(s.step), s.time, double(s.newton.iterations), double(s.newton.linear_iterations),
          double(s.newton.line_search_steps),
          s.newton.smallest_ccd_step, s.newton.converged ? 1.0 : 0.0, double(s.contacts),
          s.smallest_distance, s.kinetic_energy, s.potential_energy, s.linear_momentum.x(),
          s.linear_momentum.y(), s.linear_momentum.z(), s.orthogonality_error, s.elastic_energy,
          double(s.inverted_tets), s.kappa, s.joint_error, s.joint_force,
          s.times.broad_phase, s.times.ccd, s.times.assembly, s.times.solve, s.seconds};
}

/// A soft body's frame: all its nodes as points, tets then surface triangles as cells; surface
/// forces land on their nodes; triangles carry their tetrahedron's von Mises stress.
BodyFrame soft_frame(const Simulation& sim, const BodyModel& body, const Eigen::MatrixX3d& fc,
                     const Eigen::MatrixX3d& ff, const Eigen::MatrixX3d& nodes_x, const Eigen::MatrixX3d& nodes_v,
                     const Eigen::VectorXd& von_mises) {
  const Model& model = sim.model();
  const int n = body.node_end - body.node_begin, nt = body.tet_end - body.tet_begin,
            nf = body.face_end - body.face_begin;
  BodyFrame f;
  f.x = nodes_x.middleRows(body.node_begin, n);
  f.velocity = nodes_v.middleRows(body.node_begin, n);
  f.displacement = f.x - model.nodes.X.middleRows(body.node_begin, n);
  f.T = model.nodes.T.middleRows(body.tet_begin, nt).array() - body.node_begin;
  f.F.resize(nf, 3);
  f.von_mises.resize(nt + nf);
  f.von_mises.head(nt) = von_mises.segment(body.tet_begin, nt);
  for (int k = 0; k < nf; ++k) {
    const int face = body.face_begin + k;
    for (int j = 0; j < 3; ++j) f.F(k, j) = model.mesh.vertex_node[model.mesh.F(face, j)] - body.node_begin;
    f.von_mises[nt + k] = von_mises[model.mesh.face_tet[face]];
  }
  f.contact_force = Eigen::MatrixX3d::Zero(n, 3);
  f.friction_force = Eigen::MatrixX3d::Zero(n, 3);
  for (int v = body.vertex_begin; v < body.vertex_end; ++v) {
    const int node = model.mesh.vertex_node[v] - body.node_begin;
    f.contact_force.row(node) = fc.row(v);
    f.friction_force.row(node) = ff.row(v);
  }
  return f;
}

std::vector<BodyFrame> frame_of(const Simulation& sim, const Eigen::MatrixX3d& x0) {
  const Model& model = sim.model();
  const Eigen::MatrixX3d x = sim.surface(), v = sim.surface_velocity(), fc = sim.contact_forces(),
                         ff = sim.friction_forces();
  const bool soft = model.has_soft_bodies();
  const Eigen::MatrixX3d nodes_x = soft ? sim.node_positions() : Eigen::MatrixX3d();
  const Eigen::MatrixX3d nodes_v = soft ? sim.node_velocities() : Eigen::MatrixX3d();
  const Eigen::VectorXd von_mises = soft ? sim.von_mises() : Eigen::VectorXd();
  std::vector<BodyFrame> frames;
  for (const BodyModel& body : model.bodies) {
    BodyFrame f;
    if (body.representation == Representation::Soft) {
      f = soft_frame(sim, body, fc, ff, nodes_x, nodes_v, von_mises);
    } else {
      const int n = body.vertex_end - body.vertex_begin, nf = body.face_end - body.face_begin;
      f.x = x.middleRows(body.vertex_begin, n);
      f.F = model.mesh.F.middleRows(body.face_begin, nf).array() - body.vertex_begin;
      f.velocity = v.middleRows(body.vertex_begin, n);
      f.displacement = f.x - x0.middleRows(body.vertex_begin, n);
      f.contact_force = fc.middleRows(body.vertex_begin, n);
      f.friction_force = ff.middleRows(body.vertex_begin, n);
    }
    f.name = body.name;
    f.model = motion_name(body);
    frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace

int run_scene(const RunOptions& options) {
  std::unique_ptr<tbb::global_control> threads;
  if (options.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);

  SceneDescription scene = load_scene(options.scene);
  Model model = build_model(scene, options.scene);
  resolve_relative_defaults(scene, model);
  const SimulationSettings settings = simulation_settings(scene);
  const int total = options.steps ? *options.steps : int(std::ceil(scene.time.duration / scene.time.dt - 1e-9));
  spdlog::info("{}: {} bodies, {} DOFs, {} triangles; h = {} s, d̂ = {:.3g} m, ε_v = {:.3g} m/s, ε_d = {:.3g} m/s, {} steps",
               scene.name, model.bodies.size(), model.num_dofs, model.mesh.F.rows(), settings.h, settings.dhat,
               settings.eps_v, settings.tolerance, total);

  // Under MPI every rank simulates (the linear solve is shared); rank 0 alone writes.
  const bool writes = PetscSession::rank() == 0;
  std::optional<FrameWriter> frames;
  std::optional<StatsWriter> stats;
  std::optional<BodyStateWriter> bodies;  // per-body state per step (studies)
  std::optional<StatsWriter> joints;      // per-frame joint positions and forces
  std::optional<JointFrameWriter> joint_frames;  // the same as ParaView PolyData
  if (writes) {
    std::filesystem::create_directories(options.out);
    write_file_atomically(options.out / "scene.resolved.json",
                          [&](std::ostream& os) { os << resolved_scene_json(scene).dump(2) << '\n'; });
    frames.emplace(options.out, scene.name);
    stats.emplace(options.out / "stats.csv", kStatsColumns);
    bodies.emplace(options.out / "bodies.csv");
    if (!scene.joints.empty()) {
      joints.emplace(options.out / "joints.csv", kJointColumns);
      joint_frames.emplace(options.out, scene.name);
    }
  }
  Simulation sim(std::move(model), settings);
  const Eigen::MatrixX3d x0 = sim.surface();
  if (writes) frames->write(0.0, frame_of(sim, x0));
  if (joint_frames) joint_frames->write(0.0, joint_frame(sim));
  if (writes) bodies->add_state(0, sim);

  const double frame_dt = *scene.output.frame_dt;
  double next_frame = frame_dt;
  int failed = 0;
  Progress progress(total);
  for (int k = 0; k < total; ++k) {
    const StepStats s = sim.step();
    if (writes) stats->add_row(stats_row(s));
    if (writes) bodies->add_state(s.step, sim);
    if (!s.newton.linear_failure.empty())
      spdlog::warn("step {} (t = {:.4f} s): linear solver ({}) failed at {}", s.step, s.time, settings.linear_solver,
                   s.newton.linear_failure);
    if (!s.newton.converged) {
      ++failed;
      spdlog::warn("step {} (t = {:.4f} s): Newton did not converge after {} iterations: {} (last step speed {:.3g} m/s, tolerance {:.3g} m/s)",
                   s.step, s.time, s.newton.iterations, s.newton.failure, s.newton.last_step_speed, settings.tolerance);
    }
    if (sim.time() >= next_frame - 1e-9 * frame_dt || k + 1 == total) {
      if (writes) {
        frames->write(sim.time(), frame_of(sim, x0));
        stats->flush();
        if (joints) {
          add_joint_rows(*joints, sim, s.step);
          joints->flush();
          joint_frames->write(sim.time(), joint_frame(sim));
        }
        if (bodies->size() < (std::size_t(8) << 20)) bodies->flush();  // large ones: at the end only
      }
      next_frame += frame_dt;
    }
    if (writes) progress.update(s.step, s.time, s.newton.iterations);
  }
  if (!writes) return failed ? 3 : 0;
  progress.finish();
  stats->flush();
  bodies->flush();
  spdlog::info("wrote {} frames to {}; {} of {} steps did not converge", frames->frame_count(),
               frames->pvd_path().string(), failed, total);
  return failed ? 3 : 0;
}

}  // namespace stiffsoft

#include <stiffsoft/io/recorder.hpp>

#include <stdexcept>

#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/io/csv_rows.hpp>
#include <stiffsoft/io/paraview_script.hpp>
#include <stiffsoft/io/simulation_frame.hpp>
#include <stiffsoft/scene/scene_loader.hpp>

namespace stiffsoft {

namespace {

/// Creates `out` and writes the resolved scene into it; returns `out`. std::invalid_argument
/// when `out` is something other than a folder (a file, say).
const std::filesystem::path& prepared_folder(const std::filesystem::path& out, const SceneDescription& scene) {
  if (std::filesystem::exists(out) && !std::filesystem::is_directory(out))
    throw std::invalid_argument("output folder " + out.string() + ": exists and is not a folder");
  std::filesystem::create_directories(out);
  write_file_atomically(out / "scene.resolved.json",
                        [&](std::ostream& os) { os << resolved_scene_json(scene).dump(2) << '\n'; });
  return out;
}

}  // namespace

const std::vector<std::string>& Recorder::joint_columns() {
  static const std::vector<std::string> columns{"step", "time",    "joint",   "x",       "y",
                                                "z",    "force_x", "force_y", "force_z", "force"};
  return columns;
}

Recorder::Recorder(const std::filesystem::path& out, const SceneDescription& scene, const Simulation& sim,
                   int checkpoint_every)
    : m_sim(sim),
      m_out(out),
      m_scene_fingerprint(scene_fingerprint(scene)),
      m_checkpoint_every(checkpoint_every),
      m_x0(sim.surface()),
      m_frame_dt(scene.output.frame_dt.value()),
      m_next_frame(sim.time() + m_frame_dt),
      m_frames(prepared_folder(out, scene), scene.name),
      m_stats(out / "stats.csv", step_stats_column_names()),
      m_bodies(out / "bodies.csv"),
      m_body_names(body_names(sim.model())) {
  if (!scene.joints.empty()) {
    m_joints.emplace(out / "joints.csv", joint_columns());
    m_joint_frames.emplace(out, scene.name);
  }
  const std::vector<BodyFrame> first = body_frames(sim, m_x0);
  write_paraview_script(paraview_script_path(out, scene.name), paraview_scene(scene.name, first, scene.gravity));
  m_frames.write(sim.time(), first);
  if (m_joint_frames) m_joint_frames->write(sim.time(), joint_frame_entries(sim));
  m_bodies.add_states(0, sim.time(), m_body_names, body_states(sim));
  m_stats.flush();
  if (m_joints) m_joints->flush();
  m_bodies.flush();
  if (m_checkpoint_every > 0) write_checkpoint(checkpoint_now());
  m_frames_due = m_frames_written = m_frames.frame_count();
}

Recorder::ResumeCheck Recorder::checked_resume(const std::filesystem::path& out, const SceneDescription& scene,
                                               const Checkpoint& checkpoint) {
  const std::uint64_t fingerprint = scene_fingerprint(scene);
  if (fingerprint != checkpoint.scene_fingerprint)
    throw ResumeError(out.string() + ": the scene (its settings or a mesh file) changed since the checkpoint; " +
                      "run it again without --resume, into a new folder");
  const int step = checkpoint.state.step;
  // stats.csv and bodies.csv must reach the checkpoint's step; each file is read only back
  // from its end.
  const auto reaching_step = [&](const std::filesystem::path& file, const std::vector<std::string>& columns) {
    const CsvEnd end = csv_end_through_step(file, columns, step);
    if (end.last_step != step)
      throw ResumeError(file.string() + ": holds steps up to " + std::to_string(end.last_step) +
                        ", the checkpoint is at step " + std::to_string(step) + " (damaged output folder)");
    return end;
  };
  ResumeCheck check{fingerprint, reaching_step(out / "stats.csv", step_stats_column_names()),
                    reaching_step(out / "bodies.csv", body_state_columns()), std::nullopt};
  if (!scene.joints.empty()) check.joints = csv_end_through_step(out / "joints.csv", joint_columns(), step);
  return check;
}

Recorder::Recorder(const std::filesystem::path& out, const SceneDescription& scene, Simulation& sim,
                   const Checkpoint& checkpoint, int checkpoint_every)
    : Recorder(out, scene, sim, checkpoint, checkpoint_every, checked_resume(out, scene, checkpoint)) {}

Recorder::Recorder(const std::filesystem::path& out, const SceneDescription& scene, Simulation& sim,
                   const Checkpoint& checkpoint, int checkpoint_every, ResumeCheck check)
    : m_sim(sim),
      m_out(out),
      m_scene_fingerprint(check.scene_fingerprint),
      m_checkpoint_every(checkpoint_every),
      m_x0(sim.surface()),
      m_frame_dt(scene.output.frame_dt.value()),
      m_next_frame(checkpoint.next_frame),
      m_frames(prepared_folder(out, scene), scene.name),
      m_stats(out / "stats.csv", step_stats_column_names()),
      m_bodies(out / "bodies.csv"),
      m_body_names(body_names(sim.model())) {
  if (sim.time() != 0) throw std::invalid_argument("Recorder: a run is resumed into a simulation at t = 0");
  remove_stale_temporaries(out);  // a killed writer's half-written files
  m_stats.reload(check.stats);
  m_bodies.reload(check.bodies);
  if (check.joints) {
    m_joints.emplace(out / "joints.csv", joint_columns());
    m_joints->reload(*check.joints);
    m_joint_frames.emplace(out, scene.name);
    m_joint_frames->continue_from(checkpoint.joint_frames);
  }
  m_frames.continue_from(checkpoint.frames);
  // An older run's folder gets the script too; the camera is the first frame's, as in a fresh run.
  write_paraview_script(paraview_script_path(out, scene.name),
                        paraview_scene(scene.name, body_frames(sim, m_x0), scene.gravity));
  sim.restore(checkpoint.state);
  m_frames_due = m_frames_written = m_frames.frame_count();
}

void Recorder::record(const StepStats& s, bool last) {
  m_writer.submit([this, row = step_stats_row(s), step = s.step, time = m_sim.time(),
                   states = body_states(m_sim)] {
    m_stats.add_row(row);
    m_bodies.add_states(step, time, m_body_names, states);
  });
  if (m_sim.time() >= m_next_frame - 1e-9 * m_frame_dt || last) {
    m_next_frame += m_frame_dt;  // before the frame: its checkpoint holds the next one's time
    write_frame(s.step, last);
  }
  if (last) m_writer.wait();  // the run's files complete, for a caller that never calls finish()
}

void Recorder::write_frame(int step, bool last) {
  ++m_frames_due;
  std::optional<Checkpoint> checkpoint;
  if (m_checkpoint_every > 0 && (last || m_frames_due % m_checkpoint_every == 0))
    checkpoint = checkpoint_now();
  std::vector<JointFrameEntry> joints;
  if (m_joints) joints = joint_frame_entries(m_sim);
  m_writer.submit([this, step, time = m_sim.time(), bodies = body_frames(m_sim, m_x0),
                   joints = std::move(joints), checkpoint = std::move(checkpoint)] {
    m_frames.write(time, bodies);
    m_frames_written = m_frames.frame_count();
    m_stats.flush();
    if (m_joints) {
      for (std::size_t j = 0; j < joints.size(); ++j) {
        const Eigen::Vector3d& x = joints[j].x_a;
        const Eigen::Vector3d& f = joints[j].force;
        m_joints->add_row(
            {double(step), time, double(j), x.x(), x.y(), x.z(), f.x(), f.y(), f.z(), f.norm()});
      }
      m_joints->flush();
      m_joint_frames->write(time, joints);
    }
    m_bodies.flush();
    if (checkpoint) write_checkpoint(*checkpoint);
  });
}

Checkpoint Recorder::checkpoint_now() const {
  Checkpoint c;
  c.scene_fingerprint = m_scene_fingerprint;
  c.state = m_sim.state();
  c.next_frame = m_next_frame;
  return c;
}

void Recorder::write_checkpoint(Checkpoint c) const {
  c.frames = m_frames.frames();
  if (m_joint_frames) c.joint_frames = m_joint_frames->frames();
  stiffsoft::write_checkpoint(m_out / "checkpoint.bin", c);
}

void Recorder::finish() {
  m_writer.wait();
  m_stats.flush();
  m_bodies.flush();
}

}  // namespace stiffsoft

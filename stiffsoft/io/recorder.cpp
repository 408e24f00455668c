#include <stiffsoft/io/recorder.hpp>

#include <stdexcept>

#include <stiffsoft/io/atomic_file.hpp>
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

/// bodies.csv is flushed at every frame only while it is smaller than this (bytes of rows).
constexpr std::size_t kBodiesFlushLimit = std::size_t(8) << 20;

}  // namespace

const std::vector<std::string>& Recorder::joint_columns() {
  static const std::vector<std::string> columns{"step", "time",    "joint",   "x",       "y",
                                                "z",    "force_x", "force_y", "force_z", "force"};
  return columns;
}

Recorder::Recorder(const std::filesystem::path& out, const SceneDescription& scene, const Simulation& sim)
    : m_sim(sim),
      m_x0(sim.surface()),
      m_frame_dt(scene.output.frame_dt.value()),
      m_next_frame(sim.time() + m_frame_dt),
      m_frames(prepared_folder(out, scene), scene.name),
      m_stats(out / "stats.csv", step_stats_column_names()),
      m_bodies(out / "bodies.csv") {
  if (!scene.joints.empty()) {
    m_joints.emplace(out / "joints.csv", joint_columns());
    m_joint_frames.emplace(out, scene.name);
  }
  m_frames.write(sim.time(), body_frames(sim, m_x0));
  if (m_joint_frames) m_joint_frames->write(sim.time(), joint_frame_entries(sim));
  m_bodies.add_state(0, sim);
}

void Recorder::record(const StepStats& s, bool last) {
  m_stats.add_row(step_stats_row(s));
  m_bodies.add_state(s.step, m_sim);
  if (m_sim.time() >= m_next_frame - 1e-9 * m_frame_dt || last) {
    write_frame(s.step);
    m_next_frame += m_frame_dt;
  }
}

void Recorder::write_frame(int step) {
  m_frames.write(m_sim.time(), body_frames(m_sim, m_x0));
  m_stats.flush();
  if (m_joints) {
    const std::vector<JointFrameEntry> joints = joint_frame_entries(m_sim);
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const Eigen::Vector3d& x = joints[j].x_a;
      const Eigen::Vector3d& f = joints[j].force;
      m_joints->add_row({double(step), m_sim.time(), double(j), x.x(), x.y(), x.z(), f.x(), f.y(), f.z(), f.norm()});
    }
    m_joints->flush();
    m_joint_frames->write(m_sim.time(), joints);
  }
  if (m_bodies.size() < kBodiesFlushLimit) m_bodies.flush();  // large ones: at the end only
}

void Recorder::finish() {
  m_stats.flush();
  m_bodies.flush();
}

}  // namespace stiffsoft

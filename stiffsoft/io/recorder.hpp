#pragma once
/// @file Everything `stiffsoft run` writes, for any program that steps a Simulation: the
/// ParaView series, `stats.csv`, `bodies.csv`, the joints' output and the resolved scene.
///
///     stiffsoft::SceneSimulation run = stiffsoft::make_simulation("scenes/default.json");
///     stiffsoft::Recorder recorder("out/default", run.scene, run.simulation);
///     for (int k = 0; k < 100; ++k) recorder.record(run.simulation.step(), k + 1 == 100);
///     recorder.finish();

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>

#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/io/background_writer.hpp>
#include <stiffsoft/io/body_state_writer.hpp>
#include <stiffsoft/io/checkpoint.hpp>
#include <stiffsoft/io/csv_rows.hpp>
#include <stiffsoft/io/frame_writer.hpp>
#include <stiffsoft/io/joint_frame_writer.hpp>
#include <stiffsoft/io/stats_writer.hpp>
#include <stiffsoft/scene/scene.hpp>

namespace stiffsoft {

/// Writes one run into a folder (frames, `.pvd` files and the scene atomically, the CSV files
/// whole at their first flush and appended after it: a killed run leaves whole files, but for a
/// CSV file's partial last line, which a resumed run drops):
/// - `NAME.pvd` + `frames/NAME_NNNNNN.vtm`: a frame at t = 0, then every `output.frame_dt`
///   of simulated time and after the last step (io/frame_writer.hpp);
/// - `stats.csv`: one row per step, the columns of step_stats_columns();
/// - `bodies.csv`: every body's state at t = 0 and after every step (io/body_state_writer.hpp);
/// - with joints, `joints.csv` (per frame: each joint's anchor and force on body a) and
///   `NAME_joints.pvd` + `frames/NAME_joints_NNNNNN.vtp` (io/joint_frame_writer.hpp);
/// - `scene.resolved.json`: the scene with every default filled in;
/// - `NAME.paraview.py`: a ParaView script that opens the series coloured, with a camera
///   (io/paraview_script.hpp);
/// - `checkpoint.bin` every `checkpoint_every` frames and with the last one (io/checkpoint.hpp):
///   what a resumed run (`stiffsoft run --resume`) continues from.
/// Files are flushed at every frame, before the checkpoint, so that a checkpoint never lists
/// more than the files hold.
///
/// The simulation's thread only takes what each step and frame write (the stats row, the
/// bodies' states, the frame's arrays, the checkpoint's state); formatting, compressing and
/// writing run on a thread of the recorder's own (io/background_writer.hpp), in the same order,
/// while the next steps are computed. Everything recorded is on disk once record() with `last`
/// or finish() returns (or the recorder is destroyed); a write that fails throws from the next
/// record() or finish(), with the files then holding every frame, row and checkpoint written
/// before it.
class Recorder {
 public:
  /// Frames between two checkpoints unless told otherwise (`stiffsoft run --checkpoint-every`).
  static constexpr int kCheckpointEvery = 1;

  /// Creates `out`, writes `scene.resolved.json`, the frame at the simulation's present state
  /// and a checkpoint; std::invalid_argument when `out` exists and is not a folder. `scene` is
  /// the resolved scene `sim` was made from (SceneSimulation::scene); `sim` must outlive the
  /// recorder. `checkpoint_every`: frames between checkpoints, 0: none.
  Recorder(const std::filesystem::path& out, const SceneDescription& scene, const Simulation& sim,
           int checkpoint_every = kCheckpointEvery);
  /// Continues the run recorded in `out` from `checkpoint` (read_checkpoint(out /
  /// "checkpoint.bin")): `sim`, the scene's simulation at t = 0, is restored to the checkpoint's
  /// state; the .pvd files list exactly the checkpoint's frames again and the CSV files keep
  /// their rows up to its step. Throws ResumeError when the scene differs from the checkpoint's
  /// (settings or mesh files) or a CSV file does not reach the checkpoint's step.
  Recorder(const std::filesystem::path& out, const SceneDescription& scene, Simulation& sim, const Checkpoint& checkpoint,
           int checkpoint_every = kCheckpointEvery);
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Records the step `s` the simulation has just taken; writes a frame when one is due or
  /// when `last` is true, and with `last` returns once everything recorded is on disk.
  /// Rethrows the error of an earlier write that failed.
  void record(const StepStats& s, bool last = false);
  /// Waits for the writes in flight and flushes what is not on disk yet (stats.csv,
  /// bodies.csv); rethrows the error of a write that failed.
  void finish();
  /// Frames on disk so far (all those recorded once finish() has returned).
  int frame_count() const { return m_frames_written; }
  /// OUT/NAME.pvd.
  std::filesystem::path pvd_path() const { return m_frames.pvd_path(); }

  /// The columns of `joints.csv`.
  static const std::vector<std::string>& joint_columns();

 private:
  /// What a resume reads and checks before anything in the folder is touched (the writers,
  /// which write their files when destroyed, do not exist yet): the scene's fingerprint and
  /// where the CSV files' rows through the checkpoint's step end.
  struct ResumeCheck {
    std::uint64_t scene_fingerprint;
    CsvEnd stats;
    CsvEnd bodies;
    std::optional<CsvEnd> joints;
  };
  /// Checks the scene against the checkpoint and finds where the CSV files' rows through its
  /// step end (stats.csv and bodies.csv must reach it); a ResumeError names the file or the
  /// folder.
  static ResumeCheck checked_resume(const std::filesystem::path& out, const SceneDescription& scene,
                                    const Checkpoint& checkpoint);
  /// The resuming constructor, given what checked_resume() read.
  Recorder(const std::filesystem::path& out, const SceneDescription& scene, Simulation& sim, const Checkpoint& checkpoint,
           int checkpoint_every, ResumeCheck check);
  /// Queues the frame at the simulation's present state, the rows it closes and, when due,
  /// a checkpoint.
  void write_frame(int step, bool last);
  /// A checkpoint of the simulation's present state, without the frame lists (the writer's
  /// thread adds them once the frame is on disk).
  Checkpoint checkpoint_now() const;
  /// Writes `c` with the frame lists of the frames on disk (on the writer's thread, or before
  /// it has jobs).
  void write_checkpoint(Checkpoint c) const;

  const Simulation& m_sim;
  std::filesystem::path m_out;
  std::uint64_t m_scene_fingerprint;
  int m_checkpoint_every;
  Eigen::MatrixX3d m_x0;  ///< the surface at the first frame, for displacements
  double m_frame_dt;
  double m_next_frame;
  FrameWriter m_frames;
  StatsWriter m_stats;
  BodyStateWriter m_bodies;
  std::optional<StatsWriter> m_joints;
  std::optional<JointFrameWriter> m_joint_frames;
  std::vector<std::string> m_body_names;  ///< bodies.csv's body column, in the model's order
  int m_frames_due = 0;                   ///< frames recorded (queued or on disk)
  std::atomic<int> m_frames_written = 0;  ///< frames on disk
  /// Last, so that it is destroyed first: its destructor runs the jobs still queued, which use
  /// the writers above.
  BackgroundWriter m_writer;
};

}  // namespace stiffsoft

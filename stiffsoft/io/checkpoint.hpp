#pragma once
/// @file `OUT/checkpoint.bin`: what `stiffsoft run --resume` needs to continue a killed run
/// exactly: the simulation's state (SimulationState: time, step, q, q̇ and their previous
/// values, κ, the linear solver's choice), where the recorder was (the frames listed in the
/// .pvd files, the next frame time) and a fingerprint of the scene. Written atomically by the
/// Recorder after a frame.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/scene/scene.hpp>

namespace stiffsoft {

/// A run that cannot be resumed: no checkpoint, a damaged one, or a scene that changed.
class ResumeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The frames a .pvd lists: (time in s, file relative to the output folder).
using FrameList = std::vector<std::pair<double, std::string>>;

/// Everything a resumed run continues from.
struct Checkpoint {
  std::uint64_t scene_fingerprint = 0;  ///< scene_fingerprint() of the run's scene
  SimulationState state;                ///< the simulation after the checkpoint's step
  double next_frame = 0;                ///< simulated time of the next due frame (s)
  FrameList frames;                     ///< the bodies' .pvd entries so far
  FrameList joint_frames;               ///< the joints' .pvd entries so far (empty without joints)
};

/// A fingerprint of a resolved scene: FNV-1a of its resolved JSON and of the bytes of every
/// mesh file it names, so that any change of a setting or a mesh shows. Throws ResumeError
/// naming a mesh file that cannot be read.
std::uint64_t scene_fingerprint(const SceneDescription& scene);

/// Writes `checkpoint` to `file` atomically (binary, with a format tag and a checksum).
void write_checkpoint(const std::filesystem::path& file, const Checkpoint& checkpoint);

/// Reads a checkpoint; throws ResumeError naming the file when it is missing, not a checkpoint,
/// of another format version, truncated or damaged (checksum).
Checkpoint read_checkpoint(const std::filesystem::path& file);

}  // namespace stiffsoft

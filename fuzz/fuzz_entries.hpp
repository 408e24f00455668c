#pragma once
/// @file What the fuzzers feed to the loader, one function per input kind (docs/robustness.md,
/// "Fuzzing the loader"). The libFuzzer targets in fuzz/ and the regression test over the inputs
/// the fuzzers once found (tests/fuzz/) both call these, so a finding stays fixed in every build.

#include <cstdint>
#include <span>
#include <string>

namespace stiffsoft::fuzz {

/// What the loader made of one input: accepted, or refused with an error message.
struct Outcome {
  bool accepted = false;  ///< the input went through every stage without an error
  std::string error;      ///< the refusal's message (empty when accepted)
};

/// The name the inputs carry in error messages: a refusal must name it (a clear error names the file).
inline constexpr const char* scene_label = "fuzz.json";

/// Bytes as a scene file: load_scene_from_string() (relative mesh paths resolved against
/// tests/scene/data/good, so seeds can name tests/scene/data/meshes/tet.obj), then
/// make_simulation() within small element limits (20,000 tets and triangles per body, so that an
/// input cannot spend minutes in gmsh). Never steps. Any std::exception is a refusal.
Outcome scene_input(std::span<const std::uint8_t> bytes);

/// Bytes as a surface mesh file with `extension` (".obj" or ".stl"): written to a per-process
/// scratch file, read_surface_mesh(), check_closed_manifold(), check_not_self_intersecting(),
/// mass_moments(). Any std::exception is a refusal.
Outcome surface_mesh_input(std::span<const std::uint8_t> bytes, const std::string& extension);

/// Bytes as a gmsh .msh file: written to a per-process scratch file, read_msh() (gmsh's reader),
/// then boundary_surface() and its closed_manifold_problem(). Any std::exception is a refusal.
Outcome msh_input(std::span<const std::uint8_t> bytes);

/// The kinds of input there is a fuzzer for, named as the fuzzers are (`fuzz_scene`, …) and
/// the folders of tests/fuzz/.
enum class InputKind { scene, obj, stl, msh };

/// The kind named `name` ("scene", "obj", "stl", "msh"). @throws std::invalid_argument otherwise
InputKind input_kind(const std::string& name);

/// The function above for `kind`.
Outcome run_input(InputKind kind, std::span<const std::uint8_t> bytes);

/// What a refusal of an input of `kind` must name: scene_label, or the scratch file's name.
std::string input_label(InputKind kind);

/// True when `outcome` is accepted or its error names the input (`label`, the scene label or the
/// scratch file's name): what a user needs to find the fault.
bool is_clear(const Outcome& outcome, const std::string& label);

/// The scratch file's name for `extension` in this process (what surface_mesh_input() and
/// msh_input() errors must name).
std::string scratch_name(const std::string& extension);

}  // namespace stiffsoft::fuzz

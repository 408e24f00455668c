/// The inputs the fuzzers found (tests/fuzz/data/KIND/, docs/robustness.md "Fuzzing the loader"),
/// replayed through the same entry functions: each must now be accepted or refused with an error
/// that names the file, without a crash (and, in the sanitize build, without a sanitizer report).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz/fuzz_entries.hpp"

namespace {

using stiffsoft::fuzz::InputKind;

std::vector<std::uint8_t> bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

stiffsoft::fuzz::Outcome run_file(InputKind kind, const std::filesystem::path& file) {
  const std::vector<std::uint8_t> bytes = bytes_of(file);
  return stiffsoft::fuzz::run_input(kind, bytes);
}

const std::filesystem::path source = STIFFSOFT_SOURCE_DIR;

TEST(FuzzEntries, AcceptValidInputsOfEveryKind) {
  // The harness itself: a valid input of each kind goes through every stage.
  const std::pair<InputKind, std::filesystem::path> valid[] = {
      {InputKind::scene, source / "tests/scene/data/good/minimal.json"},
      {InputKind::obj, source / "tests/scene/data/meshes/tet.obj"},
      {InputKind::stl, source / "tests/meshing/data/tet_cube_half_metre.stl"},
      {InputKind::msh, source / "tests/meshing/data/tet_two_tets.msh"}};
  for (const auto& [kind, file] : valid) {
    const auto outcome = run_file(kind, file);
    EXPECT_TRUE(outcome.accepted) << file << ": " << outcome.error;
  }
}

TEST(FuzzEntries, RefuseInvalidInputsNamingTheFile) {
  const std::pair<InputKind, std::filesystem::path> invalid[] = {
      {InputKind::scene, source / "tests/scene/data/broken/unknown_key.json"},
      {InputKind::obj, source / "tests/apps/data/open_box.obj"},
      {InputKind::msh, source / "tests/apps/data/garbage.msh"}};
  for (const auto& [kind, file] : invalid) {
    const auto outcome = run_file(kind, file);
    EXPECT_FALSE(outcome.accepted) << file;
    EXPECT_TRUE(stiffsoft::fuzz::is_clear(outcome, stiffsoft::fuzz::input_label(kind))) << file << ": " << outcome.error;
  }
}

TEST(FuzzRegressions, EveryFindingIsAcceptedOrRefusedClearly) {
  int replayed = 0;
  for (const char* name : {"scene", "obj", "stl", "msh"}) {
    const std::filesystem::path folder = source / "tests/fuzz/data" / name;
    if (!std::filesystem::is_directory(folder)) continue;
    const InputKind kind = stiffsoft::fuzz::input_kind(name);
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      SCOPED_TRACE(entry.path().string());
      const auto outcome = run_file(kind, entry.path());
      EXPECT_TRUE(stiffsoft::fuzz::is_clear(outcome, stiffsoft::fuzz::input_label(kind))) << outcome.error;
      ++replayed;
    }
  }
  RecordProperty("replayed", replayed);
}

}  // namespace

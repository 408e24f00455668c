/// @file `stiffsoft run --resume`: a run killed with SIGKILL and resumed writes exactly the
/// files of the uninterrupted run (a rigid pile, a hybrid scene with BDF-2 and friction, a
/// jointed ragdoll), and a changed scene, another version's files, a missing or a damaged
/// checkpoint give clear errors and leave the folder as it was.

#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include <nlohmann/json.hpp>

#include "scene_helpers.hpp"

extern char** environ;

namespace stiffsoft::testing {
namespace {

namespace fs = std::filesystem;

/// Frames listed in a .pvd (0 when it is missing).
int listed_frames(const fs::path& pvd) {
  const std::string text = read_text(pvd);
  int n = 0;
  for (std::size_t at = text.find("<DataSet"); at != std::string::npos; at = text.find("<DataSet", at + 1)) ++n;
  return n;
}

/// Starts `stiffsoft run scene -o out --steps N`, kills it with SIGKILL once its .pvd lists
/// `frames` frames; returns false when it ended by itself first.
bool run_and_kill(const fs::path& scene, const fs::path& out, int steps, const fs::path& pvd, int frames) {
  const std::string steps_text = std::to_string(steps);
  std::vector<std::string> args{STIFFSOFT_BINARY, "run", scene.string(), "-o", out.string(), "--steps", steps_text};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int started = posix_spawn(&pid, STIFFSOFT_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (started != 0) return false;
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (listed_frames(pvd) >= frames) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return WIFSIGNALED(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

/// stats.csv without its wall-clock columns (seconds_*), which differ from run to run.
std::string stats_without_timings(const fs::path& file) {
  std::ifstream in(file);
  std::string line, result;
  std::vector<bool> keep;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (std::size_t i = 0; std::getline(row, cell, ','); ++i) {
      if (keep.size() <= i) keep.push_back(cell.rfind("seconds", 0) != 0);  // the header decides
      if (keep[i]) result += cell + ',';
    }
    result += '\n';
  }
  return result;
}

/// Every file under `a` equals the one under `b` (stats.csv apart from its timings), and
/// neither has a file the other lacks.
void expect_same_output(const fs::path& a, const fs::path& b) {
  std::vector<fs::path> files_a, files_b;
  for (const auto& e : fs::recursive_directory_iterator(a))
    if (e.is_regular_file()) files_a.push_back(fs::relative(e.path(), a));
  for (const auto& e : fs::recursive_directory_iterator(b))
    if (e.is_regular_file()) files_b.push_back(fs::relative(e.path(), b));
  std::sort(files_a.begin(), files_a.end());
  std::sort(files_b.begin(), files_b.end());
  EXPECT_EQ(files_a, files_b);
  int frames = 0;
  for (const fs::path& f : files_a) {
    if (f.filename() == "stats.csv") {
      EXPECT_EQ(stats_without_timings(a / f), stats_without_timings(b / f));
    } else {
      EXPECT_TRUE(read_text(a / f) == read_text(b / f)) << f << " differs between the uninterrupted and the resumed run";
      frames += f.extension() == ".vtm";
    }
  }
  EXPECT_GT(frames, 10);
}

/// Runs `scene` for `steps` steps whole, and killed after `kill_at` frames then resumed; the
/// two output folders must be the same.
void expect_resume_matches(const fs::path& scene, int steps, int kill_at) {
  const fs::path dir = temporary_folder("resume");
  const std::string name = scene.stem().string();
  ASSERT_EQ(run_stiffsoft("run " + scene.string() + " -o " + (dir / "whole").string() + " --steps " + std::to_string(steps),
                          dir / "whole.log"), 0)
      << read_text(dir / "whole.log");
  ASSERT_TRUE(run_and_kill(scene, dir / "killed", steps, dir / "killed" / (name + ".pvd"), kill_at))
      << "the run ended before it could be killed: give it more steps";
  const int listed = listed_frames(dir / "killed" / (name + ".pvd"));
  ASSERT_EQ(run_stiffsoft("run " + scene.string() + " -o " + (dir / "killed").string() + " --steps " +
                              std::to_string(steps) + " --resume",
                          dir / "resume.log"), 0)
      << read_text(dir / "resume.log");
  EXPECT_NE(read_text(dir / "resume.log").find("resuming at step"), std::string::npos);
  EXPECT_GT(listed_frames(dir / "killed" / (name + ".pvd")), listed);
  expect_same_output(dir / "whole", dir / "killed");
  fs::remove_all(dir);
}

/// A copy of a scene file with its integrator set, in `dir`.
fs::path with_integrator(const fs::path& scene, const std::string& integrator, const fs::path& dir) {
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(read_text(scene));
  j["time"]["integrator"] = integrator;
  const fs::path copy = dir / scene.filename();
  std::ofstream(copy) << j.dump(1);
  return copy;
}

const fs::path kScenes = fs::path(STIFFSOFT_SOURCE_DIR) / "scenes";

TEST(Resume, KilledRigidPileResumesToTheSameFiles) { expect_resume_matches(kScenes / "light.json", 240, 8); }

TEST(Resume, KilledHybridBdf2SceneWithFrictionResumesToTheSameFiles) {
  const fs::path dir = temporary_folder("resume_scene");
  expect_resume_matches(with_integrator(kScenes / "soft_ball_on_boxes.json", "bdf2", dir), 300, 10);
  fs::remove_all(dir);
}

TEST(Resume, KilledSceneWithSleepingBodiesResumesToTheSameFiles) {
  const fs::path dir = temporary_folder("resume_sleep");
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(read_text(kScenes / "box_stack.json"));
  j["solver"]["sleep_time"] = 0.2;
  const fs::path scene = dir / "box_stack.json";
  std::ofstream(scene) << j.dump(1);
  // The run is killed at its 70th frame (step 117 of h = 0.01 at 60 frames a second): the stack
  // must be asleep by then, for the checkpoint to carry sleeping bodies.
  ASSERT_EQ(run_stiffsoft("run " + scene.string() + " -o " + (dir / "probe").string() + " --steps 110", dir / "probe.log"), 0)
      << read_text(dir / "probe.log");
  const std::vector<double> sleeping = csv_column(dir / "probe" / "stats.csv", "sleeping_bodies");
  ASSERT_FALSE(sleeping.empty());
  EXPECT_GT(sleeping.back(), 0) << "the stack does not sleep by step 110";
  expect_resume_matches(scene, 200, 70);
  fs::remove_all(dir);
}

TEST(Resume, KilledJointedSceneResumesToTheSameFiles) { expect_resume_matches(kScenes / "ragdoll_steps.json", 240, 10); }

TEST(Resume, RefusesAChangedSceneAnotherVersionsFilesAMissingAndADamagedCheckpoint) {
  const fs::path dir = temporary_folder("resume_errors");
  const fs::path scene = with_integrator(kScenes / "box_stack.json", "backward_euler", dir);
  const fs::path out = dir / "out";
  ASSERT_EQ(run_stiffsoft("run " + scene.string() + " -o " + out.string() + " --steps 20", dir / "a.log"), 0);
  const int frames = listed_frames(out / "box_stack.pvd");
  ASSERT_GT(frames, 2);

  fs::create_directories(dir / "changed");
  const fs::path changed = with_integrator(kScenes / "box_stack.json", "bdf2", dir / "changed");
  EXPECT_EQ(run_stiffsoft("run " + changed.string() + " -o " + out.string() + " --resume", dir / "b.log"), 2);
  EXPECT_NE(read_text(dir / "b.log").find("changed since the checkpoint"), std::string::npos) << read_text(dir / "b.log");
  EXPECT_EQ(listed_frames(out / "box_stack.pvd"), frames) << "a refused resume leaves the folder as it was";

  // stats.csv from a version with other columns: refused, and nothing already written is lost.
  const std::string stats = read_text(out / "stats.csv"), bodies = read_text(out / "bodies.csv");
  const std::string pvd = read_text(out / "box_stack.pvd");
  const std::string older = "step,time,newton_iterations" + stats.substr(stats.find('\n'));
  std::ofstream(out / "stats.csv", std::ios::binary) << older;
  EXPECT_EQ(run_stiffsoft("run " + scene.string() + " -o " + out.string() + " --resume", dir / "e.log"), 2);
  EXPECT_NE(read_text(dir / "e.log").find("not the header this version writes"), std::string::npos) << read_text(dir / "e.log");
  EXPECT_EQ(read_text(out / "stats.csv"), older);
  EXPECT_EQ(read_text(out / "bodies.csv"), bodies);
  EXPECT_EQ(read_text(out / "box_stack.pvd"), pvd);
  std::ofstream(out / "stats.csv", std::ios::binary) << stats;

  std::string bytes = read_text(out / "checkpoint.bin");
  bytes[bytes.size() / 2] ^= 0x40;
  std::ofstream(out / "checkpoint.bin", std::ios::binary) << bytes;
  EXPECT_EQ(run_stiffsoft("run " + scene.string() + " -o " + out.string() + " --resume", dir / "c.log"), 2);
  EXPECT_NE(read_text(dir / "c.log").find("checkpoint.bin: damaged checkpoint"), std::string::npos) << read_text(dir / "c.log");

  EXPECT_EQ(run_stiffsoft("run " + scene.string() + " -o " + (dir / "empty").string() + " --resume", dir / "d.log"), 2);
  EXPECT_NE(read_text(dir / "d.log").find("no checkpoint to resume from"), std::string::npos) << read_text(dir / "d.log");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stiffsoft::testing

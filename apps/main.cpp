/// @file The `stiffsoft` command: run a scene, check written frames, render them to pictures, run a
/// convergence study, print the scene schema, print versions.

#include <CLI/CLI.hpp>
#include <gmsh.h>
#include <petscversion.h>
#include <spdlog/spdlog.h>
#include <vtkVersionMacros.h>

#include <Eigen/Core>
#include <iostream>

#include "check_command.hpp"
#include "apps/cli/petsc_command_line.hpp"
#include <stiffsoft/scene/scene_schema.hpp>
#include "render_command.hpp"
#include "run_command.hpp"
#include "schema_command.hpp"
#include <stiffsoft/io/checkpoint.hpp>
#include <stiffsoft/study/study.hpp>
#include <stiffsoft/study/study_spec.hpp>

namespace {
std::string version_text() {
  return std::string("stiffsoft ") + STIFFSOFT_VERSION + " (Eigen " + std::to_string(EIGEN_WORLD_VERSION) + "." +
         std::to_string(EIGEN_MAJOR_VERSION) + "." + std::to_string(EIGEN_MINOR_VERSION) + ", PETSc " +
         std::to_string(PETSC_VERSION_MAJOR) + "." + std::to_string(PETSC_VERSION_MINOR) + "." +
         std::to_string(PETSC_VERSION_SUBMINOR) + ", gmsh " + GMSH_API_VERSION + ", VTK " + VTK_VERSION + ")";
}
}  // namespace

int main(int argc, char** argv) {
  // PETSc's options (-ksp_type cg, -pc_type gamg, -ksp_monitor, -log_view, …) go to PETSc;
  // under `mpirun -n N` every rank runs the scene, the linear solve is distributed and only
  // rank 0 logs and writes.
  stiffsoft::PetscCommandLine petsc(argc, argv);
  if (stiffsoft::PetscSession::rank() != 0) spdlog::set_level(spdlog::level::off);
  CLI::App app{"stiffsoft: stiff (affine) and soft solids in contact, intersection-free"};
  app.set_version_flag("--version", version_text());
  app.require_subcommand(1);

  stiffsoft::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "run a JSON scene, writing VTK frames for ParaView");
  run_cmd->add_option("scene", run.scene, "scene file (.json)")->required();
  run_cmd->add_option("-o,--out", run.out, "output folder")->required();
  run_cmd->add_option("--steps", run.steps, "number of steps (default: the scene's duration)")->check(CLI::PositiveNumber);
  run_cmd->add_option("--threads", run.threads, "worker threads (default: all cores); the output is written on one more")->check(CLI::NonNegativeNumber);
  run_cmd->add_flag("--resume", run.resume, "continue the run in the output folder from its last checkpoint (same scene, same files)");
  run_cmd->add_option("--checkpoint-every", run.checkpoint_every, "frames between checkpoints for --resume (0: none)")
      ->check(CLI::NonNegativeNumber);
  run_cmd->add_option("--load-timeout", run.load_timeout, "seconds loading and meshing may take before the run is refused (0: no bound)")
      ->capture_default_str();
  run_cmd->add_option("--max-tets", run.limits.max_tets, "largest expected tetrahedron count of one soft body, estimated before meshing")
      ->check(CLI::PositiveNumber)->capture_default_str();
  run_cmd->add_option("--max-triangles", run.limits.max_triangles, "largest triangle count of one primitive body")
      ->check(CLI::PositiveNumber)->capture_default_str();

  std::filesystem::path pvd;
  CLI::App* check_cmd = app.add_subcommand("check", "exact intersection check of every frame of a .pvd series");
  check_cmd->add_option("pvd", pvd, "DIR/NAME.pvd written by `stiffsoft run`")->required();

  stiffsoft::RenderOptions render;
  std::string size = std::to_string(render.width) + "x" + std::to_string(render.height);
  CLI::App* render_cmd = app.add_subcommand(
      "render", "render the frames of a .pvd series to PNG (off screen; starts Xvfb without a display), a contact sheet, an .mp4");
  render_cmd->add_option("pvd", render.pvd, "DIR/NAME.pvd written by `stiffsoft run`")->required();
  render_cmd->add_option("-o,--out", render.out, "folder of the pictures (NAME_NNNNNN.png, NAME_sheet.png)")->required();
  render_cmd->add_option("--every", render.every, "render every N-th frame (and the last)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  render_cmd->add_option("--size", size, "picture size, WIDTHxHEIGHT pixels")
      ->check(CLI::Validator([](std::string& s) -> std::string {
        int w = 0, h = 0;
        char x = 0;
        return std::sscanf(s.c_str(), "%d%c%d", &w, &x, &h) == 3 && x == 'x' && w >= 16 && h >= 16 && w <= 8192 && h <= 8192
                   ? std::string() : std::string("expected WIDTHxHEIGHT, e.g. 960x540 (16 to 8192 pixels each)");
      }, "WxH"))->capture_default_str();
  render_cmd->add_option("--sheet-frames", render.sheet_frames, "frames on the contact sheet NAME_sheet.png")
      ->check(CLI::PositiveNumber)->capture_default_str();
  render_cmd->add_flag("--mp4", render.movie, "also write NAME.mp4 with ffmpeg (skipped with a message without it)");
  render_cmd->add_option("--fps", render.fps, "frames per second of the movie")->check(CLI::PositiveNumber)->capture_default_str();

  stiffsoft::study::StudyOptions study;
  CLI::App* study_cmd = app.add_subcommand("study", "run a convergence study: sweep a scene's settings, errors against a reference, orders, plots");
  study_cmd->add_option("study", study.study, "study file (.json, see studies/)")->required();
  study_cmd->add_option("-o,--out", study.out, "output folder (runs are cached in DIR/runs)")->required();
  study_cmd->add_option("--jobs", study.jobs, "runs at a time (default: the number of cores)")->check(CLI::NonNegativeNumber);
  study_cmd->add_flag("!--no-check", study.check, "skip `stiffsoft check` of every run's frames");

  bool markdown = false;
  CLI::App* schema_cmd = app.add_subcommand("schema", "print the scene schema: every key of a scene file, as JSON");
  schema_cmd->add_flag("--markdown", markdown,
                       "print it as the Markdown page docs/scenes.md instead (stiffsoft schema --markdown > docs/scenes.md)");

  CLI11_PARSE(app, petsc.program_argc(), petsc.program_argv());
  try {
    if (*run_cmd) return stiffsoft::run_scene(run);
    if (*check_cmd) return stiffsoft::check_frames(pvd);
    if (*render_cmd) {
      std::sscanf(size.c_str(), "%dx%d", &render.width, &render.height);
      return stiffsoft::render_frames(render);
    }
    if (*study_cmd) return stiffsoft::study::run_study(study);
    if (*schema_cmd) return stiffsoft::print_schema(markdown, std::cout);
  } catch (const stiffsoft::study::StudyError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const stiffsoft::SceneError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const stiffsoft::ResumeError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}

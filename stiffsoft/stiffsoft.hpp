#pragma once
/// @file stiffsoft's front door: the one header an embedding program includes.
///
///     #include <stiffsoft/stiffsoft.hpp>
///
///     stiffsoft::SceneSimulation run = stiffsoft::make_simulation("scene.json");  // or a SceneDescription
///     stiffsoft::Recorder recorder("out", run.scene, run.simulation);           // optional: ParaView output
///     while (run.simulation.time() < 1.0) recorder.record(run.simulation.step());
///     recorder.finish();
///
/// What each type is for, and which headers are stable: docs/api.md.

#include <stiffsoft/coupling/linear_solver/petsc_session.hpp>
#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/coupling/solver/simulation_settings.hpp>
#include <stiffsoft/coupling/solver/step_stats.hpp>
#include <stiffsoft/io/recorder.hpp>
#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene.hpp>
#include <stiffsoft/scene/scene_loader.hpp>
#include <stiffsoft/scene/scene_schema.hpp>
#include <stiffsoft/scene/scene_validation.hpp>
#include <stiffsoft/scene/schema_markdown.hpp>

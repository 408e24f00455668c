#pragma once
/// @file `peer_bench --verify`: checks that every engine holds the same scene as stiffsoft.
///
/// 1. Geometry: on each given scene, the engine's collision vertices (hull points, box corners,
///    mesh vertices, slice hulls), placed by its own poses at t = 0, coincide with stiffsoft's
///    surface vertices of the same body, both ways (nearest-vertex distance < 1e-5 m; one way
///    for MuJoCo's ground plane, whose rectangle is the ground's top face).
/// 2. Free flight (a tumbling box and a torus under gravity, h = 1 ms, 0.3 s): centre of mass
///    within 1e-5 m of c₀ + v₀ t + g (t² + h t)/2, where semi-implicit and backward Euler both
///    put it (a pose that lags a step, a wrong velocity or frame misses by millimetres), and
///    angular momentum R I Rᵀ ω within 2 % of its initial value (wrong inertia frames or a
///    wrong frame for ω₀ change it by far more).
/// 3. Collision in zero gravity (two boxes of different densities, off-centre, μ = 0.3):
///    total linear and angular momentum, computed with stiffsoft's masses and inertias,
///    change by < 1 % although the bodies' velocities change by > 10 % (wrong masses or
///    inertias in an engine break the balance).

#include <filesystem>
#include <string>
#include <vector>

#include "peers/engines.hpp"

namespace stiffsoft::peers {

/// Runs the checks for each engine; prints one line per check; returns the number that failed.
int verify_engines(const std::vector<std::string>& engines, const std::vector<std::filesystem::path>& scenes,
                   const EngineOptions& options);

}  // namespace stiffsoft::peers

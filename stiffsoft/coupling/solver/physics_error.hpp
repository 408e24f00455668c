#pragma once
/// @file The error of a step that cannot be taken without giving up what the scene asks for.

#include <stdexcept>
#include <string>

namespace stiffsoft {

/// A step that would break the physics the scene prescribes: an affine body deformed past its
/// rigidity bound, or a kinematic body (or prescribed soft nodes) that cannot follow its path
/// without intersection. Simulation::step() throws it before committing the step, so the
/// state (and every frame written so far) stays at the last good step. The message names the
/// body, the step and time, the measured value and what to change.
class PhysicsError : public std::runtime_error {
 public:
  /// An error with the given message.
  explicit PhysicsError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace stiffsoft

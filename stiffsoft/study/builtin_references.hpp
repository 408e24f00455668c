#pragma once
/// @file Analytic references of the validation problems (/work/shared/validation.md) by name,
/// as expressions over study constants and the time t.

#include <string>
#include <vector>

namespace stiffsoft::study {

/// A named analytic reference.
struct BuiltinReference {
  std::string name;                      ///< the name used in study files
  std::vector<std::string> expressions;  ///< one per compared component
  std::vector<std::string> constants;    ///< constants the study must define
  std::string meaning;                   ///< what it is, with units
};

/// Every built-in reference.
const std::vector<BuiltinReference>& builtin_references();

/// The built-in called `name`, or nullptr.
const BuiltinReference* find_builtin_reference(const std::string& name);

}  // namespace stiffsoft::study

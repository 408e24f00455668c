#pragma once
/// @file The scene schema (scene_schema.hpp) as a Markdown page: docs/scenes.md.

#include <string>

namespace stiffsoft {

/// The schema rendered as a Markdown page (title, conventions, one table of every key).
/// docs/scenes.md is exactly this text (`stiffsoft schema --markdown > docs/scenes.md`);
/// a test keeps the two equal.
std::string schema_markdown();

}  // namespace stiffsoft

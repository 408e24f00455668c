#pragma once
/// @file `stiffsoft schema [--markdown]`: print the scene schema.

#include <ostream>

namespace stiffsoft {

/// Writes the scene schema to out: the JSON list of scene_schema() (pretty, 2-space indent),
/// or with markdown the page schema_markdown(), which is docs/scenes.md
/// (`stiffsoft schema --markdown > docs/scenes.md` regenerates it). Returns the exit status:
/// 0, or 1 when out could not be written.
int print_schema(bool markdown, std::ostream& out);

}  // namespace stiffsoft

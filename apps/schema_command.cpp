#include "schema_command.hpp"

#include <stiffsoft/scene/schema_markdown.hpp>
#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

int print_schema(bool markdown, std::ostream& out) {
  if (markdown)
    out << schema_markdown();  // ends with a newline already, like docs/scenes.md
  else
    out << scene_schema().dump(2) << '\n';
  out.flush();
  return out ? 0 : 1;
}

}  // namespace stiffsoft

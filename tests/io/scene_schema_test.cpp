#include <functional>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "io/scene_loader.hpp"
#include "io/scene_schema.hpp"

namespace stiffsoft {
namespace {

const std::filesystem::path kSource(STIFFSOFT_SOURCE_DIR);

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

TEST(SceneSchema, DocsScenesMdIsTheRenderedSchema) {
  const std::filesystem::path doc = kSource / "docs" / "scenes.md";
  // Regenerating is explicit (an environment variable), so a normal test run never
  // rewrites a source file.
  if (std::getenv("STIFFSOFT_WRITE_DOCS") != nullptr) std::ofstream(doc, std::ios::binary) << schema_markdown();
  EXPECT_EQ(read_text(doc), schema_markdown())
      << "docs/scenes.md is out of date; regenerate with STIFFSOFT_WRITE_DOCS=1 io_tests --gtest_filter='SceneSchema*'";
}

TEST(SceneSchema, EveryEntryHasAKnownTypeAndADoc) {
  const std::set<std::string> types = {"object", "list", "number", "integer", "string", "vector3", "file"};
  for (const auto& entry : scene_schema()) {
    SCOPED_TRACE(entry.dump());
    ASSERT_TRUE(entry.contains("pointer"));
    ASSERT_TRUE(entry.contains("type"));
    EXPECT_TRUE(types.count(entry["type"].get<std::string>()));
    ASSERT_TRUE(entry.contains("doc"));
    EXPECT_FALSE(entry["doc"].get<std::string>().empty());
    if (entry.contains("default") && entry["default"].is_null()) {
      EXPECT_TRUE(entry.contains("default_doc"));
    }
  }
}

TEST(SceneSchema, EveryDefaultPassesItsOwnEntry) {
  // A default that broke its own range would be written into every scene.
  for (const auto& entry : scene_schema()) {
    if (!entry.contains("default") || entry["default"].is_null()) continue;
    SCOPED_TRACE(entry.dump());
    const double lo_exclusive = entry.value("exclusive_min", -1e300);
    const double lo = entry.value("min", -1e300);
    const auto values = entry["default"].is_array() ? entry["default"] : nlohmann::ordered_json::array({entry["default"]});
    for (const auto& v : values) {
      if (!v.is_number()) continue;
      EXPECT_GT(v.get<double>(), lo_exclusive);
      EXPECT_GE(v.get<double>(), lo);
    }
    if (entry.contains("options")) {
      const auto& options = entry["options"];
      EXPECT_NE(std::find(options.begin(), options.end(), entry["default"]), options.end());
    }
  }
}

TEST(SceneSchema, ResolvedJsonHasEveryKeyOfTheSchema) {
  // A scene whose bodies use every primitive; the resolved JSON must name every schema
  // pointer (primitive keys only where their `when` allows), so the writer cannot drift
  // from the schema.
  const SceneDescription scene =
      load_scene(kSource / "tests" / "io" / "data" / "good" / "all_keys.json");
  const nlohmann::json resolved = resolved_scene_json(scene);
  for (const auto& entry : scene_schema()) {
    const std::string pointer = entry["pointer"];
    if (pointer == "/") continue;
    SCOPED_TRACE(pointer);
    // Replace each list wildcard by the index of an element (a body, a Dirichlet condition)
    // that uses the key.
    const std::function<bool(const std::string&)> found = [&](const std::string& concrete) {
      const std::size_t star = concrete.find('*');
      if (star == std::string::npos) return resolved.contains(nlohmann::json::json_pointer(concrete));
      const nlohmann::json::json_pointer list(concrete.substr(0, star - 1));
      if (!resolved.contains(list)) return false;
      for (std::size_t i = 0; i < resolved[list].size(); ++i)
        if (found(std::string(concrete).replace(star, 1, std::to_string(i)))) return true;
      return false;
    };
    EXPECT_TRUE(found(pointer)) << pointer << " is missing from resolved_scene_json";
  }
}

TEST(SceneSchema, MarkdownListsEveryKey) {
  const std::string md = schema_markdown();
  for (const char* key : {"`description`", "`time.dt`", "`contact.dhat`", "`bodies[].mesh.minor_radius`",
                          "`bodies[].angular_velocity`", "`solver.linear`", "`output.frame_dt`"})
    EXPECT_NE(md.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace stiffsoft

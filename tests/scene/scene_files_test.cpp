#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include <stiffsoft/scene/scene_loader.hpp>

namespace stiffsoft {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(STIFFSOFT_SOURCE_DIR) / "scenes";

std::vector<std::filesystem::path> shipped_scenes() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(kScenes))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  return files;
}

TEST(SceneFiles, EveryShippedSceneLoads) {
  const auto files = shipped_scenes();
  EXPECT_FALSE(files.empty());
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    EXPECT_NO_THROW({
      try {
        load_scene(file);
      } catch (const SceneError& error) {
        ADD_FAILURE() << error.what();
        throw;
      }
    });
  }
}

TEST(SceneFiles, EveryShippedSceneSaysHowToRunIt) {
  for (const auto& file : shipped_scenes()) {
    const SceneDescription scene = load_scene(file);
    const std::string command = "stiffsoft run scenes/" + file.filename().string() + " -o out/" + file.stem().string();
    EXPECT_NE(scene.description.find(command), std::string::npos) << file << " lacks `" << command << "`";
  }
}

TEST(SceneFiles, TheScenesTheReadmeAndBenchmarksNameExist) {
  for (const char* name : {"default", "box_stack", "house_of_cards", "incline_stick", "incline_slide", "wrecking_ball",
                           "thin_wall", "light", "medium", "full"})
    EXPECT_TRUE(std::filesystem::exists(kScenes / (std::string(name) + ".json"))) << name;
}

}  // namespace
}  // namespace stiffsoft

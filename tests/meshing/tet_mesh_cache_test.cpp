#include <stiffsoft/meshing/tet_mesh_cache.hpp>

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <stiffsoft/meshing/gmsh_session.hpp>
#include <stiffsoft/meshing/tet_mesh_binary.hpp>

namespace stiffsoft {
namespace {

const std::filesystem::path data = std::filesystem::path(STIFFSOFT_SOURCE_DIR) / "tests" / "meshing" / "data";

class TetMeshCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("stiffsoft_tet_mesh_cache_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  static TetMeshRecipe box(double h) {
    TetMeshRecipe r;
    r.primitive = PrimitiveShape{};
    r.primitive->extents = {0.4, 0.3, 0.2};
    r.options.h = h;
    return r;
  }
  std::filesystem::path dir_;
};

TEST(Fnv1a64, MatchesPublishedVectors) {
  // Test vectors of the FNV reference (Fowler, Noll, Vo; draft-eastlake-fnv).
  EXPECT_EQ(fnv1a_64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a_64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a_64("foobar"), 0x85944171f73967e8ull);
  EXPECT_EQ(fnv1a_64("bar", fnv1a_64("foo")), fnv1a_64("foobar"));
}

TEST_F(TetMeshCache, SecondCallIsAHitWithoutGmshAndTheSameMesh) {
  const std::size_t before = gmsh_session_count();
  const CachedTetMesh first = cached_tet_mesh(box(0.15), dir_);
  EXPECT_FALSE(first.from_cache);
  EXPECT_EQ(first.cache_problem, "");
  EXPECT_EQ(gmsh_session_count(), before + 1);
  EXPECT_TRUE(std::filesystem::is_regular_file(first.cache_file));
  EXPECT_EQ(first.cache_file.parent_path(), dir_);

  const CachedTetMesh second = cached_tet_mesh(box(0.15), dir_);
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(second.cache_problem, "");
  EXPECT_EQ(gmsh_session_count(), before + 1);  // gmsh did not run
  EXPECT_EQ(second.cache_file, first.cache_file);
  EXPECT_EQ(second.mesh.X, first.mesh.X);  // bit-identical
  EXPECT_EQ(second.mesh.T, first.mesh.T);
  EXPECT_EQ(second.mesh.node_sets, first.mesh.node_sets);

  // Fresh meshing gives the same mesh too (gmsh single-threaded is deterministic).
  const TetMesh again = make_tet_mesh(box(0.15));
  EXPECT_EQ(again.X, first.mesh.X);
  EXPECT_EQ(again.T, first.mesh.T);
}

TEST_F(TetMeshCache, KeyDependsOnWhatTheMeshDependsOn) {
  const std::uint64_t base = tet_mesh_recipe_hash(box(0.15));
  EXPECT_NE(tet_mesh_recipe_hash(box(0.15000000000000002)), base);
  TetMeshRecipe wider = box(0.15);
  wider.primitive->extents.x() = 0.41;
  EXPECT_NE(tet_mesh_recipe_hash(wider), base);
  TetMeshRecipe curved = box(0.15);
  curved.options.elements_per_circle = 12;
  EXPECT_NE(tet_mesh_recipe_hash(curved), base);
  // Settings a primitive does not use, and the log switch, do not change the key.
  TetMeshRecipe same = box(0.15);
  same.primitive->resolution = 40;
  same.primitive->radius = 9.0;
  same.options.keep_surface = true;
  same.options.verbose = true;
  EXPECT_EQ(tet_mesh_recipe_hash(same), base);
  // A plane is meshed as the box of its extents.
  same.primitive->type = PrimitiveShape::Type::Plane;
  EXPECT_EQ(tet_mesh_recipe_hash(same), base);
}

TEST_F(TetMeshCache, FileRecipesAreKeyedByContentNotPath) {
  std::filesystem::create_directories(dir_);
  const auto a = dir_ / "a.stl", b = dir_ / "b.STL";
  std::filesystem::copy_file(data / "tet_cube_half_metre.stl", a);
  std::filesystem::copy_file(data / "tet_cube_half_metre.stl", b);
  TetMeshRecipe ra, rb;
  ra.file = a;
  rb.file = b;
  ra.options.h = rb.options.h = 0.2;
  EXPECT_EQ(tet_mesh_recipe_hash(ra), tet_mesh_recipe_hash(rb));
  EXPECT_EQ(tet_mesh_recipe_text(ra).find(a.string()), std::string::npos);
  std::ofstream(b, std::ios::app) << "\n";  // one more byte
  EXPECT_NE(tet_mesh_recipe_hash(ra), tet_mesh_recipe_hash(rb));

  const auto cache = dir_ / "cache";
  const std::size_t before = gmsh_session_count();
  const CachedTetMesh first = cached_tet_mesh(ra, cache);
  const CachedTetMesh second = cached_tet_mesh(ra, cache);
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(gmsh_session_count(), before + 1);
  EXPECT_EQ(second.mesh.X, first.mesh.X);
  EXPECT_EQ(second.mesh.T, first.mesh.T);

  TetMeshRecipe missing;
  missing.file = dir_ / "missing.obj";
  try {
    tet_mesh_recipe_hash(missing);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), missing.file.string() + ": cannot open file");
  }
}

TEST_F(TetMeshCache, CorruptEntryIsReplaced) {
  const CachedTetMesh first = cached_tet_mesh(box(0.2), dir_);
  std::filesystem::resize_file(first.cache_file, std::filesystem::file_size(first.cache_file) - 3);
  const std::size_t before = gmsh_session_count();
  const CachedTetMesh second = cached_tet_mesh(box(0.2), dir_);
  EXPECT_FALSE(second.from_cache);
  EXPECT_EQ(gmsh_session_count(), before + 1);
  EXPECT_NE(second.cache_problem.find("ignored cache entry: " + first.cache_file.string() + ": truncated"),
            std::string::npos)
      << second.cache_problem;
  EXPECT_EQ(second.mesh.T, first.mesh.T);
  EXPECT_TRUE(cached_tet_mesh(box(0.2), dir_).from_cache);  // rewritten
}

TEST_F(TetMeshCache, EntryOfAnotherRecipeIsNotUsed) {
  const CachedTetMesh a = cached_tet_mesh(box(0.2), dir_);
  const CachedTetMesh b = cached_tet_mesh(box(0.3), dir_);
  std::filesystem::copy_file(b.cache_file, a.cache_file, std::filesystem::copy_options::overwrite_existing);
  const CachedTetMesh again = cached_tet_mesh(box(0.2), dir_);
  EXPECT_FALSE(again.from_cache);
  EXPECT_NE(again.cache_problem.find("holds the mesh of another recipe"), std::string::npos)
      << again.cache_problem;
  EXPECT_EQ(again.mesh.T, a.mesh.T);
}

TEST_F(TetMeshCache, FolderComesFromArgumentThenEnvironment) {
  const char* saved = std::getenv("STIFFSOFT_MESH_CACHE");
  const std::string saved_value = saved ? saved : "";
  ::setenv("STIFFSOFT_MESH_CACHE", dir_.c_str(), 1);
  EXPECT_EQ(tet_mesh_cache_folder(), dir_);
  EXPECT_EQ(tet_mesh_cache_folder("/elsewhere"), std::filesystem::path("/elsewhere"));
  const CachedTetMesh m = cached_tet_mesh(box(0.3));
  EXPECT_EQ(m.cache_file.parent_path(), dir_);
  ::unsetenv("STIFFSOFT_MESH_CACHE");
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg) {
    EXPECT_EQ(tet_mesh_cache_folder(), std::filesystem::path(xdg) / "stiffsoft" / "meshes");
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    EXPECT_EQ(tet_mesh_cache_folder(), std::filesystem::path(home) / ".cache" / "stiffsoft" / "meshes");
  }
  if (saved) ::setenv("STIFFSOFT_MESH_CACHE", saved_value.c_str(), 1);
}

TEST_F(TetMeshCache, UnwritableFolderStillGivesTheMesh) {
  std::filesystem::create_directories(dir_);
  const auto blocker = dir_ / "file";
  std::ofstream(blocker) << "x";
  const CachedTetMesh m = cached_tet_mesh(box(0.3), blocker / "sub");
  EXPECT_FALSE(m.from_cache);
  EXPECT_GT(m.mesh.T.rows(), 0);
  EXPECT_NE(m.cache_problem.find("not cached: "), std::string::npos) << m.cache_problem;
}

TEST_F(TetMeshCache, BinaryFormatRoundTripsExactly) {
  std::filesystem::create_directories(dir_);
  TetMesh m;
  m.X.resize(4, 3);
  m.X << 0, 0, 0, 0.1, 0, 0, 0, 0.1, 0, 0, 0, 1.0 / 3.0;
  m.T.resize(1, 4);
  m.T << 0, 1, 2, 3;
  m.node_sets["a"] = {0, 3};
  m.node_sets["empty"] = {};
  const auto file = dir_ / "m.tetmesh";
  write_tet_mesh_binary(file, m, 42);
  std::uint64_t tag = 0;
  const TetMesh back = read_tet_mesh_binary(file, &tag);
  EXPECT_EQ(tag, 42u);
  EXPECT_EQ(back.X, m.X);
  EXPECT_EQ(back.T, m.T);
  EXPECT_EQ(back.node_sets, m.node_sets);
  std::ofstream(file, std::ios::app) << "x";
  EXPECT_THROW(read_tet_mesh_binary(file), std::runtime_error);
}

}  // namespace
}  // namespace stiffsoft

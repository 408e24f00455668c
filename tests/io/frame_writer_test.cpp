#include <stiffsoft/io/frame_writer.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <stiffsoft/io/frame_reader.hpp>

namespace stiffsoft {
namespace {

/// A unit tetrahedron's surface, moved by `shift`.
BodyFrame tetrahedron(const std::string& name, const std::string& model, double shift) {
  BodyFrame body;
  body.name = name;
  body.model = model;
  body.x.resize(4, 3);
  body.x << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  body.x.array() += shift;
  body.F.resize(4, 3);
  body.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return body;
}

/// A single triangle with 3 vertices whose velocities are given.
BodyFrame triangle(const std::string& name, double time) {
  BodyFrame body;
  body.name = name;
  body.model = "affine";
  body.x.resize(3, 3);
  body.x << 0.1, 0.2, 0.3, 1.0 / 3.0, 0, 0, 0, 1e-9, 7;
  body.x(0, 0) += time;
  body.F.resize(1, 3);
  body.F << 0, 1, 2;
  body.velocity = Eigen::MatrixX3d::Random(3, 3);
  body.displacement = Eigen::MatrixX3d::Constant(3, 3, time);
  return body;
}

class FrameWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("stiffsoft_frame_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static std::string content(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  std::filesystem::path dir_;
};

TEST_F(FrameWriterTest, TwoFramesOfTwoBodiesReadBackExactly) {
  FrameWriter writer(dir_, "drop");
  EXPECT_EQ(writer.frame_count(), 0);
  EXPECT_EQ(writer.pvd_path(), dir_ / "drop.pvd");
  const std::vector<double> times = {0.0, 1.0 / 60.0};
  std::vector<std::vector<BodyFrame>> frames;
  for (const double t : times) {
    frames.push_back({tetrahedron("ground", "fixed", -2.0 + t), triangle("ball one", t)});
    writer.write(t, frames.back());
  }
  EXPECT_EQ(writer.frame_count(), 2);

  const auto entries = read_pvd(writer.pvd_path());
  ASSERT_EQ(entries.size(), 2u);
  for (std::size_t f = 0; f < 2; ++f) {
    EXPECT_EQ(entries[f].time, times[f]);  // exact: times are written in round-trip form
    char stem[32];
    std::snprintf(stem, sizeof(stem), "drop_%06zu.vtm", f);
    EXPECT_EQ(entries[f].file, dir_ / "frames" / stem);
    const auto surfaces = read_frame(entries[f].file);
    ASSERT_EQ(surfaces.size(), 2u);
    for (std::size_t b = 0; b < 2; ++b) {
      const BodyFrame& expected = frames[f][b];
      EXPECT_EQ(surfaces[b].name, expected.name);
      EXPECT_EQ(surfaces[b].x, expected.x);  // exact: points are stored as Float64
      EXPECT_EQ(surfaces[b].F, expected.F);
    }
  }
  // Different frames hold different positions (not one file read twice).
  EXPECT_NE(read_frame(entries[0].file)[1].x, read_frame(entries[1].file)[1].x);
}

TEST_F(FrameWriterTest, BlocksAreNamedVtuFilesWithPointAndFieldData) {
  FrameWriter writer(dir_, "scene");
  const BodyFrame body = triangle("ball one", 0.5);
  writer.write(0.5, {tetrahedron("ground", "fixed", 0.0), body});

  const auto vtm = dir_ / "frames" / "scene_000000.vtm";
  const std::string vtm_text = content(vtm);
  EXPECT_NE(vtm_text.find("name=\"ground\" file=\"scene_000000/0_ground.vtu\""), std::string::npos)
      << vtm_text;
  EXPECT_NE(vtm_text.find("name=\"ball one\" file=\"scene_000000/1_ball_one.vtu\""),
            std::string::npos)
      << vtm_text;

  const auto vtu = dir_ / "frames" / "scene_000000" / "1_ball_one.vtu";
  const std::string xml = content(vtu);
  EXPECT_NE(xml.find("type=\"UnstructuredGrid\""), std::string::npos);
  EXPECT_NE(xml.find("<AppendedData encoding=\"raw\">"), std::string::npos);
  EXPECT_NE(xml.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  for (const char* name : {"velocity", "displacement", "contact_force", "friction_force"}) {
    const std::string tag = std::string("Name=\"") + name + "\" NumberOfComponents=\"3\"";
    EXPECT_NE(xml.find(tag), std::string::npos) << name;
  }
  for (const char* name : {"time", "body", "model"}) {
    EXPECT_NE(xml.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
  }

  EXPECT_EQ(read_point_vectors(vtu, "velocity"), body.velocity);
  EXPECT_EQ(read_point_vectors(vtu, "displacement"), body.displacement);
  // Arrays not given are written as zeros.
  EXPECT_EQ(read_point_vectors(vtu, "contact_force"), Eigen::MatrixX3d::Zero(3, 3));
  EXPECT_EQ(read_point_vectors(vtu, "friction_force"), Eigen::MatrixX3d::Zero(3, 3));
  EXPECT_THROW(read_point_vectors(vtu, "pressure"), std::runtime_error);
}

TEST_F(FrameWriterTest, LeavesNoTemporaryFiles) {
  FrameWriter writer(dir_, "scene");
  for (int f = 0; f < 3; ++f) writer.write(f * 0.1, {tetrahedron("a", "affine", f), triangle("b", f)});
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << entry.path();
    EXPECT_NE(name.front(), '.') << entry.path();
    files += entry.is_regular_file();
  }
  EXPECT_EQ(files, 1u + 3u * (1u + 2u));  // .pvd + per frame one .vtm and two .vtu
}

TEST_F(FrameWriterTest, PvdListsExactlyTheCompleteFrames) {
  FrameWriter writer(dir_, "scene");
  EXPECT_TRUE(read_pvd(writer.pvd_path()).empty());  // written by the constructor
  writer.write(0.0, {triangle("b", 0.0)});
  BodyFrame bad = triangle("b", 0.1);
  bad.F(0, 2) = 3;  // out of range
  EXPECT_THROW(writer.write(0.1, {bad}), std::invalid_argument);
  BodyFrame bad_rows = triangle("b", 0.1);
  bad_rows.contact_force = Eigen::MatrixX3d::Zero(2, 3);
  EXPECT_THROW(writer.write(0.1, {bad_rows}), std::invalid_argument);
  EXPECT_EQ(writer.frame_count(), 1);
  EXPECT_EQ(read_pvd(writer.pvd_path()).size(), 1u);
  writer.write(0.1, {triangle("b", 0.1)});
  const auto entries = read_pvd(writer.pvd_path());
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[1].time, 0.1);
}

TEST_F(FrameWriterTest, NamesWithXmlSpecialCharactersRoundTrip) {
  FrameWriter writer(dir_, "scene");
  const std::string name = "a<b> & \"c\" 'd'/e";
  writer.write(0.0, {triangle(name, 0.0)});
  const auto surfaces = read_frame(read_pvd(writer.pvd_path()).at(0).file);
  ASSERT_EQ(surfaces.size(), 1u);
  EXPECT_EQ(surfaces[0].name, name);
  EXPECT_EQ(sanitize_file_name(name), "a_b_____c___d__e");
  EXPECT_EQ(sanitize_file_name(""), "body");
}

TEST_F(FrameWriterTest, UnwritableOutputFolderThrowsNamingIt) {
  std::filesystem::create_directories(dir_);
  const auto blocker = dir_ / "file";
  std::ofstream(blocker) << "not a folder";
  try {
    FrameWriter writer(blocker / "out", "scene");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((blocker / "out").string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(FrameWriter(dir_ / "out", ""), std::invalid_argument);
}

}  // namespace
}  // namespace stiffsoft

#include <stiffsoft/io/frame_reader.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>

#include <stiffsoft/io/frame_writer.hpp>

namespace stiffsoft {
namespace {

class FrameReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("stiffsoft_reader_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// Expects `call` to throw std::runtime_error whose message names `file`.
  template <class Call>
  static void expect_error_naming(const std::filesystem::path& file, Call call) {
    try {
      call();
      ADD_FAILURE() << "no exception for " << file;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
  }

  std::filesystem::path dir_;
};

TEST_F(FrameReaderTest, MissingPvdIsAnErrorNamingIt) {
  const auto pvd = dir_ / "none.pvd";
  expect_error_naming(pvd, [&] { read_pvd(pvd); });
}

TEST_F(FrameReaderTest, MalformedPvdIsAnErrorNamingIt) {
  const auto pvd = dir_ / "bad.pvd";
  const std::vector<std::string> bad = {
      "just text",
      "<VTKFile type=\"UnstructuredGrid\"></VTKFile>",
      "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"x\" file=\"a.vtm\"/>"
      "</Collection></VTKFile>",
      "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"1\"/></Collection></VTKFile>",
      "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"1\" file=\"a.vtm\"/>",
  };
  for (const std::string& text : bad) {
    std::ofstream(pvd) << text;
    SCOPED_TRACE(text);
    expect_error_naming(pvd, [&] { read_pvd(pvd); });
  }
}

TEST_F(FrameReaderTest, PvdWrittenByOthersIsRead) {
  const auto pvd = dir_ / "other.pvd";
  std::ofstream(pvd) << "<?xml version='1.0'?>\n<VTKFile type='Collection' version='0.1'>\n"
                        "<Collection>\n<DataSet part='0' file='f/a.vtm' timestep='2.5e-1' />\n"
                        "<DataSet timestep=\"3\" file=\"/abs/b.vtm\"/></Collection></VTKFile>\n";
  const auto entries = read_pvd(pvd);
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].time, 0.25);
  EXPECT_EQ(entries[0].file, dir_ / "f" / "a.vtm");
  EXPECT_EQ(entries[1].time, 3.0);
  EXPECT_EQ(entries[1].file, std::filesystem::path("/abs/b.vtm"));
}

TEST_F(FrameReaderTest, MissingOrBrokenVtuIsAnErrorNamingIt) {
  BodyFrame body;
  body.name = "b";
  body.model = "affine";
  body.x = Eigen::MatrixX3d::Identity(3, 3);
  body.F.resize(1, 3);
  body.F << 0, 1, 2;
  FrameWriter writer(dir_ / "out", "s");
  writer.write(0.0, {body});
  const auto vtm = read_pvd(writer.pvd_path()).at(0).file;
  const auto vtu = dir_ / "out" / "frames" / "s_000000" / "0_b.vtu";
  ASSERT_TRUE(std::filesystem::exists(vtu));
  ASSERT_EQ(read_frame(vtm).size(), 1u);

  std::ofstream(vtu, std::ios::trunc) << "<VTKFile type=\"UnstructuredGrid\"";  // truncated
  expect_error_naming(vtu, [&] { read_frame(vtm); });
  std::filesystem::remove(vtu);
  expect_error_naming(vtu, [&] { read_frame(vtm); });
  expect_error_naming(dir_ / "none.vtm", [&] { read_frame(dir_ / "none.vtm"); });
}

}  // namespace
}  // namespace stiffsoft

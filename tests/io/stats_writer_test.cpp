#include <stiffsoft/io/stats_writer.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace stiffsoft {
namespace {

class StatsWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("stiffsoft_stats_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static std::vector<std::string> lines(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::string> result;
    for (std::string line; std::getline(in, line);) result.push_back(line);
    return result;
  }

  std::filesystem::path dir_;
};

TEST_F(StatsWriterTest, FileHasHeaderThenOneLinePerRow) {
  const auto file = dir_ / "stats.csv";
  StatsWriter stats(file, {"time", "newton_iterations", "min_distance"});
  stats.add_row({0.01, 3, 1.5e-4});
  stats.add_row({0.02, 7, 0.1});
  stats.flush();
  const auto text = lines(file);
  ASSERT_EQ(text.size(), 3u);
  EXPECT_EQ(text[0], "time,newton_iterations,min_distance");
  EXPECT_EQ(text[1], "0.01,3,0.00015");
  EXPECT_EQ(text[2], "0.02,7,0.1");
  EXPECT_EQ(stats.row_count(), 2u);
}

TEST_F(StatsWriterTest, ValuesReadBackExactly) {
  const auto file = dir_ / "stats.csv";
  const double value = 1.0 / 3.0;
  {
    StatsWriter stats(file, {"x"});
    stats.add_row({value});
  }  // destructor flushes
  const auto text = lines(file);
  ASSERT_EQ(text.size(), 2u);
  EXPECT_EQ(std::stod(text[1]), value);
}

TEST_F(StatsWriterTest, FlushAfterEachRowKeepsTheFileWhole) {
  const auto file = dir_ / "stats.csv";
  StatsWriter stats(file, {"a", "b"});
  for (int i = 0; i < 5; ++i) {
    stats.add_row({double(i), double(2 * i)});
    stats.flush();
    EXPECT_EQ(lines(file).size(), std::size_t(i + 2));
  }
  EXPECT_EQ(lines(file).back(), "4,8");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 1u);  // no temporaries left
}

// A flush appends the rows added since the last one and leaves the file's earlier bytes as
// they are (a long run does not rewrite its file at every frame); a resumed writer cuts the
// file after the checkpoint's rows at its first flush, then appends.
TEST_F(StatsWriterTest, FlushesAppendAndAResumedWriterCutsAfterTheKeptRows) {
  const auto file = dir_ / "stats.csv";
  {
    StatsWriter stats(file, {"step", "x"});
    stats.add_row({0, 0.5});
    stats.add_row({1, 1.5});
    stats.flush();
    // Marks the file's first row where a rewrite would restore it.
    std::fstream(file, std::ios::in | std::ios::out | std::ios::binary).seekp(7) << '9';
    stats.add_row({2, 2.5});
    stats.add_row({3, 3.5});
  }  // the destructor flushes
  EXPECT_EQ(lines(file), (std::vector<std::string>{"step,x", "9,0.5", "1,1.5", "2,2.5", "3,3.5"}));
  StatsWriter resumed(file, {"step", "x"});
  resumed.reload(csv_end_through_step(file, {"step", "x"}, 1));
  EXPECT_EQ(lines(file).size(), 5u);  // nothing cut before the first flush
  resumed.add_row({2, 7.5});
  resumed.flush();
  EXPECT_EQ(lines(file), (std::vector<std::string>{"step,x", "9,0.5", "1,1.5", "2,7.5"}));
  EXPECT_EQ(resumed.row_count(), 1u);
}

TEST_F(StatsWriterTest, DestructorWritesTheHeaderEvenWithoutRows) {
  const auto file = dir_ / "stats.csv";
  { StatsWriter stats(file, {"time"}); }
  const auto text = lines(file);
  ASSERT_EQ(text.size(), 1u);
  EXPECT_EQ(text[0], "time");
}

TEST_F(StatsWriterTest, RejectsRowsOfTheWrongWidthAndBadColumnNames) {
  StatsWriter stats(dir_ / "stats.csv", {"a", "b"});
  EXPECT_THROW(stats.add_row({1.0}), std::invalid_argument);
  EXPECT_THROW(stats.add_row({1.0, 2.0, 3.0}), std::invalid_argument);
  EXPECT_EQ(stats.row_count(), 0u);
  EXPECT_THROW(StatsWriter(dir_ / "x.csv", {}), std::invalid_argument);
  EXPECT_THROW(StatsWriter(dir_ / "x.csv", {"a,b"}), std::invalid_argument);
}

TEST_F(StatsWriterTest, FlushIntoAMissingFolderThrowsNamingTheFile) {
  const auto file = dir_ / "missing" / "stats.csv";
  StatsWriter stats(file, {"a"});
  stats.add_row({1.0});
  try {
    stats.flush();
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stiffsoft

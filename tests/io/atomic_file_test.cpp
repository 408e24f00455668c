#include <stiffsoft/io/atomic_file.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace stiffsoft {
namespace {

/// A fresh folder under the system temp dir, removed at the end of the test.
class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("stiffsoft_atomic_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static std::string content(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  /// Number of entries in dir_: only the target file may remain.
  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_)) ++n;
    return n;
  }

  std::filesystem::path dir_;
};

TEST_F(AtomicFileTest, WritesTheContentAndLeavesNoTemporary) {
  const auto file = dir_ / "a.txt";
  write_file_atomically(file, [](std::ostream& out) { out << "hello\n"; });
  EXPECT_EQ(content(file), "hello\n");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, ReplacesExistingContent) {
  const auto file = dir_ / "a.txt";
  write_file_atomically(file, [](std::ostream& out) { out << "old"; });
  write_file_atomically(file, [](std::ostream& out) { out << "new content"; });
  EXPECT_EQ(content(file), "new content");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, KeepsOldContentWhenTheWriterThrowsMidway) {
  const auto file = dir_ / "a.txt";
  write_file_atomically(file, [](std::ostream& out) { out << "old"; });
  EXPECT_THROW(write_file_atomically(file,
                                     [](std::ostream& out) {
                                       out << std::string(100000, 'x');  // partly on disk already
                                       out.flush();
                                       throw std::logic_error("writer failed");
                                     }),
               std::logic_error);
  EXPECT_EQ(content(file), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, ThrowsNamingTheFileWhenTheStreamFails) {
  const auto file = dir_ / "a.txt";
  write_file_atomically(file, [](std::ostream& out) { out << "old"; });
  // badbit is how a full disk shows up on an ofstream.
  try {
    write_file_atomically(file, [](std::ostream& out) {
      out << "partial";
      out.setstate(std::ios::badbit);
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(content(file), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, ThrowsNamingTheFileWhenTheFolderIsMissing) {
  const auto file = dir_ / "missing" / "a.txt";
  try {
    write_file_atomically(file, [](std::ostream& out) { out << "x"; });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST_F(AtomicFileTest, ThrowsWhenTheTargetIsAFolderAndKeepsIt) {
  const auto target = dir_ / "sub";
  std::filesystem::create_directories(target / "inner");
  EXPECT_THROW(write_file_atomically(target, [](std::ostream& out) { out << "x"; }),
               std::runtime_error);
  EXPECT_TRUE(std::filesystem::is_directory(target / "inner"));
  EXPECT_EQ(entries(), 1u);
}

}  // namespace
}  // namespace stiffsoft
